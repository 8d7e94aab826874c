// `dynosize sweep`: a trade study, the mission over a grid of values.
#include <unistd.h>

#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "api/mission_run.h"
#include "api/mission_catalog.h"
#include "catalog/catalog.h"
#include "commands.h"
#include "common/error.h"
#include "common/json_file.h"
#include "common/text_file.h"
#include "interrupt.h"
#include "mission/mission.h"
#include "report/sweep_report.h"
#include "study/sweep.h"

namespace dynosize::cli {

namespace {

// On a terminal's stderr only (never with --quiet, never into a pipe or a file).
std::function<void(const study::SweepProgress&)> SweepProgressLine(bool* shown) {
  return [shown](const study::SweepProgress& p) {
    *shown = true;
    std::ostringstream line;
    line << "\r" << ElapsedText(p.seconds) << ": " << p.done << " of " << p.total << " points";
    if (p.failed) line << " (" << p.failed << " failed)";
    line << "; Ctrl-C stops with the rows done so far";
    std::string text = line.str();
    if (text.size() < 79) text += std::string(79 - text.size(), ' ');
    std::cerr << text << std::flush;
  };
}

}  // namespace

// Exit 130 when SIGINT stopped it (the rows done so far written), 0 otherwise (a time limit too).
int RunSweep(const SweepCliOptions& o) {
  const SigintToFlag sigint;  // from here on Ctrl-C stops the sweep instead of the process
  study::SweepOptions so;
  so.point.deadline = api::DeadlineAfter(o.time_limit_s);
  so.point.stop = &SigintToFlag::Flag();
  so.point.top = o.top;
  so.point.distinct_designs = !o.variants;
  so.threads = o.threads;
  std::vector<study::VaryKey> vary;
  for (const std::string& spec : o.vary) vary.push_back(study::ParseVary(spec));
  const study::SweepPlan plan = study::PlanSweep(ReadJsonFile(o.mission), o.mission, std::move(vary), o.yes);
  const std::vector<study::VaryKey>& keys = plan.keys;
  const Mission base = ParseMission(plan.doc, plan.name);
  const Catalog loaded = Catalog::Load(o.catalog);  // once, for every point
  const api::MissionCatalog mission_catalog(loaded, study::PointMissions(plan));  // with the points' sized propellers
  const Catalog& cat = mission_catalog.get();
  bool shown = false;
  if (!o.quiet && isatty(fileno(stderr))) so.progress = SweepProgressLine(&shown);
  const study::SweepResult r = study::RunSweep(plan.doc, plan.name, cat, keys, so);
  if (shown) std::cerr << "\r" << std::string(79, ' ') << "\r" << std::flush;
  std::vector<std::string> figures;
  if (!o.plot_dir.empty()) figures = study::WriteSweepFigures(base, r, keys, o.plot_dir);
  // The whole document is built first and written at once (a file: atomically).
  std::string text;
  if (o.json) {
    Json j = study::SweepJson(base, r, keys);
    if (!figures.empty()) j["figures"] = figures;
    text = DumpJson(j);
  } else {
    text = study::SweepCsv(base, r, keys);
  }
  if (o.out.empty()) {
    std::cout << text << std::flush;
  } else {
    WriteFileAtomic(o.out, text);
  }
  if (r.interrupted) {
    std::cerr << "stopped after " << r.rows.size() << " of " << r.total << " points ("
              << (SigintToFlag::Received() ? "Ctrl-C" : "--time-limit") << "): the rows done so far are written\n";
  }
  if (!o.json) {
    for (const auto& f : figures) std::cerr << "wrote " << f << "\n";
  }
  return SigintToFlag::Received() ? 130 : 0;
}

}  // namespace dynosize::cli
