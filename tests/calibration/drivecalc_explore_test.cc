// Manual: leave-one-out on DriveCalc (exploration). Run with --gtest_also_run_disabled_tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "calibration/drivecalc_refit.h"
#include "fit/linear_least_squares.h"
#include "logs/log_reader.h"

namespace dynosize::calibration {
namespace {
using logs::Column;

double Med(std::vector<double> v) {
  for (double& x : v) x = std::fabs(x);
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() / 2];
}

#ifndef KOUT
#define KOUT 6.0
#endif
constexpr double kOut = KOUT;
constexpr LossType kLoss = LossType::kHuber;
constexpr double kScale = 2.0;

TEST(DriveCalcExplore, DISABLED_LeaveOneOut) {
  const std::string path = std::string(DYNOSIZE_SHARED_DIR) + "/data/drivecalc/MData.csv";
  if (!std::filesystem::exists(path)) GTEST_SKIP();
  const auto t = logs::ReadLog(path);
  auto t0 = std::chrono::steady_clock::now();
  const auto all = RefitDriveCalc(t);
  auto t1 = std::chrono::steady_clock::now();
  std::cout << "fits " << all.fits.size() << " failures " << all.failures.size() << " time "
            << std::chrono::duration<double>(t1 - t0).count() << " s\n";
  std::vector<double> bi, bw, ci, cw;
  const auto& U = t.Get(Column::kVdcV);
  const auto& W = t.Get(Column::kOmegaRadS);
  const auto& I = t.Get(Column::kIdcA);
  for (const auto& f : all.fits) {
    const auto rows = RowsOfMotor(t, f.motor_id);
    // baseline: U = n/Kv + R*I by OLS, loo
    for (std::size_t k = 0; k < rows.size(); ++k) {
      Eigen::MatrixXd a(rows.size() - 1, 2);
      Eigen::VectorXd b(rows.size() - 1);
      int j = 0;
      for (std::size_t q = 0; q < rows.size(); ++q) {
        if (q == k) continue;
        a(j, 0) = W[rows[q]];
        a(j, 1) = I[rows[q]];
        b[j] = U[rows[q]];
        ++j;
      }
      const auto s = SolveLinearLeastSquares(a, b);
      const std::size_t i = rows[k];
      const double ke = s.coefficients[0], r = s.coefficients[1];
      if (t.Get(Column::kNoLoad)[i] == 0.0) bi.push_back(((U[i] - ke * W[i]) / r - I[i]) / I[i] * 100);
      bw.push_back(((U[i] - r * I[i]) / ke - W[i]) / W[i] * 100);
    }
    const auto one = SelectRows(t, rows);
    CalibrationOptions co;
    co.outlier_sigmas = kOut;
    co.loss = kLoss;
    co.loss_scale_percent = kScale;
    const auto cv = LeaveOneOut(one, co, false);
    ci.insert(ci.end(), cv.idc_loaded_error_percent.begin(), cv.idc_loaded_error_percent.end());
    cw.insert(cw.end(), cv.omega_from_idc_error_percent.begin(), cv.omega_from_idc_error_percent.end());
  }
  std::cout << "baseline median |err| current " << Med(bi) << " % rpm " << Med(bw) << " % (n " << bi.size() << ")\n";
  std::cout << "calibrate median |err| current " << Med(ci) << " % (n " << ci.size() << ") rpm " << Med(cw)
            << " % (n " << cw.size() << ")\n";
}

}  // namespace
}  // namespace dynosize::calibration
