// Ipopt backend: a TNLP adapter over a dynosize::Problem.
//
// Ipopt traps handled here (ecosystem-notes.md): include as <IpTNLP.hpp> (works for 3.11 and
// the coin-or/ layout of 3.14); option sb=yes and print_level 0, and no console journal at all,
// because Ipopt's banner on stdout corrupts `--json`; Initialize("") so a stray ./ipopt.opt in
// the user's working directory cannot override our options.
#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>

#include <chrono>
#include <cmath>
#include <sstream>

#include "solvers/backends.h"

namespace dynosize {
namespace solvers_internal {
namespace {

using Ipopt::Index;
using Ipopt::Number;

// Ipopt treats |bound| >= 1e19 as infinite (nlp_lower/upper_bound_inf).
constexpr Number kIpoptInf = 2e19;

class ProblemTnlp : public Ipopt::TNLP {
 public:
  explicit ProblemTnlp(CallbackGuard* guard)
      : guard_(guard), p_(guard->problem), n_(p_.num_variables),
        mi_(p_.num_inequality_constraints), me_(p_.num_equality_constraints) {}

  Eigen::VectorXd x_final;
  Number objective_final = std::nan("");
  Ipopt::SolverReturn solver_return = Ipopt::UNASSIGNED;

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = n_;
    m = mi_ + me_;
    nnz_jac_g = n_ * (mi_ + me_);  // dense: problems are small
    nnz_h_lag = 0;                 // no Hessian: limited-memory quasi-Newton
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] = std::isinf(p_.Lower(i)) ? -kIpoptInf : p_.Lower(i);
      x_u[i] = std::isinf(p_.Upper(i)) ? kIpoptInf : p_.Upper(i);
    }
    for (Index j = 0; j < m; ++j) {
      g_l[j] = j < mi_ ? -kIpoptInf : 0.0;  // g(x) <= 0, then h(x) = 0
      g_u[j] = 0.0;
    }
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number*, Number*, Index,
                          bool init_lambda, Number*) override {
    if (!init_x || init_z || init_lambda) return false;
    for (Index i = 0; i < n; ++i) x[i] = p_.initial_point[i];
    return true;
  }

  bool eval_f(Index n, const Number* x, bool, Number& obj_value) override {
    return Guard([&] {
      ++guard_->objective_evaluations;
      obj_value = p_.objective(Map(n, x), nullptr);
      return std::isfinite(obj_value);
    });
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    return Guard([&] {
      ++guard_->objective_evaluations;
      Eigen::VectorXd g(n);
      p_.objective(Map(n, x), &g);
      Eigen::Map<Eigen::VectorXd>(grad_f, n) = g;
      return g.allFinite();
    });
  }

  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    return Guard([&] {
      if (m == 0) return true;
      ++guard_->constraint_evaluations;
      const Eigen::VectorXd xv = Map(n, x);
      Eigen::VectorXd v;
      if (mi_ > 0) {
        v.resize(mi_);
        p_.inequality_constraints(xv, &v, nullptr);
        Eigen::Map<Eigen::VectorXd>(g, mi_) = v;
      }
      if (me_ > 0) {
        v.resize(me_);
        p_.equality_constraints(xv, &v, nullptr);
        Eigen::Map<Eigen::VectorXd>(g + mi_, me_) = v;
      }
      return Eigen::Map<Eigen::VectorXd>(g, m).allFinite();
    });
  }

  bool eval_jac_g(Index n, const Number* x, bool, Index m, Index, Index* i_row, Index* j_col,
                  Number* values) override {
    if (values == nullptr) {  // structure: dense, row-major
      for (Index j = 0; j < m; ++j) {
        for (Index i = 0; i < n; ++i) {
          i_row[j * n + i] = j;
          j_col[j * n + i] = i;
        }
      }
      return true;
    }
    return Guard([&] {
      ++guard_->constraint_evaluations;
      const Eigen::VectorXd xv = Map(n, x);
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> jac(values, m, n);
      Eigen::VectorXd v;
      Eigen::MatrixXd jb;
      if (mi_ > 0) {
        v.resize(mi_);
        jb.resize(mi_, n);
        p_.inequality_constraints(xv, &v, &jb);
        jac.topRows(mi_) = jb;
      }
      if (me_ > 0) {
        v.resize(me_);
        jb.resize(me_, n);
        p_.equality_constraints(xv, &v, &jb);
        jac.bottomRows(me_) = jb;
      }
      return jac.allFinite();
    });
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index, Number, Number, Number, Number, Number,
                             Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    // Returning false is Ipopt's way to stop: a callback threw and its exception is waiting.
    return !guard_->error;
  }

  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x, const Number*,
                         const Number*, Index, const Number*, const Number*, Number obj_value,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solver_return = status;
    x_final = Map(n, x);
    objective_final = obj_value;
  }

 private:
  static Eigen::VectorXd Map(Index n, const Number* x) {
    return Eigen::Map<const Eigen::VectorXd>(x, n);
  }
  // Runs a callback; an exception is stored (first one wins) and reported to Ipopt as an
  // evaluation failure, after which intermediate_callback stops the run.
  template <typename F>
  bool Guard(F f) {
    if (guard_->error) return false;
    try {
      return f();
    } catch (...) {
      guard_->error = std::current_exception();
      return false;
    }
  }

  CallbackGuard* guard_;
  const Problem& p_;
  Index n_, mi_, me_;
};

}  // namespace

bool IpoptBuilt() { return true; }

SolverResult RunIpopt(const Problem& problem, const SolverOptions& options) {
  CallbackGuard guard(problem);
  Ipopt::SmartPtr<ProblemTnlp> tnlp = new ProblemTnlp(&guard);
  // create_console_out = false: no journal on stdout at all.
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication(false);
  auto opts = app->Options();
  opts->SetStringValue("sb", "yes");
  opts->SetIntegerValue("print_level", 0);
  opts->SetStringValue("hessian_approximation", "limited-memory");
  opts->SetNumericValue("tol", options.relative_tolerance);
  opts->SetNumericValue("constr_viol_tol", options.constraint_tolerance);
  opts->SetIntegerValue("max_iter", options.max_iterations);
  opts->SetNumericValue("max_cpu_time", options.max_solver_time_in_seconds);
  // Return x inside the user's bounds (Ipopt relaxes them by ~1e-8 internally).
  opts->SetStringValue("honor_original_bounds", "yes");

  SolverResult result;
  result.algorithm = "ipopt";
  Ipopt::ApplicationReturnStatus status = app->Initialize("");
  if (status != Ipopt::Solve_Succeeded) {
    result.status = SolverStatus::kNumericalFailure;
    result.message = "Ipopt could not be initialized (status " + std::to_string(status) + ")";
    return result;
  }
  status = app->OptimizeTNLP(tnlp);
  guard.RethrowIfAny();

  result.objective_evaluations = guard.objective_evaluations;
  result.constraint_evaluations = guard.constraint_evaluations;
  if (Ipopt::IsValid(app->Statistics())) result.iterations = app->Statistics()->IterationCount();
  result.x = tnlp->x_final.size() ? tnlp->x_final : problem.initial_point;
  result.objective = tnlp->objective_final;

  std::ostringstream os;
  os << "Ipopt: ";
  switch (status) {
    case Ipopt::Solve_Succeeded:
      result.status = SolverStatus::kSolved;
      os << "optimal solution found";
      break;
    case Ipopt::Solved_To_Acceptable_Level:
      result.status = SolverStatus::kSolved;
      os << "solved to acceptable level (not to the requested tolerance)";
      break;
    case Ipopt::Infeasible_Problem_Detected:
      result.status = SolverStatus::kInfeasible;
      os << "converged to a point of local infeasibility: the constraints cannot be satisfied";
      break;
    case Ipopt::Maximum_Iterations_Exceeded:
      result.status = SolverStatus::kIterationLimit;
      os << "maximum number of iterations (" << options.max_iterations << ") exceeded";
      break;
    case Ipopt::Maximum_CpuTime_Exceeded:
      result.status = SolverStatus::kTimeLimit;
      os << "maximum CPU time exceeded";
      break;
    case Ipopt::Diverging_Iterates:
      result.status = SolverStatus::kNumericalFailure;
      os << "iterates diverging: the problem may be unbounded below";
      break;
    default:
      result.status = SolverStatus::kNumericalFailure;
      os << "stopped with return status " << static_cast<int>(status)
         << " (search direction too small, restoration failure, invalid number, ...)";
      break;
  }
  result.message = os.str();
  return result;
}

}  // namespace solvers_internal
}  // namespace dynosize
