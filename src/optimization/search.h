// The catalog search of issue #6: the best N combinations (motor, ESC, propeller, battery cell,
// cells in series) for a mission, exactly as MissionEvaluator::Solve scores each, found by
// branch and bound with pruning rules that can only remove combinations that are infeasible or
// cannot enter the top N. With several free propulsion groups each picks its own motor, ESC and
// propeller (the joint search, joint_search.h, rule G2). The proofs are in search.cc, next to each rule; they rest on the
// monotonicity of the model (stated there) and are checked end to end by
// tests/optimization/search_test.cc against exhaustive evaluation.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "optimization/mission_eval.h"

namespace dynosize {

// What the search has done so far, for a progress display.
struct SearchProgress {
  // How far the search has got, 0..1: the candidate pairs drawn against those drawn plus an
  // upper bound of those still to draw below the N-th best so far (search.cc, ReportProgress;
  // the joint search: its outer pairs); 1 when the search is done.
  double fraction = 0.0;
  long long searched = 0;     // combinations evaluated exactly so far
  long long pruned = 0;       // combinations removed by a rule so far
  bool has_best = false;
  int found = 0;              // of the top N so far (the fraction stays near 0 until all N are)
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
  // A stop request: the search stops between chunks of candidate pairs (the joint search also
  // between its outer choices) once *stop is true or the deadline has passed, and returns the
  // best found so far with SearchResult::interrupted set (null / time_point::max(): never).
  // *stop may be set from another thread or a signal handler.
  const std::atomic<bool>* stop = nullptr;
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  // false: the top N are combinations (another ESC or pack of the same motor and propeller is
  // another entry); true: N different designs, the (motor, propeller) of every group, each with
  // its other ESCs and packs as alternatives (top_results.h). optimize sets it unless --variants.
  bool distinct_designs = false;
  // > 0: the one-group search also stops (interrupted) between chunks once it has solved this
  // many combinations, real and virtual ESCs together (the joint search's first inner searches,
  // joint_search.cc, G2's order). A count, so that where it stops does not depend on timing.
  long long evaluation_budget = 0;
};

// True once the options' stop flag is set or their deadline has passed.
bool StopRequested(const SearchOptions& opt);

// True when the mission's evaluations must stay on one thread: a free shaft speed is solved by
// Ipopt, whose MUMPS is not thread-safe (the search then runs one worker; a sweep one point at
// a time, study/sweep.h).
bool NeedsOneThread(const Mission& mission);

// Another ESC or pack of a result's design (SearchOptions::distinct_designs), scored exactly.
struct Alternative {
  Combination combination;
  double objective = 0, score = 0;  // as MissionResult's
  double capacity_ah = 0;           // the pack's capacity flown
};

struct RankedCombination {
  Combination combination;
  MissionResult result;
  // distinct_designs: the design's other combinations scoring below the N-th best design, best
  // first (every such one: the search cannot have pruned them); empty otherwise.
  std::vector<Alternative> alternatives;
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
  long long pruned = 0;        // combinations - searched - unsettled
  std::map<std::string, long long> pruned_by;  // rule -> combinations it removed
  long long skipped_without_mass = 0;  // motors without mass_kg (left out, counted in pruned)
  double seconds = 0.0;
  // The search was stopped (SearchOptions::stop or deadline) before it had settled every
  // combination: `best` is the best found so far (possibly empty), and every combination not
  // settled scores at least unsettled_bound_score (a proven lower bound, -inf when the
  // objective has none, e.g. max_efficiency); nth_best_score is the threshold the search had
  // (the N-th best's score, +inf while fewer than N were found). unsettled: the combinations
  // neither evaluated nor pruned (not counted in pruned).
  bool interrupted = false;
  double unsettled_bound_score = std::numeric_limits<double>::infinity();
  double nth_best_score = std::numeric_limits<double>::infinity();
  long long unsettled = 0;
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
