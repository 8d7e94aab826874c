// `dynosize evaluate` and `dynosize optimize` (issue #6): a mission flown by one combination,
// or the best combinations of the catalog.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "catalog/catalog.h"
#include "commands.h"
#include "interrupt.h"
#include "common/error.h"
#include "common/json_file.h"
#include "mission/flight.h"
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

// The parts of every group: the mission's fixed ones, --pick GROUP=MOTOR,ESC,PROP, and
// --motor/--esc/--prop for the one group left (or for a mission without groups).
void ChooseParts(const Mission& m, const Catalog& cat, const EvaluateOptions& o, Combination* c) {
  const bool single = !o.motor_id.empty() || !o.esc_id.empty() || !o.prop_id.empty();
  if (single && (o.motor_id.empty() || o.esc_id.empty() || o.prop_id.empty())) {
    throw UsageError("--motor, --esc and --prop go together (one group's parts)");
  }
  if (m.groups.empty()) {
    if (!o.picks.empty()) {
      throw UsageError("--pick " + o.picks.front() + ": the mission has no propulsion groups; use --motor, --esc, --prop");
    }
    if (!single) throw UsageError("--motor, --esc and --prop are required");
    c->motor = &cat.motor(o.motor_id);
    c->esc = &cat.esc(o.esc_id);
    c->prop = &cat.prop(o.prop_id);
    return;
  }
  c->groups.assign(m.groups.size(), GroupParts{});
  for (int g = 0; g < GroupCount(m); ++g) c->groups[g] = FixedGroupParts(m, cat, g);
  for (const std::string& pick : o.picks) {
    const auto eq = pick.find('=');
    const auto c1 = pick.find(',', eq == std::string::npos ? 0 : eq);
    const auto c2 = c1 == std::string::npos ? c1 : pick.find(',', c1 + 1);
    if (eq == std::string::npos || c1 == std::string::npos || c2 == std::string::npos ||
        pick.find(',', c2 + 1) != std::string::npos) {
      throw UsageError("--pick \"" + pick + "\": must be GROUP=MOTOR,ESC,PROP");
    }
    const std::string name = pick.substr(0, eq);
    auto it = std::find_if(m.groups.begin(), m.groups.end(), [&](const PropulsionGroup& x) { return x.name == name; });
    if (it == m.groups.end()) {
      std::string valid;
      for (const auto& x : m.groups) valid += (valid.empty() ? "" : ", ") + x.name;
      throw UsageError("--pick \"" + pick + "\": no propulsion group '" + name + "' in the mission (valid: " + valid + ")");
    }
    GroupParts& p = c->groups[it - m.groups.begin()];
    p.motor = &cat.motor(pick.substr(eq + 1, c1 - eq - 1));
    p.esc = &cat.esc(pick.substr(c1 + 1, c2 - c1 - 1));
    p.prop = &cat.prop(pick.substr(c2 + 1));
  }
  std::vector<int> missing;
  for (int g = 0; g < GroupCount(m); ++g) {
    if (!c->groups[g].motor) missing.push_back(g);
  }
  if (single) {
    if (missing.size() != 1) {
      throw UsageError("--motor/--esc/--prop: the mission has " + std::to_string(missing.size()) +
                       " groups without parts; name each with --pick GROUP=MOTOR,ESC,PROP");
    }
    c->groups[missing.front()] = GroupParts{&cat.motor(o.motor_id), &cat.esc(o.esc_id), &cat.prop(o.prop_id)};
    missing.clear();
  }
  if (!missing.empty()) {
    throw UsageError("--pick: propulsion group '" + m.groups[missing.front()].name +
                     "' has no parts: give --pick " + m.groups[missing.front()].name + "=MOTOR,ESC,PROP");
  }
  const GroupParts lift = c->groups[std::max(0, LiftGroup(m))];
  c->motor = lift.motor;
  c->esc = lift.esc;
  c->prop = lift.prop;
}

}  // namespace

int RunEvaluate(const EvaluateOptions& o) {
  const Mission mission = ReadMission(o.mission);
  const Catalog cat = Catalog::Load(o.catalog);
  Combination c;
  ChooseParts(mission, cat, o, &c);
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
    line << "; Ctrl-C stops with the best so far";
    std::string text = line.str();
    if (text.size() < 79) text += std::string(79 - text.size(), ' ');
    std::cerr << text << std::flush;
  };
}

SearchOptions OptimizeSearchOptions(const OptimizeOptions& o) {
  SearchOptions so;
  so.deadline = DeadlineAfter(o.time_limit_s);
  so.top_n = o.top;
  so.threads = o.threads;
  so.distinct_designs = !o.variants;
  so.stop = &SigintToFlag::Flag();
  return so;
}

std::string OptimizeText(const Mission& mission, const OptimizeOptions& o, const SearchResult& s) {
  std::ostringstream out;
  out << mission.name << " (" << o.mission << "): objective " << ObjectiveTypeName(mission.objective.type)
      << (mission.objective.segment.empty() ? "" : " ('" + mission.objective.segment + "')")
      << (mission.objective.ranking == DataScenario::kAsGiven ? ", ranked on the data as given"
                                                              : ", ranked on the credible value (README: Ranking)")
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
    out << "no combination of the catalog flies this mission within its constraints\n";
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
  SearchOptions so = OptimizeSearchOptions(o);
  const Mission mission = ReadMission(o.mission);
  const Catalog cat = Catalog::Load(o.catalog);
  bool shown = false;
  if (!o.json && !o.quiet && isatty(fileno(stderr))) so.progress = ProgressLine(mission, o, &shown);
  const SearchResult s = SearchCatalog(mission, cat, so);
  if (shown) std::cerr << "\r" << std::string(79, ' ') << "\r" << std::flush;
  if (o.stats) {
    std::cerr << "search: " << s.candidate_pairs << " candidate pairs bounded (" << s.candidate_batches
              << " batches after the first, which took " << std::setprecision(3) << s.candidate_seconds << " s); "
              << s.virtual_evaluations << " virtual-ESC and "
              << s.searched << " exact evaluations; total " << s.seconds << " s\n";
  }
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
