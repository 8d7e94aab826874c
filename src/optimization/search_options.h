// The catalog search's options and progress (search.h): what the caller asks of the search and
// how it stops. Below both the search's entry and its stages.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <string>

#include "mission/mission.h"

namespace dynosize {

// What the search has done so far, for a progress display.
struct SearchProgress {
  // How far the search has got, 0..1: the candidate pairs drawn against those drawn plus an
  // upper bound of those still to draw below the N-th best so far (branch_and_bound.cc, ReportProgress;
  // the joint search: its outer pairs); 1 when the search is done.
  double fraction = 0.0;
  long long searched = 0;     // combinations evaluated exactly so far
  long long pruned = 0;       // combinations removed by a rule so far
  bool has_best = false;
  int found = 0;              // of the top N so far (the fraction stays near 0 until all N are)
  double best_objective = 0;  // the best result's objective (its unit: the mission's)
  // A proven bound of every combination not yet settled (the objective's unit; below for
  // min_energy, above for max_endurance): the N-th best found and it bracket the answer, and
  // their gap narrows as the search goes. has_bound false while none is known (max_efficiency,
  // or before the joint search's first pass has bounded every outer pair).
  bool has_bound = false;
  double bound_objective = 0;
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

  // True when the options can be searched with; otherwise false and *error (when
  // not null) says which option breaks which rule.
  bool IsValid(std::string* error) const;
};

// True once the options' stop flag is set or their deadline has passed.
bool StopRequested(const SearchOptions& opt);

// True when the mission's evaluations must stay on one thread: a free shaft speed is solved by
// Ipopt, whose MUMPS is not thread-safe (the search then runs one worker; a sweep one point at
// a time, study/sweep.h).
bool NeedsOneThread(const Mission& mission);

}  // namespace dynosize
