// The mission reader (strict, one-line errors with the JSON path) and the flight physics.
#include "mission/mission.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli_runner.h"
#include "common/error.h"
#include "common/units.h"
#include "mission/flight.h"

namespace dynosize {
namespace {

const char* kGood = R"({
  "name": "t",
  "vehicle": {"mass_kg": 1.0, "rotors": 4, "drag_area_m2": 0.05, "drag_coefficient": 1.0},
  "battery": {"id": "b", "cells": [3, 4]},
  "objective": {"type": "max_endurance"},
  "segments": [
    {"name": "up", "type": "climb", "rate_m_s": 2, "distance_m": 20},
    {"name": "go", "type": "cruise", "airspeed_m_s": [5, 15], "distance_m": 1000},
    {"name": "stay", "type": "hover", "duration_s": 60},
    {"name": "pump", "type": "shaft", "power_w": 50, "rpm": [3000, 9000], "duration_s": 10}
  ]
})";

Mission Parse(const std::string& text) { return ParseMission(ParseJsonText(text, "m.json"), "m.json"); }

std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const DataError& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string s, const std::string& a, const std::string& b) {
  const auto pos = s.find(a);
  EXPECT_NE(pos, std::string::npos) << a;
  return s.replace(pos, a.size(), b);
}

TEST(MissionTest, ReadsAGoodMission) {
  const Mission m = Parse(kGood);
  EXPECT_EQ(m.vehicle.rotors, 4);
  EXPECT_EQ(m.battery.cells_min, 3);
  EXPECT_EQ(m.battery.cells_max, 4);
  ASSERT_EQ(m.segments.size(), 4u);
  EXPECT_TRUE(m.segments[1].airspeed_m_s.free());
  EXPECT_DOUBLE_EQ(m.segments[3].shaft_omega_rad_s.lo, RpmToRadPerSec(3000));
  // max_endurance without a segment stretches the last hover.
  EXPECT_EQ(m.objective.segment, "stay");
  EXPECT_DOUBLE_EQ(m.constraints.max_throttle, 0.8);
  EXPECT_NEAR(m.rho_kg_m3, 1.225, 1e-3);  // ISA sea level by default
}

TEST(MissionTest, BadFilesGiveOneLineNamingPathValueAndRule) {
  struct Case { std::string from, to, expect; };
  const Case cases[] = {
      {"\"rotors\": 4", "\"rotors\": 0", "$.vehicle.rotors = 0: must be an integer in [1, 64]"},
      {"\"mass_kg\": 1.0", "\"mass_kg\": -1", "$.vehicle.mass_kg = -1: must be a number > 0"},
      {"\"type\": \"hover\"", "\"type\": \"loiter\"", "$.segments[2].type = \"loiter\": must be one of"},
      {"\"duration_s\": 60", "\"distance_m\": 60", "$.segments[2]: unknown key(s) distance_m"},
      {"\"rate_m_s\": 2, ", "", "$.segments[0].rate_m_s: missing"},
      {"\"power_w\": 50", "\"torque_nm\": 0.1, \"power_w\": 50", "give exactly one of power_w and torque_nm"},
      {"\"max_endurance\"", "\"max_range\"", "$.objective.type = \"max_range\": must be one of"},
      {"\"airspeed_m_s\": [5, 15]", "\"airspeed_m_s\": [15, 5]", "a range must have min <= max"},
      {"\"name\": \"go\"", "\"name\": \"up\"", "$.segments[1].name = \"up\": segment names must be unique"},
      {"\"cells\": [3, 4]", "\"cells\": 3.5", "cell counts must be integers"},
      {"\"name\": \"t\",", "\"name\": \"t\", \"extra\": 1,", "$: unknown key(s) extra"},
  };
  for (const Case& c : cases) {
    const std::string err = ErrorOf(Replace(kGood, c.from, c.to));
    EXPECT_NE(err.find(c.expect), std::string::npos) << "got: " << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
    EXPECT_EQ(err.rfind("m.json: ", 0), 0u) << err;
  }
}

// The propeller data window (mission.h): defaults 0.6 and 1.5, 0 = not checked, a top below 1
// refused with the path, the value and the rule.
TEST(MissionTest, PropDataWindowDefaultsAndLimits) {
  const Mission m = ParseMission(ParseJsonText(kGood, "m.json"), "m.json");
  EXPECT_DOUBLE_EQ(m.constraints.prop_below_data_factor, 0.6);
  EXPECT_DOUBLE_EQ(m.constraints.prop_above_data_factor, 1.5);
  const std::string set = Replace(kGood, "\"name\": \"t\",",
                                  "\"name\": \"t\", \"constraints\": {\"prop_below_data_factor\": 0, \"prop_above_data_factor\": 2},");
  const Mission s = ParseMission(ParseJsonText(set, "m.json"), "m.json");
  EXPECT_DOUBLE_EQ(s.constraints.prop_below_data_factor, 0.0);
  EXPECT_DOUBLE_EQ(s.constraints.prop_above_data_factor, 2.0);
  const std::string err = ErrorOf(Replace(kGood, "\"name\": \"t\",",
                                          "\"name\": \"t\", \"constraints\": {\"prop_above_data_factor\": 0.5},"));
  EXPECT_NE(err.find("$.constraints.prop_above_data_factor = 0.5: must be 0 (not checked) or at least 1"), std::string::npos)
      << err;
  const std::string err2 = ErrorOf(Replace(kGood, "\"name\": \"t\",",
                                           "\"name\": \"t\", \"constraints\": {\"prop_below_data_factor\": 1.2},"));
  EXPECT_NE(err2.find("$.constraints.prop_below_data_factor = 1.2"), std::string::npos) << err2;
}

// The figure-of-merit limits (docs/model.md section 11): 0.8 at rest, 0.95 in axial flow by
// default; the axial one is never below the static one; each is in (0, 1].
TEST(MissionTest, FigureOfMeritLimitsAtRestAndInAxialFlow) {
  const Mission m = Parse(kGood);
  EXPECT_DOUBLE_EQ(FigureOfMeritLimit(m.constraints, 0.0), 0.8);
  EXPECT_DOUBLE_EQ(FigureOfMeritLimit(m.constraints, 0.5), 0.95);
  const Mission s = Parse(Replace(kGood, "\"name\": \"t\",",
                                  "\"name\": \"t\", \"constraints\": {\"max_figure_of_merit\": 0.9, "
                                  "\"max_axial_figure_of_merit\": 0.85},"));
  EXPECT_DOUBLE_EQ(FigureOfMeritLimit(s.constraints, 0.0), 0.9);
  EXPECT_DOUBLE_EQ(FigureOfMeritLimit(s.constraints, 20.0), 0.9);  // the larger of the two
  const std::string err = ErrorOf(Replace(kGood, "\"name\": \"t\",",
                                          "\"name\": \"t\", \"constraints\": {\"max_axial_figure_of_merit\": 0},"));
  EXPECT_NE(err.find("$.constraints.max_axial_figure_of_merit = 0"), std::string::npos) << err;
}

const char* kGroups = R"({
  "name": "g",
  "vehicle": {"mass_kg": 2.0, "drag_area_m2": 0.05, "drag_coefficient": 1.0},
  "propulsion": {"lift": {"rotors": 4, "max_prop_diameter_m": 0.4, "idle_drag_area_m2": 0.02},
                 "cruise": {"rotors": 1, "motor": "m", "esc": "e", "prop": "p"}},
  "battery": {"id": "b", "cells": 6},
  "objective": {"type": "min_energy"},
  "segments": [
    {"name": "up", "type": "climb", "rate_m_s": 2, "distance_m": 20, "group": "lift"},
    {"name": "go", "type": "cruise", "airspeed_m_s": 18, "lift_to_drag": 8, "distance_m": 1000, "group": "cruise"},
    {"name": "down", "type": "hover", "duration_s": 30, "group": "lift"}
  ]
})";

TEST(MissionTest, ReadsPropulsionGroups) {
  const Mission m = Parse(kGroups);
  ASSERT_EQ(m.groups.size(), 2u);
  EXPECT_EQ(m.vehicle.rotors, 5);
  const int lift = m.segments[0].group;
  const int cruise = m.segments[1].group;
  EXPECT_EQ(m.groups[lift].name, "lift");
  EXPECT_EQ(m.groups[cruise].name, "cruise");
  EXPECT_FALSE(m.groups[lift].fixed());
  EXPECT_TRUE(m.groups[cruise].fixed());
  EXPECT_EQ(GroupRotors(m, lift), 4);
  EXPECT_EQ(*GroupMaxPropDiameterM(m, lift), 0.4);
  EXPECT_EQ(LiftGroup(m), lift);
  EXPECT_EQ(LiftRotors(m), 4);
  // The idle lift rotors add their drag area while the cruise group flies (the wing-borne
  // cruise: WingBorneCruiseAddsTheDragItsLiftToDragDoesNotHold): in the climb the cruise
  // group's 0 is added, nothing else.
  const RotorLoad up = SegmentRotorLoad(m, m.segments[0], 3.0, 0.0);
  EXPECT_EQ(up.rotors, 4);
  const double w = 3.0 * kStandardGravity;
  EXPECT_NEAR(up.thrust_total_n, w + 0.5 * m.rho_kg_m3 * 4.0 * 0.05, 1e-12 * w);
  Mission hover_cruise = m;
  hover_cruise.segments[1].lift_to_drag = 0.0;  // a multirotor-style cruise on the pusher
  const RotorLoad go = SegmentRotorLoad(hover_cruise, hover_cruise.segments[1], 3.0, 18.0);
  EXPECT_EQ(go.rotors, 1);
  const double drag = 0.5 * m.rho_kg_m3 * 18.0 * 18.0 * (0.05 + 0.02);
  EXPECT_NEAR(go.thrust_total_n, std::hypot(w, drag), 1e-12 * w);
}

TEST(MissionTest, BadGroupsGiveOneLineNamingPathValueAndRule) {
  struct Case { std::string from, to, expect; };
  const Case cases[] = {
      {"\"group\": \"cruise\"", "\"group\": \"pusher\"", "$.segments[1].group = \"pusher\": names no propulsion group (valid: "},
      {", \"group\": \"cruise\"", "", "$.segments[1].group: missing"},
      {"\"motor\": \"m\", ", "", "$.propulsion.cruise"},
      {"\"group\": \"cruise\"", "\"group\": \"lift\"", "$.propulsion.cruise: \"cruise\": no segment uses this group"},
      {"\"mass_kg\": 2.0,", "\"mass_kg\": 2.0, \"rotors\": 4,", "$.vehicle.rotors = 4: must be the sum of the propulsion groups' rotors (5)"},
      {"\"duration_s\": 30, \"group\": \"lift\"", "\"duration_s\": 30, \"group\": \"lift\", \"rotors\": 5",
       "$.segments[2].rotors = 5: must be <= its group's rotors (4)"},
  };
  for (const Case& c : cases) {
    const std::string err = ErrorOf(Replace(kGroups, c.from, c.to));
    EXPECT_NE(err.find(c.expect), std::string::npos) << "got: " << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
  }
  // A group in a mission without propulsion groups.
  const std::string err = ErrorOf(Replace(kGood, "\"duration_s\": 60}", "\"duration_s\": 60, \"group\": \"lift\"}"));
  EXPECT_NE(err.find("$.segments[2].group = \"lift\": needs a \"propulsion\" object"), std::string::npos) << err;
}

// lift_to_drag_of: "aircraft" (the default) or "wing", only beside a lift_to_drag.
TEST(MissionTest, LiftToDragOfIsReadAndCheckedStrictly) {
  EXPECT_EQ(Parse(kGroups).segments[1].lift_to_drag_of, LiftToDragOf::kAircraft);
  const std::string wing = Replace(kGroups, "\"lift_to_drag\": 8,", "\"lift_to_drag\": 8, \"lift_to_drag_of\": \"wing\",");
  EXPECT_EQ(Parse(wing).segments[1].lift_to_drag_of, LiftToDragOf::kWing);
  const std::string aircraft = Replace(kGroups, "\"lift_to_drag\": 8,", "\"lift_to_drag\": 8, \"lift_to_drag_of\": \"aircraft\",");
  EXPECT_EQ(Parse(aircraft).segments[1].lift_to_drag_of, LiftToDragOf::kAircraft);
  struct Case { std::string from, to, expect; };
  const Case cases[] = {
      {"\"lift_to_drag\": 8,", "\"lift_to_drag\": 8, \"lift_to_drag_of\": \"body\",",
       "$.segments[1].lift_to_drag_of = \"body\": must be one of aircraft, wing"},
      {"\"lift_to_drag\": 8,", "\"lift_to_drag_of\": \"wing\",",
       "$.segments[1].lift_to_drag_of = \"wing\": needs lift_to_drag (a cruise without a wing has no L/D)"},
      {"\"lift_to_drag\": 8,", "\"lift_to_drag\": 8, \"lift_to_drag_of\": 1,", "$.segments[1].lift_to_drag_of = 1"},
      {"\"duration_s\": 30, \"group\": \"lift\"", "\"duration_s\": 30, \"group\": \"lift\", \"lift_to_drag_of\": \"wing\"",
       "lift_to_drag_of"},
  };
  for (const Case& c : cases) {
    const std::string err = ErrorOf(Replace(kGroups, c.from, c.to));
    EXPECT_NE(err.find(c.expect), std::string::npos) << "got: " << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
  }
}

TEST(MissionTest, CliRefusesABadMissionWithExit65) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dynosize_mission_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path f = dir / "bad.json";
  std::ofstream(f) << Replace(kGood, "\"rotors\": 4", "\"rotors\": \"four\"");
  const auto r = testing_util::RunCli("evaluate " + f.string() +
                                      " --motor a --esc b --prop c --battery d");
  EXPECT_EQ(r.code, 65) << r.err;
  EXPECT_NE(r.err.find("$.vehicle.rotors = \"four\""), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  const auto missing = testing_util::RunCli("optimize " + (dir / "none.json").string());
  EXPECT_EQ(missing.code, 66) << missing.err;
  fs::remove_all(dir);
}

TEST(MissionTest, ExamplesParse) {
  for (const char* f : {"quadcopter_1p5kg.json", "evtol_lift_cruise.json", "quadplane_2kg.json",
                        "sprayer_hexacopter_25kg.json", "fpv_5in.json"}) {
    EXPECT_NO_THROW(ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/" + f)) << f;
  }
}

// Flight physics: hover carries the weight; forward flight tilts the thrust so that its
// vertical part carries the weight and its horizontal part the drag.
TEST(FlightTest, ForceBalance) {
  const Mission m = Parse(kGood);
  const double mass = 1.6, w = mass * kStandardGravity;
  const RotorLoad hover = SegmentRotorLoad(m, m.segments[2], mass, 0.0);
  EXPECT_DOUBLE_EQ(hover.thrust_per_rotor_n, w / 4);
  const double v = 12.0;
  const RotorLoad cruise = SegmentRotorLoad(m, m.segments[1], mass, v);
  const double drag = 0.5 * m.rho_kg_m3 * v * v * 0.05;
  EXPECT_NEAR(cruise.thrust_total_n * std::cos(cruise.tilt_rad), w, 1e-12 * w);
  EXPECT_NEAR(cruise.thrust_total_n * std::sin(cruise.tilt_rad), drag, 1e-12 * w);
  EXPECT_NEAR(cruise.axial_airspeed_m_s, v * std::sin(cruise.tilt_rad), 1e-12);
  const RotorLoad climb = SegmentRotorLoad(m, m.segments[0], mass, 0.0);
  EXPECT_NEAR(climb.thrust_total_n, w + 0.5 * m.rho_kg_m3 * 4.0 * 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(climb.axial_airspeed_m_s, 2.0);
}

// A wing-borne cruise: T = W/(L/D) + 1/2*rho*V^2*Cd*A_add (flight.h), A_add the idle groups'
// idle_drag_area_m2 always and the body's drag_area_m2 when the L/D is the wing's; Cd the
// vehicle's drag_coefficient, which multiplies every area. Exact arithmetic: the two sides are
// the same few products, so the tolerance is a few ulps of the thrust.
TEST(FlightTest, WingBorneCruiseAddsTheDragItsLiftToDragDoesNotHold) {
  constexpr double kUlps = 1e-14;
  Mission m = Parse(kGroups);
  m.vehicle.drag_coefficient = 1.3;  // a Cd other than 1 shows which areas it multiplies
  const double mass = 3.0, w = mass * kStandardGravity, v = 18.0, q = 0.5 * m.rho_kg_m3 * v * v;
  const RotorLoad aircraft = SegmentRotorLoad(m, m.segments[1], mass, v);
  EXPECT_NEAR(aircraft.thrust_total_n, w / 8 + q * 1.3 * 0.02, kUlps * w);
  EXPECT_DOUBLE_EQ(aircraft.axial_airspeed_m_s, v);
  EXPECT_DOUBLE_EQ(aircraft.tilt_rad, 0.0);
  m.segments[1].lift_to_drag_of = LiftToDragOf::kWing;
  const RotorLoad wing = SegmentRotorLoad(m, m.segments[1], mass, v);
  EXPECT_NEAR(wing.thrust_total_n, w / 8 + q * 1.3 * (0.05 + 0.02), kUlps * w);
  // The thrust rises with the airspeed (what the free-airspeed bounds of search.cc rest on).
  EXPECT_GT(SegmentRotorLoad(m, m.segments[1], mass, v + 1).thrust_total_n, wing.thrust_total_n);
}

// The issue's goal on the example itself: the quadplane's cruise thrust rises by exactly
// 1/2*rho*V^2*Cd*A when a stopped-rotor area A is added, and a body drag area changes nothing
// while the L/D is the whole aircraft's (the example's "aircraft").
TEST(FlightTest, QuadplaneCruiseThrustRisesByTheStoppedRotorsDrag) {
  constexpr double kUlps = 1e-14;
  Mission m = ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadplane_2kg.json");
  std::size_t cruise = 0;
  while (m.segments[cruise].type != SegmentType::kCruise) ++cruise;
  const Segment& s = m.segments[cruise];
  ASSERT_GT(s.lift_to_drag, 0);
  EXPECT_EQ(s.lift_to_drag_of, LiftToDragOf::kAircraft);
  int lift = 0;
  while (m.groups[lift].name != "lift") ++lift;
  const double mass = 1.878, v = s.airspeed_m_s.lo, cd = m.vehicle.drag_coefficient;
  m.groups[lift].idle_drag_area_m2 = 0.0;
  const double t0 = SegmentRotorLoad(m, s, mass, v).thrust_total_n;
  EXPECT_NEAR(t0, mass * kStandardGravity / s.lift_to_drag, kUlps * t0);
  for (const double a : {0.006, 0.05}) {
    m.groups[lift].idle_drag_area_m2 = a;
    const double t = SegmentRotorLoad(m, s, mass, v).thrust_total_n;
    EXPECT_NEAR(t - t0, 0.5 * m.rho_kg_m3 * v * v * cd * a, kUlps * t) << a;
  }
  m.vehicle.drag_area_m2 = 0.3;
  const double with_body = SegmentRotorLoad(m, s, mass, v).thrust_total_n;
  EXPECT_NEAR(with_body - t0, 0.5 * m.rho_kg_m3 * v * v * cd * 0.05, kUlps * with_body);
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

TEST(MissionSizedProps, ReadsSizesForSearchedAndFixedGroups) {
  std::string text = Replace(kGroups, "\"idle_drag_area_m2\": 0.02}",
                             "\"idle_drag_area_m2\": 0.02, \"sized_props\": [\"16x5.5\", {\"param\": \"15x8x3\", \"family\": \"apc_e\"}]}");
  text = Replace(text, "\"prop\": \"p\"", "\"prop\": {\"param\": \"12x6\"}");
  const Mission m = Parse(text);
  const PropulsionGroup& lift = m.groups[m.segments[0].group];
  const PropulsionGroup& cruise = m.groups[m.segments[1].group];
  ASSERT_EQ(lift.sized_props.size(), 2u);
  EXPECT_EQ(SizedPropId(lift.sized_props[0]), "sized_multirotor_16x5.5x2");  // the size's default family
  EXPECT_EQ(SizedPropId(lift.sized_props[1]), "sized_apc_e_15x8x3");
  EXPECT_TRUE(lift.prop_id.empty());
  EXPECT_EQ(cruise.prop_id, "sized_multirotor_12x6x2");  // 12 in at pitch ratio 0.5: multirotor
  EXPECT_TRUE(cruise.fixed());
}

TEST(MissionSizedProps, BadSizesGiveOneLineNamingPathValueAndRule) {
  const std::string base = "\"idle_drag_area_m2\": 0.02}";
  struct Case { std::string to, expect; };
  const Case cases[] = {
      {"\"idle_drag_area_m2\": 0.02, \"sized_props\": [\"16\"]}", "$.propulsion.lift.sized_props[0]: propeller size '16'"},
      {"\"idle_drag_area_m2\": 0.02, \"sized_props\": [{\"param\": \"16x5\", \"family\": \"wood\"}]}",
       "$.propulsion.lift.sized_props[0].family = \"wood\": not a bundled family"},
      {"\"idle_drag_area_m2\": 0.02, \"sized_props\": []}", "$.propulsion.lift.sized_props = []: must be an array of 1-64"},
      {"\"idle_drag_area_m2\": 0.02, \"sized_props\": [7]}", "$.propulsion.lift.sized_props[0]: must be a size"},
  };
  for (const Case& c : cases) {
    try {
      Parse(Replace(kGroups, base, c.to));
      ADD_FAILURE() << "no error for " << c.to;
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
    }
  }
  // A fixed group's propeller is its "prop": no sized_props beside it.
  const std::string fixed = Replace(kGroups, "\"prop\": \"p\"}", "\"prop\": \"p\", \"sized_props\": [\"12x6\"]}");
  EXPECT_THROW(Parse(fixed), DataError);
}

// Rotor sizing (issue 52 item 5): a group's own families, or the catalog's within its frame.
TEST(MissionPropSizing, OffersTheGridOfTheGroupsOwnOrTheCatalogsFamilies) {
  PropSizing catalog_family;
  catalog_family.id = "fam";
  catalog_family.family = "multirotor";
  catalog_family.diameter_min_m = 0.30;
  catalog_family.diameter_max_m = 1.5;
  catalog_family.pitch_ratio_min = catalog_family.pitch_ratio_max = 0.35;
  catalog_family.blades = {2};
  const std::vector<PropSizing> families = {catalog_family};
  Mission m = Parse(kGroups);
  const int lift = m.segments[0].group, cruise = m.segments[1].group;
  // Within the lift group's 0.40 m: 0.30, 0.32, ... 0.38 and 0.40 (the frame's limit).
  const std::vector<PropSize> offered = OfferedSizes(m, families, lift);
  ASSERT_EQ(offered.size(), 6u);
  EXPECT_DOUBLE_EQ(offered.front().diameter_m, 0.30);
  EXPECT_DOUBLE_EQ(offered.back().diameter_m, 0.40);
  EXPECT_DOUBLE_EQ(offered.back().pitch_m, 0.35 * 0.40);
  EXPECT_TRUE(OfferedSizes(m, families, cruise).empty());  // a fixed group sizes nothing
  // No frame limit: the catalog's families are not offered (a 1.5 m rotor on a 2 kg quadplane).
  m.groups[static_cast<std::size_t>(lift)].max_prop_diameter_m.reset();
  EXPECT_TRUE(OfferedSizes(m, families, lift).empty());
  // The group's own: an empty list offers none; its own families replace the catalog's.
  const Mission none = Parse(Replace(kGroups, "\"idle_drag_area_m2\": 0.02}", "\"idle_drag_area_m2\": 0.02, \"prop_sizing\": []}"));
  EXPECT_TRUE(OfferedSizes(none, families, lift).empty());
  const Mission own = Parse(Replace(kGroups, "\"idle_drag_area_m2\": 0.02}",
                                    "\"idle_drag_area_m2\": 0.02, \"prop_sizing\": [{\"family\": \"apc_e\", "
                                    "\"diameter_m\": [0.2, 0.25], \"pitch_ratio\": [0.5, 0.6], \"blades\": [2, 3]}]}"));
  const std::vector<PropSize> sizes = OfferedSizes(own, families, lift);
  // 0.20, 0.22, 0.24, 0.25 m x pitch ratio 0.50, 0.55, 0.60 x 2 and 3 blades.
  ASSERT_EQ(sizes.size(), 24u);
  for (const PropSize& s : sizes) {
    EXPECT_EQ(s.family, "apc_e");
    EXPECT_GE(s.diameter_m, 0.2 - 1e-12);
    EXPECT_LE(s.diameter_m, 0.25 + 1e-12);
  }
  // Without a pitch ratio: the family's measured blades' range (multirotor 0.31-0.56: 6 ratios).
  const Mission default_pd = Parse(Replace(kGroups, "\"idle_drag_area_m2\": 0.02}",
                                           "\"idle_drag_area_m2\": 0.02, \"prop_sizing\": [{\"family\": \"multirotor\", \"diameter_m\": 0.3}]}"));
  const std::vector<PropSize> one_d = OfferedSizes(default_pd, families, lift);
  ASSERT_FALSE(one_d.empty());
  EXPECT_NEAR(one_d.front().pitch_m / 0.3, FindFamily("multirotor")->pd_min, 1e-12);
  EXPECT_NEAR(one_d.back().pitch_m / 0.3, FindFamily("multirotor")->pd_max, 1e-12);
}

TEST(MissionPropSizing, BadSizingGivesOneLineNamingPathValueAndRule) {
  const std::string base = "\"idle_drag_area_m2\": 0.02}";
  struct Case { std::string sizing, expect; };
  const Case cases[] = {
      {"{}", "$.propulsion.lift.prop_sizing: must be an array"},
      {"[{\"family\": \"wood\", \"diameter_m\": [0.2, 0.3]}]", "$.propulsion.lift.prop_sizing[0].family = \"wood\""},
      {"[{\"family\": \"apc_e\"}]", "$.propulsion.lift.prop_sizing[0].diameter_m"},
      {"[{\"family\": \"apc_e\", \"diameter_m\": [0.3, 0.2]}]", "min <= max"},
      {"[{\"family\": \"apc_e\", \"diameter_m\": [0.2, 0.3], \"pitch_ratio\": [0, 0.5]}]", "pitch_ratio[0] = 0"},
      {"[{\"family\": \"apc_e\", \"diameter_m\": [0.2, 0.3], \"blades\": [9]}]", "blades = [9]: each blade count must be an integer 1-8"},
      {"[{\"family\": \"apc_e\", \"diameter_m\": 0.2, \"twist\": 3}]", "twist"},
  };
  for (const Case& c : cases) {
    try {
      Parse(Replace(kGroups, base, "\"idle_drag_area_m2\": 0.02, \"prop_sizing\": " + c.sizing + "}"));
      ADD_FAILURE() << "no error for " << c.sizing;
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
    }
  }
  // A fixed group's propeller is its "prop".
  EXPECT_THROW(Parse(Replace(kGroups, "\"prop\": \"p\"}", "\"prop\": \"p\", \"prop_sizing\": []}")), DataError);
}

}  // namespace
}  // namespace dynosize
