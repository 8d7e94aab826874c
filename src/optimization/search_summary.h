// What a catalog search did, as a report: how many
// combinations there were, the candidate pairs bounded, what each rule pruned, the
// combinations solved exactly, the time, and whether the search was stopped and with what gap.
// Built from a SearchResult (search_result.h), whose counts it reads; the CLI prints
// BriefReport() with `optimize --stats`.
#pragma once

#include <limits>
#include <map>
#include <string>

#include "optimization/search_result.h"

namespace dynosize {

struct SearchSummary {
  static SearchSummary From(const SearchResult& r);

  int results = 0;                  // ranked combinations returned
  std::string relaxed_constraint;   // "" or the limit left out (SearchResult::relaxed_constraint)
  long long combinations = 0;       // in the catalog for the mission (saturating)
  long long candidate_pairs = 0;    // (motor, propeller, battery option) pairs bounded (stage 4)
  long long candidate_batches = 0;  // their batches after the first ones (drawn on demand, R11)
  long long pruned = 0;             // combinations removed by a rule
  std::map<std::string, long long> pruned_by;  // rule -> combinations it removed
  long long solved = 0;             // combinations solved exactly (MissionEvaluator::Solve)
  long long virtual_evaluations = 0;  // virtual-ESC solves (R5), put_back_solves included
  long long put_back_solves = 0;      // solves of inner searches put back over their budget
  long long skipped_without_mass = 0;
  double seconds = 0.0;             // elapsed, the whole search
  double candidate_seconds = 0.0;   // to the end of stage 4's first batches (stages 0-3 included)
  double first_result_s = std::numeric_limits<double>::infinity();  // SearchResult's
  SearchResult::JointPhases joint;  // the joint search's phases (zero for one free group)
  // Stopped before every combination was settled: `unsettled` combinations were neither solved
  // nor pruned, each scoring at least unsettled_bound_score; nth_best_score is the N-th best
  // found (+inf while fewer than N were).
  bool interrupted = false;
  long long unsettled = 0;
  double nth_best_score = std::numeric_limits<double>::infinity();
  double unsettled_bound_score = std::numeric_limits<double>::infinity();

  // How far the best found may be from the proven best, in score units (smaller is better):
  // the N-th best's score minus the bound of what is left, at least 0; 0 when the search
  // finished, +inf when it stopped without a bound or with fewer than N results.
  double Gap() const;
  // One line.
  std::string BriefReport() const;
  // Several lines: the counts, each rule's share, the time, the stop and its gap.
  std::string FullReport() const;
};

}  // namespace dynosize
