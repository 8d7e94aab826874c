#include "calibration/drivecalc_refit.h"

#include <cmath>
#include <map>

#include "common/error.h"
#include "fit/linear_least_squares.h"

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

DriveCalcLooErrors DriveCalcLeaveOneOut(const logs::SteadyTable& t, const DriveCalcRefit& refit,
                                        const DriveCalcRefitOptions& o) {
  DriveCalcLooErrors out;
  const auto& u = t.Get(Column::kVdcV);
  const auto& w = t.Get(Column::kOmegaRadS);
  const auto& cur = t.Get(Column::kIdcA);
  const auto& nl = t.Get(Column::kNoLoad);
  for (const auto& f : refit.fits) {
    const std::vector<std::size_t> rows = RowsOfMotor(t, f.motor_id);
    const logs::SteadyTable one = SelectRows(t, rows);
    const CrossValidation cv = LeaveOneOut(one, o.calibration, false);
    out.model_idc_loaded.insert(out.model_idc_loaded.end(), cv.idc_loaded_error_percent.begin(),
                                cv.idc_loaded_error_percent.end());
    out.model_omega.insert(out.model_omega.end(), cv.omega_from_idc_error_percent.begin(),
                           cv.omega_from_idc_error_percent.end());
    // The baseline fits U = n/Kv + R*I: rows without a speed reading (no-load, n = 0) cannot
    // enter it, nor be predicted by it.
    std::vector<std::size_t> with_speed;
    for (std::size_t i : rows) {
      if (w[i] != 0.0) with_speed.push_back(i);
    }
    for (std::size_t k = 0; k < with_speed.size(); ++k) {
      Eigen::MatrixXd a(static_cast<Eigen::Index>(with_speed.size() - 1), 2);
      Eigen::VectorXd b(a.rows());
      Eigen::Index j = 0;
      for (std::size_t q = 0; q < with_speed.size(); ++q) {
        if (q == k) continue;
        a(j, 0) = w[with_speed[q]];
        a(j, 1) = cur[with_speed[q]];
        b[j] = u[with_speed[q]];
        ++j;
      }
      const auto s = SolveLinearLeastSquares(a, b);
      const double ke = s.coefficients[0], r = s.coefficients[1];
      const std::size_t i = with_speed[k];
      if (nl[i] == 0.0 && r != 0.0) out.baseline_idc_loaded.push_back(((u[i] - ke * w[i]) / r - cur[i]) / cur[i] * 100.0);
      if (ke != 0.0) out.baseline_omega.push_back(((u[i] - r * cur[i]) / ke - w[i]) / w[i] * 100.0);
    }
  }
  return out;
}

}  // namespace dynosize::calibration
