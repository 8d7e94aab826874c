// `evaluate` and `optimize` as library calls: the parts a user names turned into a combination,
// the search options of the command line, and the documents that --json prints (the CLI,
// apps/cmd_evaluate.cc, and the Python module, python/, share them).
#pragma once

#include <chrono>
#include <limits>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/mission_eval.h"
#include "optimization/search.h"

namespace dynosize::api {

// The parts of `evaluate`: --motor/--esc/--prop (one group), --pick GROUP=MOTOR,ESC,PROP per
// group, --battery and --cells (0: the mission's only cell count).
struct EvaluateRequest {
  std::string motor_id, esc_id, prop_id, battery_id;
  std::vector<std::string> picks;
  int cells = 0;
};

// The combination the request names (pointers into `catalog`, which must outlive it). Throws
// UsageError with the CLI's message (flags named) when the parts do not fit the mission.
Combination ChooseCombination(const Mission& mission, const Catalog& catalog, const EvaluateRequest& request);

// One combination flying the mission, with its objective range and tiers
// (optimization/credibility.h AddObjectiveRange).
MissionResult EvaluateCombination(const Mission& mission, const Combination& c);

// The options of `optimize`: --top, --threads, --variants, --time-limit (seconds; +inf: none).
struct OptimizeRequest {
  int top = 5;
  int threads = 2;
  bool variants = false;
  double time_limit_s = std::numeric_limits<double>::infinity();
};

// --time-limit S (optimize, sweep): the deadline S seconds from now (time_point::max() beyond
// about 30 years); UsageError unless S > 0 (NaN too).
std::chrono::steady_clock::time_point DeadlineAfter(double time_limit_s);

// SearchOptions of the request, the deadline counted from now (DeadlineAfter). Throws UsageError for a time
// limit that is not a positive number (NaN too).
SearchOptions OptimizeSearchOptions(const OptimizeRequest& request);

}  // namespace dynosize::api
