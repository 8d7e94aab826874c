// Fuzz target: the strict mission reader (mission/mission.h ReadMission), the path `evaluate`
// and `optimize` take for their MISSION argument; a mission it accepts is then searched
// (SearchCatalog) on a small catalog, so that inputs reach the one-group and the joint search
// with their ranges (the seeds in fuzz/seeds/missions/ have two free groups and
// capacity and airspeed ranges). The search runs under a deadline (SearchOptions::deadline):
// it stops with the best so far, which is a result, not a finding.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "fuzz_reader.h"
#include "mission/mission.h"
#include "optimization/search.h"

namespace {

// Every 40th motor, ESC and propeller of the bundled catalog, the parts the examples and seeds
// fix, and every battery: written once per process to a folder of its own and loaded.
const dynosize::Catalog& SmallCatalog() {
  static const dynosize::Catalog cat = [] {
    namespace fs = std::filesystem;
    const dynosize::Catalog full = dynosize::Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
    const std::set<std::string> fixed = {"fu_m_23", "fu_m_77", "dc_e_40", "apc_per3_10x7e", "apc_per3_12x6e"};
    dynosize::Json doc;
    auto pick = [&](const auto& list, const char* key) {
      doc[key] = dynosize::Json::array();
      for (std::size_t i = 0; i < list.size(); ++i) {
        if (i % 40 == 0 || fixed.count(list[i].id)) doc[key].push_back(list[i].json);
      }
    };
    pick(full.motors(), "motors");
    pick(full.escs(), "escs");
    pick(full.props(), "props");
    doc["batteries"] = dynosize::Json::array();
    for (const auto& b : full.batteries()) doc["batteries"].push_back(b.json);
    const fs::path dir = dynosize::fuzz::InputPath("_catalog");
    fs::create_directories(dir);
    std::ofstream(dir / "small.json") << dynosize::DumpJson(doc);
    return dynosize::Catalog::Load(dir.string());
  }();
  return cat;
}

}  // namespace

DYNOSIZE_FUZZ_READER(".json", {
  const dynosize::Mission m = dynosize::ReadMission(path);
  dynosize::SearchOptions so;
  so.top_n = 2;
  so.threads = 1;
  so.distinct_designs = true;
  so.deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
  (void)dynosize::SearchCatalog(m, SmallCatalog(), so);
})
