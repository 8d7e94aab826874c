// One entry point, several backends: Solve(problem, options) with the algorithm picked by name.
//
//   "ipopt"         interior point (Ipopt 3.11+, MUMPS), limited-memory BFGS Hessian; local.
//   "nlopt_slsqp"   sequential quadratic programming (NLopt LD_SLSQP); local, gradients.
//   "nlopt_mma"     method of moving asymptotes (NLopt LD_MMA); local, gradients; equality
//                   constraints through NLopt's augmented Lagrangian (AUGLAG_EQ).
//   "nlopt_cobyla"  linear approximations (NLopt LN_COBYLA); local, derivative-free.
//   "nlopt_direct"  DIRECT-L (NLopt GN_DIRECT_L); global, needs finite bounds; constraints by
//                   NLopt's augmented Lagrangian; the result is polished by local_algorithm.
//   "nlopt_isres"   improved stochastic ranking evolution strategy (NLopt GN_ISRES); global,
//                   needs finite bounds, seeded by random_seed; polished by local_algorithm.
//   "multistart"    local_algorithm from the initial point and from multistart_count points
//                   drawn uniformly in the (finite) bounds; the best feasible result wins.
//
// Failure tiers (Drake): malformed problem/options throw UsageError; an algorithm whose
// backend this build left out throws UnavailableError (IsAlgorithmAvailable below); an exception thrown by a
// user callback is stored, the backend is told to stop, and it is rethrown by Solve(); a
// numerical outcome (not converged, infeasible) is a status in the result.
//
// After a backend reports success the wrapper re-evaluates the bounds and constraints itself at
// the returned x; if any is violated by more than feasibility_check_tolerance the status is
// downgraded to kConstraintViolation and the message names the worst constraint.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "solvers/problem.h"

namespace dynosize {

struct SolverOptions {
  // Which backend; see the list above. An unknown name throws UsageError listing all names.
  std::string algorithm = "ipopt";
  // Local algorithm used by "multistart" and to polish the global ones.
  std::string local_algorithm = "nlopt_slsqp";

  // Convergence test, per backend:
  //   ipopt:  stop when Ipopt's scaled NLP error (max of dual infeasibility, constraint
  //           violation and complementarity, scaled as in Ipopt's "tol") <= relative_tolerance;
  //   nlopt:  stop when an iteration changes f by less than relative_tolerance * |f|
  //           (ftol_rel) or every x_i by less than relative_tolerance * |x_i| (xtol_rel).
  double relative_tolerance = 1e-8;
  // Constraint violation the backends accept internally (Ipopt constr_viol_tol, NLopt
  // per-constraint tolerance), absolute, in each constraint's own unit.
  double constraint_tolerance = 1e-9;
  // The wrapper's own feasibility re-check after a claimed success, absolute:
  //   max(lower_i - x_i, x_i - upper_i, g_j(x), |h_k(x)|) <= feasibility_check_tolerance.
  // Looser than constraint_tolerance on purpose: Ipopt relaxes bounds by ~1e-8 internally.
  double feasibility_check_tolerance = 1e-6;

  int max_iterations = 3000;            // Ipopt iterations
  int max_evaluations = 200000;         // NLopt objective evaluations (NLopt has no iterations)
  double max_solver_time_in_seconds = 60.0;  // per backend run

  int multistart_count = 10;     // extra starting points for "multistart"
  std::uint32_t random_seed = 1; // multistart points and ISRES; runs are reproducible
  int population = 0;            // ISRES population; 0 = NLopt's default 20*(n+1)
  bool polish_global_result = true;  // run local_algorithm from the global algorithm's answer

  // Names the first violated rule (field, value, rule, valid choices) in *error.
  bool IsValid(std::string* error) const;
};

enum class SolverStatus {
  kNotCalled,            // a default-constructed result
  kSolved,               // converged, and the wrapper's feasibility re-check passed
  kInfeasible,           // the backend proved local infeasibility (Ipopt) or found no feasible point
  kConstraintViolation,  // the backend claimed success but the re-check found a violation
  kIterationLimit,       // max_iterations / max_evaluations reached
  kTimeLimit,            // max_solver_time_in_seconds reached
  kNumericalFailure,     // the backend gave up (round-off, restoration failure, NaN, ...)
};
const char* SolverStatusToString(SolverStatus status);

struct SolverResult {
  SolverStatus status = SolverStatus::kNotCalled;
  std::string message = "Solve was not called.";
  std::string algorithm;
  Eigen::VectorXd x;
  double objective = std::numeric_limits<double>::quiet_NaN();
  // max(lower - x, x - upper, g, |h|, 0) at x, from the wrapper's own evaluation.
  double constraint_violation = std::numeric_limits<double>::quiet_NaN();
  std::string worst_constraint;  // name of the constraint or bound attaining it ("" if none)
  int iterations = 0;             // Ipopt iterations; NLopt objective evaluations
  int objective_evaluations = 0;  // with or without gradient, counted by the wrapper
  int constraint_evaluations = 0;
  double total_time_in_seconds = 0.0;
  std::vector<std::string> variable_names;

  bool is_success() const { return status == SolverStatus::kSolved; }
  std::string BriefReport() const;  // one line
  std::string FullReport() const;   // a table with every variable
};

SolverResult Solve(const Problem& problem, const SolverOptions& options);

// Every valid value of SolverOptions::algorithm, in the order listed above.
const std::vector<std::string>& AvailableAlgorithms();

// Whether the backend that runs `algorithm` is built into this dynosize (Drake's
// is_available()). Each backend can be left out at configure time: -DDYNOSIZE_WITH_IPOPT=OFF
// ("ipopt"), -DDYNOSIZE_WITH_NLOPT=OFF (every "nlopt_*"); "multistart" is a wrapper and always
// available. When not, *why (if not null) gets the one-line message that Solve() throws as
// UnavailableError (exit code 69), e.g. "dynosize was not built with Ipopt
// (-DDYNOSIZE_WITH_IPOPT=OFF) ...". Solve() checks options.algorithm, and
// options.local_algorithm when it runs it (multistart, the polish of a global result).
// Unknown names are not available (SolverOptions::IsValid names them).
bool IsAlgorithmAvailable(const std::string& algorithm, std::string* why = nullptr);

}  // namespace dynosize
