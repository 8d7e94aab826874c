// `dynosize optimize`: the best combinations of the catalog for a mission (the search:
// src/optimization/search.h, its rules docs/search.md).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "api/mission_run.h"
#include "api/mission_catalog.h"
#include "catalog/catalog.h"
#include "commands.h"
#include "interrupt.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/search.h"
#include "report/mission_report.h"

namespace dynosize::cli {

namespace {

// Progress on a terminal's stderr only (never with --json or --quiet, never into a pipe or a
// file), and only once the search has run for a second: the elapsed time, the share of the work
// done (search.h, SearchProgress) and the best so far in the unit the result prints.
std::function<void(const SearchProgress&)> ProgressLine(const Mission& mission, const OptimizeOptions& o,
                                                       bool* shown) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string what = o.variants ? " combinations" : " designs";
  const int top = o.top;
  return [&mission, shown, t0, what, top](const SearchProgress& p) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (elapsed < 1.0) return;
    *shown = true;
    std::ostringstream line;
    line << "\r" << ElapsedText(elapsed) << ": " << std::setw(3) << static_cast<int>(100 * p.fraction) << " % done";
    // Until N are known the work left is not (SearchProgress::fraction).
    if (p.found < top && p.fraction < 1.0) line << " (finding the first " << top << what << ": " << p.found << ")";
    line << ", " << p.searched << " evaluated";
    if (p.has_best) {
      line << ", best " << std::fixed << std::setprecision(2) << DisplayObjective(mission, p.best_objective)
           << DisplayUnit(mission);
    }
    if (p.has_bound && p.fraction < 1.0) {  // what is not yet settled can do no better than this
      const bool larger_better = mission.objective.type != ObjectiveType::kMinEnergy;
      line << ", the rest " << (larger_better ? "<= " : ">= ") << std::fixed << std::setprecision(2)
           << DisplayObjective(mission, p.bound_objective) << DisplayUnit(mission);
    }
    line << "; Ctrl-C stops with the best so far";
    std::string text = line.str();
    if (text.size() < 79) text += std::string(79 - text.size(), ' ');
    std::cerr << text << std::flush;
  };
}

std::string OptimizeText(const Mission& mission, const OptimizeOptions& o, const SearchResult& s) {
  std::ostringstream out;
  out << mission.name << " (" << o.mission << "): objective " << ObjectiveTypeName(mission.objective.type)
      << (mission.objective.segment.empty() ? "" : " ('" + mission.objective.segment + "')")
      << (mission.objective.ranking == DataScenario::kAsGiven ? ", ranked on the data as given"
                                                              : ", ranked on the credible value (docs/ranking.md)")
      << (o.variants ? "; every combination listed" : "; each result a different design (motor and propeller)")
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
  out << InterruptedText(mission, s, o.top);
  if (s.best.empty() && !s.interrupted) {
    out << "no combination of the catalog flies this mission within its constraints\n" << NoDesignText(s);
  }
  if (s.best.empty() && s.interrupted) out << "no feasible combination found before the search stopped\n";
  if (!s.relaxed_constraint.empty()) {
    out << "no combination reaches " << s.relaxed_constraint << " "
        << mission.constraints.min_thrust_to_weight
        << ": the best without that limit follow, each failing it (a larger motor or propeller, or a lighter vehicle)\n";
  }
  const std::vector<std::vector<int>> tied = IndistinguishableRanks(s);
  for (std::size_t i = 0; i < s.best.size(); ++i) {
    out << "\n#" << (i + 1) << " " << MissionResultText(mission, s.best[i].combination, s.best[i].result)
        << AlternativesText(mission, s.best[i], tied[i]);
  }
  out << "\nreproduce a line: dynosize evaluate " << o.mission << " --motor M --esc E --prop P --battery B --cells N;"
      << " a segment's point: dynosize simulate --motor M --esc E --vdc VDC --throttle THR --torque Q\n";
  return out.str();
}

}  // namespace

// Exit 130 when SIGINT stopped it (the best so far printed in full), 0 otherwise (a time limit too).
int RunOptimize(const OptimizeOptions& o) {
  const SigintToFlag sigint;  // from here on Ctrl-C stops the search instead of the process
  SearchOptions so = api::OptimizeSearchOptions({o.top, o.threads, o.variants, o.time_limit_s});
  so.stop = &SigintToFlag::Flag();
  const Mission mission = ReadMission(o.mission);
  const Catalog loaded = Catalog::Load(o.catalog);
  const api::MissionCatalog mission_catalog(loaded, mission);  // with the mission's sized propellers
  const Catalog& cat = mission_catalog.get();
  bool shown = false;
  if (!o.json && !o.quiet && isatty(fileno(stderr))) so.progress = ProgressLine(mission, o, &shown);
  const SearchResult s = SearchCatalog(mission, cat, so);
  if (shown) std::cerr << "\r" << std::string(79, ' ') << "\r" << std::flush;
  if (o.stats) std::cerr << SearchSummary::From(s).BriefReport() << "\n";
  std::vector<std::string> figures;
  if (!o.plot_dir.empty()) {  // each written to a temporary file and renamed (gnuplot.h)
    figures.push_back(WriteParetoFigure(mission, s, o.plot_dir));
    if (!s.best.empty()) {
      for (const auto& f : WriteSegmentMaps(mission, s.best[0].combination, s.best[0].result, o.plot_dir)) {
        figures.push_back(f);
      }
    }
  }
  // The whole document is built first and written at once.
  if (o.json) {
    Json j = SearchResultJson(mission, s);
    if (!figures.empty()) j["figures"] = figures;
    std::cout << DumpJson(j) << std::flush;
  } else {
    std::cout << OptimizeText(mission, o, s) << std::flush;
    for (const auto& f : figures) std::cerr << "wrote " << f << "\n";
  }
  return SigintToFlag::Received() ? 130 : 0;
}

}  // namespace dynosize::cli
