// The propeller's speed for a required thrust (optimization/prop_speed.h), on every propeller
// of the bundled catalog: static (the closed form of coefficients and power laws, the root
// finder of tables) and in axial inflow (the root finder wherever the data see the inflow).
#include "optimization/prop_speed.h"

#include <gtest/gtest.h>

#include <string>

#include "catalog/catalog.h"
#include "common/units.h"

namespace dynosize {
namespace {

constexpr double kRhoKgM3 = 1.225;  // ISA sea level
// The root finder stops when its bracket is 1e-12 of the speed wide; thrust ~ omega^2 there, so
// the thrust at the returned speed (the bracket's upper end) is within a few 1e-12 of the
// request. The closed form inverts the same coefficients: rounding.
constexpr double kThrustRelTol = 1e-9;

const Catalog& Bundled() {
  static const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  return cat;
}

// Half the thrust at the top of the data is reached below the top, with the thrust asked for;
// a ceiling below that speed refuses it and returns the ceiling with the propeller there.
TEST(PropSpeedTest, GivesTheRequiredThrustOrRefusesAboveTheCeiling) {
  int checked = 0;
  for (const PropEntry& entry : Bundled().props()) {
    const PropModel prop(entry);
    const double w_top = RpmToRadPerSec(prop.valid_range().rpm_hi);
    for (const double airspeed : {0.0, 5.0}) {
      const double t_top = prop.Evaluate(w_top, kRhoKgM3, airspeed).thrust_n;
      if (!(t_top > 0.0)) continue;  // no thrust at that inflow: nothing to ask for
      const double t_req = 0.5 * t_top;
      double omega = 0.0;
      PropEvaluation ev;
      ASSERT_TRUE(PropSpeedForThrust(prop, t_req, kRhoKgM3, airspeed, w_top, &omega, &ev))
          << entry.id << " at " << airspeed << " m/s";
      EXPECT_GT(omega, 0.0) << entry.id;
      EXPECT_LE(omega, w_top) << entry.id;
      EXPECT_NEAR(ev.thrust_n, t_req, kThrustRelTol * t_req) << entry.id << " at " << airspeed << " m/s";
      EXPECT_EQ(ev.omega_rad_s, omega) << entry.id << ": the evaluation is the one at the root";
      // The same request under a ceiling just below the root: refused, held at the ceiling.
      const double w_cap = 0.9 * omega;
      double omega_cap = 0.0;
      PropEvaluation ev_cap;
      EXPECT_FALSE(PropSpeedForThrust(prop, t_req, kRhoKgM3, airspeed, w_cap, &omega_cap, &ev_cap)) << entry.id;
      EXPECT_EQ(omega_cap, w_cap) << entry.id;
      EXPECT_LT(ev_cap.thrust_n, t_req) << entry.id;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100) << "the bundled catalog has hundreds of propellers";
}

}  // namespace
}  // namespace dynosize
