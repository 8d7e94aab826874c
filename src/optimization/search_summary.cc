#include "optimization/search_summary.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/text_format.h"

namespace dynosize {

SearchSummary SearchSummary::From(const SearchResult& r) {
  SearchSummary s;
  s.results = static_cast<int>(r.best.size());
  s.relaxed_constraint = r.relaxed_constraint;
  s.combinations = r.combinations;
  s.candidate_pairs = r.candidate_pairs;
  s.candidate_batches = r.candidate_batches;
  s.pruned = r.pruned;
  s.pruned_by = r.pruned_by;
  s.solved = r.searched;
  s.virtual_evaluations = r.virtual_evaluations;
  s.put_back_solves = r.put_back_solves;
  s.skipped_without_mass = r.skipped_without_mass;
  s.seconds = r.seconds;
  s.first_result_s = r.first_result_s;
  s.candidate_seconds = r.candidate_seconds;
  s.joint = r.joint;
  s.interrupted = r.interrupted;
  s.unsettled = r.unsettled;
  s.nth_best_score = r.nth_best_score;
  s.unsettled_bound_score = r.unsettled_bound_score;
  return s;
}

double SearchSummary::Gap() const {
  if (!interrupted) return 0.0;
  if (!std::isfinite(nth_best_score) || !std::isfinite(unsettled_bound_score)) {
    return std::numeric_limits<double>::infinity();
  }
  return std::max(0.0, nth_best_score - unsettled_bound_score);
}

namespace {

std::string GapText(double gap) { return std::isfinite(gap) ? FixedText(gap, 6) : "unknown"; }

// The joint search's phases on one line ("" for a one-group search).
std::string JointPhasesText(const SearchResult::JointPhases& j) {
  if (!(j.setup_s > 0) && j.class_searches == 0 && j.triple_searches == 0) return "";
  std::ostringstream o;
  o << "joint search: bounds set up " << FixedText(j.setup_s, 3) << " s, ";
  if (j.dive_searches > 0) {
    o << "dive " << j.dive_searches << " inner searches " << j.dive_solves << " solves " << FixedText(j.dive_s, 3)
      << " s, ";
  }
  o << "first pass over the outer pairs "
    << FixedText(j.outer_pairs_s, 3) << " s, " << j.class_searches << " class searches (virtual ESC) "
    << FixedText(j.class_searches_s, 3) << " s, " << j.triple_searches << " triple searches "
    << FixedText(j.triple_searches_s, 3) << " s";
  if (j.outer_pairs_below_final > 0) o << ", " << j.outer_pairs_below_final << " outer pairs bounded below the N-th best";
  return o.str();
}

}  // namespace

std::string SearchSummary::BriefReport() const {
  std::ostringstream o;
  o << "search: " << results << " results, " << combinations << " combinations, " << candidate_pairs
    << " candidate pairs bounded, " << pruned << " pruned, " << solved << " solved exactly ("
    << virtual_evaluations << " virtual-ESC solves besides"
    << (put_back_solves > 0 ? ", " + std::to_string(put_back_solves) + " of them in inner searches put back over their budget" : "")
    << "), " << FixedText(seconds, 3) << " s, "
    << (std::isfinite(first_result_s) ? "first result after " + FixedText(first_result_s, 3) + " s, " : "")
    << (interrupted ? "interrupted (gap " + GapText(Gap()) + ")" : "done");
  if (const std::string j = JointPhasesText(joint); !j.empty()) o << "\n" << j;
  return o.str();
}

std::string SearchSummary::FullReport() const {
  std::ostringstream o;
  o << "Search summary\n"
    << "  results                  " << results << (relaxed_constraint.empty() ? "" : " (without " + relaxed_constraint + ")")
    << "\n"
    << "  combinations             " << combinations << "\n"
    << "  candidate pairs bounded  " << candidate_pairs << " (" << candidate_batches << " batches after the first)\n"
    << "  solved exactly           " << solved << "\n"
    << "  virtual-ESC solves       " << virtual_evaluations
    << (put_back_solves > 0 ? " (" + std::to_string(put_back_solves) + " in inner searches put back over their budget)" : "")
    << "\n"
    << "  pruned                   " << pruned << "\n";
  for (const auto& [rule, n] : pruned_by) {
    if (n != 0) o << "    " << rule << std::string(rule.size() < 22 ? 22 - rule.size() : 1, ' ') << n << "\n";
  }
  if (skipped_without_mass > 0) o << "  motors without mass      " << skipped_without_mass << "\n";
  o << "  time                     " << FixedText(seconds, 3) << " s (stages 0-4's first batches "
    << FixedText(candidate_seconds, 3) << " s";
  if (std::isfinite(first_result_s)) o << "; first result after " << FixedText(first_result_s, 3) << " s";
  o << ")\n";
  if (const std::string j = JointPhasesText(joint); !j.empty()) o << "  " << j << "\n";
  if (interrupted) {
    o << "  interrupted              " << unsettled << " combinations not settled, gap " << GapText(Gap())
      << " (score)\n";
  } else {
    o << "  finished                 every combination settled\n";
  }
  return o.str();
}

}  // namespace dynosize
