// The catalog search of issue #6: the best N combinations (motor, ESC, propeller, battery cell,
// cells in series) for a mission, exactly as MissionEvaluator::Solve scores each, found by
// branch and bound with pruning rules that can only remove combinations that are infeasible or
// cannot enter the top N. The proofs are in search.cc, next to each rule; they rest on the
// monotonicity of the model (stated there) and are checked end to end by
// tests/optimization/search_test.cc against exhaustive evaluation.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "optimization/mission_eval.h"

namespace dynosize {

struct SearchOptions {
  int top_n = 5;  // how many combinations to return (>= 1)
  // Called now and then with the fraction of the candidate list done (for a progress bar).
  std::function<void(double)> progress;
};

struct RankedCombination {
  Combination combination;
  MissionResult result;
};

struct SearchResult {
  std::vector<RankedCombination> best;  // at most top_n, best first, all feasible
  // Every combination evaluated exactly: propulsion mass and objective (for the Pareto front).
  std::vector<std::pair<double, double>> evaluated_mass_objective;
  long long combinations = 0;  // motors x ESCs x propellers x (battery, cells) options
  long long searched = 0;      // evaluated exactly
  long long pruned = 0;        // combinations - searched
  std::map<std::string, long long> pruned_by;  // rule -> combinations it removed
  long long skipped_without_mass = 0;  // motors without mass_kg (left out, counted in pruned)
  double seconds = 0.0;
};

// An upper bound of the integral of the pack's OCV(soc) d(soc) over [reserve_soc, 1], V: the
// terminal energy the pack can give above the reserve is at most this times its charge.
double OcvIntegralUpperBound(const BatteryPack& pack, double reserve_soc);

// Throws UsageError when a mission battery id is not in the catalog or no cell count in the
// range fits it.
SearchResult SearchCatalog(const Mission& mission, const Catalog& catalog,
                           const SearchOptions& options = {});

}  // namespace dynosize
