// Calibration: motor (KE, KT, Rm, Io) and ESC (RESC, C1, C0, tr_sat, sat_slope) parameters of
// the Brown & Chopra model (docs/model.md, src/model/drive.h) fitted to the steady
// points of a dynamometer / thrust-stand log (logs::SteadyTable).
//
// The fit is a forward-model fit: each row's known inputs are VDC, the throttle TR (assumed 1
// when the log has none, see below) and either the load torque Q (measured torque, or Q = 0 on
// a no-load row) or the measured speed omega; every other measured column is predicted from
// them and compared:
//
//   TR_eff = TR (TR <= tr_sat), tr_sat + sat_slope*(TR - tr_sat) above    (section 7)
//   U      = 3/(sqrt(2)*pi) * VDC * TR_eff                                 (46)
//   torque known:  I = Q/KT + Io,   omega = (U - (Rm+RESC)*I)/KE           (42, 48)
//   speed known:   I = (U - KE*omega)/(Rm+RESC),  Q = KT*(I - Io)          (48, 42)
//   VLL = U - RESC*I (47),  IDC = (C1*TR_eff + C0)*I (57),  PAC = sqrt(27/10)*VLL*I (51)
//
// Residuals are in percent of each column's median magnitude, so that columns in different
// units weigh alike; a robust loss (Huber by default) bounds the pull of outliers, and points
// whose residual stays beyond `outlier_sigmas` robust standard deviations are dropped and the
// fit repeated. Starting values come from the linear sub-problems of the paper solved by QR
// (eq 42: VLL = Irms*Rm + KE*omega; eq 57: IDC = C1*TR*Irms + C0*Irms; Q = KT*Irms - KT*Io);
// the joint fit is the bounded Levenberg-Marquardt of src/fit (Rm, Io, RESC >= 0; KE, KT > 0).
// The saturation knee tr_sat is found by profiling: the fit is repeated for each candidate on
// a grid and the best is kept if it beats "no knee" (tr_sat = 1) by an F test.
//
// What each column set identifies (the flags in the result say so per parameter):
//  - AC columns (vll_rms_v, irms_a) + vdc_v + throttle: all of KE, Rm, RESC separately; with
//    idc_a also C1, C0 (two or more throttle levels); with torque_nm also KT and Io.
//  - DC side only (vdc_v, throttle, omega, idc_a [, torque_nm]) - most thrust stands: KT is
//    tied to KE by the power balance KT = sqrt(27/10)*KE (docs/model.md section 5), and only the
//    sum Rm + RESC enters (eq 48): RESC is held at its prior (0 without one), Rm absorbs the
//    rest, and both are flagged unidentifiable; r_total_ohm reports the sum with its error.
//    Without torque, IDC = (C1*TR_eff + C0)*(U - KE*omega)/R determines only C1/R and C0/R:
//    C1, C0 are held at the ideal ESC of eq (56) (or the ESC prior) and R is then conditional
//    on that assumption; Io needs torque or no-load rows.
//  - No throttle column (DriveCalc MData, stands driven by an external controller): every row
//    is taken as full throttle (`assumed_throttle`). At TR = 1 the model reduces to the DC
//    relation of a brushed motor, VDC = R_dc*IDC + omega/Kv_dc with
//        KE = kv*T1/Kv_dc,  R = kv*T1*g*R_dc,  Io = Io_dc/g,   g = C1*T1 + C0, T1 = TR_eff(1),
//    so only KE, R = Rm + RESC and Io (from no-load rows) are identifiable, all conditional on
//    the assumed ESC (ideal: T1 = 1, g = 1.1095, i.e. R = 0.749*R_dc, Io = 0.901*Io_dc). The
//    ESC parameters are reported unidentifiable. If the log was in fact taken at part
//    throttle, KE and R are scaled by that throttle: a warning says so.
//
// Parameters the data cannot pin down are also found numerically: the LM identifiability test
// (singular values of the unit-scaled Jacobian) flags combinations, and e.g. all rows at one
// throttle leave the saturation knee unidentified.
//
// Files of src/calibration (the parameter table and the row rules shared with diagnose are in
// src/identification):
//   calibration_types.h    the options and the result (below every stage)
//   calibrate.h/.cc        this interface and Calibrate(): the stages in order (with the fit
//                          without the throttle offset beside them, for diagnose); PredictRow
//   prepared_fit.h         what Prepare hands to the fit (rows, terms, free parameters, starts)
//   prepare.h/.cc          the rows used (every dropped row with its reason), their residual terms,
//                          which parameters the log frees
//   starting_values.h/.cc  how KE, R, KT and Io start (linear sub-problems) and how Io is held
//                          where the log cannot identify it (label, motor prior, no-load prior)
//   forward_model.h/.cc    the equations above, the internal parametrisation (KT ratio, ESC
//                          excess), the residuals with their dual-number Jacobian
//   joint_fit.h/.cc        the bounded fit with priors, the saturation-knee profile (its grid;
//                          the profile itself is identification/knee_profile.h), the throttle
//                          offset test, the outlier pass, standard errors of KT and c1
//   cross_validation.cc    LeaveOneOut, CrossValidateForVerdict, JudgeCalibration
//   calibration_report.cc  BriefReport, FullReport
//   catalog_output.h/.cc, drivecalc_refit.h/.cc, prop_static.h/.cc: catalog entries, the DriveCalc
//                          refit and the static propeller table from a calibration
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "calibration/calibration_types.h"
#include "identification/verdict.h"
#include "logs/steady_table.h"
#include "logs/table_ops.h"

namespace dynosize::calibration {

// Fits the parameters to `table`. Throws DataError when the log lacks what any fit needs
// (omega_rad_s; vdc_v or the AC columns; enough rows with the motor turning), naming the file,
// the column and the rule; UsageError for invalid options. Non-convergence is a status.
// With without_offset, it also holds what Calibrate returns with options.fit_throttle_offset off,
// from the same run: the two share every stage (rows, knee profile, outlier pass, fits) up to the
// first fit that keeps a throttle offset, and only then go on separately. Diagnose starts from
// the fit without the offset and takes the entry from the one with it.
CalibrationResult Calibrate(const logs::SteadyTable& table, const CalibrationOptions& options = {},
                            CalibrationResult* without_offset = nullptr);

// Model predictions for row `row` of `table` with the given parameters, for the columns the fit
// compares (omega_rad_s only where the torque is known). NaN for a column not predicted.
struct RowPrediction {
  double omega_rad_s = std::numeric_limits<double>::quiet_NaN();
  double idc_a = std::numeric_limits<double>::quiet_NaN();
  double irms_a = std::numeric_limits<double>::quiet_NaN();
  double vll_rms_v = std::numeric_limits<double>::quiet_NaN();
  double pac_w = std::numeric_limits<double>::quiet_NaN();
  double torque_nm = std::numeric_limits<double>::quiet_NaN();  // speed-known rows
  // Speed from the measured DC current (I = IDC/(C1*TR_eff + C0), omega = (U - R*I)/KE): the
  // quantity a DC-side model "U = n/Kv + R*I" predicts; every row.
  double omega_from_idc_rad_s = std::numeric_limits<double>::quiet_NaN();
};
RowPrediction PredictRow(const logs::SteadyTable& table, std::size_t row, const MotorParams& motor,
                         const EscParams& esc, double assumed_throttle = 1.0);

// Leave-one-out prediction errors: for each group (one throttle level, or one row when
// `by_throttle` is false or the log has no throttle), fit on the other rows and predict the
// left-out ones. Percent errors (pred - meas)/meas*100 of idc_a and omega_rad_s (omega only
// where the torque is known, i.e. torque column or no-load rows).
struct CrossValidation {
  bool leave_one_out = true;  // every group left out in turn (else max_folds interleaved folds)
  std::vector<double> idc_error_percent;
  std::vector<double> idc_loaded_error_percent;  // rows with torque or speed known, not no-load
  std::vector<double> omega_error_percent;
  std::vector<double> omega_from_idc_error_percent;  // RowPrediction::omega_from_idc_rad_s, every row
  // The same held-out rows predicted by the plain first-order DC model fitted on the same
  // training rows (identification/dc_fit.h): the baseline reported beside the rows above.
  std::vector<double> dc_idc_error_percent;
  std::vector<double> dc_omega_error_percent;
  std::vector<double> dc_omega_from_idc_error_percent;
  std::size_t folds = 0;
  std::size_t failed_folds = 0;  // too few rows left to fit
  // Folds whose plain DC model could not be fitted (identification/dc_fit.h DcFit::why), and the
  // first reason: said instead of an error.
  std::size_t dc_failed_folds = 0;
  std::string dc_why;
};
// With max_folds > 0 and more groups than that, the groups (sorted) are dealt into max_folds
// interleaved folds instead (group k in fold k % max_folds): deterministic and bounded in time.
CrossValidation LeaveOneOut(const logs::SteadyTable& table, const CalibrationOptions& options,
                            bool by_throttle, std::size_t max_folds = 0);

// The status contract (identification/verdict.h) of a calibration: its checks over the fit, the
// label (options.labels.kv_rpm_per_v), the envelope of `table` and the held-out errors `cv`
// (nullptr: not computed).
identification::Verdict JudgeCalibration(const CalibrationResult& r, const logs::SteadyTable& table,
                                         const CalibrationOptions& options, const CrossValidation* cv);
// The cross-validation the verdict uses: leave-one-out (by throttle level where the log has a
// throttle, else by row) up to 15 groups, else 10 interleaved folds.
CrossValidation CrossValidateForVerdict(const logs::SteadyTable& table, const CalibrationOptions& options);

// Table operations (moved to logs/table_ops.h; kept here for the callers of this namespace).
using logs::MergeLogs;
using logs::SelectRows;

}  // namespace dynosize::calibration
