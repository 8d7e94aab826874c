#include "rotor/airfoil_fit.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/units.h"
#include "fit/statistics.h"
#include "fit/nonlinear_least_squares.h"

namespace dynosize {

using fit::Median;
namespace {

constexpr int kFitParameters = 6;
constexpr double kReExpPriorMean = -0.35;
constexpr double kReExpPriorSigma = 0.15;  // cl0, cl_alpha, cl_max, cd0, cd2, re_exp

AirfoilPolar PolarOf(const AirfoilPolar& start, const Eigen::VectorXd& x) {
  AirfoilPolar p = start;
  p.cl0 = x[0];
  p.cl_alpha_per_rad = x[1];
  p.cl_max = x[2];
  p.cd0 = x[3];
  p.cd2 = x[4];
  p.re_exp = x[5];
  return p;
}


// CT0, CP0 of eq B11: the median static coefficients, or the median of all points without a
// static one.
void Scales(const RotorFitCase& c, double* ct0, double* cp0) {
  std::vector<double> ct, cp;
  for (const MeasuredRotorPoint& p : c.points) {
    if (p.j == 0.0) {
      ct.push_back(p.ct);
      cp.push_back(p.cp);
    }
  }
  if (ct.empty()) {
    for (const MeasuredRotorPoint& p : c.points) {
      ct.push_back(std::fabs(p.ct));
      cp.push_back(std::fabs(p.cp));
    }
  }
  *ct0 = std::max(Median(ct), 1e-4);
  *cp0 = std::max(Median(cp), 1e-4);
}

}  // namespace

std::vector<CasePrediction> EvaluateCase(const RotorFitCase& c, const AirfoilPolar& polar,
                                         const BemtOptions& options) {
  const Bemt bemt(c.geometry, polar, options);
  std::vector<CasePrediction> out;
  out.reserve(c.points.size());
  for (const MeasuredRotorPoint& p : c.points) {
    out.push_back({p, bemt.EvaluateAtAdvanceRatio(RpmToRadPerSec(p.rpm), p.j, c.rho_kg_m3)});
  }
  return out;
}

AirfoilFitResult FitAirfoil(const std::vector<RotorFitCase>& cases, const AirfoilPolar& start,
                            const BemtOptions& options) {
  if (cases.empty()) throw UsageError("airfoil fit: no measured propellers");
  std::vector<Bemt> models;
  std::vector<double> ct0(cases.size()), cp0(cases.size()), weight(cases.size());
  int m = 0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    if (cases[k].points.empty()) throw UsageError("airfoil fit: " + cases[k].name + " has no points");
    models.emplace_back(cases[k].geometry, start, options);
    Scales(cases[k], &ct0[k], &cp0[k]);
    weight[k] = 1.0 / std::sqrt(std::sqrt(static_cast<double>(cases[k].points.size())));
    m += 2 * static_cast<int>(cases[k].points.size());
  }
  Eigen::VectorXd lo(kFitParameters), hi(kFitParameters);
  // Physical ranges: thin cambered sections at Re 1e4-1e6 (cl0 up to 1, slope up to 2*pi).
  lo << start.cl_min + 0.05, 2.0, 0.5, 0.002, 0.0, -1.0;
  hi << 1.0, 2.0 * kPi, 2.0, 0.2, 1.0, 0.0;
  auto residuals = [&](const Eigen::VectorXd& x, Eigen::VectorXd* r) {
    // The difference steps of the Jacobian may cross a bound: the polar is read inside them.
    const AirfoilPolar polar = PolarOf(start, x.cwiseMax(lo).cwiseMin(hi));
    if (!CheckAirfoil(polar).empty()) return false;
    int i = 0;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      models[k].set_polar(polar);
      for (const MeasuredRotorPoint& p : cases[k].points) {
        const BemtPoint b = models[k].EvaluateAtAdvanceRatio(RpmToRadPerSec(p.rpm), p.j, cases[k].rho_kg_m3);
        (*r)[i++] = weight[k] * (b.ct - p.ct) / ct0[k];
        (*r)[i++] = weight[k] * (b.cp - p.cp) / cp0[k];
      }
    }
    return true;
  };
  LeastSquaresProblem problem;
  problem.num_residuals = m;
  problem.num_parameters = kFitParameters;
  problem.residuals = NumericDiffResiduals(residuals);
  problem.parameter_names = {"cl0", "cl_alpha_per_rad", "cl_max", "cd0", "cd2", "re_exp"};
  // The drag's Reynolds exponent: a prior between the laminar boundary layer's skin friction
  // (Blasius, Cf ~ Re^-0.5) and the turbulent one's (Re^-0.2) (H. Schlichting, Boundary-Layer
  // Theory, ch. 7 and 21): the propellers' Re span (1e4-2e5) alone barely determines it.
  problem.priors = {{5, kReExpPriorMean, kReExpPriorSigma}};
  problem.lower_bounds = lo;
  problem.upper_bounds = hi;
  Eigen::VectorXd x(kFitParameters);
  x << start.cl0, start.cl_alpha_per_rad, start.cl_max, start.cd0, start.cd2, start.re_exp;
  for (int j = 0; j < kFitParameters; ++j) {
    x[j] = std::clamp(x[j], problem.lower_bounds[j], problem.upper_bounds[j]);
  }
  LevenbergMarquardtOptions lm;
  lm.max_num_iterations = 60;
  lm.function_tolerance = 1e-7;
  lm.parameter_tolerance = 1e-7;
  lm.use_geodesic_acceleration = false;
  const LevenbergMarquardtSummary s = SolveLeastSquares(problem, lm, &x);
  AirfoilFitResult out;
  out.polar = PolarOf(start, x);
  out.converged = s.termination_type == TerminationType::kConvergence;
  out.iterations = s.num_iterations;
  double sum_w2 = 0.0;
  for (std::size_t k = 0; k < cases.size(); ++k) sum_w2 += 2.0 * static_cast<double>(cases[k].points.size()) * weight[k] * weight[k];
  out.rms_relative = std::sqrt(2.0 * s.final_cost / sum_w2);
  out.message = s.BriefReport();
  return out;
}

}  // namespace dynosize
