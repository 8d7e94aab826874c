// The catalog a mission runs on (api/mission_catalog.h): the sized propellers a mission names are
// added, the search refuses a mission whose sized propellers its catalog lacks.
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
  EXPECT_EQ(with.get().props().size(), base.props().size() + 4);
  const PropEntry& p = with.get().prop("sized_multirotor_64x21x2");
  EXPECT_NEAR(p.diameter_m, 64 * 0.0254, 1e-9);
  EXPECT_EQ(p.tier, DataTier::kEstimated);
  // Without sized propellers the loaded catalog itself is used (no copy).
  Mission plain = m;
  for (PropulsionGroup& g : plain.groups) g.sized_props.clear();
  const api::MissionCatalog same(base, plain);
  EXPECT_EQ(&same.get(), &base);
  // The search refuses to leave them out quietly.
  EXPECT_THROW(SearchCatalog(m, base, SearchOptions{}), UsageError);
}

}  // namespace
}  // namespace dynosize
