// The types of a calibration, below every stage of src/calibration: the options, the parameter
// estimates and the result (calibrate.h explains the fit; forward_model.h, prepare.h,
// joint_fit.h and starting_values.h use these without including calibrate.h, so that no module
// of the folder includes up).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "fit/nonlinear_least_squares.h"
#include "identification/parameters.h"
#include "logs/steady_table.h"
#include "logs/table_ops.h"
#include "model/drive.h"

namespace dynosize::calibration {

// The parameter table of src/identification/parameters.h; calibrate fits the base parameters,
// the first kBaseParamCount of it (ParamName: "ke_v_s_per_rad", ..., "deadband").
using identification::kBaseParamCount;
using identification::Param;
using identification::ParamName;

struct CalibrationOptions {
  // Loss for the residuals (in percent of the column's median magnitude) and its scale a:
  // residuals beyond a percent count linearly (Huber).
  LossType loss = LossType::kHuber;
  double loss_scale_percent = 2.0;
  // After the first fit, a row whose largest |residual| exceeds outlier_sigmas robust standard
  // deviations (1.4826*MAD of all residuals, floored at outlier_floor_percent) is dropped and
  // the fit repeated once. 0 disables.
  double outlier_sigmas = 6.0;
  double outlier_floor_percent = 1.0;
  // Rows below this fraction of the largest measured speed are dropped (motor not turning).
  double min_speed_fraction = 0.02;
  // Rows below this throttle are dropped (ESC dead band: no voltage yet).
  double min_throttle = 0.02;
  // Throttle assumed for every row when the log has no throttle column.
  double assumed_throttle = 1.0;
  // Saturation knee grid: candidates knee_min, knee_min + knee_step, ... below 1.
  double knee_min = 0.5;
  double knee_step = 0.02;
  // A knee is kept when the F statistic (drop in cost per extra parameter over the residual
  // variance) exceeds this (about the 0.1 % point of F(2, 30)).
  double knee_min_f = 10.0;
  // Priors. A motor prior (e.g. a datasheet entry) anchors KE, Rm, Io by Gaussian priors with
  // these relative standard deviations, and supplies values that the data cannot identify.
  std::optional<MotorParams> motor_prior;
  double prior_ke_rel_sigma = 0.10;
  double prior_rm_rel_sigma = 0.50;
  double prior_io_rel_sigma = 0.50;
  // ESC values used where the data cannot identify them (default: the ideal ESC, RESC = 0, no
  // saturation).
  std::optional<EscParams> esc_prior;
  // The motor's label (--kv-label, --rm-label, --io-label/--io-label-v): Gaussian priors of the
  // widths in identification/parameters.h; a label takes precedence over motor_prior.
  identification::LabelPriors labels;
  // Throttle offset / dead band (docs/model.md section 9, EscParams::deadband): with three or more
  // throttle levels the fit is repeated with it free and kept when it beats "no offset" by the
  // F test of knee_min_f (one extra parameter).
  bool fit_throttle_offset = true;
  // Robust outlier pass: never more than this fraction of the rows, never a whole throttle level.
  double max_outlier_fraction = 0.10;
  LevenbergMarquardtOptions solver;  // max iterations etc.; loss fields are set from the above

  CalibrationOptions() { solver.max_num_iterations = 200; }
  // Names the first violated rule (field, value, rule) in *error.
  bool IsValid(std::string* error) const;
};

struct ParamEstimate {
  double value = 0.0;
  // Standard error from the final Jacobian; NaN when the parameter was not fitted or the fit
  // has no degrees of freedom.
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  bool fitted = false;        // a free parameter of the fit (else held at a prior / default)
  bool identifiable = false;  // the data determine it (fitted and not in a flat direction)
  bool at_bound = false;
  std::string note;           // why it is not identifiable, or how it was obtained
};

struct ColumnFit {
  logs::Column column = logs::Column::kIdcA;
  std::size_t points = 0;
  double rmse = 0.0;          // in the column's SI unit
  double rmse_percent = 0.0;  // rmse / rms of the measured values * 100
  double median_abs_percent = 0.0;  // median |pred - meas| / |meas| * 100
};

// A row the fit left out, with the reason (every dropped row is listed).
struct DroppedRow {
  std::size_t row = 0;          // row of the table
  std::size_t source_line = 0;  // line in the log file (0 when unknown)
  std::string reason;
};

struct CalibrationResult {
  bool solve_called = false;
  bool converged = false;
  std::string message = "Calibrate was not called.";
  std::string mode;  // "ac", "dc", "dc_no_throttle"
  MotorParams motor;
  EscParams esc;
  std::array<ParamEstimate, kBaseParamCount> params;
  // Where motor.io_a comes from: "fitted" (torque or no-load rows), "label" (--io-label), "motor
  // prior", "no-load prior" (catalog/noload_prior.h: the log cannot identify Io and nothing else
  // states it; never 0).
  std::string io_source;
  double r_total_ohm = 0.0;  // Rm + RESC, identifiable whenever Rm or RESC is fitted
  double r_total_standard_error = std::numeric_limits<double>::quiet_NaN();
  std::vector<ColumnFit> fit;  // one per predicted measured column
  std::size_t points_used = 0;
  std::size_t points_dropped = 0;  // by this fit (below speed / throttle floor, outliers)
  std::vector<logs::DropCount> dropped;
  std::vector<DroppedRow> dropped_rows;  // every row dropped by this fit, with its reason
  // Condition number of the unit-column-scaled Jacobian of the final fit (sigma_max/sigma_min).
  double condition_number = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> unidentifiable_directions;  // from the LM test
  std::vector<std::string> warnings;
  LevenbergMarquardtSummary solver_summary;  // of the final solve

  const ParamEstimate& param(Param p) const { return params[static_cast<int>(p)]; }
  std::string BriefReport() const;  // one line
  std::string FullReport() const;   // parameters with errors and flags, column fit, warnings
};

}  // namespace dynosize::calibration
