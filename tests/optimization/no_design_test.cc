// When nothing flies, say why (optimization/no_design.h, docs/search.md#why-nothing-flies): on
// the bundled catalog a 150 kg quadcopter meets neither the hover thrust nor the motor power it
// needs, a mission that flies meets every requirement, and each requirement is a proof: needed
// above best_available, and the search's own answer agrees.
#include "optimization/no_design.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "common/units.h"
#include "mission/mission.h"
#include "model/physics.h"
#include "optimization/search.h"
#include "optimization/small_catalog.h"
#include "report/mission_report.h"

namespace dynosize {
namespace {

namespace fs = std::filesystem;

const std::string kSource = DYNOSIZE_SOURCE_DIR;
const std::string kQuad = kSource + "/examples/missions/quadcopter_1p5kg.json";

const Catalog& Bundled() {
  static const Catalog cat = Catalog::Load(kSource + "/catalog");
  return cat;
}

// The quadcopter example edited by `edit`, written to the test's temporary folder and read back
// as a user's file would be.
template <typename Edit>
Mission EditedQuad(const std::string& tag, Edit edit) {
  Json doc = ReadJsonFile(kQuad);
  edit(doc);
  const fs::path dir = fs::temp_directory_path() / ("dynosize_no_design_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / (tag + ".json");
  std::ofstream(file) << doc.dump(2);
  Mission m = ReadMission(file.string());
  fs::remove_all(dir);
  return m;
}

Mission HeavyQuad() {
  return EditedQuad("heavy", [](Json& d) { d["vehicle"]["mass_kg"] = 150.0; });
}

const UnmetRequirement* Find(const std::vector<UnmetRequirement>& v, const std::string& name) {
  const auto it = std::find_if(v.begin(), v.end(), [&](const UnmetRequirement& r) { return r.requirement == name; });
  return it == v.end() ? nullptr : &*it;
}

TEST(NoDesign, AHeavyQuadcopterNeedsMoreThrustAndPowerThanAnyPartGives) {
  const Mission m = HeavyQuad();
  const std::vector<UnmetRequirement> why = UnmetRequirements(m, Bundled());
  ASSERT_FALSE(why.empty());
  for (const UnmetRequirement& r : why) {
    EXPECT_GT(r.needed, r.best_available) << UnmetRequirementText(r);
    EXPECT_FALSE(r.unit.empty()) << r.requirement;
    EXPECT_FALSE(r.description.empty()) << r.requirement;
  }
  const UnmetRequirement* thrust = Find(why, "hover_thrust_per_rotor");
  ASSERT_NE(thrust, nullptr) << UnmetRequirementText(why.front());
  EXPECT_EQ(thrust->unit, "N");
  // At least the vehicle alone over its 4 rotors, at most 1 % more than that with the lightest
  // parts (a quadcopter's motors, ESCs, propellers and pack weigh well under 1.5 kg).
  const double vehicle_n = 150.0 * kStandardGravity / 4;
  EXPECT_GE(thrust->needed, vehicle_n);
  EXPECT_LE(thrust->needed, 1.01 * vehicle_n);
  ASSERT_EQ(thrust->components.size(), 2u);
  EXPECT_NO_THROW(Bundled().motor(thrust->components[0]));
  EXPECT_NO_THROW(Bundled().prop(thrust->components[1]));
  // Momentum theory (docs/model.md section 11) on the frame's largest propeller (0.33 m).
  const UnmetRequirement* power = Find(why, "motor_power_per_rotor");
  ASSERT_NE(power, nullptr);
  const double d_m = Bundled().prop(power->components[1]).diameter_m;
  EXPECT_LE(d_m, 0.33);
  const double relative_tol = 1e-12;  // the same expression in another order
  EXPECT_NEAR(power->needed, IdealRotorPowerW(thrust->needed, d_m, m.rho_kg_m3) / m.constraints.max_figure_of_merit,
              relative_tol * power->needed);
  // Its mirror image: the disk the best motor could drive is larger than any that fits.
  const UnmetRequirement* disk = Find(why, "propeller_diameter");
  ASSERT_NE(disk, nullptr);
  EXPECT_DOUBLE_EQ(disk->best_available, d_m);
  const double p_best_w = power->best_available;
  EXPECT_NEAR(IdealRotorPowerW(thrust->needed, disk->needed, m.rho_kg_m3) / m.constraints.max_figure_of_merit,
              p_best_w, 1e-9 * p_best_w);
}

TEST(NoDesign, AMissionThatFliesMeetsEveryRequirement) {
  const Mission m = ReadMission(kQuad);
  EXPECT_TRUE(UnmetRequirements(m, Bundled()).empty());
}

// The search returns the reasons with its empty answer, and none with an answer.
TEST(NoDesign, TheSearchReturnsThemWhenNothingFlies) {
  SearchOptions opt;
  opt.top_n = 1;
  opt.threads = 2;
  const SearchResult heavy = SearchCatalog(HeavyQuad(), Bundled(), opt);
  ASSERT_TRUE(heavy.best.empty());
  ASSERT_FALSE(heavy.interrupted);
  ASSERT_FALSE(heavy.no_design_because.empty());
  EXPECT_NE(Find(heavy.no_design_because, "hover_thrust_per_rotor"), nullptr);
  const Json j = SearchResultJson(HeavyQuad(), heavy);
  ASSERT_TRUE(j["no_design_because"].is_array());
  for (const Json& r : j["no_design_because"]) {
    for (const char* key : {"requirement", "needed", "best_available", "unit", "components"}) {
      EXPECT_TRUE(r.contains(key)) << key << " in " << r.dump();
    }
    EXPECT_GT(r["needed"].get<double>(), r["best_available"].get<double>()) << r.dump();
  }
  EXPECT_NE(NoDesignText(heavy).find("  hover_thrust_per_rotor: needs at least "), std::string::npos)
      << NoDesignText(heavy);
  const SearchResult flies = SearchCatalog(ReadMission(kQuad), Bundled(), opt);
  ASSERT_FALSE(flies.best.empty());
  EXPECT_TRUE(flies.no_design_because.empty());
  EXPECT_EQ(NoDesignText(flies), "");
  EXPECT_EQ(SearchResultJson(ReadMission(kQuad), flies)["no_design_because"], Json::array());
}

// The small test catalog (optimization/small_catalog.h) with its "escs" array edited, read back.
template <typename Edit>
Catalog SmallCatalogWithEscs(const std::string& tag, Edit edit_escs) {
  const fs::path dir = testing_util::WriteSmallCatalog(tag);
  const fs::path file = dir / "catalog" / "small.json";
  Json doc = ReadJsonFile(file.string());
  edit_escs(doc["escs"]);
  std::ofstream(file) << DumpJson(doc);
  const Catalog cat = Catalog::Load((dir / "catalog").string());
  fs::remove_all(dir);
  return cat;
}

// The small catalog's quadcopter mission with an n-cell pack.
Mission SmallQuadWithCells(int cells) {
  Json quad = ParseJsonText(testing_util::kQuad, "quad.json");
  quad["battery"]["cells"] = cells;
  return ParseMission(quad, "quad.json");
}

// A pack no ESC is rated for: the small test catalog (optimization/small_catalog.h) with only its
// ESCs that state vdc_max_v (an ESC without a rating passes R1 at any voltage, as in the search),
// the highest of them 33.6 V (8S), and a 10S pack.
TEST(NoDesign, APackAboveEveryRatingNamesTheVoltage) {
  const Catalog cat = SmallCatalogWithEscs("no_design_volts", [](Json& escs) {
    Json rated = Json::array();
    for (const Json& e : escs) {
      if (e.contains("vdc_max_v")) rated.push_back(e);
    }
    escs = rated;
  });
  ASSERT_FALSE(cat.escs().empty());
  const Mission m = SmallQuadWithCells(10);
  const std::vector<UnmetRequirement> why = UnmetRequirements(m, cat);
  const UnmetRequirement* esc = Find(why, "controller_voltage");
  ASSERT_NE(esc, nullptr);
  EXPECT_EQ(esc->unit, "V");
  EXPECT_EQ(esc->search_rule, "esc_voltage");
  EXPECT_NEAR(esc->needed, 10 * 4.2, 0.05);  // a LiPo's full-charge OCV, 4.2 V per cell
  ASSERT_EQ(esc->components.size(), 1u);
  double highest_v = 0;
  for (const EscEntry& e : cat.escs()) highest_v = std::max(highest_v, e.params.vdc_max_v);
  EXPECT_EQ(esc->best_available, highest_v);
  EXPECT_EQ(cat.esc(esc->components[0]).params.vdc_max_v, highest_v);
  const std::string line = UnmetRequirementText(*esc);
  EXPECT_EQ(line.find("controller_voltage: needs at least 42 V, the catalog's best gives at most 33.6 V"), 0u) << line;
  // The search agrees: nothing flies, and R1 pruned every ESC.
  const SearchResult s = SearchCatalog(m, cat, {});
  EXPECT_TRUE(s.best.empty());
  EXPECT_NE(Find(s.no_design_because, "controller_voltage"), nullptr);
}

// ESCs that need more voltage than the pack keeps to its cut-off: the small test catalog with
// every ESC's least supply voltage set to 30 V (a high-voltage controller's window) and a 4S pack.
TEST(NoDesign, AnEscWhoseLeastVoltageIsAboveTheCutOffIsNamed) {
  const Catalog cat = SmallCatalogWithEscs("no_design_min_volts", [](Json& escs) {
    for (Json& e : escs) e["vdc_min_v"] = 30.0;
  });
  const Mission m = SmallQuadWithCells(4);
  const std::vector<UnmetRequirement> why = UnmetRequirements(m, cat);
  const UnmetRequirement* esc = Find(why, "controller_min_voltage");
  ASSERT_NE(esc, nullptr);
  EXPECT_EQ(esc->needed, 30.0);
  EXPECT_LT(esc->best_available, 4 * 4.2);  // a 4S pack's cut-off, below its full charge
  EXPECT_EQ(esc->search_rule, "esc_voltage");
  const std::string line = UnmetRequirementText(*esc);
  EXPECT_EQ(line.find("controller_min_voltage: needs at least 30 V"), 0u) << line;
  // The search agrees: nothing flies.
  const SearchResult s = SearchCatalog(m, cat, {});
  EXPECT_TRUE(s.best.empty());
  EXPECT_NE(Find(s.no_design_because, "controller_min_voltage"), nullptr);
}

// No propeller of the catalog fits a 1 cm frame.
TEST(NoDesign, AFrameNoPropellerFits) {
  const Mission m = EditedQuad("frame", [](Json& d) { d["vehicle"]["max_prop_diameter_m"] = 0.01; });
  const std::vector<UnmetRequirement> why = UnmetRequirements(m, Bundled());
  const UnmetRequirement* frame = Find(why, "frame_prop_diameter");
  ASSERT_NE(frame, nullptr);
  EXPECT_EQ(frame->best_available, 0.01);
  EXPECT_GT(frame->needed, 0.01);
  EXPECT_EQ(frame->search_rule, "prop_diameter");
}

// The hover-thrust bound is a bound: a mass whose thrust per rotor is just under the reported
// best is not refused by it (the requirement is met by the same pair).
TEST(NoDesign, JustUnderTheBestThrustTheRequirementIsMet) {
  const std::vector<UnmetRequirement> heavy = UnmetRequirements(HeavyQuad(), Bundled());
  const UnmetRequirement* thrust = Find(heavy, "hover_thrust_per_rotor");
  ASSERT_NE(thrust, nullptr);
  const double extra_kg = thrust->needed * 4 / kStandardGravity - 150.0;  // the lightest parts and pack
  const double mass_kg = 0.95 * thrust->best_available * 4 / kStandardGravity - extra_kg;
  const Mission m = EditedQuad("lighter", [&](Json& d) { d["vehicle"]["mass_kg"] = mass_kg; });
  EXPECT_EQ(Find(UnmetRequirements(m, Bundled()), "hover_thrust_per_rotor"), nullptr) << mass_kg << " kg";
}

}  // namespace
}  // namespace dynosize
