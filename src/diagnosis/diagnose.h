// Diagnosis: what the first-order motor + ESC model (docs/model.md, src/model/drive.h)
// gets wrong in a measured log, which physical mechanism explains it, and how much better the
// model predicts held-out data once that mechanism is part of it.
//
// Method
//  1. Rows: the steady rows of the log with the motor turning (as in src/calibration). Known
//     inputs per row are VDC, the throttle TR and either the shaft torque Q (torque column or a
//     no-load row: Q = 0) or the measured speed omega; every other measured column among
//     omega_rad_s, idc_a, irms_a, vll_rms_v, pac_w is predicted by the model (Drive::AtTorque or
//     Drive::AtSpeed, so the extensions act exactly as in simulate). Each residual is in percent
//     of its effective spread (errors in variables): sqrt(y^2 + (dy/dVDC*VDC)^2 + (dy/dx*x)^2),
//     x the speed or torque input, derivatives from a preliminary first-order fit, floored at 5 %
//     of the column's median. With sensors of equal relative noise the residuals are then
//     homoscedastic, as the F test needs (at low throttle I = (U - KE*omega)/R is a small
//     difference, and plain percent errors there would call input noise an effect), and columns
//     in different units weigh alike.
//  2. Base parameters free in every model (as src/calibration/calibrate.h explains what each
//     column set identifies): KE; R = Rm (+ RESC with AC columns); Io with a known torque; KT with
//     torque + AC columns (else KT = sqrt(27/10)*KE, section 5); C1, C0 with idc_a, several
//     throttle levels and torque or AC columns (else held at the ideal ESC of eq 56 or --esc).
//  3. Candidate extensions (docs/model.md section 9), each adding its own parameters:
//       esc_saturation                  tr_sat, sat_slope          (section 7; tr_sat profiled)
//       speed_dependent_no_load_current io1_a_s_per_rad            (needs a known torque)
//       winding_temperature_rise        rth_k_per_w
//       torque_constant_droop           kt_droop_per_a             (needs torque + current)
//       throttle_deadband               deadband
//       supply_resistance               rsupply_ohm                (VDC not measured at the ESC)
//     A candidate the data cannot test (no column that it changes) is listed as not testable.
//  4. Outliers: a Huber fit of the base model with every testable extension at once (which can
//     follow any of the effects, so effect rows are not mistaken for outliers) flags rows whose
//     residual exceeds outlier_sigmas robust standard deviations (1.4826*MAD); they are left out
//     of every later fit and score, and reported.
//  5. Greedy forward selection. For the current model M and each candidate c: least-squares fit
//     of M+c, F test of the nested pair (F = (SSE_M - SSE_M+c)/q / (SSE_M+c/(N - p)), q extra
//     parameters; the profiled knee counts as 2 and its p value is multiplied by the number of
//     knees tried, Bonferroni, and by the number of candidates tested at the step, so that alpha
//     is the step's false-alarm rate), AICc, and k-fold cross-validated rms error (folds of rows,
//     seeded; every score is on rows the fit did not see). A candidate is significant when
//     p < alpha, AICc falls, its own parameter is at least 2 standard errors from "no effect"
//     and not clipped at a bound of its physical range, and the CV error falls by at least
//     min_gain_percent. In the folds the knee is re-profiled among the full-data knee's grid
//     neighbours (a small leak of the knee choice, documented rather than hidden). The best
//     significant one (largest CV gain) is added and the search repeats; it stops when nothing
//     significant is left or after max_findings.
//  6. Ambiguity: when another significant candidate comes within ambiguity_aicc of the winner's
//     AICc or reaches ambiguity_gain_ratio of its CV gain, and is no longer significant once the
//     winner is in the model, the data cannot tell the two apart: both are reported, with the
//     measurement that would separate them.
//
// Files of src/diagnosis (the parameter table and the row rules shared with calibrate are in
// src/identification):
//   diagnose.h/.cc       this interface and Diagnose(): the stages in order, the verdict, the
//                        calibration entry
//   model_fit.h/.cc      one model's fit: parameter slots, predictions, the bounded fit with its
//                        profiled knee, the k-fold cross-validation
//   prepare.h/.cc        stages 1-6: rows and terms, the first-order model (free parameters,
//                        starts, scales, bounds), folds, effective-variance weights, outliers
//   baseline.h/.cc       stages 7-8: the first-order model cross-validated, worst points, trends
//   candidates.h/.cc     the hidden-effect extensions (steps 3, 5, 6 above): their slots, their
//                        fits and scores, the forward selection, ambiguities
//   diagnose_report.cc   FullReport
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fit/statistics.h"
#include "identification/verdict.h"
#include "logs/steady_table.h"
#include "model/drive.h"

namespace dynosize::diagnosis {

enum class Cause : int {
  kEscSaturation = 0,
  kSpeedDependentNoLoadCurrent,
  kWindingTemperatureRise,
  kTorqueConstantDroop,
  kThrottleDeadband,
  kSupplyResistance,
};
inline constexpr int kCauseCount = 6;
// "esc_saturation", "speed_dependent_no_load_current", ...
const char* CauseId(Cause c);
// One sentence: the mechanism and its law.
const char* CauseDescription(Cause c);

struct DiagnoseOptions {
  int folds = 5;             // k of the k-fold cross-validation (>= 2)
  unsigned seed = 20260521;  // fold assignment (deterministic)
  // Significance level of the nested F test, per step (Bonferroni over the candidates tested).
  double alpha = 1e-3;
  // A finding must lower the cross-validated rms error (all columns, percent residuals) by at
  // least this many percent: a statistically significant but negligible change is not reported.
  double min_gain_percent = 1.0;
  double outlier_sigmas = 5.0;  // 0 disables the outlier screen
  double outlier_floor_percent = 0.2;  // floor of the robust sd (percent of the column median)
  // The screen never drops more than this fraction of the rows, nor a whole throttle level.
  double max_outlier_fraction = 0.10;
  // The motor's label Kv (rpm/V): the verdict checks the extended model's Kv against it.
  std::optional<double> kv_label_rpm_per_v;
  int max_findings = 3;
  // A significant runner-up within this AICc of the winner, or with at least this fraction of
  // its CV gain, that adds nothing once the winner is in the model, is reported as ambiguous.
  double ambiguity_aicc = 2.0;
  double ambiguity_gain_ratio = 0.5;
  double min_speed_fraction = 0.02;  // rows below this fraction of the top speed are dropped
  double min_throttle = 0.02;        // rows below this throttle are dropped
  double assumed_throttle = 1.0;     // every row's throttle when the log has none
  // Without a throttle column, no cause is named when the baseline CV error exceeds this
  // (percent rms): the rows are then not at assumed_throttle.
  double no_throttle_max_percent = 10.0;
  // Starting / held parameters (catalog entries, --motor / --esc); the base model is still
  // refitted on the log (its free parameters), the rest are held at these values.
  std::optional<MotorParams> motor;
  std::optional<EscParams> esc;
  // Where calibrate's model holds every finding (no finding, or only a throttle offset /
  // saturation knee that calibrate's own fit also keeps) and no catalog entry is given,
  // the entry and its status are calibrate's (src/calibration: one fit and one verdict per model
  // class, so both commands give a log the same status). Off: diagnose's own fit and
  // verdict always (the hidden-effect suites, which test detection, not the entry).
  bool calibration_entry = true;
  // Candidates to consider (default: all).
  std::vector<Cause> candidates = {Cause::kEscSaturation, Cause::kSpeedDependentNoLoadCurrent,
                                   Cause::kWindingTemperatureRise, Cause::kTorqueConstantDroop,
                                   Cause::kThrottleDeadband, Cause::kSupplyResistance};
  // Names the first violated rule (field, value, rule) in *error.
  bool IsValid(std::string* error) const;
};

// Cross-validated error of one model per predicted column.
struct ColumnError {
  logs::Column column = logs::Column::kIdcA;
  std::size_t points = 0;
  double rmse = 0.0;          // SI unit of the column
  double rmse_percent = 0.0;  // rmse / rms of the measured values * 100
};

// A point the (cross-validated) model misses most.
struct WorstPoint {
  std::size_t row = 0;          // row of the table
  std::size_t source_line = 0;  // line in the log file
  logs::Column column = logs::Column::kIdcA;
  double measured = 0.0;
  double predicted = 0.0;
  double error_percent = 0.0;  // (pred - meas)/meas*100
};

// How strongly the CV residuals depend on one variable: R^2 of a quadratic in the variable
// fitted to the residuals of one column, with the F-test p value of that regression.
struct ResidualTrend {
  std::string variable;  // "throttle", "rpm", "current_a", "vdc_v", "torque_nm", "time_s", "temp_c"
  logs::Column column = logs::Column::kIdcA;
  double r2 = 0.0;
  double p_value = 1.0;
  double slope_percent_per_range = 0.0;  // linear trend of the residual over the variable's range
  bool structured = false;               // p < alpha and r2 >= 0.2
};

struct CandidateScore {
  Cause cause = Cause::kEscSaturation;
  bool testable = false;
  std::string not_testable_reason;
  std::map<std::string, double> parameters;
  std::map<std::string, double> stderrs;
  double sse = 0.0;
  double aicc = 0.0;
  double delta_aicc = 0.0;  // vs the current model (negative = better)
  double f_statistic = 0.0;
  double p_value = 1.0;
  double cv_rms_percent = 0.0;  // all columns, percent residuals
  double gain_percent = 0.0;    // CV rms error reduction vs the current model
  bool significant = false;
  std::string note;  // why a candidate with p < alpha was not kept, when that is the reason
};

struct Finding {
  Cause cause = Cause::kEscSaturation;
  std::string description;
  std::map<std::string, double> parameters;
  std::map<std::string, double> stderrs;
  std::vector<ColumnError> cv_after;  // of the model with this and the earlier findings
  double gain_percent = 0.0;          // CV rms (all columns) reduction by this finding
  // Evidence: test statistics and the scores of every candidate at this step.
  double f_statistic = 0.0;
  double p_value = 1.0;
  double delta_aicc = 0.0;
  double max_abs_correlation = 0.0;  // of its parameters with the base parameters
  std::string most_correlated_with;
  std::vector<CandidateScore> step_scores;
};

struct Ambiguity {
  std::vector<Cause> causes;
  std::string reason;
  std::string measurement;  // what would separate them
};

// Held-out error (percent rms, all columns) up to which "no finding" may be called noise.
inline constexpr double kNoiseLevelPercent = 10.0;

struct DiagnoseResult {
  std::string file;
  std::string mode;  // "ac", "dc", "dc_no_throttle"
  std::size_t points_used = 0;
  std::vector<std::size_t> outlier_rows;  // rows left out by the outlier screen
  std::vector<std::string> outlier_reasons;  // per outlier row: its line and residual
  int cv_folds = 0;            // folds of the cross-validation (rows when leave_one_out)
  bool leave_one_out = false;  // fewer than 15 rows: each row left out in turn
  int baseline_cv_failed_folds = 0;
  int extended_cv_failed_folds = 0;
  // The status contract of the extended model (identification/verdict.h): diagnose --out writes
  // only an "ok" model.
  identification::Verdict verdict;
  // The verdict and extended_motor/extended_esc are calibrate's fit of the same model class
  // (DiagnoseOptions::calibration_entry).
  bool entry_from_calibration = false;
  std::vector<logs::Column> predicted_columns;
  std::vector<std::string> base_free_parameters;
  MotorParams base_motor;
  EscParams base_esc;
  std::vector<ColumnError> baseline_cv;
  double baseline_cv_rms_percent = 0.0;
  std::vector<WorstPoint> worst_points;      // baseline, CV predictions
  std::vector<ResidualTrend> residual_trends;  // baseline, CV residuals
  std::vector<Finding> findings;             // in the order selected (importance)
  // Scores of the candidates at the step where the search stopped (what came closest).
  std::vector<CandidateScore> last_step_scores;
  std::vector<Ambiguity> ambiguous;
  std::vector<CandidateScore> not_testable;  // candidates the columns cannot reveal
  MotorParams extended_motor;
  EscParams extended_esc;
  std::vector<ColumnError> extended_cv;
  double extended_cv_rms_percent = 0.0;
  std::vector<std::string> warnings;
  // Per row of the table: baseline and final CV predictions of each predicted column (NaN where
  // not predicted or not used), for figures.
  std::map<logs::Column, std::vector<double>> baseline_cv_prediction;
  std::map<logs::Column, std::vector<double>> extended_cv_prediction;
  std::vector<char> row_used;

  std::string FullReport() const;  // the readable report
};

// Runs the diagnosis. Throws DataError when the log lacks what any fit needs (speed, VDC, a
// predicted column, enough rows), UsageError for invalid options.
DiagnoseResult Diagnose(const logs::SteadyTable& table, const DiagnoseOptions& options = {});

// Upper tail of the F(d1, d2) distribution (p value of an F statistic): fit/statistics.h.
using fit::FDistributionUpperTail;

}  // namespace dynosize::diagnosis
