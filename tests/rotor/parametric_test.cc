// Parametric eVTOL rotors (rotor/parametric.h): the hover design of a rotor of the air-taxi class
// is what an engineer expects, and each limit is named when it binds.
#include "rotor/parametric.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/error.h"
#include "common/units.h"
#include "rotor/uiuc_polar.h"

namespace dynosize {
namespace {

TEST(ParametricRotor, SolidityAndTwistAreTheBlades) {
  ParametricRotor p;
  p.radius_m = 1.2;
  p.blades = 3;
  p.solidity = 0.08;
  p.taper = 0.6;
  p.twist_deg = -12.0;
  p.collective_deg = 9.0;
  const BladeGeometry g = ParametricBlade(p);
  EXPECT_NEAR(Solidity(g), 0.08, 1e-3);  // midpoint rule over a linear chord
  EXPECT_NEAR(InterpolateStation(g, 0.75).beta_rad, 9.0 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(InterpolateStation(g, 1.0).chord_over_r / InterpolateStation(g, 0.2).chord_over_r, 0.6, 1e-9);
  p.solidity = 0.5;
  EXPECT_THROW(ParametricBlade(p), UsageError);
}

TEST(ParametricRotor, AirTaxiRotorHoversLikeAHelicopterRotor) {
  // A 2.4 m three-blade rotor lifting 3,000 N (a 1,200 kg four-rotor air taxi's share at
  // T/W 1): disk loading 663 N/m^2. Helicopter rotors hover at FM 0.7-0.8 (Leishman, section
  // 2.9); the UIUC polar at Re 1.6e6 must land there, below momentum theory.
  ParametricRotor p;
  p.radius_m = 1.2;
  const HoverDesign d = DesignHover(p, kUiucFittedPolar, 3000.0, 1.225, 0.7);
  ASSERT_TRUE(d.feasible) << d.message;
  EXPECT_NEAR(d.point.thrust_n, 3000.0, 3000.0 * 1e-4);
  EXPECT_GT(d.point.figure_of_merit, 0.65);
  EXPECT_LT(d.point.figure_of_merit, 0.85);
  EXPECT_LE(d.point.tip_mach, 0.7 + 1e-9);
  EXPECT_GT(d.point.mean_reynolds, 5e5);
  const double ideal = std::pow(d.point.thrust_n, 1.5) / std::sqrt(2.0 * 1.225 * kPi * 1.44);
  EXPECT_NEAR(d.point.power_w, ideal / d.point.figure_of_merit, 1e-6 * d.point.power_w);
}

TEST(ParametricRotor, NamesWhatLimitsIt) {
  ParametricRotor small;
  small.radius_m = 0.5;
  const HoverDesign d = DesignHover(small, kUiucFittedPolar, 3000.0, 1.225, 0.7);
  EXPECT_FALSE(d.feasible);
  // Its strongest collective at the tip limit is deep in stall (CT/sigma 0.29, 75 % of the span):
  // both limits are named.
  EXPECT_EQ(d.limit, "tip Mach and stall");
  EXPECT_GT(d.point.ct_over_sigma, kMaxBladeLoading);
  EXPECT_NE(d.message.find("past stall"), std::string::npos) << d.message;
  EXPECT_LT(d.point.thrust_n, 3000.0);
  ParametricRotor thin;
  thin.radius_m = 1.2;
  thin.solidity = 0.03;
  const HoverDesign t = DesignHover(thin, kUiucFittedPolar, 2500.0, 1.225, 0.7);
  ASSERT_TRUE(t.feasible) << t.message;
  EXPECT_EQ(t.limit, "blade loading") << t.point.ct_over_sigma;
  EXPECT_THROW(DesignHover(thin, kUiucFittedPolar, -1.0, 1.225, 0.7), UsageError);
  EXPECT_THROW(DesignHover(thin, kUiucFittedPolar, 100.0, 1.225, 0.95), UsageError);
}

}  // namespace
}  // namespace dynosize
