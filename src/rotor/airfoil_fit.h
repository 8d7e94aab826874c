// The blade sections' polar fitted on measured propellers (docs/model.md section 13, eq B11).
//
// A blade-element model is only as good as its sections' lift and drag; the propellers of UIUC's
// database are measured with their geometry but not their airfoils. So one polar (rotor/airfoil.h)
// is fitted to many measured propellers at once, by Levenberg-Marquardt (fit/nonlinear_least_squares.h):
//   (B11) minimize  sum over propellers p, points i of  w_p * ((CT_model - CT_meas)/CT0_p)^2
//                                                    + w_p * ((CP_model - CP_meas)/CP0_p)^2
// CT0_p, CP0_p: the propeller's median static coefficients (so that every point of one propeller
// counts in the same relative unit, and a J sweep's points near zero thrust neither vanish nor
// blow up); w_p = 1/sqrt(points of p) (the weight of a squared residual), so a propeller with
// many points weighs more, but less than
// in proportion. The fitted parameters are cl0, cl_alpha, cl_max, cd0, cd2 and re_exp; cl_min,
// cl_cd0 and re_ref stay at the start polar's values.
// Leaving a family out (the validation of docs/validation.md) is FitAirfoil on the other families'
// cases and EvaluateCase on the left-out ones. No I/O.
#pragma once

#include <string>
#include <vector>

#include "rotor/airfoil.h"
#include "rotor/bemt.h"

namespace dynosize {

struct MeasuredRotorPoint {
  double rpm = 0.0;
  double j = 0.0;   // advance ratio; 0 static
  double ct = 0.0;
  double cp = 0.0;
  double eta = 0.0;  // measured efficiency J*CT/CP (0 static)
};

struct RotorFitCase {
  std::string name;     // e.g. "uiuc_v1_apce_10.0x5.0_2"
  std::string family;   // e.g. "apce"
  BladeGeometry geometry;
  std::vector<MeasuredRotorPoint> points;
  double rho_kg_m3 = 1.225;
};

struct AirfoilFitResult {
  AirfoilPolar polar;
  bool converged = false;
  int iterations = 0;
  double rms_relative = 0.0;  // sqrt(mean of the squared relative residuals of B11)
  std::string message;        // the solver's one-line report
};

// Fits the polar to the cases (at least 1, each with >= 1 point), from `start`.
AirfoilFitResult FitAirfoil(const std::vector<RotorFitCase>& cases, const AirfoilPolar& start,
                            const BemtOptions& options = {});

// The model at every point of one case.
struct CasePrediction {
  MeasuredRotorPoint measured;
  BemtPoint model;
};
std::vector<CasePrediction> EvaluateCase(const RotorFitCase& c, const AirfoilPolar& polar,
                                         const BemtOptions& options = {});

}  // namespace dynosize
