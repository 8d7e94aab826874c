// NLopt backend through its C++ API (nlopt.hpp, linked as NLopt::nlopt_cxx).
//
// NLopt's own C++ wrapper catches callback exceptions but replaces them by its generic
// nlopt::forced_stop / "nlopt failure", losing the user's message and type. Our callbacks catch
// first, store the exception in the CallbackGuard, call force_stop() and return HUGE_VAL; after
// optimize() returns or throws, the stored exception is rethrown unchanged.
#include <nlopt.hpp>

#include <cmath>
#include <sstream>

#include "common/error.h"
#include "solvers/backends.h"

namespace dynosize {
namespace solvers_internal {
namespace {

struct Context {
  CallbackGuard* guard;
  nlopt::opt* opt;
};

double ObjectiveCallback(unsigned n, const double* x, double* grad, void* data) {
  auto* c = static_cast<Context*>(data);
  if (c->guard->error) {
    c->opt->force_stop();
    return HUGE_VAL;
  }
  try {
    ++c->guard->objective_evaluations;
    const Eigen::Map<const Eigen::VectorXd> xv(x, n);
    if (grad == nullptr) return c->guard->problem.objective(xv, nullptr);
    Eigen::VectorXd g(n);
    const double f = c->guard->problem.objective(xv, &g);
    Eigen::Map<Eigen::VectorXd>(grad, n) = g;
    return f;
  } catch (...) {
    c->guard->error = std::current_exception();
    c->opt->force_stop();
    return HUGE_VAL;
  }
}

template <bool kEquality>
void ConstraintCallback(unsigned m, double* result, unsigned n, const double* x, double* grad,
                        void* data) {
  auto* c = static_cast<Context*>(data);
  auto fail = [&] {
    for (unsigned j = 0; j < m; ++j) result[j] = HUGE_VAL;
    c->opt->force_stop();
  };
  if (c->guard->error) return fail();
  try {
    ++c->guard->constraint_evaluations;
    const Problem& p = c->guard->problem;
    const ConstraintFunction& f = kEquality ? p.equality_constraints : p.inequality_constraints;
    const Eigen::Map<const Eigen::VectorXd> xv(x, n);
    Eigen::VectorXd v(m);
    if (grad == nullptr) {
      f(xv, &v, nullptr);
    } else {
      Eigen::MatrixXd jac(m, n);
      f(xv, &v, &jac);
      // NLopt wants the m x n Jacobian row-major.
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(grad, m, n) = jac;
    }
    Eigen::Map<Eigen::VectorXd>(result, m) = v;
  } catch (...) {
    c->guard->error = std::current_exception();
    fail();
  }
}

struct AlgorithmChoice {
  nlopt::algorithm outer;
  bool has_inner = false;
  nlopt::algorithm inner = nlopt::LD_SLSQP;
  bool global = false;
};

AlgorithmChoice Choose(const std::string& name, const Problem& p) {
  const bool eq = p.num_equality_constraints > 0;
  const bool ineq = p.num_inequality_constraints > 0;
  if (name == "nlopt_slsqp") return {nlopt::LD_SLSQP};
  if (name == "nlopt_cobyla") return {nlopt::LN_COBYLA};
  if (name == "nlopt_mma") {
    // MMA handles inequalities only; equalities go to NLopt's augmented Lagrangian.
    if (eq) return {nlopt::AUGLAG, true, nlopt::LD_MMA};
    return {nlopt::LD_MMA};
  }
  if (name == "nlopt_isres") return {nlopt::GN_ISRES, false, nlopt::LD_SLSQP, true};
  if (name == "nlopt_direct") {
    // DIRECT-L takes no constraints; the "original" DIRECT-L takes inequalities; equalities go
    // to the augmented Lagrangian around it.
    if (eq) return {nlopt::AUGLAG_EQ, true, nlopt::GN_ORIG_DIRECT_L, true};
    if (ineq) return {nlopt::GN_ORIG_DIRECT_L, false, nlopt::LD_SLSQP, true};
    return {nlopt::GN_DIRECT_L, false, nlopt::LD_SLSQP, true};
  }
  throw InternalError("RunNlopt: algorithm '" + name + "' is not an NLopt algorithm");
}

}  // namespace

bool NloptBuilt() { return true; }

SolverResult RunNlopt(const Problem& problem, const SolverOptions& options, const std::string& algorithm) {
  const AlgorithmChoice choice = Choose(algorithm, problem);
  const unsigned n = static_cast<unsigned>(problem.num_variables);
  CallbackGuard guard(problem);
  nlopt::opt opt(choice.outer, n);
  Context ctx{&guard, &opt};

  std::vector<double> lo(n), hi(n);
  for (unsigned i = 0; i < n; ++i) {
    lo[i] = problem.Lower(static_cast<int>(i));
    hi[i] = problem.Upper(static_cast<int>(i));
  }
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_min_objective(ObjectiveCallback, &ctx);
  if (problem.num_inequality_constraints > 0) {
    opt.add_inequality_mconstraint(ConstraintCallback<false>, &ctx,
                                   std::vector<double>(problem.num_inequality_constraints, options.constraint_tolerance));
  }
  if (problem.num_equality_constraints > 0) {
    opt.add_equality_mconstraint(ConstraintCallback<true>, &ctx,
                                 std::vector<double>(problem.num_equality_constraints, options.constraint_tolerance));
  }
  opt.set_ftol_rel(options.relative_tolerance);
  opt.set_xtol_rel(options.relative_tolerance);
  opt.set_maxeval(options.max_evaluations);
  opt.set_maxtime(options.max_solver_time_in_seconds);
  if (choice.global) nlopt::srand(options.random_seed);
  if (algorithm == "nlopt_isres" && options.population > 0) opt.set_population(static_cast<unsigned>(options.population));
  if (choice.has_inner) {
    nlopt::opt inner(choice.inner, n);
    inner.set_ftol_rel(options.relative_tolerance);
    inner.set_xtol_rel(options.relative_tolerance);
    // Each augmented-Lagrangian subproblem gets a share of the budget.
    inner.set_maxeval(std::max(1000, options.max_evaluations / 20));
    opt.set_local_optimizer(inner);
  }

  std::vector<double> x(problem.initial_point.data(), problem.initial_point.data() + n);
  double f = HUGE_VAL;
  SolverResult result;
  result.algorithm = algorithm;
  std::ostringstream os;
  os << "NLopt " << opt.get_algorithm_name() << ": ";
  nlopt::result code = nlopt::FAILURE;
  bool threw = false;
  try {
    code = opt.optimize(x, f);
  } catch (const nlopt::forced_stop&) {
    guard.RethrowIfAny();  // ours: the user's exception, unchanged
    code = nlopt::FORCED_STOP;
    threw = true;
  } catch (const nlopt::roundoff_limited&) {
    code = nlopt::ROUNDOFF_LIMITED;
    threw = true;
  } catch (const std::invalid_argument& e) {
    guard.RethrowIfAny();
    throw InternalError(std::string("NLopt rejected the problem set-up: ") + e.what());
  } catch (const std::runtime_error&) {
    guard.RethrowIfAny();
    code = nlopt::FAILURE;
    threw = true;
  }
  guard.RethrowIfAny();
  (void)threw;

  result.x = Eigen::Map<const Eigen::VectorXd>(x.data(), n);
  result.objective = f;
  result.objective_evaluations = guard.objective_evaluations;
  result.constraint_evaluations = guard.constraint_evaluations;
  result.iterations = guard.objective_evaluations;
  switch (code) {
    case nlopt::SUCCESS:
    case nlopt::STOPVAL_REACHED:
    case nlopt::FTOL_REACHED:
    case nlopt::XTOL_REACHED:
      result.status = SolverStatus::kSolved;
      os << (code == nlopt::FTOL_REACHED ? "relative change of f below tolerance"
             : code == nlopt::XTOL_REACHED ? "relative change of x below tolerance"
                                           : "success");
      break;
    case nlopt::MAXEVAL_REACHED:
      // For the global algorithms the evaluation budget is the normal end of the search.
      result.status = choice.global ? SolverStatus::kSolved : SolverStatus::kIterationLimit;
      os << "evaluation budget (" << options.max_evaluations << ") used up";
      break;
    case nlopt::MAXTIME_REACHED:
      result.status = SolverStatus::kTimeLimit;
      os << "maximum time reached";
      break;
    case nlopt::ROUNDOFF_LIMITED:
      // NLopt: "the optimization still typically returns a useful result"; the feasibility
      // re-check decides.
      result.status = SolverStatus::kSolved;
      os << "round-off limited progress (result kept, feasibility re-checked)";
      break;
    default:
      result.status = SolverStatus::kNumericalFailure;
      os << "failed (NLopt result code " << static_cast<int>(code) << ")";
      break;
  }
  result.message = os.str();
  return result;
}

}  // namespace solvers_internal
}  // namespace dynosize
