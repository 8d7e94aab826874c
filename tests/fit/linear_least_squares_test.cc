#include "fit/linear_least_squares.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "common/error.h"
#include "fit/nist_strd.h"

namespace dynosize {
namespace {

// Polynomial y = 1 + x + ... + x^degree at x = 0, 1, ..., 20: NIST's Wampler1 construction
// (degree 5), extended to degree 8. Every y is an integer below 2^53, so the data are exact and
// the certified coefficients are exactly 1: any error is the solver's.
void Wampler(int degree, Eigen::MatrixXd* a, Eigen::VectorXd* y) {
  const int m = 21;
  a->resize(m, degree + 1);
  y->resize(m);
  for (int i = 0; i < m; ++i) {
    double p = 1.0, s = 0.0;
    for (int k = 0; k <= degree; ++k) {
      (*a)(i, k) = p;
      s += p;
      p *= i;
    }
    (*y)[i] = s;
  }
}

double MinLre(const Eigen::VectorXd& x) {
  double lre = 15.0;
  for (Eigen::Index k = 0; k < x.size(); ++k) lre = std::min(lre, LogRelativeError(x[k], 1.0));
  return lre;
}

// What the normal equations give, for comparison only: the method we refuse to use.
Eigen::VectorXd NormalEquations(const Eigen::MatrixXd& a, const Eigen::VectorXd& y) {
  return (a.transpose() * a).ldlt().solve(a.transpose() * y);
}

TEST(LinearLeastSquares, QrKeepsFarMoreDigitsThanNormalEquationsOnWampler) {
  struct Row { int degree; double min_qr_lre; };
  // Expected digits: about 16 - log10(cond). Wampler1 (degree 5) has cond 6.4e6 -> ~9 digits
  // by QR, ~3 fewer by A^T A; degree 8 has cond 1.3e11 -> ~5 digits by QR, none by A^T A.
  // Floors are 1 digit below what we measured on x86-64 (8.9 and 5.2) to allow other libm/BLAS.
  const Row rows[] = {{5, 7.9}, {8, 4.2}};
  std::printf("\n%-10s %12s %10s %10s\n", "degree", "cond(A)", "LRE QR", "LRE A^TA");
  for (const Row& row : rows) {
    Eigen::MatrixXd a;
    Eigen::VectorXd y;
    Wampler(row.degree, &a, &y);
    const LinearLeastSquaresResult r = SolveLinearLeastSquares(a, y);
    const double qr_lre = MinLre(r.coefficients);
    const double ne_lre = MinLre(NormalEquations(a, y));
    std::printf("%-10d %12.3g %10.1f %10.1f\n", row.degree, r.condition_number, qr_lre, ne_lre);
    EXPECT_EQ(r.rank, row.degree + 1);
    EXPECT_GE(qr_lre, row.min_qr_lre);
    // "Many more digits": at least 2 more than the normal equations.
    EXPECT_GE(qr_lre - ne_lre, 2.0) << "degree " << row.degree;
    // Exact data and a backward-stable method: residuals are rounding noise, about
    // eps * ||A|| * ||x||; 1e-10 of max |y| (2.6e10 for degree 8) leaves a margin of 1e4.
    EXPECT_LT(r.residuals.cwiseAbs().maxCoeff(), 1e-10 * y.cwiseAbs().maxCoeff());
  }
}

TEST(LinearLeastSquares, StandardErrorsMatchTextbookStraightLine) {
  // y = 2 + 3 x + noise; closed-form slope/intercept standard errors of simple regression.
  std::mt19937 rng(12345);  // seed recorded: deterministic
  std::normal_distribution<double> noise(0.0, 0.1);
  const int m = 50;
  Eigen::MatrixXd a(m, 2);
  Eigen::VectorXd y(m);
  for (int i = 0; i < m; ++i) {
    const double x = 0.1 * i;
    a(i, 0) = 1.0;
    a(i, 1) = x;
    y[i] = 2.0 + 3.0 * x + noise(rng);
  }
  const LinearLeastSquaresResult r = SolveLinearLeastSquares(a, y);
  const Eigen::VectorXd xs = a.col(1);
  const double xbar = xs.mean();
  const double sxx = (xs.array() - xbar).square().sum();
  const double s2 = r.residual_sum_of_squares / (m - 2);
  const double se_slope = std::sqrt(s2 / sxx);
  const double se_icpt = std::sqrt(s2 * (1.0 / m + xbar * xbar / sxx));
  // Both are rounding-level computations of the same quantity: 1e-10 relative.
  constexpr double kRel = 1e-10;
  EXPECT_NEAR(r.standard_errors[1], se_slope, kRel * se_slope);
  EXPECT_NEAR(r.standard_errors[0], se_icpt, kRel * se_icpt);
  EXPECT_EQ(r.degrees_of_freedom, m - 2);
}

TEST(LinearLeastSquares, DetectsRankDeficiency) {
  // Column 2 = column 0 + column 1: only two independent columns.
  Eigen::MatrixXd a(6, 3);
  Eigen::VectorXd y(6);
  for (int i = 0; i < 6; ++i) {
    a(i, 0) = 1.0;
    a(i, 1) = i;
    a(i, 2) = 1.0 + i;
    y[i] = 0.5 + 2.0 * i;
  }
  const LinearLeastSquaresResult r = SolveLinearLeastSquares(a, y);
  EXPECT_EQ(r.rank, 2);
  // Still an exact fit (rounding-level residuals), and exactly one coefficient (the column
  // the pivoting put last) has no standard error.
  EXPECT_LT(r.residuals.norm(), 1e-12);
  int nan_count = 0;
  for (int k = 0; k < 3; ++k) nan_count += std::isnan(r.standard_errors[k]);
  EXPECT_EQ(nan_count, 1);
  EXPECT_GT(r.condition_number, 1.0);
}

TEST(LinearLeastSquares, RejectsMismatchedSizesWithDetail) {
  Eigen::MatrixXd a(3, 2);
  a.setOnes();
  Eigen::VectorXd y(4);
  y.setOnes();
  try {
    SolveLinearLeastSquares(a, y);
    FAIL() << "expected UsageError";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("A has 3 rows but b has 4 entries"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace dynosize
