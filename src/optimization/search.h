// The catalog search of issue #6: the best N combinations (motor, ESC, propeller, battery cell,
// cells in series) for a mission, exactly as MissionEvaluator::Solve scores each, found by
// branch and bound with pruning rules that can only remove combinations that are infeasible or
// cannot enter the top N. With several free propulsion groups each picks its own motor, ESC and
// propeller (the joint search, joint_search.h, rule G2). The proofs are in search.cc, next to each rule; they rest on the
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

// What the search has done so far, for a progress display.
struct SearchProgress {
  double fraction = 0.0;      // of the candidate pairs' combinations settled (drawn or removed); the
                              // search usually stops well before 1 (an upper bound of the work left)
  long long searched = 0;     // combinations evaluated exactly so far
  long long pruned = 0;       // combinations removed by a rule so far
  bool has_best = false;
  double best_objective = 0;  // the best result's objective (its unit: the mission's)
};

struct SearchOptions {
  int top_n = 5;  // how many combinations to return (>= 1)
  // Worker threads for the candidate pairs and their evaluation (>= 1). The answer and the
  // counts do not depend on it (chunks merged in candidate order); missions with a free shaft
  // speed run on one thread (Ipopt's MUMPS is not thread-safe).
  int threads = 2;
  // Called now and then (between chunks of candidate pairs) with the search's state.
  std::function<void(const SearchProgress&)> progress;
};

struct RankedCombination {
  Combination combination;
  MissionResult result;
};

struct SearchResult {
  // At most top_n, best first, all feasible; except when no combination meets
  // min_thrust_to_weight: then the best without that limit, each infeasible with its
  // min_thrust_to_weight violation, and relaxed_constraint says so.
  std::vector<RankedCombination> best;
  std::string relaxed_constraint;  // "" or "min_thrust_to_weight"
  // Every combination evaluated exactly: propulsion mass and objective (for the Pareto front).
  std::vector<std::pair<double, double>> evaluated_mass_objective;
  // motors x ESCs x propellers (to the power of the free groups' count) x (battery, cells)
  // options; saturates at the largest long long (three or more free groups on a large catalog).
  long long combinations = 0;
  long long searched = 0;      // evaluated exactly
  long long pruned = 0;        // combinations - searched
  std::map<std::string, long long> pruned_by;  // rule -> combinations it removed
  long long skipped_without_mass = 0;  // motors without mass_kg (left out, counted in pruned)
  double seconds = 0.0;
  // Where the time went: the (motor, propeller, option) pairs stage 4 bounded, the seconds to
  // the end of its first batches (stages 0-3 included), its later batches (bounded as the
  // branch and bound reached them, R11), and the virtual-ESC evaluations of R5.
  long long candidate_pairs = 0;
  double candidate_seconds = 0.0;
  long long virtual_evaluations = 0;
  long long candidate_batches = 0;
};

// Throws UsageError when a mission battery id is not in the catalog or no cell count in the
// range fits it.
SearchResult SearchCatalog(const Mission& mission, const Catalog& catalog,
                           const SearchOptions& options = {});

}  // namespace dynosize
