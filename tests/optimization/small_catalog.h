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

}  // namespace dynosize::testing_util
