// Held-out errors of a calibration (LeaveOneOut, CrossValidateForVerdict, beside the plain DC
// model of identification/dc_fit.h) and its status (JudgeCalibration, identification/verdict.h).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "calibration/calibrate.h"
#include "common/error.h"
#include "calibration/prepare.h"
#include "fit/statistics.h"
#include "identification/dc_fit.h"
#include "identification/fit_rows.h"
#include "identification/trend_attribution.h"

namespace dynosize::calibration {

using fit::Median;
using internal::SpuriousSpeedRows;
using logs::Column;
using logs::SteadyTable;

namespace {

// The plain DC model's errors on held-out row i (percent of the measured value), beside the
// rms model's: DC current and speed at the row's torque (tq), speed from its measured current.
void AddDcErrors(const identification::DcFit& dc, const SteadyTable& t, std::size_t i, double assumed_throttle, bool tq,
                 CrossValidation* cv) {
  const identification::DcRowPrediction p = identification::PredictDcRow(dc.motor, t, i, assumed_throttle, dc.deadband);
  const double w = t.Get(Column::kOmegaRadS)[i], idc = t.Get(Column::kIdcA)[i];
  if (tq && idc > 0.0 && std::isfinite(p.idc_at_torque_a)) {
    cv->dc_idc_error_percent.push_back((p.idc_at_torque_a - idc) / idc * 100.0);
  }
  if (tq && std::isfinite(p.omega_at_torque_rad_s)) {
    cv->dc_omega_error_percent.push_back((p.omega_at_torque_rad_s - w) / w * 100.0);
  }
  if (std::isfinite(p.omega_from_idc_rad_s)) {
    cv->dc_omega_from_idc_error_percent.push_back((p.omega_from_idc_rad_s - w) / w * 100.0);
  }
}

}  // namespace

CrossValidation LeaveOneOut(const SteadyTable& t, const CalibrationOptions& options, bool by_throttle,
                            std::size_t max_folds) {
  CrossValidation cv;
  const std::size_t n = t.rows();
  std::vector<long long> group(n);
  const bool thr = by_throttle && t.Has(Column::kThrottle);
  for (std::size_t i = 0; i < n; ++i) {
    group[i] = thr ? std::llround(t.Get(Column::kThrottle)[i] * 1000.0) : static_cast<long long>(i);
  }
  std::vector<long long> groups = group;
  std::sort(groups.begin(), groups.end());
  groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
  if (max_folds > 0 && groups.size() > max_folds) {
    // Interleaved folds: group j (in sorted order) goes to fold j % max_folds.
    cv.leave_one_out = false;
    for (std::size_t i = 0; i < n; ++i) {
      const auto j = static_cast<std::size_t>(std::lower_bound(groups.begin(), groups.end(), group[i]) - groups.begin());
      group[i] = static_cast<long long>(j % max_folds);
    }
    groups.clear();
    for (std::size_t f = 0; f < max_folds; ++f) groups.push_back(static_cast<long long>(f));
  }
  const bool has_q = t.Has(Column::kTorqueNm);
  const bool has_nl = t.Has(Column::kNoLoad);
  double wmax = 0.0;
  for (double w : t.Get(Column::kOmegaRadS)) wmax = std::max(wmax, w);
  // The rows a fit may use (Prepare's speed and throttle rules; a no-load row without a speed
  // reading counts for the current only).
  const auto usable = [&](std::size_t i, bool* speed_unknown) {
    const double w = t.Get(Column::kOmegaRadS)[i];
    *speed_unknown = has_nl && t.Get(Column::kNoLoad)[i] != 0.0 && w == 0.0;
    if (!*speed_unknown && !(w > options.min_speed_fraction * wmax)) return false;
    return !(t.Has(Column::kThrottle) && t.Get(Column::kThrottle)[i] < options.min_throttle);
  };
  // Spurious speed readings are no test of a prediction (the fits leave them out too).
  std::vector<char> spurious(n, 0);
  for (const auto& sp : SpuriousSpeedRows(t, options, nullptr)) spurious[sp.row] = 1;
  for (long long g : groups) {
    ++cv.folds;
    std::vector<std::size_t> test;
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < n; ++i) (group[i] == g ? test : keep).push_back(i);
    const SteadyTable train = SelectRows(t, keep);
    CalibrationResult r;
    try {
      r = Calibrate(train, options);
    } catch (const Error&) {
      ++cv.failed_folds;
      continue;
    }
    std::vector<std::size_t> dc_rows;
    for (std::size_t i : keep) {
      bool unknown = false;
      if (usable(i, &unknown) && !unknown) dc_rows.push_back(i);
    }
    // The same throttle offset as the fold's own fit (identification/dc_fit.h).
    const identification::DcFit dc = identification::FitDcMotor(t, dc_rows, options.assumed_throttle,
                                                                options.labels.kv_rpm_per_v.value_or(0.0), r.esc.deadband);
    if (!dc.ok) {
      ++cv.dc_failed_folds;
      if (cv.dc_why.empty()) cv.dc_why = dc.why;
    }
    for (std::size_t i : test) {
      const double w = t.Get(Column::kOmegaRadS)[i];
      bool speed_unknown = false;
      if (spurious[i] || !usable(i, &speed_unknown)) continue;
      const bool no_load = has_nl && t.Get(Column::kNoLoad)[i] != 0.0;
      if (dc.ok && !speed_unknown) AddDcErrors(dc, t, i, options.assumed_throttle, has_q || no_load, &cv);
      const RowPrediction p = PredictRow(t, i, r.motor, r.esc, options.assumed_throttle);
      const double idc = t.Get(Column::kIdcA)[i];
      if (idc > 0.0 && std::isfinite(p.idc_a)) {
        cv.idc_error_percent.push_back((p.idc_a - idc) / idc * 100.0);
        if (!no_load) cv.idc_loaded_error_percent.push_back(cv.idc_error_percent.back());
      }
      if (speed_unknown) continue;
      const bool tq = has_q || no_load;
      if (std::isfinite(p.omega_from_idc_rad_s)) {
        cv.omega_from_idc_error_percent.push_back((p.omega_from_idc_rad_s - w) / w * 100.0);
      }
      if (tq && std::isfinite(p.omega_rad_s)) cv.omega_error_percent.push_back((p.omega_rad_s - w) / w * 100.0);
    }
  }
  return cv;
}

CrossValidation CrossValidateForVerdict(const SteadyTable& table, const CalibrationOptions& options) {
  // Up to 15 groups every group is left out in turn (small tables); beyond that 10
  // interleaved folds bound the cost of the verdict.
  constexpr std::size_t kMaxLooGroups = 15;
  constexpr std::size_t kFolds = 10;
  const bool thr = table.Has(Column::kThrottle);
  std::vector<long long> g;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    g.push_back(thr ? std::llround(table.Get(Column::kThrottle)[i] * 1000.0) : static_cast<long long>(i));
  }
  std::sort(g.begin(), g.end());
  g.erase(std::unique(g.begin(), g.end()), g.end());
  return LeaveOneOut(table, options, true, g.size() <= kMaxLooGroups ? 0 : kFolds);
}

namespace {

// The fit predicts the speed from the measured current (a DC log with throttle but neither
// torque nor the AC columns: Prepare).
bool SpeedFromCurrent(const SteadyTable& table) {
  return table.Has(Column::kThrottle) && !table.Has(Column::kTorqueNm) &&
         !(table.Has(Column::kVllRmsV) && table.Has(Column::kIrmsA));
}

// What the fitted model's residual of its predicted current (or, where the speed is predicted
// from the current, of that speed) still follows over the rows it fitted: speed, accumulated
// heat or command (identification/trend_attribution.h; in-sample residuals, at the diagnosis's
// test level). Empty when nothing is structured.
identification::TrendAttribution FitResidualTrend(const CalibrationResult& r, const SteadyTable& table) {
  constexpr double kAlpha = 1e-3;  // as DiagnoseOptions::alpha
  const bool speed_from_current = SpeedFromCurrent(table);
  if (!table.Has(Column::kIdcA) || !table.Has(Column::kOmegaRadS)) return {};
  std::vector<char> dropped(table.rows(), 0);
  for (const DroppedRow& d : r.dropped_rows) {
    if (d.row < dropped.size()) dropped[d.row] = 1;
  }
  identification::TrendRows rows;
  const auto& w = table.Get(Column::kOmegaRadS);
  const auto& idc = table.Get(Column::kIdcA);
  for (std::size_t k = 0; k < table.rows(); ++k) {
    if (dropped[k] || !(w[k] > 0.0) || !(idc[k] > 0.0)) continue;
    const RowPrediction p = PredictRow(table, k, r.motor, r.esc);
    const double pred = speed_from_current ? p.omega_from_idc_rad_s : p.idc_a;
    const double meas = speed_from_current ? w[k] : idc[k];
    if (!std::isfinite(pred)) continue;
    rows.predicted.push_back(pred);
    rows.measured.push_back(meas);
    rows.omega_rad_s.push_back(w[k]);
    rows.current_a.push_back(idc[k]);
    if (table.Has(Column::kTimeS)) rows.time_s.push_back(table.Get(Column::kTimeS)[k]);
    if (table.Has(Column::kThrottle)) rows.throttle.push_back(table.Get(Column::kThrottle)[k]);
  }
  return identification::AttributeTrend(rows, kAlpha);
}

}  // namespace

identification::Verdict JudgeCalibration(const CalibrationResult& r, const SteadyTable& table,
                                         const CalibrationOptions& options, const CrossValidation* cv) {
  identification::VerdictInputs in;
  in.converged = r.converged;
  for (int k = 0; k < kBaseParamCount; ++k) {
    const auto& e = r.params[k];
    identification::ParamState p;
    p.name = ParamName(static_cast<Param>(k));
    p.value = e.value;
    p.standard_error = e.standard_error;
    p.fitted = e.fitted;
    p.identifiable = e.identifiable;
    p.at_bound = e.at_bound;
    // The grid resolution of the profiled knee is not a standard error of the data.
    if (static_cast<Param>(k) == Param::kTrSat) p.standard_error = kNaN;
    // Without AC columns Rm stands for Rm + RESC (RESC held at its prior): the sum is what the
    // data determine, with its own error; only a flat direction makes it unidentifiable.
    if (static_cast<Param>(k) == Param::kRm && !r.param(Param::kResc).fitted && e.fitted &&
        e.note.rfind("in a direction", 0) != 0) {
      p.identifiable = true;
      p.standard_error = r.r_total_standard_error;
    }
    in.params.push_back(p);
  }
  in.motor = r.motor;
  in.esc = r.esc;
  if (table.Has(Column::kVdcV)) {
    const auto& v = table.Get(Column::kVdcV);
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (double x : v) {
      if (x > 0.0) {
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    }
    in.envelope.vdc_min_v = std::isfinite(lo) ? lo : 0.0;
    in.envelope.vdc_max_v = hi;
  }
  in.kv_label_rpm_per_v = options.labels.kv_rpm_per_v;
  if (cv != nullptr) {
    identification::HeldOut h;
    h.folds = cv->folds;
    h.failed_folds = cv->failed_folds;
    h.leave_one_out = cv->leave_one_out;
    auto med_abs = [](std::vector<double> v) {
      for (double& x : v) x = std::fabs(x);
      return Median(v);
    };
    if (SpeedFromCurrent(table)) {
      // The fit predicts the speed from the measured current (Prepare): that is its held-out test.
      h.median_abs_current_percent = med_abs(cv->omega_from_idc_error_percent);
      h.primary_quantity = "speed predicted from the measured current";
    } else {
      h.median_abs_current_percent = med_abs(cv->idc_error_percent);
      h.median_abs_speed_percent = !cv->omega_error_percent.empty() ? med_abs(cv->omega_error_percent)
                                                                     : med_abs(cv->omega_from_idc_error_percent);
    }
    in.held_out = h;
  }
  if (options.labels.kv_rpm_per_v) {
    in.torque_per_ampere_vs_label = identification::TorquePerAmpereVsLabel(table, *options.labels.kv_rpm_per_v);
  }
  in.has_torque = table.Has(Column::kTorqueNm);
  in.has_ac = table.Has(Column::kVllRmsV) && table.Has(Column::kIrmsA);
  in.has_throttle = table.Has(Column::kThrottle);
  in.pulse_min_us = table.throttle_pulse_min_us;
  in.pulse_max_us = table.throttle_pulse_max_us;
  identification::Verdict v = identification::Judge(in);
  if (v.status != identification::Status::kOk) {
    // A refusal names what is wrong with the parameters; a trend the fit leaves in its residual
    // is often why (a no-load current pushed to its bound by a current that drifts over the run).
    const identification::TrendAttribution trend = FitResidualTrend(r, table);
    if (trend.structured) {
      v.advice += std::string(v.advice.empty() ? "" : "; ") + "the fit's " +
                  (SpeedFromCurrent(table) ? "speed" : "current") + " residual is not noise: " + trend.text +
                  (trend.measurement.empty() ? "" : " (to separate them: " + trend.measurement + ")") +
                  "; `dynosize diagnose` tests the named causes";
    }
  }
  if (r.io_source == "no-load prior") {
    v.summary += " (io_a from the no-load prior: assumed, the log has neither torque nor no-load rows)";
  }
  return v;
}

}  // namespace dynosize::calibration
