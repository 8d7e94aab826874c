#include "calibration/drivecalc_refit.h"

#include <cmath>
#include <map>

#include "common/error.h"

namespace dynosize::calibration {

using logs::Column;

std::vector<std::size_t> RowsOfMotor(const logs::SteadyTable& t, long long motor_id) {
  std::vector<std::size_t> rows;
  const auto& id = t.Get(Column::kMotorId);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (std::llround(id[i]) == motor_id) rows.push_back(i);
  }
  return rows;
}

DriveCalcRefit RefitDriveCalc(const logs::SteadyTable& t, const DriveCalcRefitOptions& o) {
  if (!t.Has(Column::kMotorId) || !t.Has(Column::kNoLoad)) {
    throw DataError(t.file + ": RefitDriveCalc needs the motor_id and no_load columns (read MData.csv "
                    "with format drivecalc, all motors)");
  }
  std::map<long long, std::vector<std::size_t>> by_motor;
  const auto& id = t.Get(Column::kMotorId);
  for (std::size_t i = 0; i < t.rows(); ++i) by_motor[std::llround(id[i])].push_back(i);
  DriveCalcRefit out;
  const auto& nl = t.Get(Column::kNoLoad);
  for (const auto& [motor, rows] : by_motor) {
    ++out.motors_seen;
    DriveCalcMotorFit f;
    f.motor_id = motor;
    for (std::size_t i : rows) (nl[i] != 0.0 ? f.no_load_points : f.loaded_points)++;
    if (f.no_load_points < o.min_no_load_points || f.loaded_points < o.min_loaded_points) {
      ++out.motors_too_few_points;
      continue;
    }
    logs::SteadyTable one = SelectRows(t, rows);
    one.file = t.file + " motor_id " + std::to_string(motor);
    try {
      f.result = Calibrate(one, o.calibration);
    } catch (const Error& e) {
      out.failures.push_back("motor " + std::to_string(motor) + ": " + e.what());
      continue;
    }
    out.fits.push_back(std::move(f));
  }
  return out;
}

}  // namespace dynosize::calibration
