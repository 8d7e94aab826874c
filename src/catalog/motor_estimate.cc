#include "catalog/motor_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

#include <Eigen/Core>

#include "common/error.h"
#include "common/units.h"
#include "fit/linear_least_squares.h"
#include "fit/statistics.h"

namespace dynosize {
namespace {

bool Known(double x) { return std::isfinite(x) && x > 0.0; }

void CheckField(const std::string& who, const char* field, double x) {
  if (std::isnan(x) || Known(x)) return;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", x);
  throw UsageError("motor '" + who + "': " + field + " = " + buf +
                   ": a stated value must be finite and > 0 (NaN = not stated)");
}

void CheckStated(const StatedMotor& m) {
  const std::string who = m.maker + " " + m.model;
  CheckField(who, "mass_kg", m.mass_kg);
  CheckField(who, "p_cont_w", m.p_cont_w);
  CheckField(who, "p_peak_w", m.p_peak_w);
  CheckField(who, "t_cont_nm", m.t_cont_nm);
  CheckField(who, "t_peak_nm", m.t_peak_nm);
  CheckField(who, "rpm_max", m.rpm_max);
  CheckField(who, "rpm_rated", m.rpm_rated);
  CheckField(who, "v_nom_v", m.v_nom_v);
  CheckField(who, "v_max_v", m.v_max_v);
  CheckField(who, "kv_rpm_per_v", m.kv_rpm_per_v);
}

// The voltage (E1) divides by: v_nom, else v_max; NaN when neither is stated.
double KvVoltage(const StatedMotor& m) { return Known(m.v_nom_v) ? m.v_nom_v : m.v_max_v; }
const char* KvVoltageName(const StatedMotor& m) { return Known(m.v_nom_v) ? "v_nom" : "v_max"; }

double KvSi(double kv_rpm_per_v) { return kv_rpm_per_v * kRadPerSecPerRpm; }

// ln(true/estimate) of each law for one reference, NaN where the law or the data are missing.
double KvMaxLogRatio(const MotorEstimateCoefficients& c, const ReferenceMotor& r) {
  const double v = KvVoltage(r.stated);
  if (!Known(r.kv_rpm_per_v) || !Known(v) || !Known(r.stated.rpm_max)) return NAN;
  return std::log(r.kv_rpm_per_v / (c.kv_factor_rpm_max * r.stated.rpm_max / v));
}
double KvRatedLogRatio(const MotorEstimateCoefficients& c, const ReferenceMotor& r) {
  const double v = KvVoltage(r.stated);
  if (!Known(r.kv_rpm_per_v) || !Known(v) || !Known(r.stated.rpm_rated)) return NAN;
  return std::log(r.kv_rpm_per_v / (c.kv_factor_rpm_rated * r.stated.rpm_rated / v));
}
double EstimatedRdc(const MotorEstimateCoefficients& c, double mass_kg, double kv_rpm_per_v) {
  const double km = c.km_1kg_nm_per_sqrt_w * std::pow(mass_kg, c.km_mass_exponent);
  const double kv_si = KvSi(kv_rpm_per_v);
  return 1.0 / (kv_si * kv_si * km * km);
}
double EstimatedIodc(const MotorEstimateCoefficients& c, double mass_kg, double kv_rpm_per_v) {
  return c.t0_1kg_nm * std::pow(mass_kg, c.t0_mass_exponent) * KvSi(kv_rpm_per_v);
}
bool UsableForR(const ReferenceMotor& r) {
  return Known(r.kv_rpm_per_v) && Known(r.r_dc_ohm) && Known(r.stated.mass_kg);
}
bool UsableForIo(const ReferenceMotor& r) {
  return Known(r.kv_rpm_per_v) && Known(r.io_dc_a) && Known(r.stated.mass_kg);
}
double RLogRatio(const MotorEstimateCoefficients& c, const ReferenceMotor& r) {
  if (!UsableForR(r)) return NAN;
  return std::log(r.r_dc_ohm / EstimatedRdc(c, r.stated.mass_kg, r.kv_rpm_per_v));
}
double IoLogRatio(const MotorEstimateCoefficients& c, const ReferenceMotor& r) {
  if (!UsableForIo(r)) return NAN;
  return std::log(r.io_dc_a / EstimatedIodc(c, r.stated.mass_kg, r.kv_rpm_per_v));
}

// Fit weights: 1/(rows of the same maker and model).
std::vector<double> FrameWeights(const std::vector<const ReferenceMotor*>& rows) {
  std::map<std::pair<std::string, std::string>, int> count;
  for (const auto* r : rows) ++count[{r->stated.maker, r->stated.model}];
  std::vector<double> w;
  for (const auto* r : rows) w.push_back(1.0 / count[{r->stated.maker, r->stated.model}]);
  return w;
}

// Weighted mean of y (the log of a factor); NaN without rows.
double WeightedMeanLog(const std::vector<const ReferenceMotor*>& rows, const std::vector<double>& y) {
  if (rows.empty()) return NAN;
  const std::vector<double> w = FrameWeights(rows);
  double sw = 0.0, swy = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    sw += w[i];
    swy += w[i] * y[i];
  }
  return std::exp(swy / sw);
}

// Weighted least squares of y = ln(coef) + exponent*ln(mass); NaNs with fewer than two masses.
std::pair<double, double> FitMassPowerLaw(const std::vector<const ReferenceMotor*>& rows,
                                          const std::vector<double>& y) {
  std::set<double> masses;
  for (const auto* r : rows) masses.insert(r->stated.mass_kg);
  if (masses.size() < 2) return {NAN, NAN};
  const std::vector<double> w = FrameWeights(rows);
  const auto n = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd a(n, 2);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double sw = std::sqrt(w[static_cast<std::size_t>(i)]);
    a(i, 0) = sw;
    a(i, 1) = sw * std::log(rows[static_cast<std::size_t>(i)]->stated.mass_kg);
    b(i) = sw * y[static_cast<std::size_t>(i)];
  }
  const LinearLeastSquaresResult fit = SolveLinearLeastSquares(a, b);
  return {std::exp(fit.coefficients(0)), fit.coefficients(1)};
}

// Weighted quantile: values sorted, each at the midpoint of its weight's share (linear between).
double WeightedQuantile(std::vector<std::pair<double, double>> value_weight, double q) {
  if (value_weight.empty()) return NAN;
  std::sort(value_weight.begin(), value_weight.end());
  double total = 0.0;
  for (const auto& vw : value_weight) total += vw.second;
  std::vector<double> pos;
  double cum = 0.0;
  for (const auto& vw : value_weight) {
    pos.push_back((cum + 0.5 * vw.second) / total);
    cum += vw.second;
  }
  if (q <= pos.front()) return value_weight.front().first;
  if (q >= pos.back()) return value_weight.back().first;
  std::size_t k = 1;
  while (pos[k] < q) ++k;
  const double t = (q - pos[k - 1]) / (pos[k] - pos[k - 1]);
  return value_weight[k - 1].first + t * (value_weight[k].first - value_weight[k - 1].first);
}

// Held-out log ratios of one law, with their makers.
struct HeldOut {
  std::vector<std::string> maker;
  std::vector<double> log_ratio;
  void Add(const std::string& m, double x) {
    if (std::isnan(x)) return;
    maker.push_back(m);
    log_ratio.push_back(x);
  }
};

// Pooled range with every maker weighing alike; fills support and returns the coverage.
double PooledRange(const HeldOut& h, LawSupport* s) {
  std::map<std::string, int> per_maker;
  for (const auto& m : h.maker) ++per_maker[m];
  std::vector<std::pair<double, double>> vw;
  for (std::size_t i = 0; i < h.maker.size(); ++i) vw.push_back({h.log_ratio[i], 1.0 / per_maker[h.maker[i]]});
  s->motors = static_cast<int>(h.maker.size());
  s->makers = static_cast<int>(per_maker.size());
  // A range needs at least two makers: one maker's hold-out says nothing of another's.
  if (per_maker.size() < 2) return NAN;
  const double lo = WeightedQuantile(vw, 0.1), hi = WeightedQuantile(vw, 0.9);
  s->ratio_p10 = std::exp(lo);
  s->ratio_p90 = std::exp(hi);
  int inside = 0;
  for (double x : h.log_ratio) inside += (x >= lo && x <= hi) ? 1 : 0;
  return static_cast<double>(inside) / static_cast<double>(h.log_ratio.size());
}

// Per-maker statistics of one law: n, median |estimate/true - 1|, median ratio, coverage.
void MakerStats(const HeldOut& h, const std::string& maker, const LawSupport& s, int* n,
                double* median_abs_error, double* median_ratio, double* coverage) {
  std::vector<double> err, ratio;
  int inside = 0;
  for (std::size_t i = 0; i < h.maker.size(); ++i) {
    if (h.maker[i] != maker) continue;
    const double x = h.log_ratio[i];
    err.push_back(std::fabs(std::exp(-x) - 1.0));
    ratio.push_back(std::exp(x));
    if (Known(s.ratio_p10) && x >= std::log(s.ratio_p10) && x <= std::log(s.ratio_p90)) ++inside;
  }
  *n = static_cast<int>(err.size());
  if (err.empty()) return;
  *median_abs_error = fit::Median(err);
  *median_ratio = fit::Median(ratio);
  if (Known(s.ratio_p10)) *coverage = static_cast<double>(inside) / static_cast<double>(err.size());
}

std::string Fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

// " (law fitted on N motors of M makers, leave-one-maker-out p10-p90 x0.80-1.21)"
std::string SupportText(const LawSupport& fitted, const LawSupport& range) {
  return " (law fitted on " + std::to_string(fitted.motors) + " motors of " +
         std::to_string(fitted.makers) + " makers, leave-one-maker-out p10-p90 x" +
         Fmt("%.2f", range.ratio_p10) + "-" + Fmt("%.2f", range.ratio_p90) + ")";
}

}  // namespace

MotorEstimateCoefficients FitMotorEstimateCoefficients(const std::vector<ReferenceMotor>& refs) {
  for (const auto& r : refs) CheckStated(r.stated);
  MotorEstimateCoefficients c;
  MotorEstimateCoefficients unit;  // factors 1: the log ratio is then ln(Kv*V/rpm)
  unit.kv_factor_rpm_max = unit.kv_factor_rpm_rated = 1.0;
  std::vector<const ReferenceMotor*> kv_max, kv_rated, r_rows, io_rows;
  std::vector<double> y_max, y_rated, y_km, y_t0;
  for (const auto& r : refs) {
    const double lmax = KvMaxLogRatio(unit, r), lrated = KvRatedLogRatio(unit, r);
    if (!std::isnan(lmax)) { kv_max.push_back(&r); y_max.push_back(lmax); }
    if (!std::isnan(lrated)) { kv_rated.push_back(&r); y_rated.push_back(lrated); }
    if (UsableForR(r)) {
      r_rows.push_back(&r);
      y_km.push_back(std::log(1.0 / (KvSi(r.kv_rpm_per_v) * std::sqrt(r.r_dc_ohm))));
    }
    if (UsableForIo(r)) {
      io_rows.push_back(&r);
      y_t0.push_back(std::log(r.io_dc_a / KvSi(r.kv_rpm_per_v)));
    }
  }
  c.kv_factor_rpm_max = WeightedMeanLog(kv_max, y_max);
  c.kv_factor_rpm_rated = WeightedMeanLog(kv_rated, y_rated);
  std::tie(c.km_1kg_nm_per_sqrt_w, c.km_mass_exponent) = FitMassPowerLaw(r_rows, y_km);
  std::tie(c.t0_1kg_nm, c.t0_mass_exponent) = FitMassPowerLaw(io_rows, y_t0);
  return c;
}

LeaveOneMakerOutTable LeaveOneMakerOut(const std::vector<ReferenceMotor>& refs) {
  std::set<std::string> makers;
  for (const auto& r : refs) makers.insert(r.stated.maker);
  HeldOut kv_max, kv_rated, r_out, io_out;
  for (const auto& maker : makers) {
    std::vector<ReferenceMotor> train;
    for (const auto& r : refs) if (r.stated.maker != maker) train.push_back(r);
    const MotorEstimateCoefficients c = FitMotorEstimateCoefficients(train);
    for (const auto& r : refs) {
      if (r.stated.maker != maker) continue;
      kv_max.Add(maker, KvMaxLogRatio(c, r));
      kv_rated.Add(maker, KvRatedLogRatio(c, r));
      r_out.Add(maker, RLogRatio(c, r));
      io_out.Add(maker, IoLogRatio(c, r));
    }
  }
  LeaveOneMakerOutTable t;
  t.kv_max_coverage = PooledRange(kv_max, &t.kv_max);
  t.kv_rated_coverage = PooledRange(kv_rated, &t.kv_rated);
  t.r_coverage = PooledRange(r_out, &t.r);
  t.io_coverage = PooledRange(io_out, &t.io);
  for (const auto& maker : makers) {
    MakerHoldOut m;
    m.maker = maker;
    MakerStats(kv_max, maker, t.kv_max, &m.kv_max_n, &m.kv_max_median_abs_error,
               &m.kv_max_median_ratio, &m.kv_max_coverage);
    MakerStats(kv_rated, maker, t.kv_rated, &m.kv_rated_n, &m.kv_rated_median_abs_error,
               &m.kv_rated_median_ratio, &m.kv_rated_coverage);
    MakerStats(r_out, maker, t.r, &m.r_n, &m.r_median_abs_error, &m.r_median_ratio, &m.r_coverage);
    MakerStats(io_out, maker, t.io, &m.io_n, &m.io_median_abs_error, &m.io_median_ratio,
               &m.io_coverage);
    if (m.kv_max_n + m.kv_rated_n + m.r_n + m.io_n > 0) t.makers.push_back(m);
  }
  return t;
}

MotorEstimateLaw MotorEstimateLaw::Fit(const std::vector<ReferenceMotor>& refs) {
  MotorEstimateLaw law;
  law.coef_ = FitMotorEstimateCoefficients(refs);
  const LeaveOneMakerOutTable t = LeaveOneMakerOut(refs);
  law.kv_max_ = t.kv_max;
  law.kv_rated_ = t.kv_rated;
  law.r_ = t.r;
  law.io_ = t.io;
  // Counts and mass ranges of the fit itself (the table's counts are held-out motors, the same
  // motors: every usable row is held out once).
  for (LawSupport* s : {&law.r_, &law.io_}) {
    s->mass_min_kg = INFINITY;
    s->mass_max_kg = 0.0;
  }
  for (const auto& r : refs) {
    if (UsableForR(r)) {
      law.r_.mass_min_kg = std::min(law.r_.mass_min_kg, r.stated.mass_kg);
      law.r_.mass_max_kg = std::max(law.r_.mass_max_kg, r.stated.mass_kg);
    }
    if (UsableForIo(r)) {
      law.io_.mass_min_kg = std::min(law.io_.mass_min_kg, r.stated.mass_kg);
      law.io_.mass_max_kg = std::max(law.io_.mass_max_kg, r.stated.mass_kg);
    }
  }
  return law;
}

namespace {

// The range of a value computed from an estimated Kv: log half-widths added in quadrature,
// `kv_power` the exponent of Kv in the value (R: -2, Io: +1).
void WidenByKv(const EstimatedValue& kv, double kv_power, EstimatedValue* v) {
  if (kv.stated) return;
  const double kv_lo = std::log(kv.p10 / kv.value), kv_hi = std::log(kv.p90 / kv.value);
  // With a negative power the low end of Kv moves the value up.
  const double from_kv_lo = kv_power > 0 ? kv_power * kv_lo : kv_power * kv_hi;
  const double from_kv_hi = kv_power > 0 ? kv_power * kv_hi : kv_power * kv_lo;
  const double lo = std::log(v->p10 / v->value), hi = std::log(v->p90 / v->value);
  v->p10 = v->value * std::exp(-std::hypot(lo, from_kv_lo));
  v->p90 = v->value * std::exp(std::hypot(hi, from_kv_hi));
  v->how += "; range widened by the estimated Kv's";
}

EstimatedValue EstimateKv(const MotorEstimateCoefficients& c, const LawSupport& max_s,
                          const LawSupport& rated_s, const StatedMotor& m) {
  EstimatedValue kv;
  if (Known(m.kv_rpm_per_v)) {
    kv.known = kv.stated = true;
    kv.value = kv.p10 = kv.p90 = m.kv_rpm_per_v;
    kv.how = "Kv stated";
    return kv;
  }
  const double v = KvVoltage(m);
  const bool use_max = Known(m.rpm_max);
  const double rpm = use_max ? m.rpm_max : m.rpm_rated;
  const double factor = use_max ? c.kv_factor_rpm_max : c.kv_factor_rpm_rated;
  const LawSupport& s = use_max ? max_s : rated_s;
  if (!Known(v) || !Known(rpm)) {
    kv.how = "Kv: needs a speed (rpm_max or rpm_rated) and a DC voltage (v_nom or v_max); "
             "stated: " + std::string(Known(rpm) ? "a speed" : "no speed") + ", " +
             (Known(v) ? "a voltage" : "no voltage");
    return kv;
  }
  if (!Known(factor) || !Known(s.ratio_p10)) {
    kv.how = std::string("Kv: the law of ") + (use_max ? "rpm_max" : "rpm_rated") +
             " has no references of two makers";
    return kv;
  }
  kv.known = true;
  kv.value = factor * rpm / v;
  kv.p10 = kv.value * s.ratio_p10;
  kv.p90 = kv.value * s.ratio_p90;
  kv.how = "Kv = " + Fmt("%.3g", factor) + "*" + (use_max ? "rpm_max/" : "rpm_rated/") +
           KvVoltageName(m) + SupportText(s, s);
  return kv;
}

std::string MassNote(const LawSupport& s, double mass_kg) {
  if (mass_kg >= s.mass_min_kg && mass_kg <= s.mass_max_kg) return "";
  return "; mass " + Fmt("%.3g", mass_kg) + " kg outside the fitted " + Fmt("%.3g", s.mass_min_kg) +
         "-" + Fmt("%.3g", s.mass_max_kg) + " kg: extrapolated";
}

}  // namespace

MotorConstantsEstimate MotorEstimateLaw::Estimate(const StatedMotor& m) const {
  CheckStated(m);
  MotorConstantsEstimate e;
  e.kv_rpm_per_v = EstimateKv(coef_, kv_max_, kv_rated_, m);
  const EstimatedValue& kv = e.kv_rpm_per_v;
  struct Target {
    EstimatedValue* out;
    const char* name;
    const LawSupport* s;
    bool law_known;
  };
  const Target targets[] = {
      {&e.r_dc_ohm, "R_dc", &r_, Known(coef_.km_1kg_nm_per_sqrt_w) && Known(r_.ratio_p10)},
      {&e.io_dc_a, "Io_dc", &io_, Known(coef_.t0_1kg_nm) && Known(io_.ratio_p10)}};
  for (const Target& t : targets) {
    const std::string name = t.name;
    if (!Known(m.mass_kg) || !kv.known) {
      t.out->how = name + ": needs the mass and Kv; " +
                   (Known(m.mass_kg) ? "" : "mass not stated") +
                   (Known(m.mass_kg) || kv.known ? "" : ", ") + (kv.known ? "" : "Kv not known");
      continue;
    }
    if (!t.law_known) {
      t.out->how = name + ": the law has no references of two makers";
      continue;
    }
    const bool is_r = t.out == &e.r_dc_ohm;
    t.out->known = true;
    t.out->value = is_r ? EstimatedRdc(coef_, m.mass_kg, kv.value) : EstimatedIodc(coef_, m.mass_kg, kv.value);
    t.out->p10 = t.out->value * t.s->ratio_p10;
    t.out->p90 = t.out->value * t.s->ratio_p90;
    t.out->how = is_r ? "R_dc = (Kt/Km)^2, Kt = 30/(pi*Kv), Km = " +
                            Fmt("%.4g", coef_.km_1kg_nm_per_sqrt_w) + "*m^" +
                            Fmt("%.3f", coef_.km_mass_exponent) + " N m/sqrt(W)"
                      : "Io_dc = T0*Kv*pi/30 at 10 V, T0 = " + Fmt("%.4g", coef_.t0_1kg_nm) +
                            "*m^" + Fmt("%.3f", coef_.t0_mass_exponent) + " N m";
    t.out->how += SupportText(*t.s, *t.s) + MassNote(*t.s, m.mass_kg);
    WidenByKv(kv, is_r ? -2.0 : 1.0, t.out);
  }
  for (const EstimatedValue* v : {&e.kv_rpm_per_v, &e.r_dc_ohm, &e.io_dc_a}) {
    if (!v->known) e.not_estimated.push_back(v->how);
  }
  return e;
}

std::string MotorConstantsEstimate::FullReport() const {
  std::string out;
  const std::pair<const char*, const EstimatedValue*> rows[] = {
      {"Kv [rpm/V]", &kv_rpm_per_v}, {"R_dc [ohm]", &r_dc_ohm}, {"Io_dc [A]", &io_dc_a}};
  for (const auto& [name, v] : rows) {
    out += std::string(name) + ": ";
    if (v->known) {
      out += Fmt("%.4g", v->value) + " (p10-p90 " + Fmt("%.4g", v->p10) + "-" + Fmt("%.4g", v->p90) +
             "); " + v->how + "\n";
    } else {
      out += "not estimated; " + v->how + "\n";
    }
  }
  return out;
}

std::string MotorEstimateLaw::Describe() const {
  const auto& c = coef_;
  return "Kv = " + Fmt("%.4g", c.kv_factor_rpm_max) + "*rpm_max/V" + SupportText(kv_max_, kv_max_) +
         "\nKv = " + Fmt("%.4g", c.kv_factor_rpm_rated) + "*rpm_rated/V" +
         SupportText(kv_rated_, kv_rated_) + "\nKm = " + Fmt("%.4g", c.km_1kg_nm_per_sqrt_w) +
         "*(m/1 kg)^" + Fmt("%.4f", c.km_mass_exponent) + " N m/sqrt(W)" + SupportText(r_, r_) +
         "\nT0 = " + Fmt("%.4g", c.t0_1kg_nm) + "*(m/1 kg)^" + Fmt("%.4f", c.t0_mass_exponent) +
         " N m" + SupportText(io_, io_) + "\n";
}

std::string LeaveOneMakerOutTable::FullReport() const {
  auto cell = [](int n, double err, double ratio, double cov) {
    if (n == 0) return std::string("-");
    return std::to_string(n) + ": " + Fmt("%.0f", 100.0 * err) + " %, x" + Fmt("%.2f", ratio) +
           (std::isnan(cov) ? std::string() : ", " + Fmt("%.0f", 100.0 * cov) + " % in");
  };
  std::string out =
      "| held-out maker | Kv from rpm_max | Kv from rpm_rated | R_dc | Io_dc |\n"
      "|---|---|---|---|---|\n";
  for (const auto& m : makers) {
    out += "| " + m.maker + " | " +
           cell(m.kv_max_n, m.kv_max_median_abs_error, m.kv_max_median_ratio, m.kv_max_coverage) +
           " | " +
           cell(m.kv_rated_n, m.kv_rated_median_abs_error, m.kv_rated_median_ratio, m.kv_rated_coverage) +
           " | " + cell(m.r_n, m.r_median_abs_error, m.r_median_ratio, m.r_coverage) + " | " +
           cell(m.io_n, m.io_median_abs_error, m.io_median_ratio, m.io_coverage) + " |\n";
  }
  auto pooled = [](const LawSupport& s, double cov) {
    if (std::isnan(cov)) return std::to_string(s.motors) + " motors, " + std::to_string(s.makers) + " makers: no range";
    return "x" + Fmt("%.2f", s.ratio_p10) + "-" + Fmt("%.2f", s.ratio_p90) + ", " +
           Fmt("%.0f", 100.0 * cov) + " % of " + std::to_string(s.motors) + " in";
  };
  out += "| p10-p90 of true/estimate, coverage | " + pooled(kv_max, kv_max_coverage) + " | " +
         pooled(kv_rated, kv_rated_coverage) + " | " + pooled(r, r_coverage) + " | " +
         pooled(io, io_coverage) + " |\n";
  return out;
}

}  // namespace dynosize
