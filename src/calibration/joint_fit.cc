#include "calibration/joint_fit.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "fit/statistics.h"
#include "identification/knee_profile.h"

namespace dynosize::calibration::internal {

using fit::Median;
using logs::SteadyTable;

namespace {

// Gaussian priors on the free slot s holding parameter k: the label (--kv-label, --rm-label,
// --io-label) where given, else the motor prior, with the widths of identification/parameters.h
// and CalibrationOptions.
void AddPriors(const CalibrationOptions& o, int k, int s, std::vector<GaussianPrior>* priors) {
  auto add = [&](double mean, double rel) {
    if (mean > 0.0 && rel > 0.0) priors->push_back({s, mean, rel * mean});
  };
  const auto& lb = o.labels;
  const MotorParams* mp = o.motor_prior ? &*o.motor_prior : nullptr;
  if (k == kKeI) {
    if (lb.kv_rpm_per_v) add(identification::KeFromLabelKv(*lb.kv_rpm_per_v), identification::kKvLabelRelSigma);
    else if (mp) add(mp->ke_v_s_per_rad, o.prior_ke_rel_sigma);
  }
  if (k == static_cast<int>(Param::kRm)) {
    if (lb.rm_ohm) add(*lb.rm_ohm, identification::kRmLabelRelSigma);
    else if (mp) add(mp->rm_ohm, o.prior_rm_rel_sigma);
  }
  if (k == static_cast<int>(Param::kIo)) {
    if (lb.io_a) add(identification::IoFromLabel(*lb.io_a), identification::kIoLabelRelSigma);
    else if (mp) add(mp->io_a, o.prior_io_rel_sigma);
  }
}

SolveOutcome SolveOnce(const Prepared& pr, const CalibrationOptions& o, double tr_sat, bool free_slope,
                       bool free_offset, const std::array<double, kBaseParamCount>& start) {
  Layout lay = pr.layout;
  lay.free[static_cast<int>(Param::kSatSlope)] = free_slope;
  lay.free[kDbI] = free_offset;
  lay.free_index.clear();
  for (int k = 0; k < kBaseParamCount; ++k) {
    if (lay.free[k]) lay.free_index.push_back(k);
  }
  std::array<double, kBaseParamCount> fixed = start;
  fixed[static_cast<int>(Param::kTrSat)] = tr_sat;
  if (!free_slope) fixed[static_cast<int>(Param::kSatSlope)] = 1.0;
  const int nf = static_cast<int>(lay.free_index.size());
  LeastSquaresProblem prob;
  prob.num_residuals = static_cast<int>(pr.data.terms.size());
  prob.num_parameters = nf;
  prob.residuals = MakeResidualFunction(pr.data, lay, fixed);
  prob.lower_bounds.resize(nf);
  prob.upper_bounds.resize(nf);
  Eigen::VectorXd x(nf);
  for (int s = 0; s < nf; ++s) {
    const int k = lay.free_index[s];
    prob.parameter_names.push_back(ParamName(static_cast<Param>(k)));
    prob.lower_bounds[s] = kLower[k];
    prob.upper_bounds[s] = kUpper[k];
    if (k == kDbI) prob.upper_bounds[s] = pr.offset_upper;
    x[s] = std::clamp(start[k], prob.lower_bounds[s], prob.upper_bounds[s]);
    AddPriors(o, k, s, &prob.priors);
  }
  LevenbergMarquardtOptions lo = o.solver;
  lo.loss = o.loss;
  lo.loss_scale = o.loss_scale_percent;
  SolveOutcome out;
  out.free_count = nf;
  out.summary = SolveLeastSquares(prob, lo, &x);
  out.params = fixed;
  for (int s = 0; s < nf; ++s) out.params[lay.free_index[s]] = x[s];
  out.cost = out.summary.IsSolutionUsable() ? out.summary.final_cost : std::numeric_limits<double>::infinity();
  return out;
}

// Calibrate's knee grid: knee_min, knee_min + knee_step, ... below 1, each with at least 2
// throttle levels on either side. A regular grid (not diagnose's midpoints between levels,
// diagnosis/candidates.h KneeGrid) because calibrate reports tr_sat at the grid's resolution
// (standard error knee_step/sqrt(12)) and keeps it by one F test, with no correction for the
// number of knees tried; the user sets the resolution (knee_step).
std::vector<double> KneeGrid(const Prepared& pr, const CalibrationOptions& o) {
  std::vector<double> grid;
  for (double ts = o.knee_min; ts < 1.0 - 1e-9; ts += o.knee_step) {
    int above = 0, below = 0;
    for (double lv : pr.levels) (lv > ts + 1e-9 ? above : below)++;
    if (above < 2 || below < 2) continue;
    grid.push_back(ts);
  }
  return grid;
}

// Best fit over the knee candidates (identification/knee_profile.h) and "no knee"; returns the
// chosen outcome.
SolveOutcome FitWithKnee(const Prepared& pr, const CalibrationOptions& o, bool free_offset, bool* knee_found,
                         std::string* knee_note) {
  SolveOutcome best = SolveOnce(pr, o, 1.0, false, free_offset, pr.start);
  *knee_found = false;
  if (!pr.has_throttle) {
    *knee_note = "no throttle column";
    return best;
  }
  const SolveOutcome none = best;
  const std::vector<double> grid = KneeGrid(pr, o);
  std::array<double, kBaseParamCount> start = none.params;
  start[static_cast<int>(Param::kSatSlope)] = 0.8;
  const auto fit_at = [&](double ts, std::size_t) { return SolveOnce(pr, o, ts, true, free_offset, start); };
  const auto cost_of = [](const SolveOutcome& s) { return s.cost; };
  const SolveOutcome knee = identification::ProfileKnee<SolveOutcome>(grid, fit_at, cost_of).best_fit;
  if (grid.empty()) {
    *knee_note = "fewer than 2 throttle levels on either side of every knee candidate (" +
                 std::to_string(pr.levels.size()) + " levels)";
    return best;
  }
  const double m = static_cast<double>(pr.data.terms.size());
  const double dof = m - knee.free_count - 1.0;
  if (dof <= 0.0 || !std::isfinite(knee.cost)) {
    *knee_note = "no degrees of freedom for a knee";
    return best;
  }
  const double f = ((none.cost - knee.cost) / 2.0) / (std::max(knee.cost, 1e-300) / dof);
  if (f > o.knee_min_f && knee.params[static_cast<int>(Param::kSatSlope)] < 0.97) {
    *knee_found = true;
    std::ostringstream s;
    s << "profile over tr_sat (grid " << o.knee_step << "), F = " << std::setprecision(3) << f;
    *knee_note = s.str();
    return knee;
  }
  std::ostringstream s;
  s << "no knee found: best candidate tr_sat = " << knee.params[static_cast<int>(Param::kTrSat)]
    << " improves the fit by F = " << std::setprecision(3) << f << " <= " << o.knee_min_f;
  *knee_note = s.str();
  return best;
}

}  // namespace

std::vector<double> RowResidualMax(const Prepared& pr, const std::array<double, kBaseParamCount>& p) {
  const FitData& d = pr.data;
  std::vector<double> out(d.rows(), 0.0);
  double pred[kMeasCount];
  double qp;
  for (std::size_t k = 0; k < d.rows(); ++k) {
    if (!PredictGeneric(p.data(), p[7], d.vdc[k], d.tr[k], d.omega[k], d.q[k], d.torque_known[k] != 0,
                        pred, &qp, d.idc_in[k])) {
      continue;
    }
    for (int t = d.term_begin[k]; t < d.term_begin[k + 1]; ++t) {
      const Term& term = d.terms[t];
      out[k] = std::max(out[k], std::fabs(TermResidual(term, pred)));
    }
  }
  return out;
}

// "" when the free ESC slots (excess s, c0) of a solve are determined, else why not: a slot on
// its bound, or a standard error above half of c0 or of c1 = 1.1095 + s - c0.
std::string EscUndetermined(const LevenbergMarquardtSummary& s) {
  double ex = kNaN, c0 = kNaN, se_ex = kNaN, se_c0 = kNaN;
  for (std::size_t j = 0; j < s.parameter_names.size(); ++j) {
    const bool c1slot = s.parameter_names[j] == "c1", c0slot = s.parameter_names[j] == "c0";
    if (!c1slot && !c0slot) continue;
    if (j < s.at_bound.size() && s.at_bound[j]) return std::string(c1slot ? "c1 + c0" : "c0") + " on its bound";
    const double se = j < static_cast<std::size_t>(s.standard_errors.size()) ? s.standard_errors[j] : kNaN;
    (c1slot ? ex : c0) = s.parameters[j];
    (c1slot ? se_ex : se_c0) = se;
  }
  std::ostringstream w;
  w << std::setprecision(2);
  if (!(se_c0 <= 0.5 * std::fabs(c0))) {
    w << "c0 = " << c0 << " +- " << se_c0;
    return w.str();
  }
  const double c1 = C1FromExcess(ex, c0);
  if (!(se_ex <= 0.5 * std::fabs(c1))) {
    w << "c1 = " << c1 << " +- " << se_ex;
    return w.str();
  }
  return "";
}

// True when parameter k carries a Gaussian prior in the fit (AddPriors).
bool HasPrior(const CalibrationOptions& o, int k) {
  std::vector<GaussianPrior> pr;
  AddPriors(o, k, 0, &pr);
  return !pr.empty();
}

// The base fit (FitWithKnee), and with three or more throttle levels the same with the throttle
// offset / dead band free; the offset is kept when it lowers the cost by an F statistic above
// knee_min_f for its one extra parameter.
SolveOutcome FitWithOffset(const Prepared& pr, const CalibrationOptions& o, bool* knee_found, std::string* knee_note,
                           bool* offset_found, std::string* offset_note, OffsetFreeFit* offset_free) {
  SolveOutcome none = FitWithKnee(pr, o, false, knee_found, knee_note);
  if (offset_free != nullptr) *offset_free = {none, *knee_found, *knee_note};
  *offset_found = false;
  if (!o.fit_throttle_offset || !pr.has_throttle || pr.levels.size() < 3) {
    *offset_note = !o.fit_throttle_offset ? kOffsetNotTestedNote
                                          : "not testable: fewer than 3 throttle levels";
    return none;
  }
  // The offset enters nonlinearly (a dead band clips at zero): a few starts, the best kept.
  bool kf = false;
  std::string kn;
  SolveOutcome with;
  for (double db0 : {pr.start[kDbI], -0.1, -0.3}) {
    Prepared p2 = pr;
    p2.start[kDbI] = std::clamp(db0, kLower[kDbI], pr.offset_upper);
    bool kf2 = false;
    std::string kn2;
    SolveOutcome w = FitWithKnee(p2, o, true, &kf2, &kn2);
    if (w.cost < with.cost) {
      with = std::move(w);
      kf = kf2;
      kn = kn2;
    }
  }
  const double dof = static_cast<double>(pr.data.terms.size()) - with.free_count;
  if (!std::isfinite(with.cost) || dof <= 0.0) {
    *offset_note = "offset fit failed or has no degrees of freedom";
    return none;
  }
  const double f = (none.cost - with.cost) / (std::max(with.cost, 1e-300) / dof);
  std::ostringstream s;
  s << std::setprecision(3);
  if (f > o.knee_min_f || !std::isfinite(none.cost)) {
    *offset_found = true;
    *knee_found = kf;
    *knee_note = kn;
    s << "throttle offset/dead band fitted: F = " << f << " > " << o.knee_min_f;
    *offset_note = s.str();
    return with;
  }
  s << "no throttle offset: F = " << f << " <= " << o.knee_min_f;
  *offset_note = s.str();
  return none;
}

// Rows whose largest residual exceeds outlier_sigmas robust standard deviations, worst first,
// at most max_outlier_fraction of the rows, never the last row of a throttle level, and only when
// (free + 2) rows stay.
std::vector<DroppedRow> SelectOutliers(const Prepared& pr, const std::array<double, kBaseParamCount>& p,
                                       const SteadyTable& t, const CalibrationOptions& o, int nfree) {
  const std::vector<double> rmax = RowResidualMax(pr, p);
  const double sigma = std::max(1.4826 * Median(rmax), o.outlier_floor_percent);
  const identification::OutlierSelection sel =
      identification::SelectOutlierRows(rmax, pr.data.tr, pr.has_throttle, o.outlier_sigmas * sigma,
                                        o.max_outlier_fraction, static_cast<std::size_t>(nfree) + 3);
  std::vector<DroppedRow> out;
  out.reserve(sel.dropped.size());
  for (std::size_t k : sel.dropped) {
    const std::size_t row = pr.data.table_row[k];
    std::ostringstream why;
    why << std::setprecision(3) << "outlier: largest residual " << rmax[k] << " % > " << o.outlier_sigmas
        << " robust sd (" << sigma << " %)";
    out.push_back({row, row < t.source_line.size() ? t.source_line[row] : 0, why.str()});
  }
  return out;
}

// Standard errors and values of the physical KT and C1 from the internal ratio f and excess s
// (delta method on the covariance): KT = kp*KE*f, c1 = 1.1095 + s - c0.
void TransformStandardErrors(bool tie_kt, const std::vector<int>& slots, const LevenbergMarquardtSummary& s,
                             CalibrationResult* res) {
  auto slot_of = [&](int k) {
    for (std::size_t q = 0; q < slots.size(); ++q) {
      if (slots[q] == k) return static_cast<int>(q);
    }
    return -1;
  };
  const bool cov_ok = s.covariance.rows() == static_cast<Eigen::Index>(slots.size());
  auto cov = [&](int a, int b) { return (a < 0 || b < 0 || !cov_ok) ? 0.0 : s.covariance(a, b); };
  auto& kt = res->params[kKtI];
  const double ke = res->motor.ke_v_s_per_rad, f = kt.value;
  kt.value = res->motor.kt_nm_per_a;
  if (!tie_kt && kt.fitted) {
    const int a = slot_of(kKeI), b = slot_of(kKtI);
    const double var = kPacPerVllIrms * kPacPerVllIrms * (f * f * cov(a, a) + ke * ke * cov(b, b) + 2.0 * ke * f * cov(a, b));
    kt.standard_error = cov_ok && b >= 0 ? std::sqrt(std::max(var, 0.0)) : kNaN;
  }
  auto& c1 = res->params[kC1I];
  c1.value = res->esc.c1;
  if (c1.fitted) {
    const int a = slot_of(kC1I), b = slot_of(kC0I);
    const double var = cov(a, a) + cov(b, b) - 2.0 * cov(a, b);
    c1.standard_error = cov_ok && a >= 0 ? std::sqrt(std::max(var, 0.0)) : kNaN;
  }
}
}  // namespace dynosize::calibration::internal
