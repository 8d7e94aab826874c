// The catalog a mission runs on (api/mission_catalog.h): the sized propellers a mission names or
// sizes are added, the search refuses a mission whose sized propellers its catalog lacks.
#include "api/mission_catalog.h"

#include <gtest/gtest.h>

#include "common/error.h"
#include "optimization/search.h"

namespace dynosize {
namespace {

const std::string kMission = DYNOSIZE_SOURCE_DIR "/examples/missions/air_taxi_sized_rotors.json";

TEST(MissionCatalog, AddsTheMissionsSizedPropellers) {
  const Catalog base = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  const Mission m = ReadMission(kMission);
  const api::MissionCatalog with(base, m);
  // The four sizes it lists and the grids of the catalog's families within the lift group's 1.65 m.
  int lift = 0;
  while (m.groups[static_cast<std::size_t>(lift)].name != "lift") ++lift;
  const std::size_t offered = OfferedSizes(m, base.prop_families(), lift).size();
  EXPECT_GT(offered, 4u);
  EXPECT_EQ(static_cast<std::size_t>(with.sized_props_added()), offered);
  EXPECT_EQ(with.get().props().size(), base.props().size() + offered);
  const PropEntry& p = with.get().prop("sized_multirotor_64x21x2");
  EXPECT_NEAR(p.diameter_m, 64 * 0.0254, 1e-9);
  EXPECT_EQ(p.tier, DataTier::kEstimated);
  for (const PropEntry& e : with.get().props()) {
    if (IsSizedPropId(e.id)) {
      EXPECT_LE(e.diameter_m, 1.65 + 1e-9) << e.id;
    }
  }
  // Without sized propellers (none listed, "prop_sizing": []) the loaded catalog itself is used.
  Mission plain = m;
  for (PropulsionGroup& g : plain.groups) {
    g.sized_props.clear();
    if (!g.fixed()) g.prop_sizing = std::vector<PropSizing>{};
  }
  const api::MissionCatalog same(base, plain);
  EXPECT_EQ(&same.get(), &base);
  // The search refuses to leave them out quietly.
  EXPECT_THROW(SearchCatalog(m, base, SearchOptions{}), UsageError);
}

TEST(MissionCatalog, RefusesAGridTooLargeToBuild) {
  const Catalog base = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  Mission m = ReadMission(kMission);
  for (PropulsionGroup& g : m.groups) {
    if (g.fixed()) continue;
    PropSizing s;
    s.family = "evtol_rotor";
    s.diameter_min_m = 1.0;
    s.diameter_max_m = 8.0;
    s.pitch_ratio_min = 0.2;
    s.pitch_ratio_max = 1.0;
    s.blades = {2, 3, 4};
    g.prop_sizing = std::vector<PropSizing>{s};
    g.max_prop_diameter_m.reset();
  }
  try {
    const api::MissionCatalog big(base, m);
    ADD_FAILURE() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("$.propulsion.lift: the propeller sizing offers more than 3000 sizes"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace dynosize
