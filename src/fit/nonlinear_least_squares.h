// Bounded, robust nonlinear least squares by Levenberg-Marquardt, for calibration (dyno logs ->
// motor parameters).
//
// Problem: with residuals r_i(x), i = 1..m, parameters x in R^n, bounds lo <= x <= hi, an
// optional loss rho and optional Gaussian priors x_j ~ N(mu_j, sigma_j^2), minimize
//
//     cost(x) = 1/2 sum_i rho(r_i(x)^2) + 1/2 sum_j ((x_j - mu_j) / sigma_j)^2
//
// (the 1/2 follows Ceres; NIST's "residual sum of squares" is 2*cost for the trivial loss).
//
// Method (Moré 1978, "The Levenberg-Marquardt algorithm: implementation and theory"; Nielsen
// 1999 for the damping update; Transtrum & Sethna 2012 for geodesic acceleration):
//   - each step solves  min_d ||J d + r||^2 + lambda ||D d||^2  by Householder QR of the
//     augmented matrix [J; sqrt(lambda) D] (never J^T J, which squares the condition number);
//   - D = diag of the largest column norms of J seen so far (Moré scaling), which makes the
//     iteration invariant to the units of the parameters (rpm vs rad/s, mOhm vs Ohm);
//   - optional geodesic acceleration: a second-order correction along the curved path of the
//     model, from one extra residual evaluation; it lets LM follow narrow curved valleys
//     (MGH09, MGH10, Bennett5 from NIST's far start 1);
//   - bounds by projection onto the box; parameters at a bound whose gradient pushes outward
//     are held fixed for the step (an active set), so a fit can converge onto a bound;
//   - robust losses by the Triggs correction (as in Ceres' corrector): residual and Jacobian
//     row i are rescaled so that the Gauss-Newton model of rho matches to second order.
//
// Statistics at the solution (from the final Jacobian J, SVD, never J^T J):
//   - covariance = s^2 (J^T J)^+ with s^2 = 2*cost_data / (m - n_free);
//   - standard errors and the correlation matrix from it;
//   - identifiability: singular values of J with columns scaled to unit norm (so the test does
//     not depend on units); a singular value below identifiability_tolerance times the largest
//     marks a direction of parameter space the data do not determine, reported as a linear
//     combination of named parameters.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "common/dual.h"

namespace dynosize {

// Computes residuals (size m) and, when jacobian is not null, the m x n Jacobian dr/dx. Both
// outputs are pre-sized by the caller. Return false when x is outside the model's domain
// (e.g. a negative resistance makes the model meaningless): the step is then rejected as if
// its cost were infinite. Exceptions propagate to the caller of Solve.
using ResidualFunction =
    std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd* residuals, Eigen::MatrixXd* jacobian)>;

enum class LossType {
  kTrivial,  // rho(s) = s: ordinary least squares
  kHuber,    // rho(s) = s for s <= a^2, 2 a sqrt(s) - a^2 beyond: linear tails
  kSoftL1,   // rho(s) = 2 a^2 (sqrt(1 + s/a^2) - 1): smooth Huber
  kCauchy,   // rho(s) = a^2 log(1 + s/a^2): strongly redescending, for gross outliers
};

// A Gaussian prior x_index ~ N(mean, sigma^2), e.g. a datasheet value with its tolerance.
struct GaussianPrior {
  int index = 0;
  double mean = 0.0;
  double sigma = 1.0;  // > 0, in the parameter's unit
};

struct LeastSquaresProblem {
  int num_residuals = 0;
  int num_parameters = 0;
  ResidualFunction residuals;
  // Names for reports ("rm_ohm"); empty means "x[0]", "x[1]", ...
  std::vector<std::string> parameter_names;
  // Bounds; empty means unbounded. Entries may be +-infinity.
  Eigen::VectorXd lower_bounds;
  Eigen::VectorXd upper_bounds;
  std::vector<GaussianPrior> priors;
};

struct LevenbergMarquardtOptions {
  // Stop (CONVERGENCE) when an accepted step reduces the cost by less than
  // function_tolerance * cost:  (old_cost - new_cost) < function_tolerance * old_cost.
  double function_tolerance = 1e-10;
  // Stop (CONVERGENCE) when the gradient is orthogonal to the residual to within this cosine
  // (Moré's gtol, invariant to the units of x and r):
  //   max_j |g_j| / (||J_j||_2 ||r~||_2) <= gradient_tolerance,   g = J^T r~,
  // over parameters j not held at a bound (a parameter on its bound whose gradient pushes
  // outward counts as 0). r~, J are the loss-corrected residuals/Jacobian incl. prior rows.
  double gradient_tolerance = 1e-12;
  // Stop (CONVERGENCE) when a successful step is tiny relative to x:
  //   ||D dx||_2 <= parameter_tolerance * (||D x||_2 + parameter_tolerance).
  double parameter_tolerance = 1e-10;
  int max_num_iterations = 500;        // LM iterations (successful or not)
  double max_solver_time_in_seconds = 1e6;
  // Initial damping relative to the largest scaled diagonal of J^T J: lambda_0 =
  // initial_damping * max_i (J^T J)_ii / D_i^2 (Nielsen's tau; 1e-3 for a good start, larger if
  // the start is far).
  double initial_damping = 1e-3;
  // Declare NO_CONVERGENCE when lambda exceeds this (the model cannot be decreased further in
  // any direction the damping allows).
  double max_damping = 1e32;
  // Geodesic acceleration (Transtrum & Sethna 2012): costs one extra residual evaluation per
  // iteration; the correction a is accepted only if 2 ||a|| / ||v|| <= geodesic_max_ratio.
  bool use_geodesic_acceleration = true;
  double geodesic_max_ratio = 0.75;
  double geodesic_step = 0.1;  // h in r'' ~ 2/h ((r(x + h v) - r(x))/h - J v)
  // Loss and its scale a (in residual units): residuals beyond a count linearly (Huber, soft-L1)
  // or logarithmically (Cauchy).
  LossType loss = LossType::kTrivial;
  double loss_scale = 1.0;
  // Singular values of the unit-column-scaled Jacobian below this times the largest mark an
  // unidentifiable direction (about sqrt(machine epsilon): such a direction changes the cost by
  // less than rounding).
  double identifiability_tolerance = 1e-8;

  // Names the first violated rule (field, value, rule) in *error.
  bool IsValid(std::string* error) const;
};

enum class TerminationType {
  kConvergence,    // a tolerance test above was met
  kNoConvergence,  // iteration/time limit or damping limit reached first
  kFailure,        // the residuals are not finite / not computable at the initial point
};
const char* TerminationTypeToString(TerminationType type);

// A direction of parameter space that the data cannot determine.
struct UnidentifiableDirection {
  double relative_singular_value = 0.0;  // sigma_k / sigma_max of the unit-column-scaled J
  Eigen::VectorXd direction;             // unit vector in scaled parameter space
  std::string description;               // "0.707*ke_v_s_per_rad - 0.707*kt_nm_per_a"
};

struct LevenbergMarquardtSummary {
  TerminationType termination_type = TerminationType::kFailure;
  std::string message = "Solve was not called.";
  bool solve_called = false;
  int num_iterations = 0;
  int num_successful_steps = 0;
  int num_unsuccessful_steps = 0;
  int num_geodesic_corrections = 0;  // accepted accelerations
  int num_residual_evaluations = 0;
  int num_jacobian_evaluations = 0;
  double initial_cost = std::numeric_limits<double>::quiet_NaN();
  double final_cost = std::numeric_limits<double>::quiet_NaN();
  double total_time_in_seconds = 0.0;

  Eigen::VectorXd parameters;       // the solution (also written back to the caller's x)
  std::vector<std::string> parameter_names;
  std::vector<bool> at_bound;       // parameter sits on a bound (its error bar is one-sided)
  Eigen::VectorXd standard_errors;  // NaN when the problem has no degrees of freedom
  Eigen::MatrixXd covariance;
  Eigen::MatrixXd correlation;
  int jacobian_rank = 0;
  Eigen::VectorXd scaled_singular_values;  // of the unit-column-scaled J, descending
  std::vector<UnidentifiableDirection> unidentifiable;

  bool IsSolutionUsable() const {
    return solve_called && termination_type != TerminationType::kFailure;
  }
  std::string BriefReport() const;  // one line
  std::string FullReport() const;   // a table of parameters, errors, identifiability
};

// Minimizes from *x (size n); on return *x holds the best point found. Throws UsageError when
// the problem or options are malformed (sizes, bounds with lo > hi, x outside the bounds, a
// prior with sigma <= 0, options.IsValid false). Numerical outcomes are in the summary.
LevenbergMarquardtSummary SolveLeastSquares(const LeastSquaresProblem& problem,
                                            const LevenbergMarquardtOptions& options,
                                            Eigen::VectorXd* x);

// Residuals with a Jacobian by forward-mode dual numbers. `f` is a generic callable
//     template <class T> bool f(const T* x, T* residuals)   (or a lambda with auto parameters)
// evaluated with T = double for residuals only and T = Dual<kN> for the Jacobian. kN may be the
// fixed parameter count (fastest) or Eigen::Dynamic.
template <int kN = Eigen::Dynamic, typename Functor>
ResidualFunction AutoDiffResiduals(Functor f, int num_parameters) {
  return [f, num_parameters](const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* jac) {
    if (jac == nullptr) return static_cast<bool>(f(x.data(), r->data()));
    using D = Dual<kN>;
    std::vector<D> xd(num_parameters);
    for (int j = 0; j < num_parameters; ++j) xd[j] = D::Variable(x[j], j, num_parameters);
    std::vector<D> rd(r->size());
    if (!f(static_cast<const D*>(xd.data()), rd.data())) return false;
    for (Eigen::Index i = 0; i < r->size(); ++i) {
      (*r)[i] = rd[i].value;
      if (rd[i].derivative.size() == 0) {
        jac->row(i).setZero();  // a residual that does not depend on x
      } else {
        jac->row(i) = rd[i].derivative.transpose();
      }
    }
    return true;
  };
}

// Residuals with a central-difference Jacobian from a value-only function; each column costs two
// evaluations and the step is relative_step * max(|x_j|, 1). Loses about a third of the digits
// compared with AutoDiffResiduals: use only when the model is a black box.
ResidualFunction NumericDiffResiduals(
    std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd* residuals)> f,
    double relative_step = 6e-6);

}  // namespace dynosize
