// Diagnose(): the stages in order (model_fit.h lists them), the verdict of the extended model and
// calibrate's entry where its model holds every finding.
#include "diagnosis/diagnose.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "common/error.h"
#include "diagnosis/baseline.h"
#include "diagnosis/candidates.h"
#include "diagnosis/model_fit.h"
#include "diagnosis/prepare.h"
#include "fit/option_check.h"

namespace dynosize::diagnosis {

bool DiagnoseOptions::IsValid(std::string* error) const {
  const fit::OptionCheck check("DiagnoseOptions", error);
  if (folds < 2) return check.Fail("folds", folds, "must be >= 2");
  if (!(alpha > 0.0 && alpha < 1.0)) return check.Fail("alpha", alpha, "must be in (0, 1)");
  if (!(min_gain_percent >= 0.0)) return check.Fail("min_gain_percent", min_gain_percent, "must be >= 0");
  if (!(outlier_sigmas >= 0.0)) return check.Fail("outlier_sigmas", outlier_sigmas, "must be >= 0");
  if (max_findings < 0) return check.Fail("max_findings", max_findings, "must be >= 0");
  if (!(assumed_throttle > 0.0 && assumed_throttle <= 1.0)) {
    return check.Fail("assumed_throttle", assumed_throttle, "must be in (0, 1]");
  }
  return true;
}

namespace internal {
namespace {

using fit::Median;
using logs::Column;
using logs::SteadyTable;

// The status contract (identification/verdict.h) of the extended model: its free parameters
// (base and findings) on a bound or undetermined, the energy rules over the envelope, the label,
// and the held-out current error of the final model's cross-validation.
identification::Verdict JudgeExtended(const Data& d, const SteadyTable& t, const Model& m, const FitOut& fit,
                                      const std::vector<std::size_t>& used, const CvOut& cv,
                                      const DiagnoseResult& res, const DiagnoseOptions& o) {
  identification::VerdictInputs in;
  in.converged = fit.ok;
  for (int s = 0; s < kSlotCount; ++s) {
    if (!m.free[s]) continue;
    identification::ParamState p;
    p.name = SlotName(s);
    p.value = fit.values[s];
    p.standard_error = fit.stderr_[s];
    p.fitted = true;
    p.identifiable = std::isfinite(fit.stderr_[s]);
    // A knee slope of 0 (no voltage gain above the knee) is a physical value, not a clip.
    p.at_bound = s != kSatSlope && SlotAtBound(m, fit.values, s);
    in.params.push_back(p);
  }
  in.motor = res.extended_motor;
  in.esc = res.extended_esc;
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (std::size_t k : used) {
    lo = std::min(lo, d.vdc[k]);
    hi = std::max(hi, d.vdc[k]);
  }
  in.envelope.vdc_min_v = std::isfinite(lo) ? lo : 0.0;
  in.envelope.vdc_max_v = hi;
  in.kv_label_rpm_per_v = o.kv_label_rpm_per_v;
  if (o.kv_label_rpm_per_v) in.torque_per_ampere_vs_label = identification::TorquePerAmpereVsLabel(t, *o.kv_label_rpm_per_v);
  identification::HeldOut h;
  h.folds = static_cast<std::size_t>(res.cv_folds);
  h.failed_folds = static_cast<std::size_t>(cv.failed_folds);
  h.leave_one_out = res.leave_one_out;
  std::vector<double> ei, ew;
  for (std::size_t k : used) {
    for (int tt = d.term_begin[k]; tt < d.term_begin[k + 1]; ++tt) {
      const Term& term = d.terms[tt];
      const double p = cv.pred[term.meas][k];
      if (term.value == 0.0) continue;
      // A row without a prediction is a 100 % miss.
      const double e = std::isfinite(p) ? 100.0 * std::fabs(p - term.value) / std::fabs(term.value) : 100.0;
      if (term.meas == kMIdc || (term.meas == kMIrms && !d.measured[kMIdc])) ei.push_back(e);
      if (term.meas == kMOmega) ew.push_back(e);
    }
  }
  h.median_abs_current_percent = Median(ei);
  h.median_abs_speed_percent = Median(ew);
  h.rms_percent = cv.rms_percent;
  h.first_order_rms_percent = res.baseline_cv_rms_percent;
  in.held_out = h;
  in.has_torque = t.Has(Column::kTorqueNm);
  in.has_ac = t.Has(Column::kVllRmsV) && t.Has(Column::kIrmsA);
  in.has_throttle = t.Has(Column::kThrottle);
  in.pulse_min_us = t.throttle_pulse_min_us;
  in.pulse_max_us = t.throttle_pulse_max_us;
  return identification::Judge(in);
}

// Stage 10: the extended model into res: parameters, ratings from the catalog entries, its
// cross-validation, warnings and the status contract.
void AssembleResult(const SteadyTable& t, const DiagnoseOptions& o, const Data& d,
                    const std::vector<std::size_t>& used, const Folds& folds, const Step& cur,
                    DiagnoseResult* res) {
  ToParams(d, cur.fit.values, &res->extended_motor, &res->extended_esc);
  if (!res->findings.empty() && BaseAtBound(cur.model, cur.fit.values)) {
    res->warnings.push_back("the extended model still has a base parameter on a physical bound: its "
                            "values describe this log, they are not physical motor constants");
  }
  // Ratings and held values from the catalog entries.
  if (o.motor) {
    res->extended_motor.max_current_a = o.motor->max_current_a;
    res->extended_motor.max_power_w = o.motor->max_power_w;
  }
  if (o.esc) {
    res->extended_esc.max_current_a = o.esc->max_current_a;
    res->extended_esc.vdc_max_v = o.esc->vdc_max_v;
  }
  res->extended_cv = ColumnErrors(d, used, cur.cv);
  res->extended_cv_rms_percent = cur.cv.rms_percent;
  CvTable(d, t.rows(), used, cur.cv, &res->extended_cv_prediction);
  if (cur.cv.failed_folds > 0) {
    res->warnings.push_back(std::to_string(cur.cv.failed_folds) + " of " + std::to_string(folds.count) +
                            " cross-validation fold(s) could not be fitted (too few points to cross-validate): "
                            "their rows count as a 100 % miss");
  }
  res->extended_cv_failed_folds = cur.cv.failed_folds;
  res->verdict = JudgeExtended(d, t, cur.model, cur.fit, used, cur.cv, *res, o);
}

// Stage 11 (DiagnoseOptions::calibration_entry): where calibrate's model holds every finding - no
// finding, or only a throttle offset / saturation knee that calibrate's own F tests also keep -
// the entry and its status are calibrate's, so that a log has one status. Diagnose weighs its residuals for its tests (errors in variables, diagnose.h) and
// calibrate for its entry (percent of the column median, Huber): on a log the first-order model
// cannot follow at low command (tytodb AG5008) the two weightings put Rm in different places.
void UseCalibrationEntry(const SteadyTable& t, const DiagnoseOptions& o, const CalibrationFits& cal,
                         DiagnoseResult* res) {
  if (!o.calibration_entry || o.motor) return;
  bool deadband = false, knee = false;
  for (const auto& f : res->findings) {
    if (f.cause == Cause::kThrottleDeadband) deadband = true;
    else if (f.cause == Cause::kEscSaturation) knee = true;
    else return;  // an extension calibrate does not fit: diagnose's own entry
  }
  if (!cal.ok || !cal.has_entry) return;
  const calibration::CalibrationOptions& co = cal.entry_options;
  const calibration::CalibrationResult& r = cal.entry;
  const bool cal_deadband = r.param(calibration::Param::kDeadband).fitted;
  const bool cal_knee = r.param(calibration::Param::kTrSat).fitted;
  // Calibrate's model must hold every finding; an offset or knee it keeps beyond them is its own F
  // test's call on its own weighting (diagnose.h: the two weigh residuals differently).
  if ((deadband && !cal_deadband) || (knee && !cal_knee)) {
    res->warnings.push_back(std::string("calibrate's fit of this log keeps ") +
                            (cal_deadband ? "a throttle offset" : "no throttle offset") + " and " +
                            (cal_knee ? "a saturation knee" : "no knee") +
                            ": it does not hold these findings, so the entry and status are diagnose's own");
    return;
  }
  const calibration::CrossValidation cv = calibration::CrossValidateForVerdict(t, co);
  res->verdict = calibration::JudgeCalibration(r, t, co, &cv);
  res->extended_motor = r.motor;
  res->extended_esc = r.esc;
  res->entry_from_calibration = true;
  // Diagnose's own fit's complaint about its base parameters is not about this entry.
  const std::string own = "the extended model still has a base parameter on a physical bound";
  res->warnings.erase(std::remove_if(res->warnings.begin(), res->warnings.end(),
                                     [&](const std::string& w) { return w.rfind(own, 0) == 0; }),
                      res->warnings.end());
  res->warnings.push_back("entry and status: calibrate's fit, which holds these findings (first order" +
                          std::string(cal_deadband ? " + throttle offset" : "") + (cal_knee ? " + saturation knee" : "") +
                          "), so both commands give this log one status");
}

}  // namespace
}  // namespace internal

DiagnoseResult Diagnose(const logs::SteadyTable& t, const DiagnoseOptions& o) {
  namespace in = internal;
  std::string why;
  if (!o.IsValid(&why)) throw UsageError("diagnose options: " + why);
  DiagnoseResult res;
  res.file = t.file.empty() ? "log" : t.file;
  in::Prepared p = in::PrepareDiagnosisData(t, o, &res);
  // Calibrate's fits, once: the base model's starts and the entry (stage 11).
  const in::CalibrationFits cal = in::CalibrateForDiagnosis(t, o);
  const in::Model base = in::BuildBaseModel(t, o, p, cal, &res);
  const std::vector<double> knees = in::KneeGrid(p.levels);
  const std::vector<Cause> candidates = in::TestableCandidates(o, p, knees, &res);
  const std::size_t n = p.d.rows();
  const in::Folds folds = in::AssignFolds(n, o);
  std::vector<std::size_t> all(n);
  std::iota(all.begin(), all.end(), 0);
  in::ApplyEffectiveVarianceWeights(all, base, &p);
  const in::Data& d = p.d;
  const std::vector<std::size_t> used = in::ScreenWithUnionModel(t, o, d, base, candidates, knees, all, &res);
  in::Step cur = in::FitBaseline(t, d, used, folds, base, knees, &res);
  res.worst_points = in::WorstPoints(t, d, used, cur.cv);
  res.residual_trends = in::ResidualTrends(t, p, used, cur.cv, o.alpha);
  const in::SearchContext x{d, used, folds, knees, base.values, o};
  cur = in::SearchCandidates(x, p.has_tr, candidates, std::move(cur), &res);
  cur = in::HoldEscOnBound(x, p.ac, std::move(cur), &res);
  in::AssembleResult(t, o, d, used, folds, cur, &res);
  res.remaining_trends = in::RemainingTrends(t, p, used, cur.cv, o.alpha);
  in::UseCalibrationEntry(t, o, cal, &res);
  return res;
}

}  // namespace dynosize::diagnosis
