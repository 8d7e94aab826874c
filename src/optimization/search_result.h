// What the catalog search returns (search.h): the ranked combinations and the counts of what
// the search did.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "optimization/mission_eval.h"
#include "optimization/unmet_requirement.h"

namespace dynosize {

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
  // When the search finished and found nothing (best empty, not interrupted): the requirements
  // no part of the catalog meets on its own (no_design.h, UnmetRequirements); empty otherwise,
  // and empty too when every requirement is met by some part but no combination meets all.
  std::vector<UnmetRequirement> no_design_because;
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
  // Of virtual_evaluations, the solves of the joint search's inner searches put back over their
  // first budget (real combinations, counted once they are taken again; on a stop before that,
  // their results are shown but the combinations stay unsettled).
  long long put_back_solves = 0;
  long long candidate_batches = 0;
  // The joint search's phases (G2, docs/search.md#g2; all zero for a one-group search): its
  // bounds' set-up (the lift frontier's level 0 among them), the first pass over the outer
  // pairs, and its inner searches, per class's virtual ESC (G3) and per triple, with their counts.
  struct JointPhases {
    double setup_s = 0.0, outer_pairs_s = 0.0, class_searches_s = 0.0, triple_searches_s = 0.0;
    long long class_searches = 0, triple_searches = 0;
    // The dive (a good design first, docs/joint-search.md#dive): its inner searches, their solves
    // (not in `searched`: the complete search finds again what it found) and seconds.
    long long dive_searches = 0, dive_solves = 0;
    double dive_s = 0.0;
    // The outer pairs whose first-pass bound is below the final N-th best's score (0 when fewer
    // than N were found or the search was stopped): the pairs any search taking them by that
    // bound must take, however it orders or batches them (docs/joint-search.md, growth).
    long long outer_pairs_below_final = 0;
  };
  JointPhases joint;
  // Seconds from the search's start to its first feasible result (+inf: none): what a designer
  // waits before the progress line shows a design (issue 54's goal, optimize_bench).
  double first_result_s = std::numeric_limits<double>::infinity();
};

}  // namespace dynosize
