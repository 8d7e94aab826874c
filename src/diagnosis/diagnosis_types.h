// The types of a diagnosis, below every stage of src/diagnosis: the candidate causes, the options
// and the result (diagnose.h explains the method; prepare.h, model_fit.h, baseline.h and
// candidates.h use these without including diagnose.h, so that no module of the folder includes
// up).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "identification/trend_attribution.h"
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

// What the extended model's held-out residual of one column still follows: speed, accumulated
// heat or the command, named where the log separates them (identification/trend_attribution.h).
struct RemainingTrend {
  logs::Column column = logs::Column::kIdcA;
  identification::TrendAttribution attribution;
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
  std::vector<RemainingTrend> remaining_trends;  // extended model, CV residuals; structured ones only
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

}  // namespace dynosize::diagnosis
