// A nonlinear program, described once and handed to any backend in solvers/solver.h:
//
//     minimize    f(x)                    x in R^n
//     subject to  lower <= x <= upper     (entries may be +-infinity)
//                 g(x) <= 0               (num_inequality_constraints rows)
//                 h(x)  = 0               (num_equality_constraints rows)
//
// Gradients and Jacobians are exact: written by hand or obtained from the dual numbers of
// common/dual.h through AutoDiffObjective / AutoDiffConstraints below. Dense storage: the
// problems of dynosize (sizing, calibration with constraints) have fewer than 100 variables.
//
// No solver header is included here or in solver.h (pagmo2/Drake style): Ipopt and NLopt live
// behind solvers/*.cc only.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "common/dual.h"

namespace dynosize {

// Returns f(x); when gradient is not null (pre-sized to n) also writes df/dx into it.
// May throw: the exception is carried through the solver and rethrown by Solve().
using ObjectiveFunction = std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd* gradient)>;

// Writes the constraint values (pre-sized to m) and, when jacobian is not null (pre-sized to
// m x n), the Jacobian d values / dx.
using ConstraintFunction =
    std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd* values, Eigen::MatrixXd* jacobian)>;

struct Problem {
  std::string name;  // for reports, e.g. "HS071"
  int num_variables = 0;
  Eigen::VectorXd initial_point;  // size n, inside the bounds
  Eigen::VectorXd lower_bounds;   // size n, or empty for "all -infinity"
  Eigen::VectorXd upper_bounds;   // size n, or empty for "all +infinity"
  ObjectiveFunction objective;

  int num_inequality_constraints = 0;
  ConstraintFunction inequality_constraints;  // g(x) <= 0
  int num_equality_constraints = 0;
  ConstraintFunction equality_constraints;    // h(x) = 0

  // Names for reports; each may be empty (then "x[i]", "g[j]", "h[k]").
  std::vector<std::string> variable_names;
  std::vector<std::string> inequality_names;
  std::vector<std::string> equality_names;

  // Throws UsageError naming the field, the value and the rule when the description is
  // inconsistent (sizes, lower > upper, NaN, initial point outside the bounds, missing function).
  void CheckValid() const;

  std::string VariableName(int i) const;
  std::string InequalityName(int j) const;
  std::string EqualityName(int k) const;
  double Lower(int i) const;  // -inf when lower_bounds is empty
  double Upper(int i) const;
};

// f from a generic callable `T f(const T* x)` evaluated with T = double (value only) and
// T = Dual<kN> (value and gradient).
template <int kN = Eigen::Dynamic, typename Functor>
ObjectiveFunction AutoDiffObjective(Functor f, int num_variables) {
  return [f, num_variables](const Eigen::VectorXd& x, Eigen::VectorXd* gradient) -> double {
    if (gradient == nullptr) return static_cast<double>(f(x.data()));
    using D = Dual<kN>;
    std::vector<D> xd(num_variables);
    for (int i = 0; i < num_variables; ++i) xd[i] = D::Variable(x[i], i, num_variables);
    const D y = f(static_cast<const D*>(xd.data()));
    if (y.derivative.size() == 0) {
      gradient->setZero();
    } else {
      *gradient = y.derivative;
    }
    return y.value;
  };
}

// Constraints from a generic callable `void f(const T* x, T* values)`.
template <int kN = Eigen::Dynamic, typename Functor>
ConstraintFunction AutoDiffConstraints(Functor f, int num_variables, int num_constraints) {
  return [f, num_variables, num_constraints](const Eigen::VectorXd& x, Eigen::VectorXd* values,
                                             Eigen::MatrixXd* jacobian) {
    if (jacobian == nullptr) {
      f(x.data(), values->data());
      return;
    }
    using D = Dual<kN>;
    std::vector<D> xd(num_variables), yd(num_constraints);
    for (int i = 0; i < num_variables; ++i) xd[i] = D::Variable(x[i], i, num_variables);
    f(static_cast<const D*>(xd.data()), yd.data());
    for (int j = 0; j < num_constraints; ++j) {
      (*values)[j] = yd[j].value;
      if (yd[j].derivative.size() == 0) {
        jacobian->row(j).setZero();
      } else {
        jacobian->row(j) = yd[j].derivative.transpose();
      }
    }
  };
}

}  // namespace dynosize
