// The top-N bookkeeping of the catalog search, shared by the branch and bound
// (branch_and_bound.cc: its N-th best and the per-pair thresholds) and the joint search's merge of its
// inner searches (joint_search.cc): the N best results and the threshold they prune against.
//
// Two ways of counting the N (SearchOptions::distinct_designs):
//  - combinations (false): every (motor, ESC, propeller, pack) on its own, as before;
//  - designs (true): each of the N a different design, the (motor, propeller) of every group,
//    the sized propellers of one family and blade count (rotor/family.h) one propeller; a
//    design's other ESCs, packs and sizes are kept inside it as alternatives.
// The threshold is the N-th best entry's score (smaller is better), or the caller's cutoff while
// fewer than N are known (and never above it). Designs: a combination whose score is not below
// that threshold can neither put a new design into the top N nor better a design's best, so
// pruning against it keeps the top N designs exact; the alternatives listed are then every
// combination of the design scoring below the final threshold (the ones the search cannot have
// pruned), so they are exact too. Internal to src/optimization (and its tests).
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "optimization/mission_eval.h"
#include "optimization/search_result.h"

namespace dynosize::search_internal {

// What makes two results the same entry: the motor and propeller (a sized one: its family and
// blades) of every group (designs), and also the ESCs, the battery and the cells (combinations:
// every propeller on its own).
using EntryKey = std::vector<std::uintptr_t>;
EntryKey KeyOf(const Combination& c, bool distinct_designs);

// The threshold rule on scores alone (the per-pair copy of the branch and bound uses it as it is).
class TopScores {
 public:
  TopScores(int n, bool distinct_designs, double cutoff = std::numeric_limits<double>::infinity());
  // Kept (true) when below Threshold(): a new entry, or a better score for its design (or no
  // better: an alternative). *evicted (optional): the entry that left the N, if one did.
  bool Add(const EntryKey& key, double score, EntryKey* evicted = nullptr);
  double Threshold() const;
  bool distinct_designs() const { return distinct_; }
  // Best first (ties in the order they came).
  const std::vector<std::pair<EntryKey, double>>& entries() const { return top_; }

 private:
  int n_;
  bool distinct_;
  double cutoff_;
  std::vector<std::pair<EntryKey, double>> top_;  // ascending by score, at most n_
};

// The results themselves: TopScores's entries with each one's best combination, the cutoff its
// Solve had (the branch and bound solves them again with that cutoff, to explain them), and its
// design's alternatives.
class TopResults {
 public:
  TopResults(int n, bool distinct_designs, double cutoff = std::numeric_limits<double>::infinity());
  double Threshold() const { return scores_.Threshold(); }
  const TopScores& scores() const { return scores_; }
  bool empty() const { return best_.empty(); }
  int size() const { return static_cast<int>(best_.size()); }
  // The best result's objective (objective_unit), for progress; 0 when empty.
  double best_objective() const;
  // A feasible result (with the alternatives it carries, from an inner search); dropped when it
  // does not enter (its design's alternatives: when not below the threshold).
  void Add(RankedCombination&& r, double solve_cutoff = std::numeric_limits<double>::infinity());
  // Best first, each with its alternatives below the threshold (best first); the cutoffs of
  // their Solve in *solve_cutoffs (optional).
  std::vector<RankedCombination> Sorted(std::vector<double>* solve_cutoffs = nullptr) const;

 private:
  struct Held {
    RankedCombination best;
    double solve_cutoff = 0;
  };
  void TrimAlternatives(std::vector<Alternative>* a) const;  // those below the threshold, best first
  TopScores scores_;
  std::map<EntryKey, Held> best_;  // exactly scores_'s entries
};

}  // namespace dynosize::search_internal
