// `dynosize evaluate`: a mission flown by one combination of the catalog (`optimize`:
// cmd_optimize.cc).
#include <iostream>
#include <string>
#include <vector>

#include "api/mission_run.h"
#include "api/mission_catalog.h"
#include "catalog/catalog.h"
#include "commands.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/mission_eval.h"
#include "report/mission_report.h"

namespace dynosize::cli {

int RunEvaluate(const EvaluateOptions& o) {
  const Mission mission = ReadMission(o.mission);
  const Catalog loaded = Catalog::Load(o.catalog);
  const api::MissionCatalog mission_catalog(loaded, mission);  // with the mission's sized propellers
  const Catalog& cat = mission_catalog.get();
  const Combination c =
      api::ChooseCombination(mission, cat, {o.motor_id, o.esc_id, o.prop_id, o.battery_id, o.picks, o.cells});
  const MissionResult r = api::EvaluateCombination(mission, c);
  std::vector<std::string> figures;
  if (!o.plot_dir.empty()) figures = WriteSegmentMaps(mission, c, r, o.plot_dir);
  if (o.json) {
    Json j = MissionResultJson(mission, c, r);
    if (!figures.empty()) j["figures"] = figures;
    std::cout << DumpJson(j);
  } else {
    std::cout << mission.name << " (" << o.mission << ")\n" << MissionResultText(mission, c, r);
    for (const auto& f : figures) std::cerr << "wrote " << f << "\n";
  }
  return 0;
}

}  // namespace dynosize::cli
