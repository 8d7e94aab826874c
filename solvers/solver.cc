#include "solvers/solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

#include "common/error.h"
#include "solvers/backends.h"

namespace dynosize {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

const std::vector<std::string>& LocalAlgorithms() {
  static const std::vector<std::string> names = {"ipopt", "nlopt_slsqp", "nlopt_mma", "nlopt_cobyla"};
  return names;
}
bool IsGlobal(const std::string& a) { return a == "nlopt_direct" || a == "nlopt_isres"; }

std::string JoinNames(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s;
}

std::string IndexedName(const std::vector<std::string>& names, const char* prefix, int i) {
  if (i < static_cast<int>(names.size()) && !names[i].empty()) return names[i];
  return std::string(prefix) + "[" + std::to_string(i) + "]";
}

// The wrapper's own feasibility measure; see SolverOptions::feasibility_check_tolerance.
struct Violation {
  double amount = 0.0;
  std::string where;
};
Violation MeasureViolation(const Problem& p, const Eigen::VectorXd& x, SolverResult* counts) {
  Violation v;
  auto consider = [&v](double amount, const std::string& where) {
    if (amount > v.amount || std::isnan(amount)) {
      v.amount = std::isnan(amount) ? kInf : amount;
      v.where = where;
    }
  };
  for (int i = 0; i < p.num_variables; ++i) {
    consider(p.Lower(i) - x[i], "lower bound of " + p.VariableName(i));
    consider(x[i] - p.Upper(i), "upper bound of " + p.VariableName(i));
  }
  if (p.num_inequality_constraints > 0) {
    Eigen::VectorXd g(p.num_inequality_constraints);
    p.inequality_constraints(x, &g, nullptr);
    ++counts->constraint_evaluations;
    for (int j = 0; j < g.size(); ++j) consider(g[j], p.InequalityName(j) + " <= 0");
  }
  if (p.num_equality_constraints > 0) {
    Eigen::VectorXd h(p.num_equality_constraints);
    p.equality_constraints(x, &h, nullptr);
    ++counts->constraint_evaluations;
    for (int k = 0; k < h.size(); ++k) consider(std::abs(h[k]), p.EqualityName(k) + " = 0");
  }
  return v;
}

// One backend run followed by the independent re-check.
SolverResult SolveOnce(const Problem& p, const SolverOptions& o, const std::string& algorithm) {
  SolverResult r = algorithm == "ipopt" ? solvers_internal::RunIpopt(p, o)
                                        : solvers_internal::RunNlopt(p, o, algorithm);
  if (r.x.size() != p.num_variables || !r.x.allFinite()) {
    r.status = SolverStatus::kNumericalFailure;
    r.message += "; the returned point is not finite";
    return r;
  }
  r.objective = p.objective(r.x, nullptr);
  ++r.objective_evaluations;
  const Violation v = MeasureViolation(p, r.x, &r);
  r.constraint_violation = v.amount;
  r.worst_constraint = v.where;
  if (!std::isfinite(r.objective) && r.status == SolverStatus::kSolved) {
    r.status = SolverStatus::kNumericalFailure;
    r.message += "; but the objective is not finite at the returned point";
  }
  if (v.amount > o.feasibility_check_tolerance) {
    char buf[160];
    std::snprintf(buf, sizeof buf, " violated by %.3g (> feasibility_check_tolerance %.3g)",
                  v.amount, o.feasibility_check_tolerance);
    if (r.status == SolverStatus::kSolved) {
      r.status = SolverStatus::kConstraintViolation;
      r.message += "; but the wrapper's re-check found " + v.where + buf;
    } else {
      r.message += "; at the returned point " + v.where + buf;
    }
  }
  return r;
}

void AddCounts(const SolverResult& from, SolverResult* to) {
  to->iterations += from.iterations;
  to->objective_evaluations += from.objective_evaluations;
  to->constraint_evaluations += from.constraint_evaluations;
}

// "Better": solved beats not solved; among solved the lower objective; otherwise the smaller
// violation.
bool Better(const SolverResult& a, const SolverResult& b) {
  if (a.is_success() != b.is_success()) return a.is_success();
  if (a.is_success()) return a.objective < b.objective;
  if (a.constraint_violation != b.constraint_violation) return a.constraint_violation < b.constraint_violation;
  return a.objective < b.objective;
}

void RequireFiniteBounds(const Problem& p, const std::string& algorithm) {
  for (int i = 0; i < p.num_variables; ++i) {
    if (!std::isfinite(p.Lower(i)) || !std::isfinite(p.Upper(i))) {
      std::ostringstream os;
      os << "algorithm '" << algorithm << "' samples the box and needs finite bounds, but "
         << p.VariableName(i) << " has bounds [" << p.Lower(i) << ", " << p.Upper(i) << "]";
      throw UsageError(os.str());
    }
  }
}

SolverResult Multistart(const Problem& p, const SolverOptions& o) {
  RequireFiniteBounds(p, "multistart");
  std::mt19937 rng(o.random_seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SolverResult best, total;
  int solved = 0, best_index = -1;
  Problem q = p;
  for (int k = 0; k <= o.multistart_count; ++k) {
    if (k > 0) {
      for (int i = 0; i < p.num_variables; ++i) q.initial_point[i] = p.Lower(i) + u(rng) * (p.Upper(i) - p.Lower(i));
    }
    SolverResult r = SolveOnce(q, o, o.local_algorithm);
    AddCounts(r, &total);
    solved += r.is_success();
    if (best_index < 0 || Better(r, best)) {
      best = r;
      best_index = k;
    }
  }
  std::ostringstream os;
  os << "multistart (" << o.local_algorithm << "): best of " << o.multistart_count + 1 << " starts ("
     << solved << " solved) is start #" << best_index << ": " << best.message;
  best.message = os.str();
  best.iterations = total.iterations;
  best.objective_evaluations = total.objective_evaluations;
  best.constraint_evaluations = total.constraint_evaluations;
  return best;
}

SolverResult GlobalThenPolish(const Problem& p, const SolverOptions& o, const std::string& algorithm) {
  RequireFiniteBounds(p, algorithm);
  SolverResult global = SolveOnce(p, o, algorithm);
  if (!o.polish_global_result || global.x.size() != p.num_variables || !global.x.allFinite()) return global;
  Problem q = p;
  q.initial_point = global.x;
  SolverResult polished = SolveOnce(q, o, o.local_algorithm);
  AddCounts(global, &polished);
  if (polished.is_success() && (!global.is_success() || polished.objective <= global.objective)) {
    polished.message = global.message + "; polished by " + o.local_algorithm + ": " + polished.message;
    return polished;
  }
  global.message += "; polishing by " + o.local_algorithm + " did not improve it (" + polished.message + ")";
  // polished's counts already hold both runs.
  global.iterations = polished.iterations;
  global.objective_evaluations = polished.objective_evaluations;
  global.constraint_evaluations = polished.constraint_evaluations;
  return global;
}

}  // namespace

// --- Problem

std::string Problem::VariableName(int i) const { return IndexedName(variable_names, "x", i); }
std::string Problem::InequalityName(int j) const { return IndexedName(inequality_names, "g", j); }
std::string Problem::EqualityName(int k) const { return IndexedName(equality_names, "h", k); }
double Problem::Lower(int i) const { return lower_bounds.size() ? lower_bounds[i] : -kInf; }
double Problem::Upper(int i) const { return upper_bounds.size() ? upper_bounds[i] : kInf; }

void Problem::CheckValid() const {
  const std::string who = "Problem '" + name + "': ";
  auto fail = [&who](const std::string& s) { throw UsageError(who + s); };
  auto sized = [&](const char* field, Eigen::Index size, int want, bool may_be_empty) {
    if (size == want || (may_be_empty && size == 0)) return;
    std::ostringstream os;
    os << field << " has " << size << " entries, expected " << (may_be_empty ? "0 or " : "") << want;
    fail(os.str());
  };
  if (num_variables <= 0) fail("num_variables = " + std::to_string(num_variables) + " must be > 0");
  if (!objective) fail("objective is empty");
  if (num_inequality_constraints < 0 || num_equality_constraints < 0) fail("constraint counts must be >= 0");
  if (num_inequality_constraints > 0 && !inequality_constraints) fail("num_inequality_constraints > 0 but inequality_constraints is empty");
  if (num_equality_constraints > 0 && !equality_constraints) fail("num_equality_constraints > 0 but equality_constraints is empty");
  sized("initial_point", initial_point.size(), num_variables, false);
  sized("lower_bounds", lower_bounds.size(), num_variables, true);
  sized("upper_bounds", upper_bounds.size(), num_variables, true);
  sized("variable_names", static_cast<Eigen::Index>(variable_names.size()), num_variables, true);
  sized("inequality_names", static_cast<Eigen::Index>(inequality_names.size()), num_inequality_constraints, true);
  sized("equality_names", static_cast<Eigen::Index>(equality_names.size()), num_equality_constraints, true);
  for (int i = 0; i < num_variables; ++i) {
    std::ostringstream os;
    if (std::isnan(Lower(i)) || std::isnan(Upper(i)) || Lower(i) > Upper(i)) {
      os << "bounds of " << VariableName(i) << " [" << Lower(i) << ", " << Upper(i)
         << "] are not an interval (need lower <= upper)";
      fail(os.str());
    }
    if (!std::isfinite(initial_point[i]) || initial_point[i] < Lower(i) || initial_point[i] > Upper(i)) {
      os << "initial " << VariableName(i) << " = " << initial_point[i] << " is not a finite value in ["
         << Lower(i) << ", " << Upper(i) << "]";
      fail(os.str());
    }
  }
}

// --- Options

bool SolverOptions::IsValid(std::string* error) const {
  std::ostringstream os;
  auto fail = [&]() {
    if (error) *error = os.str();
    return false;
  };
  const auto& all = AvailableAlgorithms();
  if (std::find(all.begin(), all.end(), algorithm) == all.end()) {
    os << "SolverOptions.algorithm = '" << algorithm << "' is unknown; valid names: " << JoinNames(all);
    return fail();
  }
  const auto& local = LocalAlgorithms();
  if (std::find(local.begin(), local.end(), local_algorithm) == local.end()) {
    os << "SolverOptions.local_algorithm = '" << local_algorithm
       << "' must be a local algorithm; valid names: " << JoinNames(local);
    return fail();
  }
  auto positive = [&](const char* field, double v) {
    if (v > 0.0 && std::isfinite(v)) return true;
    os << "SolverOptions." << field << " = " << v << " must be finite and > 0";
    return false;
  };
  if (!positive("relative_tolerance", relative_tolerance)) return fail();
  if (!positive("constraint_tolerance", constraint_tolerance)) return fail();
  if (!positive("feasibility_check_tolerance", feasibility_check_tolerance)) return fail();
  if (!positive("max_solver_time_in_seconds", max_solver_time_in_seconds)) return fail();
  if (max_iterations <= 0) { os << "SolverOptions.max_iterations = " << max_iterations << " must be > 0"; return fail(); }
  if (max_evaluations <= 0) { os << "SolverOptions.max_evaluations = " << max_evaluations << " must be > 0"; return fail(); }
  if (multistart_count < 0) { os << "SolverOptions.multistart_count = " << multistart_count << " must be >= 0"; return fail(); }
  if (population < 0) { os << "SolverOptions.population = " << population << " must be >= 0 (0: NLopt's default)"; return fail(); }
  return true;
}

const std::vector<std::string>& AvailableAlgorithms() {
  static const std::vector<std::string> names = {"ipopt",        "nlopt_slsqp", "nlopt_mma",
                                                 "nlopt_cobyla", "nlopt_direct", "nlopt_isres",
                                                 "multistart"};
  return names;
}

namespace solvers_internal {
std::string NotBuiltMessage(const char* backend, const char* option, const std::string& algorithm) {
  return std::string("dynosize was not built with ") + backend + " (-D" + option + "=OFF), which algorithm '" +
         algorithm + "' needs; configure with -D" + option + "=ON to use it";
}
}  // namespace solvers_internal

bool IsAlgorithmAvailable(const std::string& algorithm, std::string* why) {
  using solvers_internal::NotBuiltMessage;
  const auto& all = AvailableAlgorithms();
  std::string reason;
  if (std::find(all.begin(), all.end(), algorithm) == all.end()) {
    reason = "algorithm '" + algorithm + "' is unknown; valid names: " + JoinNames(all);
  } else if (algorithm == "ipopt" && !solvers_internal::IpoptBuilt()) {
    reason = NotBuiltMessage("Ipopt", "DYNOSIZE_WITH_IPOPT", algorithm);
  } else if (algorithm.rfind("nlopt_", 0) == 0 && !solvers_internal::NloptBuilt()) {
    reason = NotBuiltMessage("NLopt", "DYNOSIZE_WITH_NLOPT", algorithm);
  }
  if (why) *why = reason;
  return reason.empty();
}

const char* SolverStatusToString(SolverStatus status) {
  switch (status) {
    case SolverStatus::kNotCalled: return "NOT_CALLED";
    case SolverStatus::kSolved: return "SOLVED";
    case SolverStatus::kInfeasible: return "INFEASIBLE";
    case SolverStatus::kConstraintViolation: return "CONSTRAINT_VIOLATION";
    case SolverStatus::kIterationLimit: return "ITERATION_LIMIT";
    case SolverStatus::kTimeLimit: return "TIME_LIMIT";
    case SolverStatus::kNumericalFailure: return "NUMERICAL_FAILURE";
  }
  return "UNKNOWN";
}

// --- Solve

SolverResult Solve(const Problem& problem, const SolverOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw UsageError(why);
  problem.CheckValid();
  const bool runs_local = options.algorithm == "multistart" || (IsGlobal(options.algorithm) && options.polish_global_result);
  if (!IsAlgorithmAvailable(options.algorithm, &why) || (runs_local && !IsAlgorithmAvailable(options.local_algorithm, &why))) {
    throw UnavailableError(why);
  }
  const auto t0 = std::chrono::steady_clock::now();
  SolverResult r;
  if (options.algorithm == "multistart") {
    r = Multistart(problem, options);
  } else if (IsGlobal(options.algorithm)) {
    r = GlobalThenPolish(problem, options, options.algorithm);
  } else {
    r = SolveOnce(problem, options, options.algorithm);
  }
  r.algorithm = options.algorithm;
  for (int i = 0; i < problem.num_variables; ++i) r.variable_names.push_back(problem.VariableName(i));
  r.total_time_in_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::string SolverResult::BriefReport() const {
  if (status == SolverStatus::kNotCalled) return "Solve was not called.";
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s: %s, f = %.10g, violation %.2g, %d iterations, %d f-evals, %.3g s",
                algorithm.c_str(), SolverStatusToString(status), objective, constraint_violation,
                iterations, objective_evaluations, total_time_in_seconds);
  return buf;
}

std::string SolverResult::FullReport() const {
  if (status == SolverStatus::kNotCalled) return "Solve was not called.\n";
  std::ostringstream os;
  char buf[512];
  os << "Solver summary\n";
  std::snprintf(buf, sizeof buf,
                "  %-24s %s\n  %-24s %s\n  %-24s %.12g\n  %-24s %.3g (%s)\n  %-24s %d\n"
                "  %-24s %d objective, %d constraint\n  %-24s %.3g\n",
                "algorithm", algorithm.c_str(), "status", SolverStatusToString(status), "objective",
                objective, "constraint violation", constraint_violation,
                worst_constraint.empty() ? "none" : worst_constraint.c_str(), "iterations", iterations,
                "evaluations", objective_evaluations, constraint_evaluations, "time [s]",
                total_time_in_seconds);
  os << buf << "  message                  " << message << "\n";
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const std::string n = i < static_cast<Eigen::Index>(variable_names.size()) ? variable_names[i] : "x[" + std::to_string(i) + "]";
    std::snprintf(buf, sizeof buf, "  %-24s %22.14g\n", n.c_str(), x[i]);
    os << buf;
  }
  return os.str();
}

}  // namespace dynosize
