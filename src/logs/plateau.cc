#include "logs/plateau.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/numbers.h"

namespace dynosize::logs {

namespace {

// 1.4826 = 1/Phi^-1(3/4): MAD -> standard deviation for normally distributed samples.
constexpr double kMadToSigma = 1.4826;

// Relative closeness with an absolute floor for values near zero (a motor at rest).
bool Within(double x, double ref, double band) {
  return std::fabs(x - ref) <= band * std::fabs(ref) + 1e-12;
}

}  // namespace

bool PlateauOptions::IsValid(std::string* error) const {
  auto bad = [&](const char* field, double v, const char* rule) {
    if (error) *error = std::string("PlateauOptions.") + field + " = " + std::to_string(v) + ": " + rule;
    return false;
  };
  if (!(command_step_tolerance > 0.0)) return bad("command_step_tolerance", command_step_tolerance, "must be > 0");
  if (!(settle_time_s >= 0.0)) return bad("settle_time_s", settle_time_s, "must be >= 0");
  if (!(settle_band > 0.0)) return bad("settle_band", settle_band, "must be > 0");
  if (min_samples < 1) return bad("min_samples", 0, "must be >= 1");
  if (!(outlier_mad_k > 0.0)) return bad("outlier_mad_k", outlier_mad_k, "must be > 0");
  if (!(mad_floor_rel >= 0.0)) return bad("mad_floor_rel", mad_floor_rel, "must be >= 0");
  if (!(steady_window_s > 0.0)) return bad("steady_window_s", steady_window_s, "must be > 0");
  if (!(steady_band > 0.0)) return bad("steady_band", steady_band, "must be > 0");
  if (!(steady_min_fraction > 0.0 && steady_min_fraction <= 1.0)) {
    return bad("steady_min_fraction", steady_min_fraction, "must be in (0, 1]");
  }
  if (!(stepped_min_fraction > 0.0 && stepped_min_fraction <= 1.0)) {
    return bad("stepped_min_fraction", stepped_min_fraction, "must be in (0, 1]");
  }
  if (steady_window_samples_without_time < 2) {
    return bad("steady_window_samples_without_time",
               static_cast<double>(steady_window_samples_without_time), "must be >= 2");
  }
  if (!(ramp_bin_width > 0.0)) return bad("ramp_bin_width", ramp_bin_width, "must be > 0");
  if (ramp_min_samples < 1) return bad("ramp_min_samples", 0, "must be >= 1");
  if (!(ramp_max_reversal_fraction >= 0.0 && ramp_max_reversal_fraction < 1.0)) {
    return bad("ramp_max_reversal_fraction", ramp_max_reversal_fraction, "must be in [0, 1)");
  }
  if (!(summary_min_interval_s > 0.0)) return bad("summary_min_interval_s", summary_min_interval_s, "must be > 0");
  return true;
}

double MedianOf(const double* x, std::size_t begin, std::size_t end) {
  thread_local std::vector<double> scratch;
  scratch.clear();
  for (std::size_t i = begin; i < end; ++i) {
    if (!std::isnan(x[i])) scratch.push_back(x[i]);
  }
  if (scratch.empty()) return kNaN;
  const std::size_t mid = scratch.size() / 2;
  std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(mid), scratch.end());
  double m = scratch[mid];
  if (scratch.size() % 2 == 0) {
    const double lo = *std::max_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(mid));
    m = 0.5 * (m + lo);
  }
  return m;
}

bool CommandIsStepped(const double* command, std::size_t n, const PlateauOptions& options) {
  if (command == nullptr || n == 0) return false;
  // Stand scripts hold the command exactly constant within a step; a fine ramp (0.5 us per
  // sample) changes it every sample. Sample-weighted, so that a few one-sample blips (a
  // hand-set value, a ramp between steps) do not hide the steps.
  std::size_t in_steps = 0;
  std::size_t start = 0;
  for (std::size_t i = 1; i <= n; ++i) {
    if (i == n || command[i] != command[i - 1]) {
      if (i - start >= options.min_samples) in_steps += i - start;
      start = i;
    }
  }
  return static_cast<double>(in_steps) >= options.stepped_min_fraction * static_cast<double>(n);
}

namespace {

void SearchByCommand(const double* t, const double* c, const double* s, std::size_t n,
                     const PlateauOptions& o, PlateauSearch* out) {
  std::size_t start = 0;
  for (std::size_t i = 1; i <= n; ++i) {
    if (i < n && std::fabs(c[i] - c[start]) <= o.command_step_tolerance) continue;
    const std::size_t end = i;
    // Transient by time (or by count without a time column).
    std::size_t b = start;
    if (t != nullptr) {
      while (b < end && t[b] - t[start] < o.settle_time_s) ++b;
    } else {
      b = std::min(end, start + o.settle_samples_without_time);
    }
    // "rpm settle": leading samples still far from the step's final level.
    if (s != nullptr && b < end) {
      const double ref = MedianOf(s, b + (end - b) / 2, end);
      if (!std::isnan(ref)) {
        while (b < end && !std::isnan(s[b]) && !Within(s[b], ref, o.settle_band)) ++b;
      }
    }
    out->transient_samples += b - start;
    if (end - b >= o.min_samples) {
      out->plateaus.push_back({start, b, end});
    } else {
      ++out->short_plateaus;
      out->short_plateau_samples += end - b;
    }
    start = i;
  }
}

void SearchBySignal(const double* t, const double* s, std::size_t n, const PlateauOptions& o,
                    PlateauSearch* out) {
  // Steadiness of each sample over a centred window: at least steady_min_fraction of the
  // window's samples within +-steady_band of the window median (robust to probe spikes).
  std::vector<char> steady(n, 0);
  std::vector<double> med(n, kNaN);
  std::size_t lo = 0, hi = 0;  // window [lo, hi)
  const double half = 0.5 * o.steady_window_s;
  const std::size_t half_n = o.steady_window_samples_without_time / 2;
  for (std::size_t i = 0; i < n; ++i) {
    if (t != nullptr) {
      while (lo < i && t[i] - t[lo] > half) ++lo;
      if (hi < i + 1) hi = i + 1;
      while (hi < n && t[hi] - t[i] <= half) ++hi;
      // A window cut by the start or end of the log is not evidence of steadiness.
      if (t[i] - t[0] < half || t[n - 1] - t[i] < half) continue;
    } else {
      if (i < half_n || i + half_n >= n) continue;
      lo = i - half_n;
      hi = i + half_n + 1;
    }
    const double m = MedianOf(s, lo, hi);
    if (std::isnan(m)) continue;
    med[i] = m;
    std::size_t cnt = 0, in = 0;
    for (std::size_t k = lo; k < hi; ++k) {
      if (std::isnan(s[k])) continue;
      ++cnt;
      in += Within(s[k], m, o.steady_band);
    }
    steady[i] = cnt >= 2 && static_cast<double>(in) >= o.steady_min_fraction * static_cast<double>(cnt);
  }
  std::size_t i = 0;
  while (i < n) {
    if (!steady[i]) {
      ++out->unsteady_samples;
      ++i;
      continue;
    }
    const std::size_t begin = i;
    const double ref = med[i];
    // A plateau ends where the local median leaves +-steady_band of its first median.
    while (i < n && steady[i] && Within(med[i], ref, o.steady_band)) ++i;
    if (i - begin >= o.min_samples) {
      out->plateaus.push_back({begin, begin, i});
    } else {
      ++out->short_plateaus;
      out->short_plateau_samples += i - begin;
    }
  }
}

}  // namespace

const char* PlateauMethodName(PlateauMethod m) {
  switch (m) {
    case PlateauMethod::kWholeLog: return "whole log";
    case PlateauMethod::kCommandSteps: return "throttle command steps";
    case PlateauMethod::kRampBins: return "throttle ramp bins";
    case PlateauMethod::kSignalSteadiness: return "speed/current steadiness";
  }
  return "?";
}

CommandKind ClassifyCommand(const double* command, std::size_t n, const PlateauOptions& o) {
  if (command == nullptr || n == 0) return CommandKind::kNone;
  if (CommandIsStepped(command, n, o)) return CommandKind::kStepped;
  std::size_t changes = 0, reversals = 0;
  int last_sign = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const double d = command[i] - command[i - 1];
    if (d == 0.0) continue;
    const int sign = d > 0 ? 1 : -1;
    ++changes;
    if (last_sign != 0 && sign != last_sign) ++reversals;
    last_sign = sign;
  }
  if (changes == 0) return CommandKind::kStepped;  // constant: one step
  return static_cast<double>(reversals) <= o.ramp_max_reversal_fraction * static_cast<double>(changes)
             ? CommandKind::kRamp
             : CommandKind::kVarying;
}

namespace {
void SearchByRampBins(const double* c, std::size_t n, const PlateauOptions& o, PlateauSearch* out) {
  std::size_t start = 0;
  auto bin = [&](double x) { return std::floor(x / o.ramp_bin_width + 0.5); };
  for (std::size_t i = 1; i <= n; ++i) {
    if (i < n && bin(c[i]) == bin(c[start])) continue;
    if (i - start >= o.ramp_min_samples) {
      out->plateaus.push_back({start, start, i});
    } else {
      ++out->short_plateaus;
      out->short_plateau_samples += i - start;
    }
    start = i;
  }
}
}  // namespace

PlateauSearch FindPlateaus(const double* time_s, const double* command, const double* signal,
                           std::size_t n, const PlateauOptions& options) {
  PlateauSearch out;
  if (n == 0) return out;
  const CommandKind kind = ClassifyCommand(command, n, options);
  if (kind == CommandKind::kStepped || (kind == CommandKind::kVarying && signal == nullptr)) {
    out.method = PlateauMethod::kCommandSteps;
    SearchByCommand(time_s, command, signal, n, options, &out);
  } else if (kind == CommandKind::kRamp) {
    out.method = PlateauMethod::kRampBins;
    SearchByRampBins(command, n, options, &out);
  } else if (signal != nullptr) {
    out.method = PlateauMethod::kSignalSteadiness;
    SearchBySignal(time_s, signal, n, options, &out);
  } else {
    out.method = PlateauMethod::kWholeLog;
    out.plateaus.push_back({0, 0, n});
  }
  return out;
}

std::size_t MarkOutliers(const std::vector<const double*>& columns, std::size_t begin,
                         std::size_t end, const PlateauOptions& options,
                         std::vector<char>* mask) {
  mask->assign(end - begin, 0);
  thread_local std::vector<double> dev;
  for (const double* x : columns) {
    const double med = MedianOf(x, begin, end);
    if (std::isnan(med)) continue;
    dev.clear();
    for (std::size_t i = begin; i < end; ++i) {
      if (!std::isnan(x[i])) dev.push_back(std::fabs(x[i] - med));
    }
    const double mad = MedianOf(dev.data(), 0, dev.size());
    double scale = kMadToSigma * mad;
    if (scale == 0.0) {
      // More than half the samples equal (quantised probes): the mean absolute deviation,
      // sqrt(pi/2) = 1.2533 of it for a normal sample, still sees the spread.
      double sum = 0.0;
      for (const double d : dev) sum += d;
      scale = 1.2533 * sum / static_cast<double>(dev.size());
    }
    const double sigma = std::max(scale, options.mad_floor_rel * std::fabs(med));
    if (!(sigma > 0.0)) continue;  // all equal (e.g. zero): nothing to reject
    const double limit = options.outlier_mad_k * sigma;
    for (std::size_t i = begin; i < end; ++i) {
      if (!std::isnan(x[i]) && std::fabs(x[i] - med) > limit) (*mask)[i - begin] = 1;
    }
  }
  std::size_t count = 0;
  for (const char m : *mask) count += m != 0;
  return count;
}

}  // namespace dynosize::logs
