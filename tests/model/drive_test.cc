#include "model/drive.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "catalog/catalog.h"
#include "common/units.h"
#include "model/paper_drive.h"

namespace dynosize {
namespace {

// Closed-form results agree with hand algebra to rounding: a few hundred ulps of the largest
// term involved.
constexpr double kClosedFormRelTol = 1e-12;
// Numerical maxima found by golden-section search to 1e-10 of the bracket: the located argmax
// of a smooth function is only good to about sqrt(1e-10)*scale, hence 1e-5 relative.
constexpr double kArgmaxRelTol = 1e-5;

// Maximises f on [lo, hi] by golden-section search.
template <typename F>
double ArgMax(F f, double lo, double hi) {
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = lo, b = hi;
  while (b - a > 1e-10 * (hi - lo)) {
    const double x1 = b - g * (b - a), x2 = a + g * (b - a);
    if (f(x1) < f(x2)) a = x1; else b = x2;
  }
  return 0.5 * (a + b);
}

TEST(Constants, PaperIdentities) {
  EXPECT_NEAR(kVllRmsPerVdc, 3.0 / (std::sqrt(2.0) * kPi), 1e-15);
  EXPECT_NEAR(kVllRmsPerVdc, 0.675, 0.0003);  // eq (46) "~0.675"
  EXPECT_NEAR(kPacPerVllIrms, std::sqrt(27.0 / 10.0), 1e-15);  // eq (41)
  EXPECT_NEAR(kIdealIdcPerIrmsPerThrottle, 3.0 / kPi * std::sqrt(27.0 / 20.0), 1e-15);
  EXPECT_NEAR(kIdealIdcPerIrmsPerThrottle, 10.0 / 9.0, 0.002);  // eq (56) "~10/9"
  // The ideal ESC moves power without loss: sqrt(27/10)*0.675 = (3/pi)*sqrt(27/20).
  EXPECT_NEAR(kPacPerVllIrms * kVllRmsPerVdc, kIdealIdcPerIrmsPerThrottle, 1e-15);
  // Section 8: Kv = 1900 rpm/V gives KE = 0.675/(1900*pi/30).
  EXPECT_NEAR(KeFromKvBldc(1900.0), 3.0 / (std::sqrt(2.0) * kPi) / (1900.0 * kPi / 30.0), 1e-15 * 0.0034);
}

TEST(Drive, IdealEscHasUnitEfficiencyAndTenNinthsRatio) {
  MotorParams m = paper_drive::Motor();
  EscParams ideal;  // defaults: resc 0, c1 = (3/pi)*sqrt(27/20), c0 0, no saturation
  const Drive d(m, ideal);
  for (double tr : {0.3, 0.6, 1.0}) {
    const OperatingPoint p = d.AtTorque(11.1, tr, 0.05);
    EXPECT_NEAR(p.idc_a / p.irms_a, kIdealIdcPerIrmsPerThrottle * tr, kClosedFormRelTol);  // (56)
    EXPECT_NEAR(p.eta_esc, 1.0, 1e-12);
    EXPECT_NEAR(p.pesc_w, 0.0, 1e-10 * p.pdc_w);
  }
}

TEST(Drive, ForwardSatisfiesCircuitAndPowerBalance) {
  const Drive d(paper_drive::Motor(), paper_drive::Esc());
  const OperatingPoint p = d.AtTorque(7.2, 0.6, 0.04);
  const auto& m = d.motor();
  const auto& e = d.esc();
  // (48): 0.675*VDC*TR = (RESC + Rm)*Irms + KE*omega.
  EXPECT_NEAR(kVllRmsPerVdc * 7.2 * 0.6, (e.resc_ohm + m.rm_ohm) * p.irms_a + m.ke_v_s_per_rad * p.omega_rad_s,
              kClosedFormRelTol * 7.2);
  EXPECT_NEAR(p.torque_nm, 0.04, 1e-15);
  // PESC closed form of docs/model.md section 6 equals PDC - PAC.
  const double pesc = 7.2 * p.irms_a * ((e.c1 - kIdealIdcPerIrmsPerThrottle) * 0.6 + e.c0) +
                      kPacPerVllIrms * e.resc_ohm * p.irms_a * p.irms_a;
  EXPECT_NEAR(p.pesc_w, pesc, kClosedFormRelTol * p.pdc_w);
  // Motor losses: copper sqrt(27/10)*I^2*Rm plus no-load KT*Io*omega when KT = sqrt(27/10)*KE.
  EXPECT_NEAR(p.pac_w - p.pmech_w,
              kPacPerVllIrms * p.irms_a * p.irms_a * m.rm_ohm + m.kt_nm_per_a * m.io_a * p.omega_rad_s,
              kClosedFormRelTol * p.pac_w);
  EXPECT_NEAR(p.eta_system, p.eta_motor * p.eta_esc, 1e-14);
  EXPECT_TRUE(p.feasible());
  EXPECT_FALSE(p.saturated);
}

TEST(Drive, BrushedMaxPowerAtHalfNoLoadSpeedAndEq14Optimum) {
  MotorParams m;
  m.type = MotorType::kBrushed;
  m.ke_v_s_per_rad = 0.01;
  m.kt_nm_per_a = 0.01;
  m.rm_ohm = 0.3;
  m.io_a = 0.4;
  EscParams regulator;  // the paper's voltage regulator: input power VDC*I (eqs 13, 18)
  regulator.c1 = 0.0;
  regulator.c0 = 1.0;
  const Drive d(m, regulator);
  const double v = 12.0;
  const double w_nl = d.NoLoadSpeed(v, 1.0);
  EXPECT_NEAR(w_nl, (v - m.io_a * m.rm_ohm) / m.ke_v_s_per_rad, kClosedFormRelTol * w_nl);
  EXPECT_NEAR(d.StallTorque(v, 1.0), m.kt_nm_per_a * (v / m.rm_ohm - m.io_a), 1e-12);
  const double w_p = ArgMax([&](double w) { return d.AtSpeed(v, 1.0, w).pmech_w; }, 0.0, w_nl);
  EXPECT_NEAR(w_p, w_nl / 2.0, kArgmaxRelTol * w_nl);  // (12)
  EXPECT_NEAR(d.MaxPowerSpeed(v, 1.0), w_nl / 2.0, 1e-9);
  // (14): omega_opt = (V - sqrt(Io*Rm*V))/KE maximises eta_sys = Pm/(V*I).
  const double w_opt_14 = (v - std::sqrt(m.io_a * m.rm_ohm * v)) / m.ke_v_s_per_rad;
  const double w_opt = ArgMax([&](double w) { return d.AtSpeed(v, 1.0, w).eta_system; }, 0.0, w_nl);
  EXPECT_NEAR(w_opt, w_opt_14, kArgmaxRelTol * w_nl);
  EXPECT_NEAR(d.MaxEfficiencySpeed(v, 1.0), w_opt_14, kClosedFormRelTol * w_nl);
  // With the regulator the input power is V*I (eq 13).
  const OperatingPoint p = d.AtSpeed(v, 1.0, w_opt);
  EXPECT_NEAR(p.pdc_w, v * p.irms_a, 1e-12 * p.pdc_w);
  // "Typical: omega_opt is 75-95 % of omega_NL".
  EXPECT_GT(w_opt / w_nl, 0.75);
  EXPECT_LT(w_opt / w_nl, 0.95);
}

TEST(Drive, CombinedOptimumAgainstNumericalMaximum) {
  const Drive d(paper_drive::Motor(), paper_drive::Esc());
  for (double tr : {0.4, 0.7, 0.95}) {
    const double w_nl = d.NoLoadSpeed(14.8, tr);
    const double w_num =
        ArgMax([&](double w) { return d.AtSpeed(14.8, tr, w).eta_system; }, 0.0, w_nl);
    EXPECT_NEAR(d.MaxEfficiencySpeed(14.8, tr), w_num, kArgmaxRelTol * w_nl) << "TR " << tr;
    const double w_p = ArgMax([&](double w) { return d.AtSpeed(14.8, tr, w).pmech_w; }, 0.0, w_nl);
    EXPECT_NEAR(d.MaxPowerSpeed(14.8, tr), w_p, kArgmaxRelTol * w_nl);
  }
}

TEST(Drive, ForwardInverseRoundTrip) {
  const Drive d(paper_drive::Motor(), paper_drive::Esc());
  std::mt19937 rng(20261121);
  std::uniform_real_distribution<double> tr_dist(0.15, 1.0), q_dist(0.0, 0.08),
      v_dist(7.0, 16.8);
  for (int k = 0; k < 500; ++k) {
    const double v = v_dist(rng), tr = tr_dist(rng), q = q_dist(rng);
    const OperatingPoint fwd = d.AtTorque(v, tr, q);
    if (!fwd.feasible()) continue;  // stalled points have no inverse
    const OperatingPoint inv = d.Inverse(v, fwd.torque_nm, fwd.omega_rad_s);
    EXPECT_NEAR(inv.throttle, tr, 1e-12) << "v " << v << " q " << q;
    EXPECT_NEAR(inv.irms_a, fwd.irms_a, 1e-12 * (1 + fwd.irms_a));
    EXPECT_EQ(inv.saturated, fwd.saturated);
    const OperatingPoint spd = d.AtSpeed(v, tr, fwd.omega_rad_s);
    EXPECT_NEAR(spd.torque_nm, q, 1e-12);
  }
}

TEST(Drive, PropellerLoadMatchesQuadraticLaw) {
  const Drive d(paper_drive::Motor(), paper_drive::Esc());
  const TorqueLaw prop{0.001, 2e-6, 1.2e-7};
  for (double tr : {0.2, 0.5, 0.9, 1.0}) {
    const OperatingPoint p = d.AtLoad(11.1, tr, prop);
    const double w = p.omega_rad_s;
    EXPECT_NEAR(p.torque_nm, prop.a_nm + prop.b_nm_s_per_rad * w + prop.c_nm_s2_per_rad2 * w * w,
                1e-12);
    EXPECT_GT(w, 0.0);
  }
}

TEST(Drive, SaturationAboveKneeReducesSlope) {
  const Drive d(paper_drive::Motor(), paper_drive::Esc());
  EXPECT_DOUBLE_EQ(d.EffectiveThrottle(0.8), 0.8);
  EXPECT_NEAR(d.EffectiveThrottle(1.0), 0.9 + 0.61 * 0.1, 1e-15);
  EXPECT_NEAR(d.ThrottleFromEffective(d.EffectiveThrottle(0.97)), 0.97, 1e-15);
  EXPECT_TRUE(d.AtTorque(7.2, 0.95, 0.01).saturated);
  EXPECT_FALSE(d.AtTorque(7.2, 0.9, 0.01).saturated);
}

TEST(Drive, LimitsAreFlagged) {
  MotorParams m = paper_drive::Motor();
  m.max_current_a = 5.0;
  EscParams e = paper_drive::Esc();
  e.vdc_max_v = 12.0;
  const Drive d(m, e);
  // Inverse above full throttle.
  const double w_nl_full = d.NoLoadSpeed(7.2, 1.0);
  OperatingPoint p = d.Inverse(7.2, 0.01, 1.2 * w_nl_full);
  EXPECT_TRUE(p.limits & kLimitThrottleAboveOne);
  EXPECT_GT(p.throttle, 1.0);
  // Over the motor's current rating.
  p = d.AtTorque(7.2, 0.9, 0.06);
  EXPECT_TRUE(p.limits & kLimitMotorCurrent) << p.irms_a;
  // Load above stall torque: stalled, omega 0, never negative.
  p = d.AtTorque(7.2, 0.1, 1.0);
  EXPECT_TRUE(p.limits & kLimitStalled);
  EXPECT_EQ(p.omega_rad_s, 0.0);
  // Supply over the ESC rating.
  EXPECT_TRUE(d.AtTorque(14.8, 0.5, 0.01).limits & kLimitEscVoltage);
  // Driven beyond no-load speed.
  EXPECT_TRUE(d.AtSpeed(7.2, 0.5, 2.0 * d.NoLoadSpeed(7.2, 0.5)).limits & kLimitOverrunning);
  // A negative load torque (the load drives the shaft) runs past no-load speed: overrunning,
  // with the base model and with an extension active (the extended closed-form path).
  p = d.AtTorque(7.2, 0.5, -0.01);
  EXPECT_TRUE(p.limits & kLimitOverrunning);
  EXPECT_GT(p.omega_rad_s, d.NoLoadSpeed(7.2, 0.5));
  EXPECT_FALSE(d.AtTorque(7.2, 0.5, 0.0).limits & kLimitOverrunning);  // exactly no load: I = Io
  MotorParams m_ext = m;
  m_ext.io1_a_s_per_rad = 1e-4;
  EXPECT_TRUE(Drive(m_ext, e).AtTorque(7.2, 0.5, -0.01).limits & kLimitOverrunning);
  EXPECT_FALSE(Drive(m_ext, e).AtTorque(7.2, 0.5, 0.01).limits & kLimitOverrunning);
  EXPECT_EQ(LimitNames(kLimitMotorCurrent | kLimitStalled),
            (std::vector<std::string>{"motor_current", "stalled"}));
}

TEST(Drive, EscTimingFigureEq62) {
  const Drive d(paper_drive::Motor(), paper_drive::Esc());
  EXPECT_NEAR(d.EscTimingFigure(0.5), (1.2 - kIdealIdcPerIrmsPerThrottle) * 0.5 + 0.03, 1e-15);
  // Derived from PESC: the switching-like part over VDC*Irms.
  const OperatingPoint p = d.AtTorque(7.2, 0.5, 0.03);
  const double conduction = kPacPerVllIrms * 0.02 * p.irms_a * p.irms_a;
  EXPECT_NEAR((p.pesc_w - conduction) / (7.2 * p.irms_a), d.EscTimingFigure(0.5), 1e-12);
}

// InverseLight is Inverse without the powers: the same throttle, IDC and Irms bit for bit, and
// with InverseAcPower the same PAC (the evaluator's pack fixed point and the search's bounds
// rely on it to give the same numbers as before), below and above the saturation knee, over
// 100 % throttle, and with every extension on.
TEST(Drive, InverseLightEqualsInverse) {
  MotorParams ext_m = paper_drive::Motor();
  ext_m.kt_droop_per_a = 0.01;
  ext_m.io1_a_s_per_rad = 2e-4;
  ext_m.rth_k_per_w = 2.0;
  EscParams ext_e = paper_drive::Esc();
  ext_e.deadband = 0.05;
  ext_e.rsupply_ohm = 0.03;
  const Drive drives[2] = {Drive(paper_drive::Motor(), paper_drive::Esc()), Drive(ext_m, ext_e)};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int saturated = 0;
  for (const Drive& d : drives) {
    for (int i = 0; i < 500; ++i) {
      const double vdc = 6 + 20 * u(rng), q = 0.2 * u(rng), w = 3000 * u(rng);
      const OperatingPoint p = d.Inverse(vdc, q, w);
      const Drive::InverseCurrents c = d.InverseLight(vdc, q, w);
      saturated += p.saturated ? 1 : 0;
      EXPECT_EQ(c.throttle, p.throttle) << i;
      EXPECT_EQ(c.idc_a, p.idc_a) << i;
      EXPECT_EQ(c.irms_a, p.irms_a) << i;
      EXPECT_EQ(d.InverseAcPower(vdc, c, q, w), p.pac_w) << i;
      EXPECT_EQ(vdc * c.idc_a, p.pdc_w) << i;  // PDC = VDC*IDC (eq 59), as the search reads it
      EXPECT_EQ(d.InversePdcW(vdc, q, w), p.pdc_w) << i;
    }
  }
  EXPECT_GT(saturated, 50);  // the saturated branch is exercised
}

// The paper's own check (docs/model.md section 7): EMAX 1900 KV + MultiStar 30 A at 7.2 V, torque-
// speed lines 1230 rpm apart per 10 % throttle up to 90 % and 750 rpm from 90 % to 100 %.
TEST(PaperCheck, TorqueSpeedLineSpacingWithShippedEntries) {
  const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  const Drive d(cat.motor("emax_1900kv_paper").params, cat.esc("multistar_30a_paper").params);
  const double kRpmTol = 30.0;  // the paper reads the spacing off a figure: +-30 rpm
  for (double q : {0.0, 0.02, 0.05}) {
    for (int k = 1; k < 9; ++k) {
      const double lo = d.AtTorque(7.2, 0.1 * k, q).rpm, hi = d.AtTorque(7.2, 0.1 * (k + 1), q).rpm;
      if (lo <= 0.0) continue;  // stalled at this torque and throttle
      EXPECT_NEAR(hi - lo, 1230.0, kRpmTol) << "TR " << 0.1 * k << " Q " << q;
    }
    const double d90 = d.AtTorque(7.2, 1.0, q).rpm - d.AtTorque(7.2, 0.9, q).rpm;
    EXPECT_NEAR(d90, 750.0, kRpmTol) << "Q " << q;
  }
}

}  // namespace
}  // namespace dynosize
