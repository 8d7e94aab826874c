// The rotor diameter as a sizing variable (issue 52 item 5): the search over a family's grid of
// sizes (rotor/family.h SizingGrid, mission.h OfferedSizes, api/mission_catalog.h) against every
// combination evaluated, and each group searching only the sizes offered to it.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "api/mission_catalog.h"
#include "catalog/catalog.h"
#include "common/json_file.h"
#include "optimization/mission_eval.h"
#include "optimization/search.h"
#include "optimization/search_stages.h"

namespace dynosize {
namespace {

// The 150 kg cargo octocopter (examples/missions/cargo_octocopter_150kg.json) on a few of the
// bundled catalog's heavy-lift parts, its rotor sized within 1.00-1.32 m at pitch ratios
// 0.35-0.45 (17 x 3 sizes) beside KDE's measured 35.5 in.
Catalog CargoCatalog() {
  const Catalog full = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  Json doc;
  for (const char* id : {"ev_m_u15l_kv43_manned_aircraft_type_uav_motor", "hl_m_t_motor_u15ii_kv80", "ev_m_reg_60"}) {
    doc["motors"].push_back(full.motor(id).json);
  }
  doc["escs"].push_back(full.esc("hv_e_advanced_power_drives_uhv_28s").json);
  doc["props"].push_back(full.prop("kde_p_35.5x12.1x2").json);
  doc["batteries"].push_back(full.battery("pc_b_tattuplus25c22000mah12s1p").json);
  Catalog c;
  std::vector<std::string> problems;
  c.AddDocument(doc, "cargo.json", &problems);
  EXPECT_TRUE(problems.empty()) << problems.front();
  return c;
}

Mission CargoMission() {
  Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/cargo_octocopter_150kg.json");
  j["battery"]["id"] = Json::array({"pc_b_tattuplus25c22000mah12s1p"});
  j["vehicle"]["prop_sizing"] =
      Json::array({{{"family", "multirotor"}, {"diameter_m", {1.0, 1.32}}, {"pitch_ratio", {0.35, 0.45}}}});
  return ParseMission(j, "cargo");
}

std::string Name(const Combination& c) { return c.motor->id + "|" + c.prop->id + "|" + std::to_string(c.cells); }

// The search's best three against every (motor, ESC, propeller, pack) of the grid evaluated: the
// sizing is exact on its grid (the bounds of docs/search.md hold for a sized entry as for any).
TEST(PropSizingSearch, EqualsTheBestOfItsGridEvaluatedExhaustively) {
  const Catalog base = CargoCatalog();
  const Mission m = CargoMission();
  const api::MissionCatalog mc(base, m);
  const Catalog& cat = mc.get();
  ASSERT_EQ(mc.sized_props_added(), 17 * 3);
  std::vector<std::pair<double, std::string>> all;
  for (const MotorEntry& mo : cat.motors()) {
    for (const PropEntry& p : cat.props()) {
      const Combination c{&mo, &cat.escs()[0], &p, &cat.batteries()[0], 24, {}};
      const MissionResult r = MissionEvaluator(m, c).Solve();
      if (r.feasible) all.emplace_back(r.score, Name(c));
    }
  }
  ASSERT_GE(all.size(), 3u);
  std::sort(all.begin(), all.end());
  SearchOptions so;
  so.top_n = 3;
  so.distinct_designs = false;
  const SearchResult s = SearchCatalog(m, cat, so);
  ASSERT_EQ(s.best.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(Name(s.best[i].combination), all[i].second) << i;
    EXPECT_EQ(s.best[i].result.score, all[i].first) << i;  // same code path, bit for bit
  }
  // The best is a sized rotor (KDE's measured 35.5 in is in the list too).
  EXPECT_NE(s.best[0].combination.prop->id.find("sized_multirotor_"), std::string::npos);
  EXPECT_GT(s.pruned, 0);
}

// Designs: the sizes of one family and blade count with one motor are one design.
TEST(PropSizingSearch, SizesOfOneFamilyAreOneDesign) {
  const Catalog base = CargoCatalog();
  const Mission m = CargoMission();
  const api::MissionCatalog mc(base, m);
  SearchOptions so;
  so.top_n = 3;
  so.distinct_designs = true;
  const SearchResult s = SearchCatalog(m, mc.get(), so);
  ASSERT_GE(s.best.size(), 2u);
  for (std::size_t i = 0; i < s.best.size(); ++i) {
    for (std::size_t k = 0; k < i; ++k) {
      const Combination& a = s.best[i].combination;
      const Combination& b = s.best[k].combination;
      const bool both_sized = IsSizedPropId(a.prop->id) && IsSizedPropId(b.prop->id);
      EXPECT_FALSE(a.motor == b.motor && (a.prop == b.prop || both_sized)) << Name(a) << " and " << Name(b);
    }
  }
}

// Each group searches the sizes offered to it only (R0, "prop_not_offered").
TEST(PropSizingSearch, AGroupIsNotOfferedAnotherGroupsSizes) {
  const Catalog base = CargoCatalog();
  Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/cargo_octocopter_150kg.json");
  j["battery"]["id"] = Json::array({"pc_b_tattuplus25c22000mah12s1p"});
  j["vehicle"].erase("max_prop_diameter_m");
  j["vehicle"].erase("rotors");
  j["propulsion"] = {
      {"lift", {{"rotors", 8}, {"max_prop_diameter_m", 1.32},
                {"prop_sizing", Json::array({{{"family", "multirotor"}, {"diameter_m", {1.2, 1.32}}, {"pitch_ratio", 0.4}}})}}},
      {"pusher", {{"rotors", 1}, {"max_prop_diameter_m", 1.32}, {"prop_sizing", Json::array()}}}};
  for (Json& sg : j["segments"]) sg["group"] = sg["type"] == "cruise" ? "pusher" : "lift";
  const Mission m = ParseMission(j, "groups");
  const api::MissionCatalog mc(base, m);
  const Catalog& cat = mc.get();
  ASSERT_EQ(mc.sized_props_added(), 7);  // 1.20, 1.22, ..., 1.30, 1.32 m at 0.4
  const search_internal::SizedPropOffer offer(m, cat);
  int lift = 0;
  while (m.groups[static_cast<std::size_t>(lift)].name != "lift") ++lift;
  const int pusher = 1 - lift;
  for (std::size_t p = 0; p < cat.props().size(); ++p) {
    const bool sized = IsSizedPropId(cat.props()[p].id);
    EXPECT_TRUE(offer.Offered(lift, p)) << cat.props()[p].id;
    EXPECT_EQ(offer.Offered(pusher, p), !sized) << cat.props()[p].id;
    if (sized) {
      EXPECT_STREQ(search_internal::PropFrameRule(m, offer, pusher, false, cat, p), "prop_not_offered");
    }
  }
}

}  // namespace
}  // namespace dynosize
