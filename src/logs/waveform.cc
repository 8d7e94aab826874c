#include "logs/waveform.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.h"
#include "common/units.h"
#include "logs/csv_scan.h"
#include "logs/plateau.h"

namespace dynosize::logs {

std::string WaveformOptions::Validate() const {
  if (!(hysteresis_fraction > 0.0 && hysteresis_fraction < 1.0)) {
    return "WaveformOptions.hysteresis_fraction = " + std::to_string(hysteresis_fraction) +
           ": must be in (0, 1)";
  }
  if (min_periods < 1) return "WaveformOptions.min_periods = 0: must be >= 1";
  return "";
}

namespace {

// Integral over the fractional sample interval [a, b] of a sampled integrand f(k): trapezoid
// rule on the whole sample intervals inside, linear interpolation for the partial intervals at
// both ends (a and b are interpolated zero crossings). Result in "samples" (divide by the
// span for a mean).
template <typename F>
double IntegrateSamples(F f, double a, double b) {
  const auto ia = static_cast<std::size_t>(std::ceil(a));
  const auto ib = static_cast<std::size_t>(std::floor(b));
  double sum = 0.0;
  for (std::size_t k = ia; k < ib; ++k) sum += 0.5 * (f(k) + f(k + 1));
  auto at = [&](double x) {
    const auto k = static_cast<std::size_t>(std::floor(x));
    const double fr = x - static_cast<double>(k);
    return fr == 0.0 ? f(k) : (1.0 - fr) * f(k) + fr * f(k + 1);
  };
  if (static_cast<double>(ia) > a) sum += 0.5 * (at(a) + f(ia)) * (static_cast<double>(ia) - a);
  if (static_cast<double>(ib) < b) sum += 0.5 * (f(ib) + at(b)) * (b - static_cast<double>(ib));
  return sum;
}

}  // namespace

AcQuantities AnalyzeThreePhase(const double* v_an, const double* v_bn, const double* v_cn,
                               const double* i_a, const double* i_b, std::size_t n,
                               double sample_rate_hz, const WaveformOptions& options) {
  const std::string bad = options.Validate();
  if (!bad.empty()) throw UsageError(bad);
  if (v_an == nullptr || v_bn == nullptr || v_cn == nullptr || i_a == nullptr || i_b == nullptr) {
    throw UsageError("AnalyzeThreePhase: a waveform pointer is null");
  }
  if (n < 3) throw UsageError("AnalyzeThreePhase: n = " + std::to_string(n) + ": need >= 3 samples");
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw UsageError("AnalyzeThreePhase: sample_rate_hz must be > 0");
  }
  auto vab = [&](std::size_t k) { return v_an[k] - v_bn[k]; };
  // Hysteresis thresholds from vAB's rms over the whole capture.
  double ss = 0.0, mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += vab(k);
  mean /= static_cast<double>(n);
  for (std::size_t k = 0; k < n; ++k) ss += (vab(k) - mean) * (vab(k) - mean);
  const double rms = std::sqrt(ss / static_cast<double>(n));
  if (!(rms > 0.0)) throw DataError("AnalyzeThreePhase: vAB = vAN - vBN is constant: no AC waveform");
  const double h = options.hysteresis_fraction * rms;
  // Rising crossings: armed once vAB < mean - h, fired when it rises through the mean (the
  // instant interpolated between the two samples straddling the mean), then re-armed only
  // after going below -h again.
  std::vector<double> crossings;
  bool armed = false;
  for (std::size_t k = 1; k < n; ++k) {
    const double x0 = vab(k - 1) - mean, x1 = vab(k) - mean;
    if (x1 < -h) armed = true;
    if (armed && x0 < 0.0 && x1 >= 0.0) {
      // Confirm it is a real rise: vAB must reach +h before the next dip below -h.
      std::size_t j = k;
      while (j < n && vab(j) - mean < h && vab(j) - mean >= -h) ++j;
      if (j < n && vab(j) - mean >= h) {
        crossings.push_back(static_cast<double>(k - 1) + x0 / (x0 - x1));
        armed = false;
      }
    }
  }
  if (crossings.size() < options.min_periods + 1) {
    throw DataError("AnalyzeThreePhase: " + std::to_string(crossings.empty() ? 0 : crossings.size() - 1) +
                    " whole electrical period(s) of vAB in " + std::to_string(n) +
                    " samples; need at least " + std::to_string(options.min_periods));
  }
  const double a = crossings.front(), b = crossings.back();
  const double span = b - a;  // samples
  AcQuantities q;
  q.periods = crossings.size() - 1;
  q.window_s = span / sample_rate_hz;
  q.electrical_frequency_hz = static_cast<double>(q.periods) / q.window_s;
  auto mean_of = [&](auto f) { return IntegrateSamples(f, a, b) / span; };
  auto vbc = [&](std::size_t k) { return v_bn[k] - v_cn[k]; };
  auto vca = [&](std::size_t k) { return v_cn[k] - v_an[k]; };
  auto vac = [&](std::size_t k) { return v_an[k] - v_cn[k]; };
  auto ic = [&](std::size_t k) { return -(i_a[k] + i_b[k]); };
  q.v_ab_rms_v = std::sqrt(mean_of([&](std::size_t k) { return vab(k) * vab(k); }));
  q.v_bc_rms_v = std::sqrt(mean_of([&](std::size_t k) { return vbc(k) * vbc(k); }));
  q.v_ca_rms_v = std::sqrt(mean_of([&](std::size_t k) { return vca(k) * vca(k); }));
  q.i_a_rms_a = std::sqrt(mean_of([&](std::size_t k) { return i_a[k] * i_a[k]; }));
  q.i_b_rms_a = std::sqrt(mean_of([&](std::size_t k) { return i_b[k] * i_b[k]; }));
  q.i_c_rms_a = std::sqrt(mean_of([&](std::size_t k) { return ic(k) * ic(k); }));
  q.pac_w = mean_of([&](std::size_t k) { return vac(k) * i_a[k] + vbc(k) * i_b[k]; });
  q.vll_rms_v = (q.v_ab_rms_v + q.v_bc_rms_v + q.v_ca_rms_v) / 3.0;  // (33)
  q.irms_a = 0.5 * (q.i_a_rms_a + q.i_b_rms_a);                      // (34)
  const double denom = kPacPerVllIrms * q.vll_rms_v * q.irms_a;
  q.exchange_rate_ratio = denom > 0.0 ? q.pac_w / denom : 0.0;
  return q;
}

WaveformCapture ReadWaveformCsv(const std::string& path, double sample_rate_hz) {
  LineReader lr(path);
  std::string_view line;
  if (!lr.Next(&line)) throw DataError(path + ": empty file: no header line");
  const std::string header = ToUtf8(line);
  const char delim = DetectDelimiter(header);
  std::vector<std::string_view> f;
  SplitFields(header, delim, &f);
  const char* names[] = {"v_an_v", "v_bn_v", "v_cn_v", "i_a_a", "i_b_a", "time_s"};
  int idx[6] = {-1, -1, -1, -1, -1, -1};
  std::vector<std::string> unknown;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const std::string_view name = Trim(f[i]);
    bool found = false;
    for (int k = 0; k < 6; ++k) {
      if (name == names[k]) {
        if (idx[k] >= 0) throw DataError(path + ": line 1: column \"" + std::string(name) + "\" given twice");
        idx[k] = static_cast<int>(i), found = true;
      }
    }
    if (!found) unknown.push_back("\"" + std::string(name) + "\"");
  }
  if (!unknown.empty()) {
    std::sort(unknown.begin(), unknown.end());
    std::string u;
    for (const auto& s : unknown) u += (u.empty() ? "" : ", ") + s;
    throw DataError(path + ": line 1: unknown column(s) " + u +
                    "; valid: v_an_v, v_bn_v, v_cn_v, i_a_a, i_b_a, time_s");
  }
  for (int k = 0; k < 5; ++k) {
    if (idx[k] < 0) {
      throw DataError(path + ": line 1: missing column " + names[k] +
                      " (required: v_an_v, v_bn_v, v_cn_v, i_a_a, i_b_a)");
    }
  }
  if (idx[5] < 0 && !(sample_rate_hz > 0.0)) {
    throw UsageError(path + ": no time_s column: give the sample rate (sample_rate_hz > 0)");
  }
  WaveformCapture cap;
  cap.file = path;
  std::vector<double>* out[5] = {&cap.v_an, &cap.v_bn, &cap.v_cn, &cap.i_a, &cap.i_b};
  std::vector<double> time;
  const std::size_t ncols = f.size();
  while (lr.Next(&line)) {
    if (Trim(line).empty()) continue;
    SplitFields(line, delim, &f);
    if (f.size() != ncols) {
      throw DataError(path + ": line " + std::to_string(lr.line_number()) + ": " +
                      std::to_string(f.size()) + " cells, the header has " + std::to_string(ncols));
    }
    for (int k = 0; k < 6; ++k) {
      if (idx[k] < 0) continue;
      double v;
      const std::string_view cell = f[static_cast<std::size_t>(idx[k])];
      if (!ParseDouble(cell, &v)) {
        throw DataError(path + ": line " + std::to_string(lr.line_number()) + ", column \"" +
                        names[k] + "\": " + QuoteCell(cell) + ": not a finite number");
      }
      (k < 5 ? *out[k] : time).push_back(v);
    }
  }
  if (cap.v_an.size() < 3) throw DataError(path + ": fewer than 3 samples");
  if (idx[5] >= 0) {
    std::vector<double> d(time.size() - 1);
    for (std::size_t i = 1; i < time.size(); ++i) d[i - 1] = time[i] - time[i - 1];
    const double med = MedianOf(d.data(), 0, d.size());
    if (!(med > 0.0)) throw DataError(path + ": time_s does not increase");
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (std::fabs(d[i] - med) > 0.01 * med) {
        std::ostringstream s;
        s << path << ": line " << i + 3 << ", column \"time_s\": interval " << d[i]
          << " s differs from the median interval " << med
          << " s by more than 1 % (rule: uniform sampling)";
        throw DataError(s.str());
      }
    }
    cap.sample_rate_hz = 1.0 / med;
  } else {
    cap.sample_rate_hz = sample_rate_hz;
  }
  return cap;
}

}  // namespace dynosize::logs
