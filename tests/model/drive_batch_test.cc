#include "model/drive_batch.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "common/units.h"
#include "model/paper_drive.h"

namespace dynosize {
namespace {

// The batch runs Drive's expressions in Drive's order, so every number is compared to the bit
// (no tolerance): a vectorised loop that reordered an operation would show here.
std::uint64_t Bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// The paper's pair (model/paper_drive.h) with ratings low enough that the grid crosses each.
MotorParams RatedMotor() {
  MotorParams m = paper_drive::Motor();
  m.max_current_a = 25.0;
  m.max_power_w = 150.0;
  return m;
}
EscParams RatedEsc() {
  EscParams e = paper_drive::Esc();
  e.max_current_a = 30.0;
  e.vdc_max_v = 16.8;
  return e;
}

// A seeded grid over VDC 4-20 V (past the ESC's 16.8 V), throttle -0.1..1.1 with points on the
// knee (0.9) and at 0 and 1, torque -0.02..0.4 N*m (past the stall torque and the current
// ratings; negative: the motor overruns), speed -500..40,000 rpm (past no-load speed: the
// inverse needs a throttle above 1).
struct Grid {
  std::vector<double> vdc, throttle, torque, omega;
};
Grid SeededGrid(std::size_t n) {
  std::mt19937 rng(2025);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Grid g;
  for (std::size_t i = 0; i < n; ++i) {
    g.vdc.push_back(4.0 + 16.0 * u(rng));
    const double specials[] = {0.0, 0.9, 1.0, 0.9 + 1e-12};
    g.throttle.push_back(i % 7 == 0 ? specials[(i / 7) % 4] : -0.1 + 1.2 * u(rng));
    g.torque.push_back(i % 11 == 0 ? 0.0 : -0.02 + 0.42 * u(rng));
    g.omega.push_back(RpmToRadPerSec(i % 13 == 0 ? 0.0 : -500.0 + 40500.0 * u(rng)));
  }
  return g;
}

OperatingPoint PointByPoint(const Drive& d, BatchMode mode, const Grid& g, std::size_t i) {
  switch (mode) {
    case BatchMode::kInverse: return d.Inverse(g.vdc[i], g.torque[i], g.omega[i]);
    case BatchMode::kAtTorque: return d.AtTorque(g.vdc[i], g.throttle[i], g.torque[i]);
    case BatchMode::kAtSpeed: break;
  }
  return d.AtSpeed(g.vdc[i], g.throttle[i], g.omega[i]);
}

// Runs the batch and the scalar path on the grid; returns the union of the limits seen.
std::uint32_t ExpectBatchEqualsPointByPoint(const Drive& d, BatchMode mode, std::size_t n, const std::string& what) {
  const Grid g = SeededGrid(n);
  const PointColumnsStorage out(n);
  BatchInputs in;
  in.vdc_v = g.vdc.data();
  in.throttle = g.throttle.data();
  in.torque_nm = g.torque.data();
  in.omega_rad_s = g.omega.data();
  SolveBatch(d, mode, n, in, out.columns());
  std::uint32_t seen = 0;
  int mismatches = 0;
  for (std::size_t i = 0; i < n && mismatches < 5; ++i) {
    const OperatingPoint p = PointByPoint(d, mode, g, i);
    const OperatingPoint b = out.columns().Get(i);
    const double want[] = {p.vdc_v, p.throttle, p.throttle_effective, p.rpm, p.omega_rad_s, p.torque_nm,
                           p.irms_a, p.vll_rms_v, p.pac_w, p.idc_a, p.pdc_w, p.pesc_w,
                           p.pmech_w, p.eta_motor, p.eta_esc, p.eta_system};
    const double got[] = {b.vdc_v, b.throttle, b.throttle_effective, b.rpm, b.omega_rad_s, b.torque_nm,
                          b.irms_a, b.vll_rms_v, b.pac_w, b.idc_a, b.pdc_w, b.pesc_w,
                          b.pmech_w, b.eta_motor, b.eta_esc, b.eta_system};
    bool same = b.limits == p.limits && b.saturated == p.saturated && out.columns().feasible[i] == p.feasible();
    for (std::size_t k = 0; k < 16; ++k) same = same && Bits(got[k]) == Bits(want[k]);
    if (!same) {
      ++mismatches;
      ADD_FAILURE() << what << ": point " << i << " differs (field order of PointColumns; limits " << b.limits
                    << " vs " << p.limits << ", throttle " << b.throttle << " vs " << p.throttle << ", idc "
                    << b.idc_a << " vs " << p.idc_a << ", torque " << b.torque_nm << " vs " << p.torque_nm << ")";
    }
    seen |= p.limits;
  }
  return seen;
}

constexpr std::size_t kPoints = 3001;  // several chunks of the batch, the last one partial

TEST(DriveBatch, FirstOrderEqualsPointByPointInEveryMode) {
  const Drive d(RatedMotor(), RatedEsc());
  ASSERT_FALSE(d.extended());
  const std::uint32_t inverse = ExpectBatchEqualsPointByPoint(d, BatchMode::kInverse, kPoints, "inverse");
  const std::uint32_t torque = ExpectBatchEqualsPointByPoint(d, BatchMode::kAtTorque, kPoints, "at torque");
  const std::uint32_t speed = ExpectBatchEqualsPointByPoint(d, BatchMode::kAtSpeed, kPoints, "at speed");
  // The grid crosses every limit a first-order drive can raise (all but thermal runaway).
  const std::uint32_t all = inverse | torque | speed;
  for (std::uint32_t bit = 0; bit < 10; ++bit) {
    if ((1u << bit) == kLimitThermalRunaway) continue;
    EXPECT_TRUE(all & (1u << bit)) << LimitNames(1u << bit)[0] << " never reached: the grid does not test it";
  }
  EXPECT_TRUE(inverse & kLimitThrottleAboveOne);  // infeasible inversions
  EXPECT_TRUE(torque & kLimitStalled);
}

// An ESC below the ideal one (C1 + C0 < 1.1095, docs/model.md section 10) creates energy: the
// batch flags it as the scalar path does.
TEST(DriveBatch, CreatesEnergyFlaggedAsPointByPoint) {
  EscParams e = RatedEsc();
  e.c1 = 0.9;
  e.c0 = 0.0;
  const Drive d(RatedMotor(), e);
  const std::uint32_t seen = ExpectBatchEqualsPointByPoint(d, BatchMode::kAtTorque, 700, "lossless ESC");
  EXPECT_TRUE(seen & kLimitCreatesEnergy);
}

// A brushed motor (kv = kp = 1) and an ESC without a knee.
TEST(DriveBatch, BrushedMotorEqualsPointByPoint) {
  MotorParams m = RatedMotor();
  m.type = MotorType::kBrushed;
  m.kt_nm_per_a = m.ke_v_s_per_rad;
  EscParams e = RatedEsc();
  e.c1 = 0.0;
  e.c0 = 1.0;
  e.tr_sat = 1.0;
  e.sat_slope = 1.0;
  const Drive d(m, e);
  for (BatchMode mode : {BatchMode::kInverse, BatchMode::kAtTorque, BatchMode::kAtSpeed}) {
    ExpectBatchEqualsPointByPoint(d, mode, 1100, "brushed");
  }
}

// The extensions of section 9 run Drive's scalar path into the same columns.
TEST(DriveBatch, ExtendedDrivesEqualPointByPoint) {
  MotorParams m = RatedMotor();
  m.io1_a_s_per_rad = 4e-4;
  m.rth_k_per_w = 2.0;
  m.kt_droop_per_a = 0.002;
  EscParams e = RatedEsc();
  e.deadband = 0.05;
  e.rsupply_ohm = 0.01;
  const Drive d(m, e);
  ASSERT_TRUE(d.extended());
  for (BatchMode mode : {BatchMode::kInverse, BatchMode::kAtTorque, BatchMode::kAtSpeed}) {
    ExpectBatchEqualsPointByPoint(d, mode, 600, "extended");
  }
}

// The linear extensions alone (Io(omega) and a dead band: closed forms, no root finder) also run
// Drive's scalar path, whatever the mode, down to the throttle range's ends.
TEST(DriveBatch, LinearExtensionsEqualPointByPoint) {
  MotorParams m = RatedMotor();
  m.io1_a_s_per_rad = 3e-4;
  EscParams e = RatedEsc();
  e.deadband = 0.08;
  const Drive d(m, e);
  ASSERT_TRUE(d.extended());
  ASSERT_FALSE(d.nonlinear());
  for (BatchMode mode : {BatchMode::kInverse, BatchMode::kAtTorque, BatchMode::kAtSpeed}) {
    ExpectBatchEqualsPointByPoint(d, mode, 600, "linear extensions");
  }
}

TEST(DriveBatch, EmptyBatchWritesNothing) {
  const Drive d(RatedMotor(), RatedEsc());
  SolveBatch(d, BatchMode::kInverse, 0, BatchInputs{}, PointColumns{});
}

}  // namespace
}  // namespace dynosize
