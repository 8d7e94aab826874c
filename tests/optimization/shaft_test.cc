// The shaft segment's speed: Ipopt and NLopt on the same problem, the dual-number restatement
// against Drive::Inverse, and the optimum against the analytic optimality condition.
#include "optimization/shaft.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/dual.h"
#include "common/units.h"
#include "solver_backends.h"

namespace dynosize {
namespace {

// The restated equations must match Drive to rounding: both are a handful of flops.
constexpr double kRestateRelTol = 1e-12;
// Ipopt and SLSQP at relative_tolerance 1e-10 locate a smooth 1-D optimum to ~1e-6 relative in
// speed (the objective is flat there: an error e in speed changes it by ~e^2).
constexpr double kSpeedRelTol = 1e-4;
// COBYLA (derivative-free) stops on its trust radius: a looser but still tight check.
constexpr double kCobylaSpeedRelTol = 2e-3;

MotorParams TestMotor() {
  MotorParams m;
  m.ke_v_s_per_rad = KeFromKvBldc(920.0);
  m.kt_nm_per_a = kPacPerVllIrms * m.ke_v_s_per_rad;
  m.rm_ohm = 0.12;
  m.io_a = 0.45;
  return m;
}

EscParams IdealEsc() {
  EscParams e;  // C1 ideal, C0 = 0, no saturation (tr_sat = 1)
  e.resc_ohm = 0.01;
  return e;
}

TEST(ShaftTest, DualRestatementMatchesDriveInverse) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    MotorParams m = TestMotor();
    m.rm_ohm = 0.02 + 0.3 * u(rng);
    m.io_a = 0.1 + u(rng);
    EscParams e;
    e.resc_ohm = 0.05 * u(rng);
    e.c1 = 1.0 + 0.3 * u(rng);
    e.c0 = 0.05 * u(rng);
    e.tr_sat = 0.8 + 0.15 * u(rng);
    e.sat_slope = 0.4 + 0.5 * u(rng);
    const Drive d(m, e);
    const double vdc = 7 + 20 * u(rng), w = 100 + 1500 * u(rng), q = 0.01 + 0.3 * u(rng);
    const OperatingPoint p = d.Inverse(vdc, q, w);
    const ShaftEval<double> s = ShaftPdc<double>(d, vdc, w, q);
    EXPECT_NEAR(s.pdc_w, p.pdc_w, kRestateRelTol * std::fabs(p.pdc_w));
    EXPECT_NEAR(s.throttle, p.throttle, kRestateRelTol * std::fabs(p.throttle));
    EXPECT_NEAR(s.idc_a, p.idc_a, kRestateRelTol * std::fabs(p.idc_a));
    EXPECT_NEAR(s.current_a, p.irms_a, kRestateRelTol * std::fabs(p.irms_a));
  }
}

// Ideal ESC: PDC = (C1/kv)*(R*I + KE*omega)*I; with omega = P/(KT*(I - Io)) the minimum of PDC
// over I solves 2*R*I*(I - Io)^2 = KE*P*Io/KT (derived in shaft.h). Bisection on I > Io.
double AnalyticOptimalSpeed(const Drive& d, double power_w) {
  const MotorParams& m = d.motor();
  const double r = d.r_total_ohm();
  auto f = [&](double i) { return 2 * r * i * (i - m.io_a) * (i - m.io_a) - m.ke_v_s_per_rad * power_w * m.io_a / m.kt_nm_per_a; };
  double lo = m.io_a, hi = m.io_a + 1000.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? hi : lo) = mid;
  }
  const double i = 0.5 * (lo + hi);
  return power_w / (m.kt_nm_per_a * (i - m.io_a));
}

TEST(ShaftTest, IpoptAndNloptFindTheAnalyticOptimum) {
  const Drive d(TestMotor(), IdealEsc());
  ShaftRequest q;
  q.vdc_v = 22.2;  // the free optimum needs ~64 % throttle: the limit does not bind
  q.power_w = 60.0;
  q.omega_rad_s = Range{200.0, 1500.0};
  const double w_star = AnalyticOptimalSpeed(d, *q.power_w);
  ASSERT_LT(d.Inverse(q.vdc_v, *q.power_w / w_star, w_star).throttle, 0.9);
  ASSERT_GT(w_star, q.omega_rad_s.lo);
  ASSERT_LT(w_star, q.omega_rad_s.hi);
  for (const std::string alg : {"ipopt", "nlopt_slsqp", "nlopt_mma", "nlopt_cobyla"}) {
    if (!IsAlgorithmAvailable(alg)) continue;  // a build without its backend
    const ShaftSolution s = SolveShaftSpeed(d, q, alg);
    EXPECT_TRUE(s.solved) << alg << ": " << s.message;
    const double tol = alg == "nlopt_cobyla" ? kCobylaSpeedRelTol : kSpeedRelTol;
    EXPECT_NEAR(s.omega_rad_s, w_star, tol * w_star) << alg;
    // The reported point is Drive's and delivers the power.
    EXPECT_NEAR(s.point.pmech_w, *q.power_w, 1e-9 * *q.power_w) << alg;
  }
}

TEST(ShaftTest, OptimumBeatsEveryPointOfADenseGrid) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("ipopt");
  EscParams e = IdealEsc();
  e.c0 = 0.02;  // a real ESC: no closed form, the grid is the reference
  e.c1 = 1.15;
  const Drive d(TestMotor(), e);
  ShaftRequest q;
  q.vdc_v = 22.2;
  q.power_w = 120.0;
  q.omega_rad_s = Range{150.0, 2000.0};
  const ShaftSolution s = SolveShaftSpeed(d, q, "ipopt");
  ASSERT_TRUE(s.solved) << s.message;
  double best = 0.0, w_best = 0.0;
  for (int i = 0; i <= 20000; ++i) {
    const double w = q.omega_rad_s.lo + (q.omega_rad_s.hi - q.omega_rad_s.lo) * i / 20000.0;
    const OperatingPoint p = d.Inverse(q.vdc_v, *q.power_w / w, w);
    if (p.eta_system > best) { best = p.eta_system; w_best = w; }
  }
  // The grid step is 0.09 rad/s; the optimum is flat, so the efficiency agrees to ~1e-9.
  EXPECT_GE(s.point.eta_system, best - 1e-9);
  EXPECT_NEAR(s.omega_rad_s, w_best, 1.0);
}

TEST(ShaftTest, ThrottleLimitBindsWhenTheOptimumIsOutOfReach) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("ipopt");
  const Drive d(TestMotor(), IdealEsc());
  ShaftRequest q;
  q.vdc_v = 22.2;
  q.power_w = 60.0;
  q.omega_rad_s = Range{200.0, 1500.0};
  const double w_star = AnalyticOptimalSpeed(d, *q.power_w);
  // Limit the throttle below what the free optimum needs: the solution sits on the limit.
  q.max_throttle = 0.9 * d.Inverse(q.vdc_v, *q.power_w / w_star, w_star).throttle;
  const ShaftSolution s = SolveShaftSpeed(d, q, "ipopt");
  ASSERT_TRUE(s.solved) << s.message;
  EXPECT_NEAR(s.point.throttle, q.max_throttle, 1e-6);
}

}  // namespace
}  // namespace dynosize
