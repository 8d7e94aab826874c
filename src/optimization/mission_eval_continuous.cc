// The continuous variables of the mission evaluator (the capacity of a range, free cruise
// airspeeds): one free variable by a bracketed 1-D search (a 9-point grid, then Brent's
// method), several by a coarse grid polished with COBYLA (derivative-free: the objective passes
// through tabulated propeller data). (MissionEvaluator's other files: mission_eval.cc.)
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include "common/text_format.h"
#include "optimization/mission_eval.h"
#include "optimization/mission_eval_internal.h"
#include "solvers/solver.h"

namespace dynosize {

using eval_internal::kInf;

namespace {

// A simulated point as the 1-D search compares and fits it: where, and its outcome.
struct ResultKey {
  double x = 0.0;
  bool feasible = false;
  double score = 0.0, min_slack = 0.0;
  static ResultKey Of(const MissionResult& r, double x) { return {x, r.feasible, r.score, r.min_slack}; }
};

// Which of two simulated results is better: a feasible one with the lower score, else (both
// infeasible) the one closer to feasibility (larger smallest relative slack).
bool Better(const ResultKey& a, const ResultKey& b) {
  if (a.feasible != b.feasible) return a.feasible;
  return a.feasible ? a.score < b.score : a.min_slack > b.min_slack;
}
bool Better(const MissionResult& a, const MissionResult& b) { return Better(ResultKey::Of(a, 0), ResultKey::Of(b, 0)); }

// Brent's minimization (Brent 1973, "Algorithms for Minimization without Derivatives", ch. 5)
// on [a, b] from its best point x (result best) and two more simulated points w (second best)
// and v: a step to the vertex of the parabola through x, w and v when the three are alike (all
// feasible: fitting the score; all infeasible: fitting the smallest slack, negated) and the
// step is safe (inside [a, b], less than half the step before last), else a golden-section
// step into the larger side. It keeps the golden section's bracket invariant, so it ends in
// the same tolerance, in fewer simulations on the smooth score of a capacity or an airspeed.
template <typename Simulate, typename Enough>
MissionResult BrentPolish(const Simulate& simulate, const Enough& enough, double a, double b, double x0,
                          MissionResult best, ResultKey w, ResultKey v, double tolerance) {
  constexpr double kGoldenStep = 0.3819660112501051;  // (3 - sqrt(5))/2
  ResultKey x = ResultKey::Of(best, x0);
  if (Better(v, w)) std::swap(v, w);
  const double tol1 = 0.25 * tolerance, tol2 = 2.0 * tol1;  // ends with b - a <= tolerance
  double d = 0.0, e = b - a;  // the last step and the one before: the grid's neighbours
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (a + b);
    if (std::fabs(x.x - m) <= tol2 - 0.5 * (b - a)) break;
    bool parabolic = false;
    if (std::fabs(e) > tol1 && x.feasible == w.feasible && x.feasible == v.feasible) {
      auto f = [](const ResultKey& k) { return k.feasible ? k.score : -k.min_slack; };
      const double r = (x.x - w.x) * (f(x) - f(v));
      double q = (x.x - v.x) * (f(x) - f(w));
      double p = (x.x - v.x) * q - (x.x - w.x) * r;
      q = 2.0 * (q - r);
      if (q > 0) p = -p;
      q = std::fabs(q);
      if (std::fabs(p) < std::fabs(0.5 * q * e) && p > q * (a - x.x) && p < q * (b - x.x)) {
        e = d;
        d = p / q;
        const double u = x.x + d;
        if (u - a < tol2 || b - u < tol2) d = m >= x.x ? tol1 : -tol1;
        parabolic = true;
      }
    }
    if (!parabolic) {
      e = x.x >= m ? a - x.x : b - x.x;
      d = kGoldenStep * e;
    }
    const double ux = std::fabs(d) >= tol1 ? x.x + d : x.x + (d >= 0 ? tol1 : -tol1);
    MissionResult ru = simulate(ux);
    if (enough(ru)) return ru;
    const ResultKey u = ResultKey::Of(ru, ux);
    if (!Better(x, u)) {  // u is no worse: the new best
      (ux >= x.x ? a : b) = x.x;
      v = w; w = x; x = u;
      best = std::move(ru);
    } else {
      (ux < x.x ? a : b) = ux;
      if (!Better(w, u) || w.x == x.x) { v = w; w = u; }
      else if (!Better(v, u) || v.x == x.x || v.x == w.x) v = u;
    }
  }
  return best;
}

// The best result over x in [0, 1] of one scaled variable: a 9-point grid brackets the best
// point, then Brent's method (BrentPolish) on [x_best - 1/8, x_best + 1/8] down to a width of
// 1e-6; a best on an end of the range is settled by one point inside it. Infeasible points
// compare worse than every feasible one, so an optimum on a constraint boundary is approached
// from the feasible side. The result is the best point simulated, never worse than the grid's.
// The variable's function is taken to be unimodal on the bracket, as any bracketing method
// takes it.
//
// bounded_after_grid(best, a, b): called once after the grid with the grid's best and the
// bracket; true when it proves that neither the grid's best nor any point of [a, b] can beat
// the caller's cutoff. The polish only simulates points of [a, b], so the result could not
// beat the cutoff either: the search stops there (a result with bounded_out set).
// enough(r): true when r settles the caller's question (Solve's decide); r is then returned
// at once. top_first: the grid from x = 1 down (only how soon `enough` is met changes).
template <typename Simulate, typename Bounded, typename Enough>
MissionResult SolveOneVariable(const Simulate& simulate, const Bounded& bounded_after_grid, const Enough& enough,
                               bool top_first) {
  constexpr int kGrid = 9;
  constexpr double kTolerance = 1e-6;  // of the scaled variable's range
  MissionResult best;
  double best_x = -1.0;
  int best_k = 0;
  std::array<ResultKey, kGrid> grid_keys;
  for (int i = 0; i < kGrid; ++i) {
    const int k = top_first ? kGrid - 1 - i : i;
    const double x = k / double(kGrid - 1);
    MissionResult r = simulate(x);
    if (enough(r)) return r;
    grid_keys[k] = ResultKey::Of(r, x);
    // Of equal points the lowest x, so that the grid's best does not depend on the order.
    if (best_x < 0 || Better(r, best) || (!Better(best, r) && x < best_x)) {
      best = std::move(r);
      best_x = x;
      best_k = k;
    }
  }
  double a = std::max(0.0, best_x - 1.0 / (kGrid - 1)), b = std::min(1.0, best_x + 1.0 / (kGrid - 1));
  if (bounded_after_grid(best, a, b)) {
    MissionResult out;
    out.bounded_out = true;
    out.score = kInf;
    return out;
  }
  // The grid's best on an end of the range: one point a tolerance inside it settles it. If
  // that point is worse, the variable's unimodal function (the golden section's assumption)
  // has its best within the tolerance of the end, and every point the golden section would
  // simulate is worse than the end itself: its answer would be the grid's best.
  if (best_x == 0.0 || best_x == 1.0) {
    MissionResult r_in = simulate(best_x == 0.0 ? kTolerance : 1.0 - kTolerance);
    if (enough(r_in)) return r_in;
    if (Better(best, r_in)) return best;
  }
  return BrentPolish(simulate, enough, a, b, best_x, std::move(best), grid_keys[best_k - 1 < 0 ? 0 : best_k - 1],
                     grid_keys[std::min(best_k + 1, kGrid - 1)], kTolerance);
}

// The last feasible point on the segment from `feasible_x` (feasible) to `infeasible_x` (not),
// by bisection on the segment's parameter: kSteps halvings keeping the lower end feasible, so
// the answer is feasible whatever the shape of the feasible set. simulate(x) solves at a scaled
// point; its result and point are returned (*x).
template <typename Simulate>
MissionResult LastFeasibleOnSegment(const Simulate& simulate, const Eigen::VectorXd& feasible_x,
                                    const Eigen::VectorXd& infeasible_x, Eigen::VectorXd* x) {
  constexpr int kSteps = 24;  // 6e-8 of the segment: below the solver's relative tolerance, 1e-6
  double lo = 0.0, hi = 1.0;
  MissionResult best = simulate(feasible_x);
  for (int i = 0; i < kSteps; ++i) {
    const double mid = 0.5 * (lo + hi);
    MissionResult r = simulate(Eigen::VectorXd(feasible_x + mid * (infeasible_x - feasible_x)));
    if (r.feasible) {
      lo = mid;
      best = std::move(r);
    } else {
      hi = mid;
    }
  }
  *x = feasible_x + lo * (infeasible_x - feasible_x);
  return best;
}

}  // namespace

std::vector<MissionEvaluator::FreeVar> MissionEvaluator::FreeVariables() const {
  std::vector<FreeVar> free;
  if (m_.battery.capacity_ah && m_.battery.capacity_ah->free()) {
    free.push_back({-1, m_.battery.capacity_ah->lo, m_.battery.capacity_ah->hi});
  }
  for (std::size_t i = 0; i < m_.segments.size(); ++i) {
    const Segment& s = m_.segments[i];
    if (s.type == SegmentType::kCruise && s.airspeed_m_s.free()) {
      free.push_back({static_cast<int>(i), s.airspeed_m_s.lo, s.airspeed_m_s.hi});
    }
  }
  return free;
}

ContinuousVars MissionEvaluator::VarsAt(const std::vector<FreeVar>& free, const double* x) const {
  ContinuousVars v;
  v.airspeed_m_s.assign(m_.segments.size(), 0.0);
  if (m_.battery.capacity_ah) v.capacity_ah = m_.battery.capacity_ah->lo;
  for (std::size_t i = 0; i < free.size(); ++i) {
    const double val = free[i].lo + std::clamp(x[i], 0.0, 1.0) * (free[i].hi - free[i].lo);
    if (free[i].segment < 0) v.capacity_ah = val;
    else v.airspeed_m_s[free[i].segment] = val;
  }
  return v;
}

MissionResult MissionEvaluator::SolveContinuous(double cutoff_score, bool explain, bool decide, bool search) const {
  if (MissionResult early; EarlyExit(cutoff_score, explain, search, &early)) return early;
  const std::vector<FreeVar> free = FreeVariables();  // each scaled to [0, 1]
  if (free.size() == 1) return SolveOneFree(free, cutoff_score, explain, decide);
  if (free.size() > 1) return SolveManyFree(free, cutoff_score, explain, decide);
  // decide: a feasible point that beats the cutoff answers the caller (Solve).
  MissionResult r = WithEndurance(VarsAt(free, nullptr), decide ? cutoff_score : -kInf);
  r.violations_everywhere = !r.feasible;  // nothing free: the one point is the whole problem
  if (decide && r.feasible && r.score < cutoff_score) return r;
  if (explain) {
    Summarize(&r);
    AddWarnings(&r);
  }
  return r;
}

// One free variable (the usual case: the capacity, or one cruise airspeed): a bracketed 1-D
// search, which also finds an optimum that sits on a constraint boundary (a heavier pack breaking
// a current or thrust-to-weight limit), where COBYLA tends to end just on the infeasible side and
// fall back to its coarse start.
MissionResult MissionEvaluator::SolveOneFree(const std::vector<FreeVar>& free, double cutoff_score, bool explain,
                                             bool decide) const {
  auto enough = [&](const MissionResult& r) { return decide && r.feasible && r.score < cutoff_score; };
  const double decide_cutoff = decide ? cutoff_score : -kInf;  // for WithEndurance
  auto vars_at = [&](const double* x) { return VarsAt(free, x); };
  // With a cutoff (max_endurance, the capacity free): after the grid, the bound of
  // EnduranceUpperBound over the golden section's bracket decides whether it can still
  // produce a score below the cutoff.
  const bool bound_bracket = std::isfinite(cutoff_score) && m_.objective.type == ObjectiveType::kMaxEndurance &&
                             free[0].segment < 0;
  // min_energy with the capacity free and a voltage-independent terminal power (C0 = 0, no
  // supply resistance, as in EarlyExit): every segment's energy rises with the
  // capacity (M3), so the energy at the bracket's low end bounds every point of it.
  const bool energy_bracket = std::isfinite(cutoff_score) && m_.objective.type == ObjectiveType::kMinEnergy &&
                              free[0].segment < 0 &&
                              std::all_of(groups_.begin(), groups_.end(), [](const GroupDrive& g) {
                                return g.drive.esc().c0 == 0.0 && g.drive.esc().rsupply_ohm == 0.0;
                              });
  // Deciding (only whether some point beats the cutoff): the grid from the largest capacity
  // down for max_endurance, where a larger pack is the usual optimum. The order changes only
  // how soon a point that beats the cutoff is met, not which point is the grid's best.
  const bool top_first_decides = m_.objective.type == ObjectiveType::kMaxEndurance && free[0].segment < 0;
  auto bounded = [&](const MissionResult& grid_best, double a, double b) {
    if (grid_best.feasible && grid_best.score < cutoff_score) return false;
    if (energy_bracket) {
      const MissionResult ra = Run(vars_at(&a), 0.0);
      return ra.segments.size() == m_.segments.size() && ra.energy_wh >= cutoff_score;
    }
    if (!bound_bracket) return false;
    const double ub = EnduranceUpperBound(-cutoff_score, free[0].lo + a * (free[0].hi - free[0].lo),
                                          free[0].lo + b * (free[0].hi - free[0].lo));
    return -ub >= cutoff_score;
  };
  MissionResult r =
      SolveOneVariable([&](double x) { return WithEndurance(vars_at(&x), decide_cutoff); }, bounded, enough,
                       decide && top_first_decides);
  if (enough(r)) return r;
  if (r.bounded_out) return r;
  if (!explain) return r;
  std::ostringstream msg;
  msg << "bracketed 1-D search (9-point grid, golden section to 1e-6 of the range); "
      << (free[0].segment < 0 ? std::string("capacity_ah")
                              : m_.segments[free[0].segment].name + ".airspeed_m_s")
      << " = " << SignificantText(free[0].segment < 0 ? r.capacity_ah : r.segments[free[0].segment].airspeed_m_s, 6);
  r.solver = msg.str();
  Summarize(&r);
  AddWarnings(&r);
  return r;
}

// SolveManyFree: with no feasible grid point, COBYLA's answer, feasible or infeasible within this
// relative slack of a constraint, is followed by 1-D searches along each variable (a feasible
// corner the grid missed); further out the combination is taken as infeasible, as before (most
// infeasible combinations of a search end far outside, and the 1-D searches cost about 100 runs).
constexpr double kNearlyFeasibleSlack = 1e-3;

// Several free variables: a coarse grid (5 levels per variable, at most 125 points) picks the
// start; COBYLA (derivative-free: the objective passes through tabulated propeller data) polishes it.
MissionResult MissionEvaluator::SolveManyFree(const std::vector<FreeVar>& free, double cutoff_score, bool explain,
                                              bool decide) const {
  auto enough = [&](const MissionResult& r) { return decide && r.feasible && r.score < cutoff_score; };
  const double decide_cutoff = decide ? cutoff_score : -kInf;  // for WithEndurance
  auto vars_at = [&](const double* x) { return VarsAt(free, x); };
  const int n = static_cast<int>(free.size());
  const int levels = 5;
  int total = 1;
  for (int i = 0; i < n && i < 3; ++i) total *= levels;
  Eigen::VectorXd best_x = Eigen::VectorXd::Constant(n, 0.5);
  double best_score = kInf, best_slack = -kInf;
  std::vector<double> x(n, 0.5);
  for (int g = 0; g < total; ++g) {
    int code = g;
    for (int i = 0; i < n; ++i) {
      x[i] = i < 3 ? (code % levels) / double(levels - 1) : 0.5;
      code /= levels;
    }
    MissionResult r = WithEndurance(vars_at(x.data()), decide_cutoff);
    if (enough(r)) return r;
    const bool better = r.feasible ? r.score < best_score
                                   : (best_score == kInf && r.min_slack > best_slack);
    if (better) {
      best_score = r.feasible ? r.score : kInf;
      best_slack = r.min_slack;
      best_x = Eigen::Map<Eigen::VectorXd>(x.data(), n);
    }
  }
  Problem p;
  p.name = "combination continuous variables";
  p.num_variables = n;
  p.initial_point = best_x;
  p.lower_bounds = Eigen::VectorXd::Zero(n);
  p.upper_bounds = Eigen::VectorXd::Ones(n);
  for (const FreeVar& v : free) {
    p.variable_names.push_back(v.segment < 0 ? "capacity_ah" : m_.segments[v.segment].name + ".airspeed_m_s");
  }
  // Scale of the objective: the grid's best score (so that the solver sees O(1) values).
  const double scale = std::isfinite(best_score) && best_score != 0 ? std::fabs(best_score) : 1.0;
  // NLopt asks for the objective and the constraint at the same x one after the other: one
  // simulation serves both.
  Eigen::VectorXd memo_x;
  double memo_score = 0, memo_slack = 0;
  auto at = [&](const Eigen::VectorXd& xv) {
    if (memo_x.size() != xv.size() || memo_x != xv) {
      const MissionResult r = WithEndurance(vars_at(xv.data()));
      memo_x = xv;
      memo_score = std::isfinite(r.score) ? r.score / scale : 1e3;
      memo_slack = std::isfinite(r.min_slack) ? r.min_slack : -1.0;
    }
  };
  p.objective = [&](const Eigen::VectorXd& xv, Eigen::VectorXd*) {
    at(xv);
    return memo_score;
  };
  p.num_inequality_constraints = 1;
  p.inequality_names = {"-min constraint slack"};
  p.inequality_constraints = [&](const Eigen::VectorXd& xv, Eigen::VectorXd* g, Eigen::MatrixXd*) {
    at(xv);
    (*g)[0] = -memo_slack;
  };
  SolverOptions o;
  o.algorithm = "nlopt_cobyla";
  o.relative_tolerance = 1e-6;
  o.max_evaluations = 80;
  o.max_solver_time_in_seconds = 10.0;
  const SolverResult sr = dynosize::Solve(p, o);
  Eigen::VectorXd xs = best_x;
  if (sr.x.size() == n && sr.x.allFinite()) xs = sr.x;
  MissionResult r = WithEndurance(vars_at(xs.data()));
  const MissionResult grid = WithEndurance(vars_at(best_x.data()));
  double broke_by = 0;  // > 0: COBYLA's answer broke a constraint by this relative slack
  if (!r.feasible && grid.feasible && xs != best_x) {
    // COBYLA ended just outside a constraint it was following (an optimum on a feasibility
    // boundary, e.g. the smallest pack that still meets a limit): the last feasible point on
    // the segment from the grid's (feasible) best to its answer.
    broke_by = -r.min_slack;
    const Eigen::VectorXd from = best_x, to = xs;
    r = LastFeasibleOnSegment([&](const Eigen::VectorXd& xv) { return WithEndurance(vars_at(xv.data())); }, from, to,
                              &xs);
  }
  if (!(r.feasible && r.score <= grid.score) && grid.feasible) {  // never worse than the grid
    r = grid;
    xs = best_x;
    broke_by = 0;
  }
  bool by_coordinates = false;
  if (!grid.feasible && (r.feasible || (std::isfinite(r.min_slack) && r.min_slack > -kNearlyFeasibleSlack))) {
    // No grid point is feasible: the feasible set is a corner the 5 x 5 grid misses, and COBYLA,
    // started outside it, ends a hair outside a constraint or short of the optimum (quadplane,
    // capacity [2, 10] Ah, airspeed [12, 26] m/s, lift dc_m_550 + GWS 9x5: with ESC fu_e_60
    // 1.1e-6 outside though it flies near 3 Ah and 12 m/s; with dc_e_113 at its iteration limit,
    // 3.67 Ah and 34.60 Wh against 33.56 Wh at 3 Ah). Each variable in turn over its whole range,
    // the others held, by the bracketed 1-D search, which approaches a boundary from the
    // feasible side; twice, or until a round changes nothing.
    for (int round = 0; round < 2; ++round) {
      bool changed = false;
      for (int i = 0; i < n; ++i) {
        auto along = [&](double t) {
          Eigen::VectorXd y = xs;
          y[i] = t;
          return WithEndurance(vars_at(y.data()));
        };
        MissionResult ri = SolveOneVariable(
            along, [](const MissionResult&, double, double) { return false; },
            [](const MissionResult&) { return false; }, false);
        if (!Better(ri, r)) continue;
        const double value = free[i].segment < 0 ? ri.capacity_ah : ri.segments[free[i].segment].airspeed_m_s;
        xs[i] = (value - free[i].lo) / (free[i].hi - free[i].lo);
        r = std::move(ri);
        by_coordinates = changed = true;
      }
      if (!changed) break;
    }
  }
  if (!explain) return r;
  std::ostringstream msg;
  msg << sr.BriefReport();
  if (scale != 1.0) msg << " (f: the objective over the grid's best, " << SignificantText(best_score, 6) << ")";
  if (by_coordinates) {
    msg << "; no grid point feasible: bracketed 1-D searches along each variable from its answer";
  }
  if (broke_by > 0) {
    msg << "; its answer broke a constraint by " << SignificantText(broke_by, 2)
        << " (relative slack): the last feasible point towards it from the grid's best";
  }
  for (int i = 0; i < n; ++i) msg << (i ? ", " : "; ") << p.variable_names[i] << " = "
                                  << SignificantText(free[i].lo + std::clamp(xs[i], 0.0, 1.0) * (free[i].hi - free[i].lo), 6);
  r.solver = msg.str();
  Summarize(&r);
  AddWarnings(&r);
  return r;
}

}  // namespace dynosize
