// The example quadcopter and its old pick, shared by credibility_test.cc and
// objective_range_test.cc.
#pragma once

#include <string>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/mission_eval.h"

namespace dynosize {
namespace credibility_fixture {

inline const Catalog& Bundled() {
  static const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  return cat;
}

// The example quadcopter with the pick it had before the credibility model: a folding glider
// prop whose DriveCalc power law promises FM 0.79 in hover.
inline Mission QuadMission(bool allow_folding, const char* ranking = "credible") {
  Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
  j["constraints"]["allow_folding_props_for_lift"] = allow_folding;
  // The old pick reaches a thrust-to-weight of 1.92 at full throttle on the credible propeller
  // (2.19 on the data as given): below the mission's 2, a limit these tests do not check.
  j["constraints"]["min_thrust_to_weight"] = 1.5;
  j["objective"]["ranking"] = ranking;
  return ParseMission(j, "quad");
}

inline Combination OldQuadPick() {
  const Catalog& c = Bundled();
  return Combination{&c.motor("dc_m_56"), &c.esc("dc_e_142"), &c.prop("dc_p_127"), &c.battery("dc_b_363"), 4, {}};
}

}  // namespace credibility_fixture
}  // namespace dynosize
