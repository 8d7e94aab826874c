// Refitting the DriveCalc motor database from its own measurement points (MData.csv).
//
// DriveCalc stores Kv, Rm and loss terms per motor, but its Rm is about 1.6x below what its own
// (U, n, I) points imply (shared/data/drivecalc/README.md). Each motor's points - full-throttle
// runs on different propellers and batteries, plus no-load runs - are fitted with Calibrate()
// in its no-throttle mode (calibrate.h): every row at full throttle with the ideal ESC, so
//     U = R_dc*I + omega/Kv_dc,   R_dc = R/(kv*g),  Kv_dc = kv/KE,  g = 1.1095  (docs/model.md 6, 8)
// loaded rows predict the current from (U, n), no-load rows the speed and the current from U
// (Q = 0, I = Io). The fitted R is Rm + RESC + wiring of the measurement set-up.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "calibration/calibrate.h"
#include "logs/steady_table.h"

namespace dynosize::calibration {

struct DriveCalcRefitOptions {
  CalibrationOptions calibration;
  std::size_t min_no_load_points = 1;  // rows with IsNoLoad = 1 (and rpm measured)
  std::size_t min_loaded_points = 3;
};

struct DriveCalcMotorFit {
  long long motor_id = 0;
  std::size_t no_load_points = 0;
  std::size_t loaded_points = 0;
  CalibrationResult result;
};

struct DriveCalcRefit {
  std::vector<DriveCalcMotorFit> fits;  // by increasing motor id
  std::size_t motors_seen = 0;
  std::size_t motors_too_few_points = 0;
  std::vector<std::string> failures;    // "motor 17: <error>"
};

// `mdata` is MData.csv read with format drivecalc and all motors (motor_id and no_load columns).
// Throws DataError when those columns are absent. Deterministic: same input, same output.
DriveCalcRefit RefitDriveCalc(const logs::SteadyTable& mdata, const DriveCalcRefitOptions& options = {});

// Leave-one-out prediction errors over every motor of `refit` (percent, signed):
//  - model: this calibration refitted without the row (Calibrate + PredictRow): DC current of
//    loaded rows from (U, n), speed of every row from (U, I);
//  - baseline: the plain per-motor least-squares fit U = n/Kv + R*I (QR, no intercept), the
//    same two predictions, same rows.
struct DriveCalcLooErrors {
  std::vector<double> model_idc_loaded, model_omega;
  std::vector<double> baseline_idc_loaded, baseline_omega;
};
DriveCalcLooErrors DriveCalcLeaveOneOut(const logs::SteadyTable& mdata, const DriveCalcRefit& refit,
                                        const DriveCalcRefitOptions& options = {});

// Rows of one motor.
std::vector<std::size_t> RowsOfMotor(const logs::SteadyTable& mdata, long long motor_id);

}  // namespace dynosize::calibration
