// Model extensions of docs/model.md section 9 (src/model/drive.h): each is checked against the
// equation it implements, and the closed-form and nonlinear paths against each other.
#include <cmath>

#include <gtest/gtest.h>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "model/drive.h"

namespace dynosize {
namespace {

// Root finders stop at about 1e-14 relative; the identities below hold to rounding.
constexpr double kRelTol = 1e-9;

MotorParams Motor() {
  MotorParams m;
  m.ke_v_s_per_rad = 0.0071;
  m.kt_nm_per_a = 0.0118;
  m.rm_ohm = 0.11;
  m.io_a = 0.6;
  return m;
}

EscParams Esc() {
  EscParams e;
  e.resc_ohm = 0.02;
  e.c1 = 1.10;  // c1 + c0 = 1.13 >= 1.1095: an ESC that conserves energy (docs/model.md section 10)
  e.c0 = 0.03;
  e.tr_sat = 0.9;
  e.sat_slope = 0.6;
  return e;
}

void ExpectRel(double a, double b, double tol, const char* what) {
  EXPECT_NEAR(a, b, tol * std::max(std::fabs(b), 1e-12)) << what;
}

TEST(DriveExtensionsTest, DeadbandMapsCommandBeforeTheKnee) {
  EscParams e = Esc();
  e.deadband = 0.1;
  const Drive d(Motor(), e);
  EXPECT_EQ(d.EffectiveThrottle(0.05), 0.0);
  EXPECT_EQ(d.EffectiveThrottle(0.1), 0.0);
  ExpectRel(d.EffectiveThrottle(0.55), 0.5, kRelTol, "(0.55-0.1)/0.9");
  // Knee on the dead-band-mapped throttle: d(1.0) = 1 > tr_sat = 0.9.
  ExpectRel(d.EffectiveThrottle(1.0), 0.9 + 0.6 * 0.1, kRelTol, "knee after dead band");
  for (double tr : {0.2, 0.5, 0.93, 1.0}) {
    ExpectRel(d.ThrottleFromEffective(d.EffectiveThrottle(tr)), tr, kRelTol, "round trip");
  }
  // AtLoad with the dead band equals the base drive at the mapped throttle (below the knee).
  const Drive base(Motor(), Esc());
  const TorqueLaw prop{0.0, 0.0, 3e-7};
  const auto p = d.AtLoad(12.0, 0.55, prop);
  const auto q = base.AtLoad(12.0, 0.5, prop);
  ExpectRel(p.omega_rad_s, q.omega_rad_s, kRelTol, "omega");
  ExpectRel(p.idc_a, q.idc_a, kRelTol, "idc");
}

TEST(DriveExtensionsTest, SpeedDependentNoLoadCurrent) {
  MotorParams m = Motor();
  m.io1_a_s_per_rad = 4e-4;
  const Drive d(m, Esc());
  const auto p = d.AtTorque(12.0, 0.7, 0.05);
  const double io = m.io_a + m.io1_a_s_per_rad * p.omega_rad_s;
  ExpectRel(p.torque_nm, 0.05, kRelTol, "torque balance");
  ExpectRel(m.kt_nm_per_a * (p.irms_a - io), 0.05, kRelTol, "Q = KT*(I - Io(omega))");
  ExpectRel(d.r_total_ohm() * p.irms_a + m.ke_v_s_per_rad * p.omega_rad_s,
            kVllRmsPerVdc * 12.0 * 0.7, kRelTol, "eq 48");
  // No-load speed: zero torque there.
  const double wnl = d.NoLoadSpeed(12.0, 0.7);
  EXPECT_NEAR(d.AtSpeed(12.0, 0.7, wnl).torque_nm, 0.0, 1e-12);
  // Closed-form best-efficiency speed: no neighbour is better.
  const double wopt = d.MaxEfficiencySpeed(12.0, 0.7);
  const double e0 = d.AtSpeed(12.0, 0.7, wopt).eta_system;
  EXPECT_GE(e0, d.AtSpeed(12.0, 0.7, wopt * 1.001).eta_system);
  EXPECT_GE(e0, d.AtSpeed(12.0, 0.7, wopt * 0.999).eta_system);
  // Inverse round trip.
  const auto inv = d.Inverse(12.0, p.torque_nm, p.omega_rad_s);
  ExpectRel(inv.throttle, 0.7, kRelTol, "inverse throttle");
}

TEST(DriveExtensionsTest, WindingTemperatureRiseIsSteadyAndConsistent) {
  MotorParams m = Motor();
  m.rth_k_per_w = 2.0;  // K/W
  const Drive d(m, Esc());
  ASSERT_TRUE(d.nonlinear());
  const auto p = d.AtTorque(14.8, 0.8, 0.08);
  const double rm_hot = d.WindingResistance(p.irms_a);
  ExpectRel(rm_hot, m.rm_ohm * (1.0 + kAlphaCopperPerK * p.winding_rise_k), kRelTol,
            "Rm = Rm0*(1 + alpha*dT)");
  ExpectRel(p.winding_rise_k, m.rth_k_per_w * kPacPerVllIrms * rm_hot * p.irms_a * p.irms_a,
            kRelTol, "dT = rth*kp*Rm*I^2");
  ExpectRel((rm_hot + 0.02) * p.irms_a + m.ke_v_s_per_rad * p.omega_rad_s,
            kVllRmsPerVdc * 14.8 * 0.8, kRelTol, "eq 48 with hot Rm");
  ExpectRel(p.torque_nm, 0.08, kRelTol, "torque");
  // Hotter winding: slower than the cold model at the same torque.
  EXPECT_LT(p.omega_rad_s, Drive(Motor(), Esc()).AtTorque(14.8, 0.8, 0.08).omega_rad_s);
  const auto s = d.AtSpeed(14.8, 0.8, p.omega_rad_s);
  ExpectRel(s.irms_a, p.irms_a, 1e-8, "AtSpeed inverts AtTorque");
  const auto inv = d.Inverse(14.8, p.torque_nm, p.omega_rad_s);
  ExpectRel(inv.throttle, 0.8, 1e-8, "Inverse");
}

TEST(DriveExtensionsTest, TorqueConstantDroopAndPropellerLoad) {
  MotorParams m = Motor();
  m.kt_droop_per_a = 0.01;
  m.rth_k_per_w = 1.0;
  m.io1_a_s_per_rad = 2e-4;
  EscParams e = Esc();
  e.deadband = 0.05;
  e.rsupply_ohm = 0.03;
  const Drive d(m, e);
  const TorqueLaw prop{0.0, 0.0, 4e-7};
  for (double tr : {0.3, 0.6, 0.95}) {
    const auto p = d.AtLoad(12.0, tr, prop);
    ASSERT_TRUE(std::isfinite(p.omega_rad_s));
    ExpectRel(p.torque_nm, prop.c_nm_s2_per_rad2 * p.omega_rad_s * p.omega_rad_s, 1e-8, "load");
    ExpectRel(p.torque_nm,
              m.kt_nm_per_a / (1.0 + m.kt_droop_per_a * p.irms_a) *
                  (p.irms_a - m.io_a - m.io1_a_s_per_rad * p.omega_rad_s),
              1e-8, "KT(I)*(I - Io(omega))");
    // The ESC sees VDC - rsupply*IDC (eq 47 with the supply drop).
    ExpectRel(p.vll_rms_v,
              kVllRmsPerVdc * (12.0 - e.rsupply_ohm * p.idc_a) * p.throttle_effective -
                  e.resc_ohm * p.irms_a,
              1e-9, "eq 47");
    const auto inv = d.Inverse(12.0, p.torque_nm, p.omega_rad_s);
    ExpectRel(inv.throttle, tr, 1e-7, "inverse");
  }
}

TEST(DriveExtensionsTest, CatalogKeysReachTheModel) {
  Catalog cat;
  std::vector<std::string> problems;
  cat.AddDocument(ParseJsonText(R"({"motors": [{"id": "m", "name": "m", "type": "bldc",
      "ke_v_s_per_rad": 0.007, "rm_ohm": 0.1, "io_a": 0.5, "io1_a_s_per_rad": 0.0002,
      "rth_k_per_w": 1.5, "kt_droop_per_a": 0.004, "source": {"dataset": "t", "values":
      {"io1_a_s_per_rad": "fitted", "rth_k_per_w": "fitted", "kt_droop_per_a": "fitted"}}}],
      "escs": [{"id": "e", "name": "e", "resc_ohm": 0.01, "c1": 1.12, "c0": 0, "tr_sat": 1,
      "sat_slope": 1, "deadband": 0.07, "rsupply_ohm": 0.02, "source": {"dataset": "t"}}]})",
                                "t.json"),
                  "t.json", &problems);
  ASSERT_TRUE(problems.empty()) << problems.front();
  const MotorParams& m = cat.motor("m").params;
  EXPECT_EQ(m.io1_a_s_per_rad, 0.0002);
  EXPECT_EQ(m.rth_k_per_w, 1.5);
  EXPECT_EQ(m.kt_droop_per_a, 0.004);
  const EscParams& e = cat.esc("e").params;
  EXPECT_EQ(e.deadband, 0.07);
  EXPECT_EQ(e.rsupply_ohm, 0.02);

  Catalog bad;
  problems.clear();
  bad.AddDocument(ParseJsonText(R"({"escs": [{"id": "e", "name": "e", "resc_ohm": 0.01, "c1": 1.12,
      "c0": 0, "tr_sat": 1, "sat_slope": 1, "deadband": 0.5, "source": {"dataset": "t"}}]})",
                                "t.json"),
                  "t.json", &problems);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("deadband"), std::string::npos) << problems[0];
  EXPECT_NE(problems[0].find("< 0.5"), std::string::npos) << problems[0];
}

// With a supply resistance, a point the ESC cannot reach at any throttle (its output voltage
// peaks below the winding's need) is flagged, at least full throttle, and every figure finite:
// simulate's JSON and CSV refuse a non-finite number (docs/model.md section 9's supply drop).
TEST(DriveExtensionsTest, SupplyDropBeyondReachIsFlaggedAndFinite) {
  EscParams e = Esc();
  e.rsupply_ohm = 0.05;
  const Drive d(Motor(), e);
  // 0.3 N*m needs about 26 A; at 1,000 rad/s the back-EMF alone is 7.1 V of the 7.2 V supply.
  const OperatingPoint p = d.Inverse(7.2, 0.3, 1000.0);
  EXPECT_TRUE(p.limits & kLimitThrottleAboveOne);
  EXPECT_GE(p.throttle, 1.0);
  for (double v : {p.throttle, p.throttle_effective, p.irms_a, p.vll_rms_v, p.pac_w, p.idc_a, p.pdc_w, p.pesc_w,
                   p.pmech_w, p.eta_motor, p.eta_esc, p.eta_system}) {
    EXPECT_TRUE(std::isfinite(v)) << v;
  }
  // A reachable point of the same drive still solves the quadratic (the round trip holds).
  const OperatingPoint q = d.Inverse(12.0, 0.05, 800.0);
  ASSERT_FALSE(q.limits & kLimitThrottleAboveOne);
  ExpectRel(d.AtSpeed(12.0, q.throttle, 800.0).torque_nm, 0.05, 1e-7, "round trip");
}

}  // namespace
}  // namespace dynosize
