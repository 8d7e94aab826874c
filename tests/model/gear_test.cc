// The gearbox (model/gear.h): a geared motor seen at the propeller shaft is the same electrical
// point as the motor driving the load moved through the gear by hand, and the gear loss is the
// difference of the shaft powers.
#include "model/gear.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/drive.h"

namespace dynosize {
namespace {

// Two algebraic routes to the same point (a product of a few terms each way): agreement to a
// few hundred ulps.
constexpr double kRel = 1e-12;

MotorParams AMotor() {
  MotorParams m;  // a 1300 Kv class inrunner (the KIRA 650-13's motor order of magnitude)
  m.ke_v_s_per_rad = 0.00487;
  m.kt_nm_per_a = 1.6432 * m.ke_v_s_per_rad;
  m.rm_ohm = 0.027;
  m.io_a = 0.64;
  m.io1_a_s_per_rad = 2e-5;
  m.kt_droop_per_a = 0.002;
  return m;
}

TEST(GearTest, DirectDriveLeavesTheMotorAsItIs) {
  const MotorParams m = AMotor();
  const MotorParams p = MotorAtPropellerShaft(m, Gear{});
  EXPECT_EQ(p.ke_v_s_per_rad, m.ke_v_s_per_rad);
  EXPECT_EQ(p.kt_nm_per_a, m.kt_nm_per_a);
  EXPECT_EQ(p.io1_a_s_per_rad, m.io1_a_s_per_rad);
  const MotorShaft s = MotorShaftOf(300.0, 1.2, Gear{});
  EXPECT_EQ(s.omega_rad_s, 300.0);
  EXPECT_EQ(s.torque_nm, 1.2);
  EXPECT_EQ(s.gear_loss_w, 0.0);
}

// omega_motor = N*omega_prop, Q_motor = Q_prop/(N*eta): the equivalent motor at the propeller
// shaft draws the same current, throttle and DC power as the motor itself at the motor's speed
// and torque, and its shaft power is eta times the motor's.
TEST(GearTest, ThePropellerShaftPointIsTheMotorsPointThroughTheGear) {
  const MotorParams m = AMotor();
  EscParams e;
  e.resc_ohm = 0.005;
  const Gear gear{6.7, 0.968};
  const Drive at_motor(m, e), at_prop(MotorAtPropellerShaft(m, gear), e);
  const double vdc = 44.4;
  for (const double omega_prop : {200.0, 343.0, 420.0}) {
    const double q_prop = 1.1e-5 * omega_prop * omega_prop;  // a propeller's load
    const OperatingPoint p = at_prop.Inverse(vdc, q_prop, omega_prop);
    const MotorShaft s = MotorShaftOf(omega_prop, q_prop, gear);
    const OperatingPoint q = at_motor.Inverse(vdc, s.torque_nm, s.omega_rad_s);
    EXPECT_NEAR(p.irms_a, q.irms_a, kRel * q.irms_a);
    EXPECT_NEAR(p.throttle, q.throttle, kRel * q.throttle);
    EXPECT_NEAR(p.pdc_w, q.pdc_w, kRel * q.pdc_w);
    EXPECT_NEAR(p.pmech_w, gear.efficiency * q.pmech_w, kRel * q.pmech_w);
    // The gear loss: the motor's shaft power less the propeller's, (1/eta - 1) x the latter.
    EXPECT_NEAR(s.gear_loss_w, q.pmech_w - p.pmech_w, kRel * q.pmech_w);
    EXPECT_NEAR(s.gear_loss_w, (1.0 / gear.efficiency - 1.0) * q_prop * omega_prop, kRel * q.pmech_w);
    EXPECT_GT(s.gear_loss_w, 0.0);
    // Restated at the motor's shaft, the point is the motor's own.
    const OperatingPoint back = MotorSidePoint(p, gear);
    EXPECT_NEAR(back.rpm, q.rpm, kRel * q.rpm);
    EXPECT_NEAR(back.torque_nm, q.torque_nm, kRel * q.torque_nm);
    EXPECT_NEAR(back.eta_motor, q.eta_motor, kRel);
    EXPECT_NEAR(back.eta_system, q.eta_system, kRel);
  }
}

// The equivalent motor never creates energy where the motor does not (docs/model.md section 10):
// KT'/KE' = eta*KT/KE.
TEST(GearTest, TheEquivalentMotorKeepsKtOverKe) {
  const MotorParams m = AMotor();
  const MotorParams p = MotorAtPropellerShaft(m, Gear{5.2, 0.97});
  EXPECT_NEAR(p.kt_nm_per_a / p.ke_v_s_per_rad, 0.97 * m.kt_nm_per_a / m.ke_v_s_per_rad, 1e-15);
  EXPECT_EQ(p.rm_ohm, m.rm_ohm);
  EXPECT_EQ(p.io_a, m.io_a);
  EXPECT_NEAR(p.io1_a_s_per_rad, 5.2 * m.io1_a_s_per_rad, 1e-20);
}

}  // namespace
}  // namespace dynosize
