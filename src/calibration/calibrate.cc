// Calibrate(): prepare (prepare.h, starting_values.h), the joint fit (joint_fit.h), the outlier
// pass, and the result with its standard errors, flags, column fits and warnings.
#include "calibration/calibrate.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "calibration/forward_model.h"
#include "calibration/joint_fit.h"
#include "calibration/prepare.h"
#include "calibration/starting_values.h"
#include "common/error.h"
#include "fit/option_check.h"
#include "fit/statistics.h"

namespace dynosize::calibration {

using fit::Median;
using internal::EscUndetermined;
using internal::FileTag;
using internal::FitWithOffset;
using internal::HasPrior;
using internal::HeldIo;
using internal::kC0I;
using internal::kC1I;
using internal::kDbI;
using internal::kKtI;
using internal::kMeasColumn;
using internal::kMeasCount;
using internal::kMIdc;
using internal::kMIrms;
using internal::kMOmega;
using internal::kMPac;
using internal::kMVll;
using internal::kLower;
using internal::kUpper;
using internal::Layout;
using internal::Prepare;
using internal::Prepared;
using internal::PredictGeneric;
using internal::SelectOutliers;
using internal::SolveOutcome;
using internal::ToEsc;
using internal::ToInternal;
using internal::ToMotor;
using internal::TransformStandardErrors;
using logs::Column;
using logs::SteadyTable;

namespace {

// Warnings for parameters on a bound (the energy rules named) and for a single throttle level.
void AddBoundWarnings(const Prepared& pr, CalibrationResult* out) {
  CalibrationResult& res = *out;
  for (int k = 0; k < kBaseParamCount; ++k) {
    if (!res.params[k].at_bound) continue;
    if (k == kC1I) {
      res.warnings.push_back("c1 + c0 is on the ideal-ESC bound 1.1095 (model.md section 10): the data ask for an "
                             "ESC that creates energy");
    } else if (k == kKtI && !pr.layout.tie_kt) {
      res.warnings.push_back("kt_nm_per_a is on its bound sqrt(27/10)*KE (model.md section 10): the data ask for a "
                             "motor efficiency above 1");
    } else {
      res.warnings.push_back(std::string(ParamName(static_cast<Param>(k))) + " is at its bound (" +
                             std::to_string(res.params[k].value) + "): the data push it outside the physical range");
    }
  }
  if (pr.has_throttle && pr.levels.size() < 2) {
    res.warnings.push_back("all rows at one throttle level: ESC ratio and saturation not identifiable");
  }
}

// Per measured column: rmse, rmse in percent and median |error| of the final fit (the speed from
// the current on rows whose current is the input, whose current is then not scored), and the no-throttle plausibility warning.
void AddColumnFits(const Prepared& pr, const SteadyTable& table, const CalibrationOptions& options,
                   CalibrationResult* out) {
  CalibrationResult& res = *out;
  for (int m = 0; m < kMeasCount; ++m) {
    if (!pr.data.measured[m]) continue;
    ColumnFit cf;
    cf.column = kMeasColumn[m];
    double sse = 0.0, ss = 0.0;
    std::vector<double> rel;
    for (std::size_t k = 0; k < pr.data.rows(); ++k) {
      const RowPrediction rp = PredictRow(table, pr.data.table_row[k], res.motor, res.esc, options.assumed_throttle);
      // Rows whose current is the fit's input: their speed prediction is the one from the current.
      const bool current_input = pr.data.idc_in[k] == pr.data.idc_in[k];
      // Its current is an input there, not a fitted value: not scored (the held-out report has
      // the current from the measured speed).
      if (current_input && m == kMIdc) continue;
      const double pv[kMeasCount] = {current_input ? rp.omega_from_idc_rad_s : rp.omega_rad_s, rp.idc_a, rp.irms_a,
                                     rp.vll_rms_v, rp.pac_w};
      if (!std::isfinite(pv[m])) continue;
      const double meas = table.Get(kMeasColumn[m])[pr.data.table_row[k]];
      sse += (pv[m] - meas) * (pv[m] - meas);
      ss += meas * meas;
      if (meas != 0.0) rel.push_back(std::fabs(pv[m] - meas) / std::fabs(meas) * 100.0);
      ++cf.points;
    }
    if (cf.points == 0) continue;
    cf.rmse = std::sqrt(sse / static_cast<double>(cf.points));
    cf.rmse_percent = ss > 0.0 ? 100.0 * std::sqrt(sse / ss) : kNaN;
    cf.median_abs_percent = Median(rel);
    res.fit.push_back(cf);
  }
  if (!pr.has_throttle) {
    for (const auto& f : res.fit) {
      if (f.rmse_percent > 10.0) {
        res.warnings.push_back(std::string("no throttle column and ") + logs::ColumnName(f.column) + " misfit by " +
                               std::to_string(f.rmse_percent) +
                               " % rms: the rows do not look like full-throttle points, so KE and R are not "
                               "meaningful; calibrate a log that records the throttle");
        break;
      }
    }
  }
}

}  // namespace

bool CalibrationOptions::IsValid(std::string* error) const {
  const fit::OptionCheck check("CalibrationOptions", error);
  if (!(loss_scale_percent > 0.0)) return check.Fail("loss_scale_percent", loss_scale_percent, "must be > 0");
  if (!(outlier_sigmas >= 0.0)) return check.Fail("outlier_sigmas", outlier_sigmas, "must be >= 0");
  if (!(min_speed_fraction >= 0.0 && min_speed_fraction < 1.0)) {
    return check.Fail("min_speed_fraction", min_speed_fraction, "must be in [0, 1)");
  }
  if (!(assumed_throttle > 0.0 && assumed_throttle <= 1.0)) {
    return check.Fail("assumed_throttle", assumed_throttle, "must be in (0, 1]");
  }
  if (!(knee_min > 0.0 && knee_min < 1.0)) return check.Fail("knee_min", knee_min, "must be in (0, 1)");
  if (!(knee_step > 0.0 && knee_step <= 0.5)) return check.Fail("knee_step", knee_step, "must be in (0, 0.5]");
  if (!(knee_min_f >= 0.0)) return check.Fail("knee_min_f", knee_min_f, "must be >= 0");
  if (!(prior_ke_rel_sigma > 0.0)) return check.Fail("prior_ke_rel_sigma", prior_ke_rel_sigma, "must be > 0");
  if (!(prior_rm_rel_sigma > 0.0)) return check.Fail("prior_rm_rel_sigma", prior_rm_rel_sigma, "must be > 0");
  if (!(prior_io_rel_sigma > 0.0)) return check.Fail("prior_io_rel_sigma", prior_io_rel_sigma, "must be > 0");
  std::string e;
  if (!labels.IsValid(&e)) return check.Fail("labels", e.c_str());
  if (!solver.IsValid(error)) return false;
  return true;
}

namespace {

// The state of one calibration between its stages (Calibrate).
struct Run {
  Prepared pr;
  SolveOutcome best;
  bool knee_found = false, offset_found = false;
  std::string knee_note, offset_note;
  std::size_t outliers = 0;
};

// The same calibration with fit_throttle_offset off, run beside one with it on: both take the
// same stages with the same rows and fits until the run with the offset tested keeps it (the
// fit without it is FitWithOffset's "none"); from there on the twin goes its own way.
struct OffsetFreeTwin {
  CalibrationOptions options;  // fit_throttle_offset off
  bool forked = false;
  int next_stage = 0;  // the stage the forked twin resumes at
  Run run;             // once forked
};

// The stage's fit (FitWithOffset) of run r; a twin that still shares r's path forks when r keeps
// an offset.
void FitStage(int stage, const CalibrationOptions& o, Run* r, OffsetFreeTwin* twin) {
  if (twin == nullptr || twin->forked) {
    r->best = FitWithOffset(r->pr, o, &r->knee_found, &r->knee_note, &r->offset_found, &r->offset_note);
    return;
  }
  internal::OffsetFreeFit none;
  r->best = FitWithOffset(r->pr, o, &r->knee_found, &r->knee_note, &r->offset_found, &r->offset_note, &none);
  if (!r->offset_found) return;
  twin->forked = true;
  twin->next_stage = stage + 1;
  twin->run = *r;
  twin->run.best = std::move(none.outcome);
  twin->run.knee_found = none.knee_found;
  twin->run.knee_note = std::move(none.knee_note);
  twin->run.offset_found = false;
  twin->run.offset_note = internal::kOffsetNotTestedNote;
}

// Stage 1: the outlier pass: rows beyond outlier_sigmas dropped and the fit repeated.
void OutlierPass(const SteadyTable& table, const CalibrationOptions& options, int nfree_base, Run* r,
                 OffsetFreeTwin* twin) {
  Prepared& pr = r->pr;
  if (options.outlier_sigmas > 0.0 && r->best.summary.IsSolutionUsable()) {
    const std::vector<DroppedRow> out = SelectOutliers(pr, r->best.params, table, options, nfree_base);
    if (!out.empty()) {
      std::vector<char> excl(table.rows(), 1);  // rows dropped before stay dropped
      for (std::size_t i : pr.data.table_row) excl[i] = 0;
      for (const auto& o : out) excl[o.row] = 1;
      Prepared pr2 = Prepare(table, options, &excl);
      pr2.dropped = pr.dropped;
      pr2.dropped_rows = pr.dropped_rows;
      pr2.dropped.push_back({"outlier (residual > outlier_sigmas robust sd)", out.size()});
      pr2.dropped_rows.insert(pr2.dropped_rows.end(), out.begin(), out.end());
      pr2.warnings = pr.warnings;
      pr = std::move(pr2);
      r->outliers = out.size();
      FitStage(1, options, r, twin);
    }
  }
}

// Stage 2: without AC columns the ESC ratio is only seen through the tied KT (section 5): where
// the log cannot determine C1, C0 (on a bound, or a standard error above half the value) they are
// held at the ESC prior (ideal unless --prior-esc) and the fit repeated.
void HoldUndeterminedEsc(const CalibrationOptions& options, Run* r, OffsetFreeTwin* twin) {
  Prepared& pr = r->pr;
  if (pr.mode != "ac" && pr.layout.free[kC1I]) {
    const std::string why = EscUndetermined(r->best.summary);
    if (!why.empty()) {
      const EscParams e0 = options.esc_prior ? *options.esc_prior : EscParams{};
      pr.layout.free[kC1I] = pr.layout.free[kC0I] = false;
      pr.start[kC0I] = std::clamp(e0.c0, kLower[kC0I], kUpper[kC0I]);
      pr.start[kC1I] = std::clamp(identification::EscExcess(e0.c1, pr.start[kC0I]), kLower[kC1I], kUpper[kC1I]);
      pr.notes[kC1I] = pr.notes[kC0I] = "held at prior: without AC columns this log cannot determine them (" + why + ")";
      FitStage(2, options, r, twin);
    }
  }
}

// The stages from `from` on: 0 the first fit, 1 the outlier pass, 2 the ESC hold.
void RunStages(const SteadyTable& table, const CalibrationOptions& options, int nfree_base, int from, Run* r,
               OffsetFreeTwin* twin) {
  if (from <= 0) FitStage(0, options, r, twin);
  if (from <= 1) OutlierPass(table, options, nfree_base, r, twin);
  if (from <= 2) HoldUndeterminedEsc(options, r, twin);
}

// The result of a run: values, standard errors, flags, notes, column fits and warnings.
CalibrationResult Assemble(const SteadyTable& table, const CalibrationOptions& options, const Run& run) {
  const Prepared& pr = run.pr;
  const SolveOutcome& best = run.best;
  const bool knee_found = run.knee_found, offset_found = run.offset_found;
  const std::string& knee_note = run.knee_note;
  const std::string& offset_note = run.offset_note;
  CalibrationResult res;
  res.solve_called = true;
  const auto& s = best.summary;
  res.solver_summary = s;
  res.converged = s.termination_type == TerminationType::kConvergence;
  res.message = std::string(TerminationTypeToString(s.termination_type)) + ": " + s.message;
  res.mode = pr.mode;
  res.motor = ToMotor(best.params);
  res.esc = ToEsc(best.params, options.esc_prior);
  res.dropped = pr.dropped;
  res.dropped_rows = pr.dropped_rows;
  res.points_used = pr.data.rows();
  for (const auto& dc : pr.dropped) res.points_dropped += dc.count;
  res.warnings = pr.warnings;
  if (!res.converged) res.warnings.push_back("fit did not converge: " + s.message);

  // Per-parameter report.
  std::vector<int> slots;
  {
    Layout lay = pr.layout;
    lay.free[8] = knee_found;
    lay.free[kDbI] = offset_found;
    for (int k = 0; k < kBaseParamCount; ++k) {
      if (lay.free[k]) slots.push_back(k);
    }
  }
  for (int k = 0; k < kBaseParamCount; ++k) {
    ParamEstimate& e = res.params[k];
    e.value = best.params[k];
    e.note = pr.notes[k];
  }
  HeldIo(pr, table, options, &res);
  for (std::size_t sl = 0; sl < slots.size() && sl < static_cast<std::size_t>(s.parameters.size()); ++sl) {
    ParamEstimate& e = res.params[slots[sl]];
    e.fitted = true;
    e.identifiable = true;
    e.standard_error = s.standard_errors.size() > static_cast<Eigen::Index>(sl) ? s.standard_errors[sl] : kNaN;
    e.at_bound = sl < s.at_bound.size() && s.at_bound[sl];
  }
  for (const auto& u : s.unidentifiable) {
    res.unidentifiable_directions.push_back(u.description);
    for (Eigen::Index sl = 0; sl < u.direction.size() && sl < static_cast<Eigen::Index>(slots.size()); ++sl) {
      if (std::fabs(u.direction[sl]) > 0.2) {
        ParamEstimate& e = res.params[slots[sl]];
        if (HasPrior(options, slots[sl])) {
          // The prior pins what the data leave flat: its standard error is the prior's.
          e.note = "set by its prior (the data alone do not determine it: " + u.description + ")";
          continue;
        }
        e.identifiable = false;
        e.note = "in a direction the data do not determine: " + u.description;
      }
    }
  }
  TransformStandardErrors(pr.layout.tie_kt, slots, s, &res);
  if (!offset_found) res.params[kDbI].note = pr.notes[kDbI].empty() ? offset_note : pr.notes[kDbI];
  else res.params[kDbI].note = offset_note;
  auto& tk = res.params[static_cast<int>(Param::kTrSat)];
  tk.fitted = knee_found;
  tk.identifiable = knee_found;
  tk.note = knee_note;
  if (knee_found) tk.standard_error = options.knee_step / std::sqrt(12.0);  // grid resolution
  auto& sl = res.params[static_cast<int>(Param::kSatSlope)];
  if (!knee_found) sl.note = "no knee: " + knee_note;
  // KT tied to KE: its error follows KE's.
  auto& kt = res.params[static_cast<int>(Param::kKt)];
  if (pr.layout.tie_kt) {
    const auto& ke = res.params[0];
    kt.standard_error = kPacPerVllIrms * ke.standard_error;
    kt.identifiable = false;
  }
  // Rm + RESC with its error (covariance when both fitted).
  res.r_total_ohm = res.motor.rm_ohm + res.esc.resc_ohm;
  {
    double var = 0.0;
    int irm = -1, iresc = -1;
    for (std::size_t q = 0; q < slots.size(); ++q) {
      if (slots[q] == 2) irm = static_cast<int>(q);
      if (slots[q] == 4) iresc = static_cast<int>(q);
    }
    if (s.covariance.rows() == static_cast<Eigen::Index>(slots.size()) && irm >= 0) {
      var = s.covariance(irm, irm);
      if (iresc >= 0) var += s.covariance(iresc, iresc) + 2.0 * s.covariance(irm, iresc);
      res.r_total_standard_error = std::sqrt(std::max(var, 0.0));
    }
  }
  if (!pr.layout.free[static_cast<int>(Param::kResc)]) {
    res.params[static_cast<int>(Param::kRm)].identifiable = false;
    res.params[static_cast<int>(Param::kResc)].identifiable = false;
  }
  if (s.scaled_singular_values.size() > 0) {
    const double smin = s.scaled_singular_values.minCoeff();
    res.condition_number = smin > 0.0 ? s.scaled_singular_values.maxCoeff() / smin
                                      : std::numeric_limits<double>::infinity();
  }
  AddBoundWarnings(pr, &res);
  if (run.outliers > 0) res.warnings.push_back(std::to_string(run.outliers) + " outlier row(s) dropped and the fit repeated");

  AddColumnFits(pr, table, options, &res);
  return res;
}

}  // namespace

CalibrationResult Calibrate(const SteadyTable& table, const CalibrationOptions& options,
                            CalibrationResult* without_offset) {
  std::string err;
  if (!options.IsValid(&err)) throw UsageError("calibration options: " + err);
  Run run;
  run.pr = Prepare(table, options, nullptr);
  const Prepared& pr = run.pr;
  const int nfree_base = static_cast<int>(std::count(pr.layout.free.begin(), pr.layout.free.end(), true));
  if (pr.data.terms.size() <= static_cast<std::size_t>(nfree_base)) {
    throw DataError(FileTag(table) + ": " + std::to_string(pr.data.terms.size()) +
                    " measured values for " + std::to_string(nfree_base) +
                    " free parameters: calibration needs more rows");
  }
  OffsetFreeTwin twin;
  twin.options = options;
  twin.options.fit_throttle_offset = false;
  const bool with_twin = without_offset != nullptr && options.fit_throttle_offset;
  RunStages(table, options, nfree_base, 0, &run, with_twin ? &twin : nullptr);
  CalibrationResult res = Assemble(table, options, run);
  if (without_offset == nullptr) return res;
  if (!with_twin) {
    *without_offset = res;
  } else if (twin.forked) {
    RunStages(table, twin.options, nfree_base, twin.next_stage, &twin.run, nullptr);
    *without_offset = Assemble(table, twin.options, twin.run);
  } else {
    // Never forked: the twin took every stage with the run (no offset kept); only its note differs.
    run.offset_note = internal::kOffsetNotTestedNote;
    *without_offset = Assemble(table, twin.options, run);
  }
  return res;
}

RowPrediction PredictRow(const SteadyTable& t, std::size_t row, const MotorParams& motor, const EscParams& esc,
                         double assumed_throttle) {
  RowPrediction out;
  const std::array<double, kBaseParamCount> p = ToInternal(motor, esc);
  const bool has_q = t.Has(Column::kTorqueNm);
  const bool nl = t.Has(Column::kNoLoad) && t.Get(Column::kNoLoad)[row] != 0.0;
  const bool tq = has_q || nl;
  const double tr = t.Has(Column::kThrottle) ? t.Get(Column::kThrottle)[row] : assumed_throttle;
  double pred[kMeasCount], qp;
  if (!PredictGeneric(p.data(), esc.tr_sat, t.Get(Column::kVdcV)[row], tr, t.Get(Column::kOmegaRadS)[row],
                      has_q ? t.Get(Column::kTorqueNm)[row] : 0.0, tq, pred, &qp)) {
    return out;
  }
  if (tq) out.omega_rad_s = pred[kMOmega];
  {
    const double tre = circuit::EffectiveThrottle(tr, esc.tr_sat, esc.sat_slope, esc.deadband);
    const double g = esc.c1 * tre + esc.c0;  // (57): IDC = g*I
    const double u = circuit::AppliedVoltage(kVllRmsPerVdc, t.Get(Column::kVdcV)[row], tre);
    if (g > 0.0 && motor.ke_v_s_per_rad > 0.0) {
      out.omega_from_idc_rad_s = circuit::SpeedAtCurrent(u, motor.rm_ohm + esc.resc_ohm,
                                                         t.Get(Column::kIdcA)[row] / g, motor.ke_v_s_per_rad);
    }
  }
  if (!tq) out.torque_nm = qp;
  out.idc_a = pred[kMIdc];
  out.irms_a = pred[kMIrms];
  out.vll_rms_v = pred[kMVll];
  out.pac_w = pred[kMPac];
  return out;
}

}  // namespace dynosize::calibration
