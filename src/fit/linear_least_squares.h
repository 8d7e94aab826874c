// Linear least squares  min_x ||A x - b||_2  by Householder QR with column pivoting.
//
// Why QR and never the normal equations: forming A^T A squares the condition number, so a
// problem with cond(A) = 1e7 keeps about 16 - 14 = 2 digits through A^T A but about 16 - 7 = 9
// through QR (ecosystem-notes.md: on NIST Longley 7 vs 13 digits). Column pivoting also
// reveals the numerical rank: columns whose pivot |R_kk| falls below the rank tolerance are
// treated as dependent, their coefficients set to 0 (the basic solution) and their standard
// errors to NaN.
//
// With A P = Q R (P a permutation), the coefficient covariance is
//     Cov(x) = s^2 (A^T A)^-1 = s^2 P R^-1 R^-T P^T,   s^2 = ||r||^2 / (m - rank),
// so the standard error of x_P(k) is s times the 2-norm of row k of R^-1, computed from R by
// triangular solves; A^T A is never formed.
#pragma once

#include <Eigen/Core>

namespace dynosize {

struct LinearLeastSquaresOptions {
  // A pivot |R_kk| <= rank_tolerance * |R_00| marks column k (and all later ones) as linearly
  // dependent on earlier columns. The default is a few hundred ulps, the level at which a
  // pivot is indistinguishable from rounding noise in the QR of a well-scaled matrix.
  double rank_tolerance = 1e-13;
};

struct LinearLeastSquaresResult {
  Eigen::VectorXd coefficients;      // x; 0 for columns found dependent
  Eigen::VectorXd standard_errors;   // sqrt(diag(Cov)); NaN for dependent columns or m <= rank
  Eigen::VectorXd residuals;         // b - A x
  double residual_sum_of_squares = 0.0;  // ||b - A x||^2
  int rank = 0;                      // numerical rank found by the pivoted QR
  int degrees_of_freedom = 0;        // m - rank
  // 2-norm condition number of A (of its rank-revealing leading block if rank deficient):
  // sigma_max / sigma_min of R, exact for R (and therefore for A, since Q is orthogonal).
  double condition_number = 0.0;
};

// Throws UsageError when A and b disagree in rows, A has no columns, or an entry is not finite.
LinearLeastSquaresResult SolveLinearLeastSquares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                                 const LinearLeastSquaresOptions& options = {});

}  // namespace dynosize
