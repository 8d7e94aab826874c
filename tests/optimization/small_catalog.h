// A small catalog for the search tests, written from entries of the bundled one: feasible
// and infeasible pairs, one propeller whose data break momentum theory, ESCs that dominate each
// other. WriteSmallCatalog returns a fresh temporary folder with catalog/small.json in it.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "optimization/mission_eval.h"

namespace dynosize::testing_util {

inline std::filesystem::path WriteSmallCatalog(const std::string& tag) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dynosize_" + tag + "_" + std::to_string(getpid()));
  fs::create_directories(dir / "catalog");
  const Catalog full = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  Json doc;
  doc["motors"] = Json::array();
  // These three carry the bundled catalog's "exclude" (catalog/motor_credibility.h: their
  // stored R is a decade too small); the search mechanics tested here need strong motors, so the
  // copy drops the key (CatalogExcludedEntriesAreNotSearched sets its own).
  for (const char* id : {"dc_m_223", "dc_m_1020", "dc_m_1444", "emax_935kv_paper"}) {
    Json m = full.motor(id).json;
    m.erase("exclude");
    doc["motors"].push_back(std::move(m));
  }
  // A geared motor (Hacker A20-6XL with a 4:1 gearbox of efficiency 0.975, model/gear.h): the
  // search's bounds and exhaustive evaluation must agree with a gearbox in the drive too.
  doc["motors"].push_back(full.motor("dc_m_1600").json);
  int extra = 0;
  for (const MotorEntry& m : full.motors()) {  // a few more of the right size
    if (extra < 3 && m.mass_kg && m.kv_rpm_per_v && *m.kv_rpm_per_v > 600 && *m.kv_rpm_per_v < 1000 &&
        *m.mass_kg > 0.05 && *m.mass_kg < 0.12 && m.id != "dc_m_223" && m.id != "dc_m_1020" &&
        m.exclude_reason.empty()) {
      doc["motors"].push_back(m.json);
      ++extra;
    }
  }
  doc["escs"] = Json::array();
  for (const char* id : {"dc_e_252", "dc_e_237", "dc_e_56", "multistar_30a_paper"}) doc["escs"].push_back(full.esc(id).json);
  doc["props"] = Json::array();
  for (const char* id : {"dc_p_410", "dc_p_372", "dc_p_440", "dc_p_173", "apc_per3_10x45mr", "apc_per3_15x8e"}) doc["props"].push_back(full.prop(id).json);
  doc["batteries"] = Json::array();
  doc["batteries"].push_back(full.battery("dc_b_361").json);
  std::ofstream(dir / "catalog" / "small.json") << DumpJson(doc);
  return dir;
}

// Every combination of the small catalog with its battery, 3S and 4S (motors without mass are left
// out, as the search does): exhaustive evaluation's list, which the search tests compare with.
template <typename F>
void ForEachCombination(const Catalog& cat, F&& f) {
  for (const auto& mo : cat.motors()) {
    if (!mo.mass_kg) continue;
    for (const auto& e : cat.escs()) {
      for (const auto& p : cat.props()) {
        for (int cells : {3, 4}) f(Combination{&mo, &e, &p, &cat.battery("dc_b_361"), cells, {}});
      }
    }
  }
}

// Missions flown on the small catalog by the search tests (search_test.cc, joint_search_test.cc,
// top_results_test.cc). A quad with one free group, max_endurance of its loiter:
inline constexpr const char* kQuad = R"({
  "name": "test quad",
  "vehicle": {"mass_kg": 0.75, "rotors": 4, "drag_area_m2": 0.04, "drag_coefficient": 1.0, "avionics_power_w": 5},
  "battery": {"id": "dc_b_361", "cells": [3, 4], "reserve_soc": 0.2},
  "constraints": {"min_thrust_to_weight": 1.1, "allow_folding_props_for_lift": true},
  "objective": {"type": "max_endurance", "segment": "loiter"},
  "segments": [
    {"name": "takeoff", "type": "climb", "rate_m_s": 2, "distance_m": 30},
    {"name": "outbound", "type": "cruise", "airspeed_m_s": 10, "distance_m": 1000},
    {"name": "loiter", "type": "hover", "duration_s": 300},
    {"name": "landing", "type": "climb", "rate_m_s": -1, "distance_m": 30}
  ]
})";

// A small quadplane: four lift rotors climb, hover and descend, one pusher flies a wing-borne
// cruise; both groups free (no motor/esc/prop). The pusher's frame takes props up to 11 in.
inline constexpr const char* kFreeQuadplane = R"({
  "name": "test quadplane, both groups free",
  "vehicle": {"mass_kg": 0.6, "drag_area_m2": 0.03, "drag_coefficient": 1.0, "avionics_power_w": 4},
  "propulsion": {
    "lift": {"rotors": 4, "idle_drag_area_m2": 0.004},
    "pusher": {"rotors": 1, "max_prop_diameter_m": 0.28}
  },
  "battery": {"id": "dc_b_361", "cells": [3, 4], "reserve_soc": 0.25},
  "constraints": {"allow_folding_props_for_lift": true},
  "objective": {"type": "min_energy"},
  "segments": [
    {"name": "up", "type": "climb", "rate_m_s": 1.5, "distance_m": 20, "group": "lift"},
    {"name": "cruise", "type": "cruise", "airspeed_m_s": 12, "lift_to_drag": 6, "distance_m": 3000, "group": "pusher"},
    {"name": "hover", "type": "hover", "duration_s": 30, "group": "lift"},
    {"name": "down", "type": "climb", "rate_m_s": -1, "distance_m": 20, "group": "lift"}
  ]
})";

}  // namespace dynosize::testing_util
