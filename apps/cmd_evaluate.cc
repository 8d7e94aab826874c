// `dynosize evaluate` and `dynosize optimize` (issue #6): a mission flown by one combination,
// or the best combinations of the catalog.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "catalog/catalog.h"
#include "commands.h"
#include "common/error.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/mission_eval.h"
#include "optimization/search.h"
#include "report/mission_report.h"

namespace dynosize::cli {

namespace {

int CellsFor(const Mission& m, const BatteryEntry& b, int cells) {
  if (cells == 0) {
    if (m.battery.cells_min != m.battery.cells_max) {
      throw UsageError("--cells: the mission allows " + std::to_string(m.battery.cells_min) + "-" +
                       std::to_string(m.battery.cells_max) + " cells in series: say which");
    }
    cells = m.battery.cells_min;
  }
  if (cells % b.cells_series != 0) {
    throw UsageError("--cells " + std::to_string(cells) + ": battery '" + b.id + "' has " +
                     std::to_string(b.cells_series) + " cells in series; give a multiple");
  }
  return cells;
}

}  // namespace

int RunEvaluate(const EvaluateOptions& o) {
  const Mission mission = ReadMission(o.mission);
  const Catalog cat = Catalog::Load(o.catalog_dir);
  Combination c;
  c.motor = &cat.motor(o.motor_id);
  c.esc = &cat.esc(o.esc_id);
  c.prop = &cat.prop(o.prop_id);
  c.battery = &cat.battery(o.battery_id);
  c.cells = CellsFor(mission, *c.battery, o.cells);
  const MissionEvaluator ev(mission, c);
  MissionResult r = ev.Solve();
  AddObjectiveRange(mission, c, &r);  // objective_range and tiers (optimization/credibility.h)
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

int RunOptimize(const OptimizeOptions& o) {
  const Mission mission = ReadMission(o.mission);
  const Catalog cat = Catalog::Load(o.catalog_dir);
  SearchOptions so;
  so.top_n = o.top;
  const bool bar = !o.json && !o.quiet && isatty(fileno(stderr));
  if (bar) {
    so.progress = [](double f) {
      const int width = 40;
      const int filled = static_cast<int>(f * width + 0.5);
      std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] "
                << std::setw(3) << static_cast<int>(100 * f) << " %" << std::flush;
    };
  }
  const SearchResult s = SearchCatalog(mission, cat, so);
  if (bar) std::cerr << "\r" << std::string(50, ' ') << "\r";
  std::vector<std::string> figures;
  if (!o.plot_dir.empty()) {
    figures.push_back(WriteParetoFigure(mission, s, o.plot_dir));
    if (!s.best.empty()) {
      for (const auto& f : WriteSegmentMaps(mission, s.best[0].combination, s.best[0].result, o.plot_dir)) {
        figures.push_back(f);
      }
    }
  }
  if (o.json) {
    Json j;
    Json results = Json::array();
    for (const auto& b : s.best) results.push_back(MissionResultJson(mission, b.combination, b.result));
    j["results"] = results;
    j["searched"] = s.searched;
    j["pruned"] = s.pruned;
    j["combinations"] = s.combinations;
    Json by = Json::object();
    for (const auto& [rule, n] : s.pruned_by) by[rule] = n;
    j["pruned_by"] = by;
    j["seconds"] = s.seconds;
    if (!figures.empty()) j["figures"] = figures;
    std::cout << DumpJson(j);
    return 0;
  }
  std::ostringstream out;
  out << mission.name << " (" << o.mission << "): objective " << ObjectiveTypeName(mission.objective.type)
      << (mission.objective.segment.empty() ? "" : " ('" + mission.objective.segment + "')")
      << (mission.objective.ranking == DataScenario::kAsGiven ? ", ranked on the data as given"
                                                              : ", ranked on the credible value (README: Ranking)")
      << "\n";
  out << s.combinations << " combinations: " << s.searched << " evaluated exactly, " << s.pruned
      << " pruned by provably safe bounds (";
  bool first = true;
  for (const auto& [rule, n] : s.pruned_by) {
    if (n == 0) continue;
    out << (first ? "" : ", ") << rule << " " << n;
    first = false;
  }
  out << ") in " << std::fixed << std::setprecision(2) << s.seconds << " s\n";
  if (s.best.empty()) {
    out << "no combination of the catalog flies this mission within its constraints\n";
  }
  for (std::size_t i = 0; i < s.best.size(); ++i) {
    out << "\n#" << (i + 1) << " "
        << MissionResultText(mission, s.best[i].combination, s.best[i].result);
  }
  out << "\nreproduce a line: dynosize evaluate " << o.mission << " --motor M --esc E --prop P --battery B --cells N;"
      << " a segment's point: dynosize simulate --motor M --esc E --vdc VDC --throttle THR --torque Q\n";
  std::cout << out.str();
  for (const auto& f : figures) std::cerr << "wrote " << f << "\n";
  return 0;
}

}  // namespace dynosize::cli
