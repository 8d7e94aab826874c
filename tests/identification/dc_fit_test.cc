// identification/dc_fit.h: the plain DC model fitted to a log. On a table the DC model itself
// generated (a lossless chopper, U = throttle*VDC), the fit returns its R and Io and predicts
// every row exactly, with the label's Kv held or fitted.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "identification/dc_fit.h"
#include "model/dc_motor.h"

namespace dynosize::identification {
namespace {

// Rows of a 900 rpm/V, 0.09 ohm, 0.7 A DC motor at 12 and 16 V over throttle and torque.
logs::SteadyTable DcGeneratedTable(const DcMotor& m) {
  logs::SteadyTable t;
  for (double vdc : {12.0, 16.0}) {
    for (double tr : {0.3, 0.5, 0.7, 0.9, 1.0}) {
      const double q = 0.02 + 0.15 * tr * tr;
      const DcPoint p = DcAtThrottleTorque(m, vdc, tr, q);
      t.Mutable(logs::Column::kVdcV).push_back(vdc);
      t.Mutable(logs::Column::kThrottle).push_back(tr);
      t.Mutable(logs::Column::kTorqueNm).push_back(q);
      t.Mutable(logs::Column::kOmegaRadS).push_back(p.omega_rad_s);
      t.Mutable(logs::Column::kIdcA).push_back(p.idc_a);
      t.source_line.push_back(t.source_line.size() + 2);
    }
  }
  for (auto c : {logs::Column::kVdcV, logs::Column::kThrottle, logs::Column::kTorqueNm, logs::Column::kOmegaRadS,
                 logs::Column::kIdcA}) {
    t.info[static_cast<int>(c)].present = true;
  }
  return t;
}

TEST(DcFit, RecoversTheDcModelThatMadeTheTable) {
  DcMotor truth;
  truth.kv_rpm_per_v = 900.0;
  truth.r_ohm = 0.09;
  truth.io_a = 0.7;
  const logs::SteadyTable t = DcGeneratedTable(truth);
  std::vector<std::size_t> rows(t.rows());
  std::iota(rows.begin(), rows.end(), 0);
  for (double label : {0.0, 900.0}) {  // Kv fitted, then held at the (true) label
    const DcFit f = FitDcMotor(t, rows, 1.0, label);
    ASSERT_TRUE(f.ok);
    EXPECT_NEAR(f.motor.kv_rpm_per_v, 900.0, 1e-8);
    EXPECT_NEAR(f.motor.r_ohm, 0.09, 1e-10);
    EXPECT_NEAR(f.motor.io_a, 0.7, 1e-10);
    for (std::size_t i : rows) {
      const DcRowPrediction p = PredictDcRow(f.motor, t, i, 1.0);
      const double w = t.Get(logs::Column::kOmegaRadS)[i];
      EXPECT_NEAR(p.omega_at_torque_rad_s, w, 1e-8 * w);
      EXPECT_NEAR(p.omega_from_idc_rad_s, w, 1e-8 * w);
      EXPECT_NEAR(p.idc_at_torque_a, t.Get(logs::Column::kIdcA)[i], 1e-9);
    }
  }
  // A wrong label moves R, not Kv: the held Kv is the label's.
  EXPECT_DOUBLE_EQ(FitDcMotor(t, rows, 1.0, 1000.0).motor.kv_rpm_per_v, 1000.0);
}

// A command with a throttle offset (the ESC delivers more than the command: dead band -0.08,
// model/circuit.h): corrected by the offset dynosize's fit found, the DC fit recovers the motor;
// taken at face value it does not (issue 55: Kv and R absorb the offset).
TEST(DcFit, TheThrottleOffsetOfTheFitCorrectsTheDuty) {
  DcMotor truth;
  truth.kv_rpm_per_v = 900.0;
  truth.r_ohm = 0.09;
  truth.io_a = 0.7;
  const double deadband = -0.08;
  logs::SteadyTable t = DcGeneratedTable(truth);
  for (std::size_t i = 0; i < t.rows(); ++i) {  // the same rows, commanded with the offset
    const double effective = t.Get(logs::Column::kThrottle)[i];
    t.Mutable(logs::Column::kThrottle)[i] = deadband + effective * (1.0 - deadband);
  }
  std::vector<std::size_t> rows(t.rows());
  std::iota(rows.begin(), rows.end(), 0);
  const DcFit f = FitDcMotor(t, rows, 1.0, 0.0, deadband);
  ASSERT_TRUE(f.ok);
  EXPECT_NEAR(f.motor.kv_rpm_per_v, 900.0, 1e-6);
  EXPECT_NEAR(f.motor.r_ohm, 0.09, 1e-9);
  for (std::size_t i : rows) {
    const double w = t.Get(logs::Column::kOmegaRadS)[i];
    EXPECT_NEAR(PredictDcRow(f.motor, t, i, 1.0, deadband).omega_at_torque_rad_s, w, 1e-7 * w);
  }
  const DcFit raw = FitDcMotor(t, rows, 1.0, 0.0);
  EXPECT_GT(std::fabs(raw.motor.kv_rpm_per_v / 900.0 - 1.0), 0.02);  // the offset absorbed by Kv and R
}

TEST(DcFit, TooFewRowsIsNotOk) {
  DcMotor m;
  m.kv_rpm_per_v = 900.0;
  m.r_ohm = 0.09;
  const logs::SteadyTable t = DcGeneratedTable(m);
  const DcFit f = FitDcMotor(t, {3}, 1.0);
  EXPECT_FALSE(f.ok);
  EXPECT_NE(f.why.find("fewer than 2 rows"), std::string::npos);
}

// A label far above the motor's Kv leaves a negative resistance to explain the voltage: a careful
// user keeps none, and the baseline says it cannot be fitted instead of printing its errors.
TEST(DcFit, ANegativeResistanceIsNotAFit) {
  DcMotor m;
  m.kv_rpm_per_v = 900.0;
  m.r_ohm = 0.09;
  m.io_a = 0.7;
  const logs::SteadyTable t = DcGeneratedTable(m);
  std::vector<std::size_t> rows(t.rows());
  std::iota(rows.begin(), rows.end(), 0);
  const DcFit f = FitDcMotor(t, rows, 1.0, 600.0);  // KE too large: U - KE*omega < 0
  EXPECT_FALSE(f.ok);
  EXPECT_NE(f.why.find("negative"), std::string::npos) << f.why;
}

}  // namespace
}  // namespace dynosize::identification
