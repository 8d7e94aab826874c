#include "fit/linear_least_squares.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"

namespace dynosize {

LinearLeastSquaresResult SolveLinearLeastSquares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                                 const LinearLeastSquaresOptions& options) {
  const Eigen::Index m = a.rows();
  const Eigen::Index n = a.cols();
  if (n == 0) throw UsageError("SolveLinearLeastSquares: the matrix A has no columns");
  if (b.size() != m) {
    std::ostringstream os;
    os << "SolveLinearLeastSquares: A has " << m << " rows but b has " << b.size()
       << " entries; they must be equal";
    throw UsageError(os.str());
  }
  if (!a.allFinite() || !b.allFinite()) {
    throw UsageError("SolveLinearLeastSquares: A or b contains NaN or infinity");
  }
  if (!(options.rank_tolerance >= 0.0 && options.rank_tolerance < 1.0)) {
    std::ostringstream os;
    os << "LinearLeastSquaresOptions.rank_tolerance = " << options.rank_tolerance
       << " must be in [0, 1)";
    throw UsageError(os.str());
  }

  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  // Eigen's threshold is relative to the largest pivot, the same rule as documented above.
  qr.setThreshold(options.rank_tolerance);
  const Eigen::Index rank = qr.rank();

  LinearLeastSquaresResult result;
  result.rank = static_cast<int>(rank);
  result.degrees_of_freedom = static_cast<int>(m - rank);

  // Basic solution: solve R11 z = (Q^T b)_1 on the independent columns, zero elsewhere.
  // (Eigen's solve() does the same, but we need Q^T b and R anyway.)
  Eigen::VectorXd qtb = b;
  qtb.applyOnTheLeft(qr.householderQ().transpose());
  const auto r11 = qr.matrixQR().topLeftCorner(rank, rank).triangularView<Eigen::Upper>();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  if (rank > 0) z.head(rank) = r11.solve(qtb.head(rank));
  result.coefficients = qr.colsPermutation() * z;
  result.residuals = b - a * result.coefficients;
  result.residual_sum_of_squares = result.residuals.squaredNorm();

  // Standard errors from R^-1 (row norms), never from (A^T A)^-1.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXd se_permuted = Eigen::VectorXd::Constant(n, nan);
  if (rank > 0 && m > rank) {
    const double s2 = result.residual_sum_of_squares / static_cast<double>(m - rank);
    Eigen::MatrixXd r_inv = r11.solve(Eigen::MatrixXd::Identity(rank, rank));
    se_permuted.head(rank) = (r_inv.rowwise().squaredNorm() * s2).cwiseSqrt();
  }
  result.standard_errors = qr.colsPermutation() * se_permuted;

  if (rank > 0) {
    Eigen::MatrixXd r_dense = qr.matrixQR().topLeftCorner(rank, rank).triangularView<Eigen::Upper>();
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(r_dense);
    const auto& sv = svd.singularValues();
    result.condition_number = sv(0) / sv(rank - 1);
  } else {
    result.condition_number = std::numeric_limits<double>::infinity();
  }
  return result;
}

}  // namespace dynosize
