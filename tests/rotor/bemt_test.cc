// The blade-element model (rotor/bemt.h): its element equations conserve momentum, an ideal
// rotor reaches the figure of merit of momentum theory, and no real geometry beats it.
#include "rotor/bemt.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/error.h"
#include "common/units.h"

namespace dynosize {
namespace {

// Solved to psi within 1e-9 rad: the identities below hold to about that, relative.
constexpr double kIdentityRel = 1e-7;

AirfoilPolar NoDragPolar() {
  AirfoilPolar p;
  p.cd0 = 0.0;
  p.cd2 = 0.0;
  p.cl_max = 3.0;  // no stall in these tests
  p.cl_min = -3.0;
  p.cl0 = 0.0;
  p.cl_alpha_per_rad = 2.0 * kPi;
  return p;
}

// A 0.5 m radius two-blade rotor: constant chord c/R 0.08 and twist beta = atan(k/x) + alpha0
// (the ideal twist of a uniform inflow, Leishman eq 3.67 in small angles).
BladeGeometry IdealTwistRotor(double root = 0.02) {
  BladeGeometry g;
  g.name = "ideal";
  g.radius_m = 0.5;
  g.blades = 2;
  g.root_r_over_r = root;
  for (int i = 0; i <= 40; ++i) {
    const double x = root + (1.0 - root) * i / 40.0;
    g.stations.push_back({x, 0.08, std::atan(0.06 / x) + 0.03, 0.0});
  }
  return g;
}

TEST(Bemt, ElementsConserveAxialAndAngularMomentum) {
  BemtOptions opt;
  opt.elements = 30;
  for (const bool tip_loss : {false, true}) {
    opt.tip_loss = tip_loss;
    const Bemt bemt(IdealTwistRotor(0.15), NoDragPolar(), opt);
    for (const double v : {0.0, 5.0, 20.0}) {
      for (int i = 0; i < bemt.elements(); ++i) {
        const BemtElement e = bemt.SolveElement(i, 300.0, v, 1.2);
        ASSERT_TRUE(e.solved) << i;
        const double k = 4.0 * e.wa_m_s / (kPi * 2 * e.wt_m_s);
        const double s = std::sqrt(1.0 + k * k);  // eq B7's heavy-loading term
        const double annulus = 4.0 * kPi * 1.2 * e.r_m * e.tip_loss_f * s * e.dr_m;
        EXPECT_NEAR(e.dthrust_n, annulus * e.va_m_s * (v + e.va_m_s), kIdentityRel * std::fabs(e.dthrust_n) + 1e-15)
            << "element " << i << " V " << v;
        EXPECT_NEAR(e.dtorque_nm, annulus * e.r_m * e.vt_m_s * (v + e.va_m_s),
                    kIdentityRel * std::fabs(e.dtorque_nm) + 1e-15);
      }
    }
  }
}

TEST(Bemt, IdealRotorReachesMomentumTheory) {
  // No drag, no tip loss, ideal twist: the only losses left are the swirl of the wake and the
  // root cut-out (2 % of the radius); momentum theory's FM = 1 is approached from below.
  BemtOptions opt;
  opt.tip_loss = false;
  opt.elements = 200;
  const Bemt bemt(IdealTwistRotor(), NoDragPolar(), opt);
  const BemtPoint p = bemt.Evaluate(300.0, 0.0, 1.225);
  EXPECT_GT(p.thrust_n, 0.0);
  EXPECT_LE(p.figure_of_merit, 1.0);
  EXPECT_GT(p.figure_of_merit, 0.98);  // swirl of a light-loaded rotor: < 1 %
}

TEST(Bemt, DragAndTipLossOnlyLowerTheFigureOfMerit) {
  BemtOptions opt;
  opt.elements = 60;
  const BladeGeometry g = IdealTwistRotor();
  opt.tip_loss = false;
  const double ideal = Bemt(g, NoDragPolar(), opt).Evaluate(300.0, 0.0, 1.225).figure_of_merit;
  opt.tip_loss = true;
  const double tip = Bemt(g, NoDragPolar(), opt).Evaluate(300.0, 0.0, 1.225).figure_of_merit;
  const double real = Bemt(g, AirfoilPolar(), opt).Evaluate(300.0, 0.0, 1.225).figure_of_merit;
  EXPECT_LT(tip, ideal);
  EXPECT_LT(real, tip);
  EXPECT_GT(real, 0.3);
}

TEST(Bemt, AxialFlowNeverBeatsMomentumTheory) {
  const Bemt bemt(IdealTwistRotor(), AirfoilPolar());
  for (const double j : {0.0, 0.1, 0.3, 0.5, 0.7}) {
    const BemtPoint p = bemt.EvaluateAtAdvanceRatio(400.0, j, 1.225);
    if (p.thrust_n <= 0.0) continue;
    EXPECT_LT(p.figure_of_merit, 1.0) << "J " << j;
    EXPECT_LT(p.efficiency, 1.0) << "J " << j;
    EXPECT_NEAR(p.j, j, 1e-12);
  }
}

TEST(Bemt, CoefficientsFollowTheUiucDefinitions) {
  const Bemt bemt(IdealTwistRotor(), AirfoilPolar());
  const double omega = 250.0, rho = 1.1;
  const BemtPoint p = bemt.Evaluate(omega, 3.0, rho);
  const double n = omega / (2.0 * kPi), d = 1.0;
  EXPECT_NEAR(p.ct, p.thrust_n / (rho * n * n * std::pow(d, 4)), 1e-12);
  EXPECT_NEAR(p.cp, p.torque_nm * omega / (rho * n * n * n * std::pow(d, 5)), 1e-12);
  EXPECT_NEAR(p.tip_mach, std::hypot(omega * 0.5, 3.0) / kIsaSeaLevelSpeedOfSoundMS, 1e-12);
  EXPECT_GT(bemt.solidity(), 2 * 0.08 * 0.98 / kPi * 0.99);
  EXPECT_LT(bemt.solidity(), 2 * 0.08 * 0.98 / kPi * 1.01);
}

TEST(Bemt, BadInputGetsOneLine) {
  BladeGeometry g = IdealTwistRotor();
  g.stations[3].r_over_r = g.stations[2].r_over_r;
  try {
    Bemt bad(g, AirfoilPolar());
    FAIL() << "no throw";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("station 4"), std::string::npos) << e.what();
  }
  const Bemt bemt(IdealTwistRotor(), AirfoilPolar());
  EXPECT_THROW(bemt.Evaluate(0.0, 0.0, 1.2), UsageError);
  EXPECT_THROW(bemt.Evaluate(100.0, -1.0, 1.2), UsageError);
  EXPECT_THROW(bemt.Evaluate(100.0, 0.0, std::nan("")), UsageError);
  AirfoilPolar p;
  p.cl_max = 0.2;  // below cl0
  EXPECT_THROW(Bemt(IdealTwistRotor(), p), UsageError);
}

}  // namespace
}  // namespace dynosize
