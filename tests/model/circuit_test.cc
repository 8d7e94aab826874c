// model/circuit.h: the rms circuit written once for doubles (Drive) and dual numbers
// (calibrate's Jacobians, the shaft solver's gradients). The same functions must give Drive's
// numbers in both types, and the dual numbers' tangents must be the equations' derivatives.
#include <cmath>

#include <gtest/gtest.h>

#include "common/dual.h"
#include "common/units.h"
#include "model/circuit.h"
#include "model/drive.h"

namespace dynosize {
namespace {

using D2 = Dual<2>;

// Drive and the circuit functions are the same expressions: equal to rounding.
constexpr double kRelTol = 1e-13;
// Central differences with h = 1e-6 on smooth functions of O(1) inputs: error ~h^2*f''' plus
// rounding ~1e-16/h, so 1e-8 relative is safe and still catches a wrong derivative.
constexpr double kFdRelTol = 1e-8;

EscParams EscWithKneeAndDeadband() {
  EscParams e;
  e.resc_ohm = 0.015;
  e.c1 = 1.10;
  e.c0 = 0.02;
  e.tr_sat = 0.85;
  e.sat_slope = 0.55;
  e.deadband = 0.06;
  return e;
}

// A 990 rpm/V outrunner (docs/model.md section 8) with KT below the energy bound sqrt(27/10)*KE.
MotorParams Motor() {
  MotorParams m;
  m.ke_v_s_per_rad = 0.0065;
  m.kt_nm_per_a = 0.0101;
  m.rm_ohm = 0.07;
  m.io_a = 0.9;
  return m;
}

TEST(CircuitTest, EffectiveThrottleAndItsInverseMatchDriveWithKneeAndDeadband) {
  const MotorParams m = Motor();
  const EscParams e = EscWithKneeAndDeadband();
  const Drive drive(m, e);
  for (double tr : {0.0, 0.03, 0.06, 0.3, 0.85, 0.87, 0.95, 1.0}) {
    const double tre = circuit::EffectiveThrottle(tr, e.tr_sat, e.sat_slope, e.deadband);
    EXPECT_DOUBLE_EQ(tre, drive.EffectiveThrottle(tr)) << "throttle " << tr;
    EXPECT_GE(tre, 0.0) << "below the dead band the effective throttle is held at 0";
    if (tr > e.deadband) {
      EXPECT_NEAR(circuit::ThrottleFromEffective(tre, e.tr_sat, e.sat_slope, e.deadband), tr, 1e-14)
          << "round trip at throttle " << tr;
    }
  }
  // Without a dead band a negative command (an inverse model's "throttle below zero") stays
  // visible instead of being held at 0.
  EXPECT_LT(circuit::EffectiveThrottle(-0.1, 0.9, 0.6, 0.0), 0.0);
}

TEST(CircuitTest, DualTangentsAreTheDerivativesOfTheKneeAndDeadband) {
  const EscParams e = EscWithKneeAndDeadband();
  for (double tr : {0.4, 0.95}) {  // below and above the knee
    const D2 tre = circuit::EffectiveThrottle(tr, e.tr_sat, D2::Variable(e.sat_slope, 0),
                                              D2::Variable(e.deadband, 1));
    const double h = 1e-6;
    const auto f = [&](double slope, double db) { return circuit::EffectiveThrottle(tr, e.tr_sat, slope, db); };
    const double d_slope = (f(e.sat_slope + h, e.deadband) - f(e.sat_slope - h, e.deadband)) / (2 * h);
    const double d_db = (f(e.sat_slope, e.deadband + h) - f(e.sat_slope, e.deadband - h)) / (2 * h);
    EXPECT_DOUBLE_EQ(tre.value, f(e.sat_slope, e.deadband));
    EXPECT_NEAR(tre.derivative[0], d_slope, kFdRelTol * std::max(1.0, std::fabs(d_slope))) << tr;
    EXPECT_NEAR(tre.derivative[1], d_db, kFdRelTol * std::max(1.0, std::fabs(d_db))) << tr;
  }
}

// The first-order point at a given torque composed from the circuit functions in dual numbers
// (as calibrate's residuals are) equals Drive::AtTorque in every column.
TEST(CircuitTest, ComposedDualPointEqualsDriveAtTorque) {
  const MotorParams m = Motor();
  EscParams e = EscWithKneeAndDeadband();
  e.deadband = 0.0;  // Drive's extended path (dead band) is not the first-order one composed here
  const Drive drive(m, e);
  const double vdc = 15.2, q = 0.21;
  for (double tr : {0.45, 0.92}) {
    const OperatingPoint p = drive.AtTorque(vdc, tr, q);
    const D2 ke = D2::Variable(m.ke_v_s_per_rad, 0);
    const D2 rm = D2::Variable(m.rm_ohm, 1);
    const D2 tre = circuit::EffectiveThrottle(tr, e.tr_sat, D2(e.sat_slope), D2(e.deadband));
    const D2 u = circuit::AppliedVoltage(kVllRmsPerVdc, vdc, tre);
    const D2 i = circuit::CurrentAtTorque(q, D2(m.kt_nm_per_a), D2(m.io_a));
    const D2 w = circuit::SpeedAtCurrent(u, rm + e.resc_ohm, i, ke);
    const D2 vll = circuit::LineVoltage(u, D2(e.resc_ohm), i);
    const D2 pac = circuit::AcPower(kPacPerVllIrms, vll, i);
    const D2 idc = circuit::DcCurrent(D2(e.c1), tre, D2(e.c0), i);
    EXPECT_NEAR(w.value, p.omega_rad_s, kRelTol * p.omega_rad_s);
    EXPECT_NEAR(i.value, p.irms_a, kRelTol * p.irms_a);
    EXPECT_NEAR(vll.value, p.vll_rms_v, kRelTol * p.vll_rms_v);
    EXPECT_NEAR(pac.value, p.pac_w, kRelTol * p.pac_w);
    EXPECT_NEAR(idc.value, p.idc_a, kRelTol * p.idc_a);
    // (48): d omega / d KE = -omega/KE and d omega / d Rm = -I/KE, exactly.
    EXPECT_NEAR(w.derivative[0], -w.value / m.ke_v_s_per_rad, 1e-12 * std::fabs(w.value / m.ke_v_s_per_rad));
    EXPECT_NEAR(w.derivative[1], -i.value / m.ke_v_s_per_rad, 1e-12 * std::fabs(i.value / m.ke_v_s_per_rad));
  }
}

}  // namespace
}  // namespace dynosize
