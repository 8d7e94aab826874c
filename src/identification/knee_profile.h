// The saturation knee's profile, shared by calibrate and diagnose: tr_sat (docs/model.md section 7)
// enters the model through a kink, so no fit frees it from the start; instead the fit is repeated
// with tr_sat held at each knee of a grid and the knee of the lowest cost is kept. Each command
// brings its grid and its fit (src/calibration/joint_fit.cc, src/diagnosis/model_fit.cc say why
// their grids differ) and decides what to do with the best knee (an F test, a refinement).
#pragma once

#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace dynosize::identification {

template <typename Outcome>
struct KneeProfile {
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<double> knees;  // the grid, in the order fitted
  std::vector<double> costs;  // the cost curve: the fit's cost at each knee (+inf where it failed)
  std::size_t best = kNone;   // index of the lowest cost (the first of equal ones); kNone: all failed
  Outcome best_fit{};         // the fit at knees[best]; a default Outcome when every fit failed

  bool found() const { return best != kNone; }
};

// Fits at each knee of `knees` in order: fit_at(knee, index) returns an Outcome and cost_of(outcome)
// its cost, +inf (or NaN) for a failed fit. Keeps the first knee whose cost is below every
// earlier one.
template <typename Outcome, typename FitAt, typename CostOf>
KneeProfile<Outcome> ProfileKnee(const std::vector<double>& knees, const FitAt& fit_at, const CostOf& cost_of) {
  KneeProfile<Outcome> p;
  p.knees = knees;
  p.costs.reserve(knees.size());
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < knees.size(); ++j) {
    Outcome f = fit_at(knees[j], j);
    const double c = cost_of(f);
    p.costs.push_back(c == c ? c : std::numeric_limits<double>::infinity());
    if (c < best_cost) {
      best_cost = c;
      p.best = j;
      p.best_fit = std::move(f);
    }
  }
  return p;
}

}  // namespace dynosize::identification
