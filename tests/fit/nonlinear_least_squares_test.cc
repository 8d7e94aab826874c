#include "fit/nonlinear_least_squares.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/error.h"

namespace dynosize {
namespace {

// Synthetic motor-like data: a no-load current curve I(omega) = io + c * omega^2 style is too
// easy; we use an exponential decay y = a * exp(-b t) + c, 30 points, Gaussian noise sigma = 0.01
// from a locally seeded generator (seed 2024).
struct Data {
  Eigen::VectorXd t, y;
};
Data MakeDecay(double a, double b, double c, double sigma, unsigned seed, int m = 30) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  Data d{Eigen::VectorXd(m), Eigen::VectorXd(m)};
  for (int i = 0; i < m; ++i) {
    d.t[i] = 0.1 * i;
    d.y[i] = a * std::exp(-b * d.t[i]) + c + noise(rng);
  }
  return d;
}

LeastSquaresProblem DecayProblem(const Data& d) {
  LeastSquaresProblem p;
  p.num_parameters = 3;
  p.num_residuals = static_cast<int>(d.t.size());
  p.parameter_names = {"a", "b_per_s", "c"};
  p.residuals = AutoDiffResiduals<3>(
      [d](const auto* x, auto* r) {
        using std::exp;
        for (Eigen::Index i = 0; i < d.t.size(); ++i) r[i] = x[0] * exp(-x[1] * d.t[i]) + x[2] - d.y[i];
        return true;
      },
      3);
  return p;
}

// With sigma = 0.01 and 30 points the parameters are determined to about 0.01/sqrt(30) *
// (sensitivity factor ~ 3) ~ 0.006; five standard errors keeps the test from passing by luck
// or failing by chance.
constexpr double kParamTol = 0.03;

TEST(LevenbergMarquardt, FitsNoisyDecayAndReportsErrors) {
  const Data d = MakeDecay(2.0, 1.5, 0.5, 0.01, 2024);
  LeastSquaresProblem p = DecayProblem(d);
  Eigen::VectorXd x(3);
  x << 1.0, 1.0, 0.0;
  const LevenbergMarquardtSummary s = SolveLeastSquares(p, {}, &x);
  EXPECT_EQ(s.termination_type, TerminationType::kConvergence) << s.FullReport();
  EXPECT_NEAR(x[0], 2.0, kParamTol);
  EXPECT_NEAR(x[1], 1.5, kParamTol);
  EXPECT_NEAR(x[2], 0.5, kParamTol);
  // Residual standard deviation recovers the noise level (chi-square with 27 dof: +-30 %).
  EXPECT_NEAR(std::sqrt(2.0 * s.final_cost / 27.0), 0.01, 0.003);
  for (int j = 0; j < 3; ++j) {
    EXPECT_GT(s.standard_errors[j], 0.0);
    EXPECT_LT(s.standard_errors[j], 0.05);
    EXPECT_NEAR(s.correlation(j, j), 1.0, 1e-12);
  }
  EXPECT_EQ(s.jacobian_rank, 3);
  EXPECT_TRUE(s.unidentifiable.empty());
  EXPECT_NE(s.BriefReport().find("CONVERGENCE"), std::string::npos);
  EXPECT_NE(s.FullReport().find("b_per_s"), std::string::npos);
}

TEST(LevenbergMarquardt, NumericDiffAgreesWithAutoDiff) {
  const Data d = MakeDecay(2.0, 1.5, 0.5, 0.01, 7);
  LeastSquaresProblem p = DecayProblem(d);
  p.residuals = NumericDiffResiduals([d](const Eigen::VectorXd& x, Eigen::VectorXd* r) {
    for (Eigen::Index i = 0; i < d.t.size(); ++i) (*r)[i] = x[0] * std::exp(-x[1] * d.t[i]) + x[2] - d.y[i];
    return true;
  });
  Eigen::VectorXd xn(3), xa(3);
  xn << 1.0, 1.0, 0.0;
  xa = xn;
  SolveLeastSquares(p, {}, &xn);
  SolveLeastSquares(DecayProblem(d), {}, &xa);
  // Same minimum; central differences carry ~1e-10 relative Jacobian error, which moves the
  // converged point by far less than 1e-6.
  EXPECT_LT((xn - xa).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(LevenbergMarquardt, ConvergesOntoAnActiveBound) {
  // Unconstrained optimum c ~ 0.5; upper bound c <= 0.3 must end exactly on the bound.
  const Data d = MakeDecay(2.0, 1.5, 0.5, 0.01, 11);
  LeastSquaresProblem p = DecayProblem(d);
  p.lower_bounds = Eigen::Vector3d(-10, 0.0, -10);
  p.upper_bounds = Eigen::Vector3d(10, 10, 0.3);
  Eigen::VectorXd x(3);
  x << 1.0, 1.0, 0.0;
  const LevenbergMarquardtSummary s = SolveLeastSquares(p, {}, &x);
  EXPECT_EQ(s.termination_type, TerminationType::kConvergence) << s.FullReport();
  EXPECT_EQ(x[2], 0.3);  // projection puts it exactly on the bound
  EXPECT_TRUE(s.at_bound[2]);
  EXPECT_TRUE(std::isnan(s.standard_errors[2]));
  EXPECT_NE(s.FullReport().find("(at bound)"), std::string::npos);
}

TEST(LevenbergMarquardt, RobustLossesResistOutliers) {
  Data d = MakeDecay(2.0, 1.5, 0.5, 0.01, 99);
  // Three gross outliers (a glitching current sensor), +5 each.
  d.y[5] += 5.0;
  d.y[12] += 5.0;
  d.y[20] += 5.0;
  for (LossType loss : {LossType::kHuber, LossType::kSoftL1, LossType::kCauchy}) {
    LeastSquaresProblem p = DecayProblem(d);
    LevenbergMarquardtOptions o;
    o.loss = loss;
    o.loss_scale = 0.05;  // 5 sigma: inliers are in the quadratic zone
    Eigen::VectorXd x(3);
    x << 1.0, 1.0, 0.0;
    const LevenbergMarquardtSummary s = SolveLeastSquares(p, o, &x);
    EXPECT_EQ(s.termination_type, TerminationType::kConvergence) << s.FullReport();
    // Outliers of 5 pull plain LS off by ~0.5 in c; a robust fit stays within kParamTol.
    EXPECT_NEAR(x[2], 0.5, kParamTol) << s.FullReport();
    EXPECT_NEAR(x[1], 1.5, 2 * kParamTol) << s.FullReport();
  }
  LeastSquaresProblem p = DecayProblem(d);
  Eigen::VectorXd x(3);
  x << 1.0, 1.0, 0.0;
  SolveLeastSquares(p, {}, &x);
  EXPECT_GT(std::abs(x[2] - 0.5), 0.2) << "the outliers should spoil the plain fit";
}

TEST(LevenbergMarquardt, ReportsUnidentifiableCombination) {
  // y = ka * kb * t: only the product is determined; (ka, kb) -> (ka s, kb / s) is invisible.
  const int m = 20;
  LeastSquaresProblem p;
  p.num_parameters = 2;
  p.num_residuals = m;
  p.parameter_names = {"ka", "kb"};
  p.residuals = AutoDiffResiduals<2>(
      [](const auto* x, auto* r) {
        for (int i = 0; i < m; ++i) r[i] = x[0] * x[1] * (0.1 * i) - 0.6 * (0.1 * i);
        return true;
      },
      2);
  Eigen::VectorXd x(2);
  x << 1.0, 1.0;
  const LevenbergMarquardtSummary s = SolveLeastSquares(p, {}, &x);
  EXPECT_NEAR(x[0] * x[1], 0.6, 1e-9);
  EXPECT_EQ(s.jacobian_rank, 1);
  ASSERT_EQ(s.unidentifiable.size(), 1u);
  EXPECT_NE(s.unidentifiable[0].description.find("ka"), std::string::npos);
  EXPECT_NE(s.unidentifiable[0].description.find("kb"), std::string::npos);
  EXPECT_NE(s.FullReport().find("UNIDENTIFIABLE"), std::string::npos) << s.FullReport();
}

TEST(LevenbergMarquardt, PriorPinsDownAnUnidentifiableParameter) {
  // Same product model plus a datasheet prior kb ~ N(2, 0.01^2): ka -> 0.3.
  const int m = 20;
  LeastSquaresProblem p;
  p.num_parameters = 2;
  p.num_residuals = m;
  p.residuals = AutoDiffResiduals(
      [](const auto* x, auto* r) {
        for (int i = 0; i < m; ++i) r[i] = x[0] * x[1] * (0.1 * i) - 0.6 * (0.1 * i);
        return true;
      },
      2);
  p.priors = {GaussianPrior{1, 2.0, 0.01}};
  Eigen::VectorXd x(2);
  x << 1.0, 1.0;
  const LevenbergMarquardtSummary s = SolveLeastSquares(p, {}, &x);
  EXPECT_NEAR(x[1], 2.0, 1e-6);
  EXPECT_NEAR(x[0], 0.3, 1e-6);
  EXPECT_TRUE(std::isfinite(s.standard_errors[0]));
}

TEST(LevenbergMarquardt, NonFiniteStartIsFailureNotException) {
  LeastSquaresProblem p;
  p.num_parameters = 1;
  p.num_residuals = 1;
  p.residuals = [](const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* j) {
    (*r)[0] = std::log(x[0]);  // NaN for x < 0
    if (j) (*j)(0, 0) = 1.0 / x[0];
    return true;
  };
  Eigen::VectorXd x(1);
  x << -1.0;
  const LevenbergMarquardtSummary s = SolveLeastSquares(p, {}, &x);
  EXPECT_EQ(s.termination_type, TerminationType::kFailure);
  EXPECT_NE(s.message.find("initial point"), std::string::npos);
}

TEST(LevenbergMarquardt, UntouchedSummarySaysSolveWasNotCalled) {
  LevenbergMarquardtSummary s;
  EXPECT_EQ(s.BriefReport(), "Solve was not called.");
  EXPECT_NE(s.FullReport().find("Solve was not called."), std::string::npos);
}

TEST(LevenbergMarquardt, BadInputThrowsWithFieldAndValue) {
  LevenbergMarquardtOptions o;
  o.function_tolerance = -1.0;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("function_tolerance = -1"), std::string::npos) << error;

  const Data d = MakeDecay(2.0, 1.5, 0.5, 0.01, 1);
  LeastSquaresProblem p = DecayProblem(d);
  p.lower_bounds = Eigen::Vector3d(0, 0, 0);
  p.upper_bounds = Eigen::Vector3d(10, 10, 10);
  Eigen::VectorXd x(3);
  x << 1.0, 1.0, -1.0;
  try {
    SolveLeastSquares(p, {}, &x);
    FAIL() << "expected UsageError";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("initial c = -1 is outside its bounds [0, 10]"),
              std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dynosize
