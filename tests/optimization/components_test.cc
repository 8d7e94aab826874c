// The mission-level component rules of optimization/components.h: the propeller speed limit
// (max_rpm and the tip Mach limit) and the mission's pack (units in parallel, mass factor).
#include "optimization/components.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error.h"
#include "common/json_file.h"
#include "common/units.h"

namespace dynosize {
namespace {

Json BaseMission() {
  return ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
}

PropEntry Prop(double diameter_m, std::optional<double> max_rpm) {
  PropEntry p;
  p.id = "test_prop";
  p.diameter_m = diameter_m;
  p.max_rpm = max_rpm;
  return p;
}

// The speed of sound at 15 C: sqrt(1.4*287.05*288.15) = 340.29 m/s.
constexpr double kSound15CMS = 340.294;
// The limit is a closed form; the tolerance is the rounding of kSound15CMS's digits.
constexpr double kRpmTol = 0.05;

TEST(PropSpeedLimit, TipMachLimitsALargeRotorBelowItsMaxRpm) {
  const Mission m = ParseMission(BaseMission(), "quad");
  ASSERT_DOUBLE_EQ(m.constraints.max_tip_mach, 0.7);  // the documented default
  // A 1 m rotor: 60*0.7*340.29/(pi*1) = 4549 rpm, below a stated 6000 rpm limit.
  const PropSpeedLimit big = PropSpeedLimitOf(m, Prop(1.0, 6000.0));
  EXPECT_STREQ(big.rule, "prop_tip_mach");
  EXPECT_NEAR(big.rpm, 60.0 * 0.7 * kSound15CMS / kPi, kRpmTol);
  // A 10 in propeller's tip Mach limit (17,912 rpm) is above its stated 15,000 rpm.
  const PropSpeedLimit small = PropSpeedLimitOf(m, Prop(0.254, 15000.0));
  EXPECT_STREQ(small.rule, "prop_max_rpm");
  EXPECT_DOUBLE_EQ(small.rpm, 15000.0);
}

TEST(PropSpeedLimit, ColderAirLowersTheLimitAndZeroTurnsItOff) {
  Json j = BaseMission();
  j["air"] = {{"temperature_c", -20.0}};
  const Mission cold = ParseMission(j, "quad");
  const double sound_cold = std::sqrt(1.4 * 287.05 * 253.15);
  EXPECT_NEAR(PropSpeedLimitOf(cold, Prop(1.0, std::nullopt)).rpm, 60.0 * 0.7 * sound_cold / kPi, kRpmTol);
  j["constraints"]["max_tip_mach"] = 0.0;
  const Mission off = ParseMission(j, "quad");
  const PropSpeedLimit none = PropSpeedLimitOf(off, Prop(1.0, std::nullopt));
  EXPECT_EQ(none.rule, nullptr);
  EXPECT_TRUE(std::isinf(none.rpm));
}

BatteryEntry Cell() {
  BatteryEntry b;
  b.id = "test_cell";
  b.chemistry = BatteryChemistry::kLiIon;
  b.cells_series = 1;
  b.capacity_ah = 5.0;
  b.voltage_nominal_v = 3.6;
  b.mass_kg = 0.07;
  return b;
}

// A 180S pack of 21700 cells (648 V nominal, 756 V full) with 40 in parallel and a 1.35 pack
// mass factor: capacity and mass as the counts and the factor say.
TEST(MissionPack, AirTaxiPackOfCellsInSeriesAndParallel) {
  Json j = BaseMission();
  j["battery"] = {{"id", "test_cell"}, {"cells", 180}, {"cells_parallel", 40}, {"mass_factor", 1.35},
                  {"mass_factor_source", "test"}};
  const Mission m = ParseMission(j, "taxi");
  const BatteryPack pack(MissionPackParams(m.battery, Cell(), 180));
  EXPECT_DOUBLE_EQ(pack.capacity_ah(), 200.0);
  EXPECT_NEAR(pack.mass_kg(), 180 * 40 * 0.07 * 1.35, 1e-9);
  EXPECT_NEAR(pack.OcvV(1.0), 180 * CellOcvV(BatteryChemistry::kLiIon, 1.0), 1e-9);
}

TEST(MissionPack, LimitsAreStatedNotSilent) {
  Json j = BaseMission();
  j["battery"]["cells"] = 239;  // 239 x 4.2 V = 1,003.8 V: above the 1,000 V limit
  EXPECT_THROW(ParseMission(j, "over"), DataError);
  j["battery"]["cells"] = 238;
  EXPECT_NO_THROW(ParseMission(j, "at the limit"));
  j["battery"]["mass_factor"] = 1.3;  // a factor without its source
  EXPECT_THROW(ParseMission(j, "unsourced"), DataError);
}

}  // namespace
}  // namespace dynosize
