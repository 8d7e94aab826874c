// Every algorithm through the same reference problems (house style: Drake/pagmo2).
#include "solvers/solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <map>
#include <memory>
#include <stdexcept>

#include "common/error.h"
#include "solver_backends.h"

namespace dynosize {
namespace {

// Tolerances, with reasons:
// The minima below are quadratic, so an objective within eps_f of f* pins x only to about
// sqrt(eps_f / curvature). Gradient-based solvers at relative_tolerance 1e-10 reach f* + ~1e-12;
// COBYLA (derivative-free) and the stochastic/global searches (then polished) reach ~1e-9.
constexpr double kObjectiveAbsTol = 1e-6;
// x within 1e-3: sqrt(1e-6), the resolution an objective tolerance of 1e-6 implies.
constexpr double kXAbsTol = 1e-3;
// HS071's certified optimum has 9 significant digits: 17.0140173 (Hock & Schittkowski 1981);
// 1e-6 relative is well inside that and allows Ipopt to stop ~1e-8 from the active bound x1 = 1.
constexpr double kHs071Optimum = 17.0140173;
constexpr double kHs071RelTol = 1e-6;

bool IsGlobal(const std::string& a) {
  return a == "nlopt_direct" || a == "nlopt_isres" || a == "multistart";
}

SolverOptions OptionsFor(const std::string& algorithm) {
  SolverOptions o;
  o.algorithm = algorithm;
  o.max_evaluations = 100000;
  o.random_seed = 12345;  // ISRES and multistart draw from it: reproducible runs
  if (IsGlobal(algorithm)) {
    // The global searches stop on their evaluation budget; 20000 is plenty for n <= 4 in a box
    // and keeps an infeasible problem from running for minutes.
    o.max_evaluations = 20000;
    o.max_solver_time_in_seconds = 20.0;
  }
  return o;
}

Problem Rosenbrock(bool bounded) {
  Problem p;
  p.name = bounded ? "Rosenbrock (box [-1.5, 1.5]^2)" : "Rosenbrock";
  p.num_variables = 2;
  p.initial_point = Eigen::Vector2d(-1.2, 1.0);
  if (bounded) {
    p.lower_bounds = Eigen::Vector2d(-1.5, -1.5);
    p.upper_bounds = Eigen::Vector2d(1.5, 1.5);
  }
  p.variable_names = {"x", "y"};
  p.objective = AutoDiffObjective<2>(
      [](const auto* x) { return 100.0 * (x[1] - x[0] * x[0]) * (x[1] - x[0] * x[0]) + (1.0 - x[0]) * (1.0 - x[0]); }, 2);
  return p;
}

// Rosenbrock with x <= 0.5: the bound is active; on the curve y = x^2 the objective is (1-x)^2,
// so the optimum is (0.5, 0.25) with f = 0.25.
Problem RosenbrockActiveBound() {
  Problem p = Rosenbrock(true);
  p.name = "Rosenbrock with active bound x <= 0.5";
  p.upper_bounds = Eigen::Vector2d(0.5, 1.5);
  return p;
}

// Hock-Schittkowski problem 71, Ipopt's classic example.
Problem Hs071() {
  Problem p;
  p.name = "HS071";
  p.num_variables = 4;
  p.initial_point = Eigen::Vector4d(1, 5, 5, 1);
  p.lower_bounds = Eigen::Vector4d::Constant(1.0);
  p.upper_bounds = Eigen::Vector4d::Constant(5.0);
  p.objective = AutoDiffObjective<4>([](const auto* x) { return x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2]; }, 4);
  p.num_inequality_constraints = 1;
  p.inequality_names = {"product_at_least_25"};
  p.inequality_constraints = AutoDiffConstraints<4>(
      [](const auto* x, auto* g) { g[0] = 25.0 - x[0] * x[1] * x[2] * x[3]; }, 4, 1);
  p.num_equality_constraints = 1;
  p.equality_names = {"sum_of_squares_is_40"};
  p.equality_constraints = AutoDiffConstraints<4>(
      [](const auto* x, auto* h) { h[0] = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3] - 40.0; }, 4, 1);
  return p;
}

// x, y in [0, 1] and x + y >= 3: no feasible point.
Problem Infeasible() {
  Problem p;
  p.name = "infeasible";
  p.num_variables = 2;
  p.initial_point = Eigen::Vector2d(0.5, 0.5);
  p.lower_bounds = Eigen::Vector2d(0, 0);
  p.upper_bounds = Eigen::Vector2d(1, 1);
  p.objective = AutoDiffObjective<2>([](const auto* x) { return x[0] * x[0] + x[1] * x[1]; }, 2);
  p.num_inequality_constraints = 1;
  p.inequality_names = {"sum_at_least_3"};
  p.inequality_constraints = AutoDiffConstraints<2>([](const auto* x, auto* g) { g[0] = 3.0 - x[0] - x[1]; }, 2, 1);
  return p;
}

// f = x^4 - 3 x^2 + x on [-3, 3]: global minimum near -1.30 (f ~ -3.51), a local one near 1.13.
Problem OneDimensional(double x0) {
  Problem p;
  p.name = "1-D quartic";
  p.num_variables = 1;
  p.initial_point = Eigen::VectorXd::Constant(1, x0);
  p.lower_bounds = Eigen::VectorXd::Constant(1, -3.0);
  p.upper_bounds = Eigen::VectorXd::Constant(1, 3.0);
  p.objective = AutoDiffObjective<1>([](const auto* x) { return x[0] * x[0] * x[0] * x[0] - 3.0 * x[0] * x[0] + x[0]; }, 1);
  return p;
}
double QuarticRoot(double x) {  // Newton on f' = 4x^3 - 6x + 1, to machine precision
  for (int i = 0; i < 50; ++i) x -= (4 * x * x * x - 6 * x + 1) / (12 * x * x - 6);
  return x;
}

std::map<std::string, std::string>& Table() {
  static std::map<std::string, std::string> t;
  return t;
}
void Record(const std::string& algorithm, const std::string& problem, const SolverResult& r) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%-22s f=%-16.10g viol=%-9.2g it=%-6d fev=%-6d", SolverStatusToString(r.status),
                r.objective, r.constraint_violation, r.iterations, r.objective_evaluations);
  Table()[problem + " | " + algorithm] = buf;
}

class EveryAlgorithm : public testing::TestWithParam<std::string> {};

TEST_P(EveryAlgorithm, RosenbrockUnbounded) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE(GetParam());
  if (IsGlobal(GetParam())) DYNOSIZE_SKIP_UNLESS_AVAILABLE(OptionsFor(GetParam()).local_algorithm);
  const Problem p = Rosenbrock(false);
  if (IsGlobal(GetParam())) {
    // Global searches sample the box: an unbounded problem is a usage error naming the variable.
    try {
      Solve(p, OptionsFor(GetParam()));
      FAIL() << "expected UsageError";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("needs finite bounds"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("x has bounds [-inf, inf]"), std::string::npos) << e.what();
    }
    return;
  }
  const SolverResult r = Solve(p, OptionsFor(GetParam()));
  Record(GetParam(), "Rosenbrock", r);
  ASSERT_TRUE(r.is_success()) << r.FullReport();
  EXPECT_NEAR(r.objective, 0.0, kObjectiveAbsTol) << r.FullReport();
  EXPECT_NEAR(r.x[0], 1.0, kXAbsTol);
  EXPECT_NEAR(r.x[1], 1.0, 2 * kXAbsTol);  // y = x^2 doubles the error along the valley
}

TEST_P(EveryAlgorithm, RosenbrockBounded) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE(GetParam());
  if (IsGlobal(GetParam())) DYNOSIZE_SKIP_UNLESS_AVAILABLE(OptionsFor(GetParam()).local_algorithm);
  const SolverResult r = Solve(Rosenbrock(true), OptionsFor(GetParam()));
  Record(GetParam(), "Rosenbrock bounded", r);
  ASSERT_TRUE(r.is_success()) << r.FullReport();
  EXPECT_NEAR(r.objective, 0.0, kObjectiveAbsTol) << r.FullReport();
  EXPECT_NEAR(r.x[0], 1.0, kXAbsTol);
  EXPECT_NEAR(r.x[1], 1.0, 2 * kXAbsTol);
}

TEST_P(EveryAlgorithm, ActiveBound) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE(GetParam());
  if (IsGlobal(GetParam())) DYNOSIZE_SKIP_UNLESS_AVAILABLE(OptionsFor(GetParam()).local_algorithm);
  const SolverResult r = Solve(RosenbrockActiveBound(), OptionsFor(GetParam()));
  Record(GetParam(), "active bound", r);
  ASSERT_TRUE(r.is_success()) << r.FullReport();
  EXPECT_NEAR(r.objective, 0.25, kObjectiveAbsTol) << r.FullReport();
  EXPECT_NEAR(r.x[0], 0.5, kXAbsTol);
  EXPECT_LE(r.x[0], 0.5);  // never outside the bound (the wrapper re-checks this too)
}

TEST_P(EveryAlgorithm, Hs071) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE(GetParam());
  if (IsGlobal(GetParam())) DYNOSIZE_SKIP_UNLESS_AVAILABLE(OptionsFor(GetParam()).local_algorithm);
  SolverOptions o = OptionsFor(GetParam());
  if (GetParam() == "nlopt_cobyla") {
    // Derivative-free COBYLA (NLopt 2.7.1) cycles at HS071's equality constraint and never
    // meets a relative tolerance of 1e-7 or below (it spends the whole evaluation budget at the
    // optimum); 1e-6 stops it after ~90 evaluations within 1.2e-7 of f*.
    o.relative_tolerance = 1e-6;
  }
  const SolverResult r = Solve(Hs071(), o);
  Record(GetParam(), "HS071", r);
  ASSERT_TRUE(r.is_success()) << r.FullReport();
  EXPECT_NEAR(r.objective, kHs071Optimum, kHs071RelTol * kHs071Optimum) << r.FullReport();
  EXPECT_LE(r.constraint_violation, 1e-6);
  EXPECT_NEAR(r.x[0], 1.0, kXAbsTol);
}

TEST_P(EveryAlgorithm, InfeasibleIsAStatusNamingTheConstraint) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE(GetParam());
  if (IsGlobal(GetParam())) DYNOSIZE_SKIP_UNLESS_AVAILABLE(OptionsFor(GetParam()).local_algorithm);
  SolverOptions o = OptionsFor(GetParam());
  // NLopt's constrained DIRECT-L (GN_ORIG_DIRECT_L) never stops on an infeasible problem
  // before its budget and slows to ~1 ms per evaluation there; 2 s is enough to show the status.
  o.max_solver_time_in_seconds = 2.0;
  const SolverResult r = Solve(Infeasible(), o);
  Record(GetParam(), "infeasible", r);
  EXPECT_FALSE(r.is_success()) << r.FullReport();
  // Ipopt proves local infeasibility; the NLopt methods cannot, and either claim success (the
  // re-check downgrades it) or run out of budget/progress: every one of these is "not solved".
  EXPECT_NE(r.status, SolverStatus::kNotCalled);
  // The best any point in the box can do is x + y = 2: violation >= 1.
  EXPECT_GE(r.constraint_violation, 1.0 - 1e-6);
  EXPECT_EQ(r.worst_constraint, "sum_at_least_3 <= 0");
  EXPECT_NE(r.message.find("sum_at_least_3"), std::string::npos) << r.message;
}

TEST_P(EveryAlgorithm, CallbackExceptionIsRethrownUnchanged) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE(GetParam());
  if (IsGlobal(GetParam())) DYNOSIZE_SKIP_UNLESS_AVAILABLE(OptionsFor(GetParam()).local_algorithm);
  Problem p = Hs071();
  int calls = 0;
  const ObjectiveFunction inner = p.objective;
  p.objective = [&calls, inner](const Eigen::VectorXd& x, Eigen::VectorXd* g) {
    if (++calls == 5) throw std::domain_error("motor model undefined at this throttle");
    return inner(x, g);
  };
  try {
    Solve(p, OptionsFor(GetParam()));
    FAIL() << "expected the callback's exception";
  } catch (const std::domain_error& e) {
    EXPECT_STREQ(e.what(), "motor model undefined at this throttle");
  }
  EXPECT_LE(calls, 6) << "the solver kept calling after the exception";
}

TEST_P(EveryAlgorithm, ConstraintCallbackExceptionIsRethrown) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE(GetParam());
  if (IsGlobal(GetParam())) DYNOSIZE_SKIP_UNLESS_AVAILABLE(OptionsFor(GetParam()).local_algorithm);
  Problem p = Hs071();
  const ConstraintFunction inner = p.inequality_constraints;
  int calls = 0;
  p.inequality_constraints = [&calls, inner](const Eigen::VectorXd& x, Eigen::VectorXd* v, Eigen::MatrixXd* j) {
    if (++calls == 3) throw DataError("catalog entry broken");
    inner(x, v, j);
  };
  EXPECT_THROW(Solve(p, OptionsFor(GetParam())), DataError);
}

TEST_P(EveryAlgorithm, OneDimensional) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE(GetParam());
  if (IsGlobal(GetParam())) DYNOSIZE_SKIP_UNLESS_AVAILABLE(OptionsFor(GetParam()).local_algorithm);
  // From x0 = -2 the global ones must find the global minimum; a local method is only promised
  // a local minimum, and Ipopt/MMA do step over the hump into the right well, so for them either
  // minimizer is correct.
  const SolverResult r = Solve(OneDimensional(-2.0), OptionsFor(GetParam()));
  Record(GetParam(), "1-D", r);
  ASSERT_TRUE(r.is_success()) << r.FullReport();
  const double global = QuarticRoot(-1.3), local = QuarticRoot(1.1);
  if (IsGlobal(GetParam())) {
    EXPECT_NEAR(r.x[0], global, kXAbsTol) << r.FullReport();
  } else {
    EXPECT_LT(std::min(std::abs(r.x[0] - global), std::abs(r.x[0] - local)), kXAbsTol) << r.FullReport();
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, EveryAlgorithm, testing::ValuesIn(AvailableAlgorithms()),
                         [](const testing::TestParamInfo<std::string>& i) { return i.param; });

TEST(GlobalAlgorithms, LeaveTheLocalWellThatTrapsLocalOnes) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("nlopt_slsqp");  // every global run here polishes with it
  // From x0 = 2 a local method stops in the right well (x ~ 1.13); global ones find x ~ -1.30.
  for (const std::string a : {"nlopt_direct", "nlopt_isres", "multistart"}) {
    const SolverResult r = Solve(OneDimensional(2.0), OptionsFor(a));
    ASSERT_TRUE(r.is_success()) << r.FullReport();
    EXPECT_NEAR(r.x[0], QuarticRoot(-1.3), kXAbsTol) << a << "\n" << r.FullReport();
  }
  const SolverResult local = Solve(OneDimensional(2.0), OptionsFor("nlopt_slsqp"));
  EXPECT_NEAR(local.x[0], QuarticRoot(1.1), kXAbsTol);
}

TEST(Solver, UnknownAlgorithmListsEveryValidName) {
  SolverOptions o;
  o.algorithm = "snopt";
  try {
    Solve(Hs071(), o);
    FAIL() << "expected UsageError";
  } catch (const UsageError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'snopt' is unknown"), std::string::npos) << what;
    for (const std::string& name : AvailableAlgorithms()) EXPECT_NE(what.find(name), std::string::npos) << name;
  }
}

// Each backend can be left out of the build (CMake DYNOSIZE_WITH_IPOPT / DYNOSIZE_WITH_NLOPT):
// its algorithms stay known names, IsAlgorithmAvailable says why not, and Solve throws that
// line as UnavailableError (exit code 69) before running anything. In a full build every
// algorithm is available; a build with either option OFF checks the other branch.
TEST(Solver, AlgorithmLeftOutOfTheBuildIsUnavailableErrorNamingTheOption) {
  int unavailable = 0;
  for (const std::string& a : AvailableAlgorithms()) {
    std::string why = "not cleared";
    if (IsAlgorithmAvailable(a, &why)) {
      EXPECT_EQ(why, "") << a;
      continue;
    }
    ++unavailable;
    const bool ipopt = a == "ipopt";
    EXPECT_EQ(why.rfind(ipopt ? "dynosize was not built with Ipopt (-DDYNOSIZE_WITH_IPOPT=OFF)"
                              : "dynosize was not built with NLopt (-DDYNOSIZE_WITH_NLOPT=OFF)", 0), 0u) << why;
    EXPECT_NE(why.find("'" + a + "'"), std::string::npos) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << "one line: " << why;
    try {
      Solve(Hs071(), OptionsFor(a));
      ADD_FAILURE() << a << ": expected UnavailableError";
    } catch (const UnavailableError& e) {
      EXPECT_EQ(static_cast<int>(e.code()), 69);
      // multistart itself is a wrapper: the error names its local algorithm's backend.
      EXPECT_EQ(std::string(e.what()).rfind("dynosize was not built with", 0), 0u) << e.what();
    }
  }
#if !DYNOSIZE_TEST_WITH_IPOPT || !DYNOSIZE_TEST_WITH_NLOPT
  EXPECT_GT(unavailable, 0) << "this build left a backend out, but every algorithm says it is available";
#else
  EXPECT_EQ(unavailable, 0);
#endif
  std::string why;
  EXPECT_FALSE(IsAlgorithmAvailable("snopt", &why));
  EXPECT_NE(why.find("'snopt' is unknown"), std::string::npos) << why;
}

TEST(Solver, UntouchedResultSaysSolveWasNotCalled) {
  SolverResult r;
  EXPECT_EQ(r.BriefReport(), "Solve was not called.");
  EXPECT_EQ(r.message, "Solve was not called.");
  EXPECT_NE(r.FullReport().find("Solve was not called."), std::string::npos);
}

TEST(Solver, OptionsIsValidNamesFieldValueAndRule) {
  SolverOptions o;
  o.relative_tolerance = -1;
  std::string e;
  EXPECT_FALSE(o.IsValid(&e));
  EXPECT_EQ(e, "SolverOptions.relative_tolerance = -1 must be finite and > 0");
  o = SolverOptions();
  o.local_algorithm = "nlopt_isres";
  EXPECT_FALSE(o.IsValid(&e));
  EXPECT_NE(e.find("must be a local algorithm"), std::string::npos) << e;
}

TEST(Solver, InitialPointOutsideBoundsIsUsageErrorNotClamped) {
  Problem p = Hs071();
  p.initial_point[2] = 7.0;
  try {
    Solve(p, SolverOptions());
    FAIL() << "expected UsageError";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("initial x[2] = 7 is not a finite value in [1, 5]"), std::string::npos)
        << e.what();
  }
}

TEST(Solver, ReCheckDowngradesAFalseSuccessAndNamesTheConstraint) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("nlopt_slsqp");
  // A backend that claims success at an infeasible point, emulated with a constraint that lies
  // to the solver: SLSQP always asks for the objective's gradient, while the wrapper's re-check
  // evaluates the objective without one and then the constraints. The constraint reports
  // "satisfied" until that moment and "violated by 0.5" afterwards.
  Problem p = Rosenbrock(true);
  auto rechecking = std::make_shared<bool>(false);
  const ObjectiveFunction f = p.objective;
  p.objective = [f, rechecking](const Eigen::VectorXd& x, Eigen::VectorXd* g) {
    if (g == nullptr) *rechecking = true;
    return f(x, g);
  };
  p.num_inequality_constraints = 1;
  p.inequality_names = {"thermal_limit"};
  p.inequality_constraints = [rechecking](const Eigen::VectorXd&, Eigen::VectorXd* v, Eigen::MatrixXd* j) {
    (*v)[0] = *rechecking ? 0.5 : -1.0;
    if (j) j->setZero();
  };
  const SolverResult r = Solve(p, OptionsFor("nlopt_slsqp"));
  EXPECT_EQ(r.status, SolverStatus::kConstraintViolation) << r.FullReport();
  EXPECT_EQ(r.worst_constraint, "thermal_limit <= 0");
  EXPECT_DOUBLE_EQ(r.constraint_violation, 0.5);
  EXPECT_NE(r.message.find("re-check found thermal_limit <= 0 violated by 0.5"), std::string::npos) << r.message;
}

TEST(Ipopt, PrintsNothingOnStdoutAndIgnoresIpoptOptFile) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("ipopt");
  // Two traps of Ipopt (ecosystem-notes.md): its banner on stdout would corrupt `--json`, and
  // Initialize() would read ./ipopt.opt, letting a stray file override our options. Put an
  // ipopt.opt that would cap Ipopt at 1 iteration into the working directory and check both.
  namespace fs = std::filesystem;
  const fs::path old_cwd = fs::current_path();
  const fs::path dir = fs::temp_directory_path() / ("dynosize_ipopt_opt_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  { std::ofstream(dir / "ipopt.opt") << "max_iter 1\nprint_level 12\n"; }
  fs::current_path(dir);
  testing::internal::CaptureStdout();
  SolverResult r;
  try {
    r = Solve(Hs071(), OptionsFor("ipopt"));
  } catch (...) {
    testing::internal::GetCapturedStdout();
    fs::current_path(old_cwd);
    throw;
  }
  const std::string out = testing::internal::GetCapturedStdout();
  fs::current_path(old_cwd);
  fs::remove_all(dir);
  EXPECT_EQ(out, "");
  EXPECT_TRUE(r.is_success()) << r.FullReport();
  EXPECT_GT(r.iterations, 1) << "ipopt.opt was read";
}

class ReferenceTablePrinter : public testing::Environment {
 public:
  void TearDown() override {
    if (Table().empty()) return;
    std::printf("\nSolver reference problems\n");
    for (const auto& [k, v] : Table()) std::printf("%-42s %s\n", k.c_str(), v.c_str());
  }
};
[[maybe_unused]] testing::Environment* const kReferenceTablePrinter =
    testing::AddGlobalTestEnvironment(new ReferenceTablePrinter);

}  // namespace
}  // namespace dynosize
