#include "fit/nonlinear_least_squares.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "common/error.h"
#include "common/numbers.h"
#include "fit/option_check.h"

namespace dynosize {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// rho(s), rho'(s), rho''(s) of the loss at s = r^2.
struct LossValue {
  double rho, rho1, rho2;
};
LossValue EvaluateLoss(LossType type, double a, double s) {
  const double b = a * a;
  switch (type) {
    case LossType::kTrivial:
      return {s, 1.0, 0.0};
    case LossType::kHuber: {
      if (s <= b) return {s, 1.0, 0.0};
      const double r = std::sqrt(s);
      const double rho1 = a / r;
      return {2.0 * a * r - b, rho1, -rho1 / (2.0 * s)};
    }
    case LossType::kSoftL1: {
      const double sum = 1.0 + s / b;
      const double tmp = std::sqrt(sum);
      const double rho1 = 1.0 / tmp;
      return {2.0 * b * (tmp - 1.0), rho1, -rho1 / (2.0 * b * sum)};
    }
    case LossType::kCauchy: {
      const double sum = 1.0 + s / b;
      const double inv = 1.0 / sum;
      return {b * std::log(sum), inv, -inv * inv / b};
    }
  }
  return {s, 1.0, 0.0};
}

std::string ParameterName(const LeastSquaresProblem& p, int j) {
  if (j < static_cast<int>(p.parameter_names.size()) && !p.parameter_names[j].empty()) {
    return p.parameter_names[j];
  }
  return "x[" + std::to_string(j) + "]";
}

// Residuals/Jacobian of the whole objective, after the loss correction, with prior rows below
// the data rows: cost = 1/2 sum rho(r_i^2) + 1/2 sum prior_k^2, and the Gauss-Newton model
// 1/2 ||r~ + J~ d||^2 of it.
class Evaluator {
 public:
  Evaluator(const LeastSquaresProblem& p, const LevenbergMarquardtOptions& o,
            LevenbergMarquardtSummary* s)
      : p_(p), o_(o), s_(s), m_(p.num_residuals), n_(p.num_parameters),
        k_(static_cast<int>(p.priors.size())), r_data_(m_), j_data_(m_, n_) {}

  int rows() const { return m_ + k_; }

  // Returns false (cost = inf) when the model refuses x or produces non-finite numbers.
  bool Evaluate(const Eigen::VectorXd& x, bool want_jacobian, double* cost, Eigen::VectorXd* r,
                Eigen::MatrixXd* jac) {
    ++s_->num_residual_evaluations;
    if (want_jacobian) ++s_->num_jacobian_evaluations;
    r_data_.setZero();
    if (want_jacobian) j_data_.setZero();
    const bool ok = p_.residuals(x, &r_data_, want_jacobian ? &j_data_ : nullptr);
    if (!ok || !r_data_.allFinite() || (want_jacobian && !j_data_.allFinite())) {
      *cost = kInf;
      return false;
    }
    r->resize(rows());
    raw_.resize(rows());
    if (want_jacobian) {
      jac->resize(rows(), n_);
      jac_row_scale_.resize(rows());
    }
    double c = 0.0;
    for (int i = 0; i < m_; ++i) {
      const double ri = r_data_[i];
      const double sq = ri * ri;
      const LossValue l = EvaluateLoss(o_.loss, o_.loss_scale, sq);
      c += l.rho;
      // Triggs correction, as Ceres' Corrector for a 1-dimensional residual.
      const double sqrt_rho1 = std::sqrt(l.rho1);
      double r_scale = sqrt_rho1, j_scale = sqrt_rho1;
      if (sq > 0.0 && l.rho2 > 0.0) {
        const double alpha = 1.0 - std::sqrt(1.0 + 2.0 * sq * l.rho2 / l.rho1);
        r_scale = sqrt_rho1 / (1.0 - alpha);
        j_scale = sqrt_rho1 * (1.0 - alpha);
      }
      (*r)[i] = r_scale * ri;
      raw_[i] = ri;
      if (want_jacobian) {
        jac->row(i) = j_scale * j_data_.row(i);
        jac_row_scale_[i] = j_scale;
      }
    }
    for (int k = 0; k < k_; ++k) {
      const GaussianPrior& pr = p_.priors[k];
      const double z = (x[pr.index] - pr.mean) / pr.sigma;
      c += z * z;
      (*r)[m_ + k] = z;
      raw_[m_ + k] = z;
      if (want_jacobian) {
        jac_row_scale_[m_ + k] = 1.0;
        jac->row(m_ + k).setZero();
        (*jac)(m_ + k, pr.index) = 1.0 / pr.sigma;
      }
    }
    *cost = 0.5 * c;
    if (want_jacobian) raw_at_jacobian_ = raw_;
    return std::isfinite(*cost);
  }

  // Residuals before the loss correction (data rows, then prior rows) of the last evaluation,
  // and of the last evaluation with a Jacobian, with the row scales applied to that Jacobian.
  // Geodesic acceleration differentiates the raw residuals and applies the row scales of the
  // current point: differencing corrected residuals would mix in the change of the loss
  // weights between the two points, which is not curvature of the model.
  const Eigen::VectorXd& raw() const { return raw_; }
  const Eigen::VectorXd& raw_at_jacobian() const { return raw_at_jacobian_; }
  const Eigen::VectorXd& jacobian_row_scale() const { return jac_row_scale_; }

  const Eigen::MatrixXd& data_jacobian() const { return j_data_; }
  const Eigen::VectorXd& data_residuals() const { return r_data_; }

 private:
  const LeastSquaresProblem& p_;
  const LevenbergMarquardtOptions& o_;
  LevenbergMarquardtSummary* s_;
  int m_, n_, k_;
  Eigen::VectorXd r_data_;
  Eigen::MatrixXd j_data_;
  Eigen::VectorXd raw_, raw_at_jacobian_, jac_row_scale_;
};

void ValidateProblem(const LeastSquaresProblem& p, const Eigen::VectorXd& x) {
  std::ostringstream os;
  os << "SolveLeastSquares: ";
  if (p.num_parameters <= 0) {
    os << "num_parameters = " << p.num_parameters << " must be > 0";
  } else if (p.num_residuals <= 0) {
    os << "num_residuals = " << p.num_residuals << " must be > 0";
  } else if (!p.residuals) {
    os << "the residual function is empty";
  } else if (x.size() != p.num_parameters) {
    os << "x has " << x.size() << " entries but num_parameters = " << p.num_parameters;
  } else if (!p.parameter_names.empty() &&
             static_cast<int>(p.parameter_names.size()) != p.num_parameters) {
    os << "parameter_names has " << p.parameter_names.size() << " entries, expected "
       << p.num_parameters;
  } else if (p.lower_bounds.size() != 0 && p.lower_bounds.size() != p.num_parameters) {
    os << "lower_bounds has " << p.lower_bounds.size() << " entries, expected 0 or "
       << p.num_parameters;
  } else if (p.upper_bounds.size() != 0 && p.upper_bounds.size() != p.num_parameters) {
    os << "upper_bounds has " << p.upper_bounds.size() << " entries, expected 0 or "
       << p.num_parameters;
  } else {
    for (int j = 0; j < p.num_parameters; ++j) {
      const double lo = p.lower_bounds.size() ? p.lower_bounds[j] : -kInf;
      const double hi = p.upper_bounds.size() ? p.upper_bounds[j] : kInf;
      if (!std::isfinite(x[j])) {
        os << "initial " << ParameterName(p, j) << " = " << x[j] << " is not finite";
        throw UsageError(os.str());
      }
      if (std::isnan(lo) || std::isnan(hi) || lo > hi) {
        os << "bounds of " << ParameterName(p, j) << " [" << lo << ", " << hi
           << "] are not an interval (need lower <= upper)";
        throw UsageError(os.str());
      }
      if (x[j] < lo || x[j] > hi) {
        os << "initial " << ParameterName(p, j) << " = " << x[j] << " is outside its bounds ["
           << lo << ", " << hi << "]";
        throw UsageError(os.str());
      }
    }
    for (size_t k = 0; k < p.priors.size(); ++k) {
      const GaussianPrior& pr = p.priors[k];
      if (pr.index < 0 || pr.index >= p.num_parameters) {
        os << "priors[" << k << "].index = " << pr.index << " is not in [0, "
           << p.num_parameters << ")";
        throw UsageError(os.str());
      }
      if (!(pr.sigma > 0.0) || !std::isfinite(pr.sigma) || !std::isfinite(pr.mean)) {
        os << "priors[" << k << "] (" << ParameterName(p, pr.index) << "): mean = " << pr.mean
           << ", sigma = " << pr.sigma << "; need a finite mean and 0 < sigma < inf";
        throw UsageError(os.str());
      }
    }
    return;
  }
  throw UsageError(os.str());
}

// min ||A d - b|| for A = [J_F; sqrt(lambda) D_F] by Householder QR of the augmented matrix.
Eigen::VectorXd SolveDampedStep(const Eigen::MatrixXd& jf, const Eigen::VectorXd& df, double lambda,
                                const Eigen::VectorXd& rhs_top) {
  const Eigen::Index rows = jf.rows(), nf = jf.cols();
  Eigen::MatrixXd a(rows + nf, nf);
  a.topRows(rows) = jf;
  a.bottomRows(nf) = (std::sqrt(lambda) * df).asDiagonal();
  Eigen::VectorXd b = Eigen::VectorXd::Zero(rows + nf);
  b.head(rows) = rhs_top;
  return a.householderQr().solve(b);
}

std::string FormatDirection(const Eigen::VectorXd& v, const LeastSquaresProblem& p,
                            const std::vector<int>& cols) {
  std::ostringstream os;
  bool first = true;
  // Components below 5 % are noise from the SVD, not part of the dependency.
  for (Eigen::Index k = 0; k < v.size(); ++k) {
    if (std::abs(v[k]) < 0.05) continue;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", std::abs(v[k]));
    os << (first ? (v[k] < 0 ? "-" : "") : (v[k] < 0 ? " - " : " + ")) << buf << "*"
       << ParameterName(p, cols[k]);
    first = false;
  }
  return os.str();
}

// Active set of SolveLeastSquares: the parameters free to move at x, i.e. all but those on a
// bound whose descent direction -g points out of the box.
std::vector<int> FreeOfActiveSet(const Eigen::VectorXd& x, const Eigen::VectorXd& g, const Eigen::VectorXd& lo,
                                 const Eigen::VectorXd& hi) {
  std::vector<int> free;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const bool blocked = (x[j] <= lo[j] && g[j] > 0.0) || (x[j] >= hi[j] && g[j] < 0.0);
    if (!blocked) free.push_back(static_cast<int>(j));
  }
  return free;
}

// The gradient test of SolveLeastSquares: max over the free parameters j of |g_j| / (||J_j|| ||r||)
// = |cos(J_j, r)| (g = J^T r); 0 where a column or r is zero.
double MaxGradientCosine(const Eigen::MatrixXd& jac, const Eigen::VectorXd& g, double r_norm,
                         const std::vector<int>& free) {
  double cosine = 0.0;
  for (int j : free) {
    const double cn = jac.col(j).norm();
    if (cn > 0.0 && r_norm > 0.0) cosine = std::max(cosine, std::abs(g[j]) / (cn * r_norm));
  }
  return cosine;
}

// Geodesic acceleration of the LM step vf (on the free parameters `free`, scaled by df, damping
// lambda): directional second derivative of r along v by a finite difference of the residuals,
// then the acceleration solves the same damped system with r'' on the right. Adds half the
// acceleration to *step and returns true, or returns false (step untouched) when the path curves
// too much for this damping (the caller shortens). A probe that cannot be evaluated leaves the
// step as it is (true).
bool GeodesicCorrection(const LevenbergMarquardtOptions& options, const Eigen::VectorXd& x,
                        const Eigen::MatrixXd& jac, const Eigen::MatrixXd& jf, const Eigen::VectorXd& df,
                        double lambda, const Eigen::VectorXd& vf, const std::vector<int>& free,
                        Evaluator* eval, Eigen::VectorXd* step, Eigen::VectorXd* r_probe,
                        LevenbergMarquardtSummary* s) {
  const double h = options.geodesic_step;
  Eigen::VectorXd x_probe = x + h * *step;
  double cost_probe;
  Eigen::MatrixXd unused;
  if (!eval->Evaluate(x_probe, false, &cost_probe, r_probe, &unused)) return true;
  const Eigen::VectorXd rpp =
      (2.0 / h) * (eval->jacobian_row_scale().cwiseProduct(eval->raw() - eval->raw_at_jacobian()) / h -
                   jac * *step);
  const Eigen::VectorXd af = SolveDampedStep(jf, df, lambda, -rpp);
  if (2.0 * (df.cwiseProduct(af)).norm() <= options.geodesic_max_ratio * (df.cwiseProduct(vf)).norm()) {
    for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(free.size()); ++k) (*step)[free[k]] += 0.5 * af[k];
    ++s->num_geodesic_corrections;
    return true;
  }
  return false;
}

// Identifiability of the data alone (SolveLeastSquares' statistics): singular values of the
// data Jacobian jd (columns: the parameters cols off their bounds) on unit-norm columns; a
// direction below identifiability_tolerance of the largest is reported as unidentifiable.
void Identifiability(const LeastSquaresProblem& problem, const LevenbergMarquardtOptions& options,
                     const Eigen::MatrixXd& jd, const std::vector<int>& cols, LevenbergMarquardtSummary* s) {
  const int nf = static_cast<int>(cols.size());
  Eigen::VectorXd cn = jd.colwise().norm().transpose();
  Eigen::VectorXd cn_safe = cn.unaryExpr([](double v) { return v > 0.0 ? v : 1.0; });
  Eigen::MatrixXd js = jd * cn_safe.cwiseInverse().asDiagonal();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(js, Eigen::ComputeFullV);
  s->scaled_singular_values = Eigen::VectorXd::Zero(nf);
  s->scaled_singular_values.head(svd.singularValues().size()) = svd.singularValues();
  const double smax = s->scaled_singular_values.size() ? s->scaled_singular_values[0] : 0.0;
  s->jacobian_rank = 0;
  for (int c = 0; c < nf; ++c) {
    const double rel = smax > 0.0 ? s->scaled_singular_values[c] / smax : 0.0;
    if (rel > options.identifiability_tolerance) {
      ++s->jacobian_rank;
    } else {
      UnidentifiableDirection u;
      u.relative_singular_value = rel;
      u.direction = svd.matrixV().col(c);
      u.description = FormatDirection(u.direction, problem, cols);
      s->unidentifiable.push_back(u);
    }
  }
}

// Covariance (J_w^T J_w)^-1 with data rows scaled by 1/s (s^2 estimated from them) and prior
// rows as they are (their sigma is absolute), then standard errors and correlations (into s).
// jw: the Jacobian (m data rows, then prior rows) of the parameters cols off their bounds;
// r: the corrected residuals at the solution (data rows first).
void Covariance(int m, const Eigen::VectorXd& r, Eigen::MatrixXd jw, const std::vector<int>& cols,
                LevenbergMarquardtSummary* s) {
  const int nf = static_cast<int>(cols.size());
  const int dof = m - nf;
  if (dof > 0) {
    // r holds the corrected residuals at x: it is only replaced when a step is accepted.
    const double sigma2 = r.head(m).squaredNorm() / dof;
    if (sigma2 > 0.0) jw.topRows(m) /= std::sqrt(sigma2);
    Eigen::VectorXd wn = jw.colwise().norm().transpose().unaryExpr(
        [](double v) { return v > 0.0 ? v : 1.0; });
    Eigen::JacobiSVD<Eigen::MatrixXd> wsvd(jw * wn.cwiseInverse().asDiagonal(),
                                          Eigen::ComputeThinV);
    Eigen::VectorXd inv_s2(wsvd.singularValues().size());
    for (Eigen::Index c = 0; c < inv_s2.size(); ++c) {
      const double sv = wsvd.singularValues()[c];
      inv_s2[c] = sv > 0.0 ? 1.0 / (sv * sv) : kInf;
    }
    const Eigen::MatrixXd& v = wsvd.matrixV();
    Eigen::MatrixXd cov_s = v * inv_s2.asDiagonal() * v.transpose();
    if (!cov_s.allFinite()) {
      // An exactly singular direction: those parameters have unbounded variance.
      for (Eigen::Index c = 0; c < inv_s2.size(); ++c) {
        if (std::isfinite(inv_s2[c])) continue;
        for (int a = 0; a < nf; ++a)
          if (std::abs(v(a, c)) > 1e-12) cov_s.row(a).setConstant(kInf), cov_s.col(a).setConstant(kInf);
      }
    }
    for (int a = 0; a < nf; ++a) {
      for (int b = 0; b < nf; ++b) {
        s->covariance(cols[a], cols[b]) = cov_s(a, b) / (wn[a] * wn[b]);
      }
    }
    for (int a = 0; a < nf; ++a) s->standard_errors[cols[a]] = std::sqrt(s->covariance(cols[a], cols[a]));
    for (int a = 0; a < nf; ++a) {
      for (int b = 0; b < nf; ++b) {
        const int ia = cols[a], ib = cols[b];
        s->correlation(ia, ib) = s->covariance(ia, ib) / (s->standard_errors[ia] * s->standard_errors[ib]);
      }
    }
  }
}

// Statistics at the solution x of SolveLeastSquares: which parameters sit on a bound, the
// identifiability of the others, their covariance, standard errors and correlations.
void StatisticsAtSolution(const LeastSquaresProblem& problem, const LevenbergMarquardtOptions& options,
                          const Eigen::VectorXd& x, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                          const Eigen::VectorXd& r, const Eigen::MatrixXd& jac, LevenbergMarquardtSummary* s) {
  const int n = problem.num_parameters;
  const int m = problem.num_residuals;
  std::vector<int> cols;
  s->at_bound.assign(n, false);
  for (int j = 0; j < n; ++j) {
    s->at_bound[j] = (x[j] <= lo[j] || x[j] >= hi[j]);
    if (!s->at_bound[j]) cols.push_back(j);
  }
  const int nf = static_cast<int>(cols.size());
  s->standard_errors = Eigen::VectorXd::Constant(n, kNaN);
  s->covariance = Eigen::MatrixXd::Constant(n, n, kNaN);
  s->correlation = Eigen::MatrixXd::Constant(n, n, kNaN);
  if (nf > 0) {
    const int k = static_cast<int>(problem.priors.size());
    Eigen::MatrixXd jd(m, nf), jw(m + k, nf);
    for (int c = 0; c < nf; ++c) {
      jd.col(c) = jac.col(cols[c]).head(m);
      jw.col(c) = jac.col(cols[c]);
    }
    Identifiability(problem, options, jd, cols, s);
    Covariance(m, r, std::move(jw), cols, s);
  }
}

}  // namespace

const char* TerminationTypeToString(TerminationType type) {
  switch (type) {
    case TerminationType::kConvergence: return "CONVERGENCE";
    case TerminationType::kNoConvergence: return "NO_CONVERGENCE";
    case TerminationType::kFailure: return "FAILURE";
  }
  return "UNKNOWN";
}

bool LevenbergMarquardtOptions::IsValid(std::string* error) const {
  const fit::OptionCheck check("LevenbergMarquardtOptions", error);
  auto fail = [&check](const char* field, double value, const char* rule) { return check.Fail(field, value, rule); };
  if (!(function_tolerance >= 0.0)) return fail("function_tolerance", function_tolerance, "must be >= 0");
  if (!(gradient_tolerance >= 0.0)) return fail("gradient_tolerance", gradient_tolerance, "must be >= 0");
  if (!(parameter_tolerance >= 0.0)) return fail("parameter_tolerance", parameter_tolerance, "must be >= 0");
  if (max_num_iterations < 0) return fail("max_num_iterations", max_num_iterations, "must be >= 0");
  if (!(max_solver_time_in_seconds > 0.0)) return fail("max_solver_time_in_seconds", max_solver_time_in_seconds, "must be > 0");
  if (!(initial_damping > 0.0) || !std::isfinite(initial_damping)) return fail("initial_damping", initial_damping, "must be finite and > 0");
  if (!(max_damping > initial_damping)) return fail("max_damping", max_damping, "must be > initial_damping");
  if (!(geodesic_max_ratio > 0.0)) return fail("geodesic_max_ratio", geodesic_max_ratio, "must be > 0");
  if (!(geodesic_step > 0.0 && geodesic_step <= 1.0)) return fail("geodesic_step", geodesic_step, "must be in (0, 1]");
  if (!(loss_scale > 0.0) || !std::isfinite(loss_scale)) return fail("loss_scale", loss_scale, "must be finite and > 0");
  if (!(identifiability_tolerance > 0.0 && identifiability_tolerance < 1.0)) return fail("identifiability_tolerance", identifiability_tolerance, "must be in (0, 1)");
  return true;
}

LevenbergMarquardtSummary SolveLeastSquares(const LeastSquaresProblem& problem,
                                            const LevenbergMarquardtOptions& options,
                                            Eigen::VectorXd* x_inout) {
  if (x_inout == nullptr) throw UsageError("SolveLeastSquares: x is null");
  std::string why;
  if (!options.IsValid(&why)) throw UsageError(why);
  ValidateProblem(problem, *x_inout);

  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };

  LevenbergMarquardtSummary s;
  s.solve_called = true;
  const int n = problem.num_parameters;
  for (int j = 0; j < n; ++j) s.parameter_names.push_back(ParameterName(problem, j));
  const Eigen::VectorXd lo =
      problem.lower_bounds.size() ? problem.lower_bounds : Eigen::VectorXd::Constant(n, -kInf);
  const Eigen::VectorXd hi =
      problem.upper_bounds.size() ? problem.upper_bounds : Eigen::VectorXd::Constant(n, kInf);

  Evaluator eval(problem, options, &s);
  Eigen::VectorXd x = *x_inout;
  Eigen::VectorXd r, r_new, r_probe;
  Eigen::MatrixXd jac;
  double cost = kInf;
  if (!eval.Evaluate(x, true, &cost, &r, &jac)) {
    s.termination_type = TerminationType::kFailure;
    s.message = "the residuals or Jacobian are not finite (or the model refused) at the initial point";
    s.parameters = x;
    s.total_time_in_seconds = elapsed();
    return s;
  }
  s.initial_cost = cost;

  // Moré scaling: D_j = running max of column norms (1 for a column that has been all zero).
  Eigen::VectorXd d = jac.colwise().norm().transpose();
  for (int j = 0; j < n; ++j) if (!(d[j] > 0.0)) d[j] = 1.0;
  double lambda = options.initial_damping;  // in D-scaled units (D_j^2 = (J^T J)_jj at start)
  double nu = 2.0;
  s.termination_type = TerminationType::kNoConvergence;
  s.message = "maximum number of iterations reached";

  for (;;) {
    if (s.num_iterations >= options.max_num_iterations) break;
    if (elapsed() > options.max_solver_time_in_seconds) {
      s.message = "maximum solver time reached";
      break;
    }
    const Eigen::VectorXd g = jac.transpose() * r;
    const std::vector<int> free = FreeOfActiveSet(x, g, lo, hi);
    const double r_norm = r.norm();
    const double cosine = MaxGradientCosine(jac, g, r_norm, free);
    if (r_norm == 0.0 || cosine <= options.gradient_tolerance) {
      s.termination_type = TerminationType::kConvergence;
      std::ostringstream os;
      os << "gradient tolerance reached: max cosine(J_j, r) = " << cosine
         << " <= " << options.gradient_tolerance;
      s.message = os.str();
      break;
    }
    ++s.num_iterations;

    const Eigen::Index nf = static_cast<Eigen::Index>(free.size());
    Eigen::MatrixXd jf(jac.rows(), nf);
    Eigen::VectorXd df(nf);
    for (Eigen::Index k = 0; k < nf; ++k) {
      jf.col(k) = jac.col(free[k]);
      df[k] = d[free[k]];
    }
    const Eigen::VectorXd vf = SolveDampedStep(jf, df, lambda, -r);
    Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
    for (Eigen::Index k = 0; k < nf; ++k) step[free[k]] = vf[k];

    // Parameter test on the proposed (LM) step, before spending an evaluation on it.
    const double dx_norm = (d.cwiseProduct(step)).norm();
    const double x_norm = (d.cwiseProduct(x)).norm();
    if (dx_norm <= options.parameter_tolerance * (x_norm + options.parameter_tolerance)) {
      s.termination_type = TerminationType::kConvergence;
      std::ostringstream os;
      os << "parameter tolerance reached: ||D dx|| = " << dx_norm << " <= "
         << options.parameter_tolerance << " * (||D x|| + tol)";
      s.message = os.str();
      break;
    }

    const bool geodesic_rejected =
        options.use_geodesic_acceleration &&
        !GeodesicCorrection(options, x, jac, jf, df, lambda, vf, free, &eval, &step, &r_probe, &s);

    double new_cost = kInf;
    Eigen::VectorXd x_new = x;
    bool accepted = false;
    double rho = -1.0;
    if (!geodesic_rejected) {
      x_new = (x + step).cwiseMax(lo).cwiseMin(hi);
      const Eigen::VectorXd dx = x_new - x;
      Eigen::MatrixXd unused;
      const bool ok = eval.Evaluate(x_new, false, &new_cost, &r_new, &unused);
      const double actual = cost - new_cost;
      const double predicted = 0.5 * r.squaredNorm() - 0.5 * (r + jac * dx).squaredNorm();
      if (ok && actual > 0.0) {
        rho = predicted > 0.0 ? actual / predicted : 0.5;
        accepted = rho > 1e-4;
      }
    }

    if (accepted) {
      ++s.num_successful_steps;
      const double old_cost = cost;
      Eigen::VectorXd x_old = x;
      x = x_new;
      if (!eval.Evaluate(x, true, &cost, &r, &jac)) {
        // The residuals were finite at x a moment ago; a Jacobian that is not is a model bug
        // we cannot step around.
        s.termination_type = TerminationType::kFailure;
        s.message = "the Jacobian is not finite at an accepted point";
        break;
      }
      d = d.cwiseMax(jac.colwise().norm().transpose());
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      nu = 2.0;
      if (old_cost - cost < options.function_tolerance * old_cost) {
        s.termination_type = TerminationType::kConvergence;
        std::ostringstream os;
        os << "function tolerance reached: |cost change|/cost = " << (old_cost - cost) / old_cost
           << " < " << options.function_tolerance;
        s.message = os.str();
        break;
      }
    } else {
      ++s.num_unsuccessful_steps;
      lambda *= nu;
      nu *= 2.0;
      if (lambda > options.max_damping) {
        s.message = "damping exceeded max_damping: no step reduces the cost";
        break;
      }
    }
  }

  s.final_cost = cost;
  s.parameters = x;
  *x_inout = x;

  StatisticsAtSolution(problem, options, x, lo, hi, r, jac, &s);
  s.total_time_in_seconds = elapsed();
  return s;
}

std::string LevenbergMarquardtSummary::BriefReport() const {
  if (!solve_called) return "Solve was not called.";
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "Levenberg-Marquardt: %s, iterations %d, cost %.6e -> %.6e, rank %d/%d, %.3g s",
                TerminationTypeToString(termination_type), num_iterations, initial_cost,
                final_cost, jacobian_rank, static_cast<int>(parameters.size()),
                total_time_in_seconds);
  return buf;
}

std::string LevenbergMarquardtSummary::FullReport() const {
  if (!solve_called) return "Solve was not called.\n";
  std::ostringstream os;
  char buf[512];
  os << "Levenberg-Marquardt summary\n";
  std::snprintf(buf, sizeof buf, "  %-28s %s\n", "termination", TerminationTypeToString(termination_type));
  os << buf << "  message                      " << message << "\n";
  std::snprintf(buf, sizeof buf,
                "  %-28s %d (%d successful, %d unsuccessful, %d geodesic)\n"
                "  %-28s %d residual, %d Jacobian\n"
                "  %-28s %.10e\n  %-28s %.10e\n  %-28s %.3g\n",
                "iterations", num_iterations, num_successful_steps, num_unsuccessful_steps,
                num_geodesic_corrections, "evaluations", num_residual_evaluations,
                num_jacobian_evaluations, "initial cost", initial_cost, "final cost", final_cost,
                "time [s]", total_time_in_seconds);
  os << buf;
  std::snprintf(buf, sizeof buf, "  %-24s %20s %14s  %s\n", "parameter", "value", "std. error", "");
  os << buf;
  for (Eigen::Index j = 0; j < parameters.size(); ++j) {
    const bool b = j < static_cast<Eigen::Index>(at_bound.size()) && at_bound[j];
    std::snprintf(buf, sizeof buf, "  %-24s %20.12g %14.6g  %s\n", parameter_names[j].c_str(),
                  parameters[j], standard_errors.size() ? standard_errors[j] : kNaN,
                  b ? "(at bound)" : "");
    os << buf;
  }
  // Correlations near +-1 flag pairs the data barely separate (e.g. KT and Io from torque
  // data at a single current), before they become outright unidentifiable.
  if (correlation.rows() == parameters.size() && parameters.size() > 1) {
    os << "  correlation\n";
    for (Eigen::Index a = 0; a < correlation.rows(); ++a) {
      std::snprintf(buf, sizeof buf, "  %-24s", parameter_names[a].c_str());
      os << buf;
      for (Eigen::Index b = 0; b <= a; ++b) {
        std::snprintf(buf, sizeof buf, " %7.3f", correlation(a, b));
        os << buf;
      }
      os << "\n";
    }
  }
  os << "  Jacobian rank (unit-scaled columns): " << jacobian_rank << "\n";
  if (unidentifiable.empty()) {
    os << "  all free parameters are identifiable from the data\n";
  } else {
    for (const auto& u : unidentifiable) {
      std::snprintf(buf, sizeof buf, "  UNIDENTIFIABLE (sigma/sigma_max = %.2e): ", u.relative_singular_value);
      os << buf << u.description << " (in units of each parameter's sensitivity)\n";
    }
  }
  return os.str();
}

ResidualFunction NumericDiffResiduals(
    std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd* residuals)> f,
    double relative_step) {
  return [f, relative_step](const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* jac) {
    if (!f(x, r)) return false;
    if (jac == nullptr) return true;
    Eigen::VectorXd xp = x, rp(r->size()), rm(r->size());
    for (Eigen::Index j = 0; j < x.size(); ++j) {
      const double h = relative_step * std::max(std::abs(x[j]), 1.0);
      xp[j] = x[j] + h;
      if (!f(xp, &rp)) return false;
      xp[j] = x[j] - h;
      if (!f(xp, &rm)) return false;
      xp[j] = x[j];
      jac->col(j) = (rp - rm) / (2.0 * h);
    }
    return true;
  };
}

}  // namespace dynosize
