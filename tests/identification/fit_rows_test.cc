// The row rules calibrate and diagnose share (identification/fit_rows.h): each rule can reject
// a row, in its documented order, and a NaN reading is never used.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/units.h"
#include "identification/fit_rows.h"
#include "identification/parameters.h"
#include "model/drive.h"

namespace dynosize::identification {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A row: 500 rad/s of at most 1000, throttle 0.5, 12 V; min speed fraction 0.1, min throttle 0.05.
const char* Reject(double w, double tr, double vdc, bool has_tr = true, bool speed_unknown = false) {
  return RowRejection(w, 1000.0, 0.1, has_tr, tr, 0.05, vdc, speed_unknown);
}

TEST(IdentificationFitRows, UsesATurningRowWithThrottleAndVoltage) {
  EXPECT_EQ(Reject(500.0, 0.5, 12.0), nullptr);
}

TEST(IdentificationFitRows, EachRuleRejectsWithItsReason) {
  EXPECT_EQ(std::string(Reject(100.0, 0.5, 12.0)), "speed below min_speed_fraction of the largest");  // not > 10 %
  EXPECT_EQ(std::string(Reject(500.0, 0.04, 12.0)), "throttle below min_throttle");
  EXPECT_EQ(std::string(Reject(500.0, 0.5, 0.0)), "vdc_v not positive");
  // The speed rule comes first when several fail.
  EXPECT_EQ(std::string(Reject(0.0, 0.0, -1.0)), "speed below min_speed_fraction of the largest");
}

TEST(IdentificationFitRows, NanReadingsAreRejected) {
  EXPECT_NE(Reject(kNaN, 0.5, 12.0), nullptr);
  EXPECT_NE(Reject(500.0, 0.5, kNaN), nullptr);
}

TEST(IdentificationFitRows, ThrottleRuleOnlyWithAThrottleColumn) {
  EXPECT_EQ(Reject(500.0, 0.0, 12.0, /*has_tr=*/false), nullptr);
}

TEST(IdentificationFitRows, UnmeasuredSpeedIsNotASpeedRejection) {
  // A DriveCalc no-load row (n = 0) still measures Io: only its voltage and throttle are checked.
  EXPECT_EQ(Reject(0.0, 0.5, 12.0, true, /*speed_unknown=*/true), nullptr);
  EXPECT_EQ(std::string(Reject(0.0, 0.5, 0.0, true, true)), "vdc_v not positive");
}

TEST(IdentificationFitRows, ThrottleLevelsRoundedDistinctAscending) {
  const std::vector<double> levels = ThrottleLevels({0.5, 0.2, 0.5004, 0.2001, 1.0, 0.7996});
  ASSERT_EQ(levels.size(), 4u);
  EXPECT_DOUBLE_EQ(levels[0], 0.2);
  EXPECT_DOUBLE_EQ(levels[1], 0.5);
  EXPECT_DOUBLE_EQ(levels[2], 0.8);
  EXPECT_DOUBLE_EQ(levels[3], 1.0);
  EXPECT_TRUE(ThrottleLevels({}).empty());
}

TEST(IdentificationFitRows, MedianMagnitudeOverTheChosenRows) {
  const std::vector<double> column = {-4.0, 100.0, 2.0, -3.0, 1.0};
  EXPECT_DOUBLE_EQ(MedianMagnitude(column, {0, 2, 3}), 3.0);     // |-4|, 2, |-3|
  EXPECT_DOUBLE_EQ(MedianMagnitude(column, {0, 2, 3, 4}), 2.5);  // even count: mean of 2 and 3
  EXPECT_TRUE(std::isnan(MedianMagnitude(column, {})));
}

TEST(IdentificationFitRows, MedianPercentScalesMarkEmptyColumnsUnmeasured) {
  logs::SteadyTable t;
  t.source_line = {2, 3, 4};
  t.Mutable(logs::Column::kOmegaRadS) = {100.0, 200.0, 400.0};
  t.Mutable(logs::Column::kIdcA) = {0.0, 0.0, 0.0};  // logged but all zero: nothing to compare
  t.info[static_cast<int>(logs::Column::kOmegaRadS)].present = true;
  t.info[static_cast<int>(logs::Column::kIdcA)].present = true;
  std::array<bool, kMeasCount> measured{};
  measured[kMOmega] = measured[kMIdc] = true;
  const std::array<double, kMeasCount> s = MedianPercentScales(t, {0, 1, 2}, &measured);
  EXPECT_DOUBLE_EQ(s[kMOmega], 100.0 / 200.0);  // a residual of 2 rad/s is 1 %
  EXPECT_TRUE(measured[kMOmega]);
  EXPECT_EQ(s[kMIdc], 0.0);
  EXPECT_FALSE(measured[kMIdc]);
  EXPECT_EQ(s[kMIrms], 0.0);  // not measured to begin with: untouched
  EXPECT_FALSE(measured[kMIrms]);
}

TEST(IdentificationFitRows, TermResidualIsAPercentOfTheScale) {
  const ResidualTerm term{kMIdc, 10.0, 100.0 / 20.0};  // 10 A measured, scale 20 A
  const double pred[kMeasCount] = {0.0, 11.0, 0.0, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(TermResidual(term, pred), 5.0);  // 1 A of 20 A
}

// Ten rows at two throttle levels; rows 2, 7 and 9 are far off (rmax in percent).
TEST(IdentificationFitRows, OutliersWorstFirstWithinTheCap) {
  const std::vector<double> rmax = {1, 2, 50, 1, 2, 1, 2, 80, 1, 30};
  const std::vector<double> tr = {0.3, 0.3, 0.3, 0.3, 0.3, 0.6, 0.6, 0.6, 0.6, 0.6};
  // 20 % of 10 rows: the two worst go, the third is spared.
  const OutlierSelection sel = SelectOutlierRows(rmax, tr, true, 10.0, 0.2, 0);
  EXPECT_EQ(sel.cap, 2u);
  EXPECT_EQ(sel.dropped, (std::vector<std::size_t>{7, 2}));
  EXPECT_EQ(sel.spared, 1u);
}

TEST(IdentificationFitRows, OutliersNeverAWholeThrottleLevel) {
  // Level 0.3 has two rows, both off: only the worse goes; level 0.6 keeps its single row.
  const std::vector<double> rmax = {40, 60, 90};
  const std::vector<double> tr = {0.3, 0.3, 0.6};
  const OutlierSelection sel = SelectOutlierRows(rmax, tr, true, 10.0, 1.0, 0);
  EXPECT_EQ(sel.dropped, (std::vector<std::size_t>{1}));
  EXPECT_EQ(sel.spared, 2u);
  // Without a throttle column the levels do not protect rows.
  EXPECT_EQ(SelectOutlierRows(rmax, tr, false, 10.0, 1.0, 0).dropped.size(), 3u);
}

TEST(IdentificationFitRows, OutliersLeaveMinKeptRows) {
  const std::vector<double> rmax = {90, 80, 70, 1, 1};
  const std::vector<double> tr(5, 1.0);
  // A drop needs at least 4 rows left before it: 5 -> 4 -> 3, then no more.
  const OutlierSelection sel = SelectOutlierRows(rmax, tr, false, 10.0, 1.0, 4);
  EXPECT_EQ(sel.dropped, (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(sel.spared, 1u);
}

// Eq 48 on exact rows U = R*I + KE*omega: the linear start recovers KE and R to rounding, and
// with KE held at the truth the held-KE resistance is R.
TEST(LinearCircuitStartTest, RecoversKeAndRFromExactRows) {
  const double ke = 0.0062, r = 0.083;
  std::vector<double> cur, omega, u;
  for (int k = 0; k < 8; ++k) {
    cur.push_back(1.0 + 3.0 * k);
    omega.push_back(400.0 + 150.0 * k - 9.0 * k * k);
    u.push_back(r * cur.back() + ke * omega.back());
  }
  const CircuitStart s = LinearCircuitStart(cur, omega, u);
  EXPECT_NEAR(s.ke_v_s_per_rad, ke, 1e-12);
  EXPECT_NEAR(s.r_total_ohm, r, 1e-10);
  EXPECT_NEAR(ResistanceWithKeHeld(cur, omega, u, ke), r, 1e-12);
}

// Rows whose least-squares KE is negative (exact rows of R = 1 ohm, KE = -0.001: speed not
// following the voltage): KE falls back on max(U/omega), the no-load relation; R stays as solved.
// Without current the held-KE resistance is 0.
TEST(LinearCircuitStartTest, FallsBackOnTheNoLoadRelation) {
  const std::vector<double> cur = {1.0, 2.0, 3.0}, omega = {100.0, 300.0, 200.0}, u = {0.9, 1.7, 2.8};
  const CircuitStart s = LinearCircuitStart(cur, omega, u);
  EXPECT_NEAR(s.ke_v_s_per_rad, 2.8 / 200.0, 1e-15);
  EXPECT_NEAR(s.r_total_ohm, 1.0, 1e-12);
  EXPECT_EQ(ResistanceWithKeHeld({0.0, 0.0}, {10.0, 20.0}, {1.0, 2.0}, 0.006), 0.0);
}

// TorquePerAmpereVsLabel: a physical drive of the label's Kv (KT just below the energy bound, an
// ESC with losses) gives at most 1 at full command, whatever the load (0.93 here); a torque sensor
// reading 40 % high puts the log beyond any motor within the label's 25 % tolerance.
TEST(IdentificationFitRows, TorquePerAmpereOfAPhysicalDriveIsAtMostOne) {
  const double kv = 1000.0;
  MotorParams m;
  m.ke_v_s_per_rad = KeFromLabelKv(kv);
  m.kt_nm_per_a = 0.98 * kPacPerVllIrms * m.ke_v_s_per_rad;
  m.rm_ohm = 0.08;
  m.io_a = 0.6;
  EscParams e;
  e.c1 = 1.12;
  e.c0 = 0.02;
  e.resc_ohm = 0.01;
  const Drive drive(m, e);
  logs::SteadyTable t;
  auto& tr = t.Mutable(logs::Column::kThrottle);
  auto& q = t.Mutable(logs::Column::kTorqueNm);
  auto& idc = t.Mutable(logs::Column::kIdcA);
  for (double load : {0.05, 0.2, 0.5}) {
    for (double throttle : {0.5, 1.0}) {
      const OperatingPoint p = drive.AtTorque(14.8, throttle, load);
      tr.push_back(throttle);
      q.push_back(p.torque_nm);
      idc.push_back(p.idc_a);
      t.source_line.push_back(t.source_line.size() + 2);
    }
  }
  for (auto c : {logs::Column::kThrottle, logs::Column::kTorqueNm, logs::Column::kIdcA}) {
    t.info[static_cast<int>(c)].present = true;
  }
  const double r = TorquePerAmpereVsLabel(t, kv);
  EXPECT_LE(r, 1.0);
  EXPECT_GT(r, 0.8);  // the losses above are a few percent, not 20
  for (double& x : q) x *= 1.4;
  EXPECT_GT(TorquePerAmpereVsLabel(t, kv), 1.0 + kKvLabelMaxRelDeviation);
  EXPECT_TRUE(std::isnan(TorquePerAmpereVsLabel(t, 0.0)));
  for (double& x : tr) x *= 0.9;  // no row at full command: nothing to compare
  EXPECT_TRUE(std::isnan(TorquePerAmpereVsLabel(t, kv)));
}

}  // namespace
}  // namespace dynosize::identification
