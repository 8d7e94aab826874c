// The blade-element model against measured propellers (docs/validation.md, "Propellers from their
// geometry"):
//   1. UIUC volumes 1-3 by leaving each family out: the polar (rotor/airfoil_fit.h) fitted on the
//      other families' propellers predicts the left-out family's static CT and CP against rpm and
//      its CT, CP and efficiency against J;
//   2. APC's propellers that UIUC measured, point by point: dynosize's model from APC's own
//      geometry (PE0) with the polar fitted without APC's families, against APC's computed PER3
//      table at the same rpm and airspeed, both against UIUC's measurement.
// Errors: static points |model/measured - 1| of CT and CP; sweep points |eta_model - eta_meas|
// (absolute), only where the measured thrust is > 0. Medians over points. No I/O.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "rotor/airfoil_fit.h"
#include "rotor/per3.h"

namespace dynosize {

struct ErrorSummary {
  int props = 0;
  int static_points = 0;
  int sweep_points = 0;
  double ct_median = 0.0;   // static, relative
  double cp_median = 0.0;   // static, relative
  double eta_median = 0.0;  // sweeps, absolute
  double ct_p90 = 0.0, cp_p90 = 0.0;
};

struct FamilyFold {
  std::string family;
  AirfoilFitResult fit;  // on the other families
  ErrorSummary errors;   // of this family's propellers
};

struct LeaveFamilyOutReport {
  AirfoilFitResult all;           // on every family (the polar dynosize uses)
  ErrorSummary in_sample;         // every family with `all`'s polar
  std::vector<FamilyFold> folds;  // by family name
  ErrorSummary left_out;          // every point predicted by its fold's polar
  std::vector<CasePrediction> left_out_points;  // static and sweep, for the figure
  std::vector<std::string> left_out_family;     // family of each point
};

// Fits on all cases (from `start`), then each fold from the all-cases polar, `threads` folds at
// a time.
LeaveFamilyOutReport LeaveFamilyOut(const std::vector<RotorFitCase>& cases, const AirfoilPolar& start,
                                    int threads);

ErrorSummary Summarize(const std::vector<CasePrediction>& points, int props);

// APC's propellers measured by UIUC.
struct ApcCase {
  RotorFitCase measured;  // UIUC's points
  BladeGeometry apc_geometry;
  Per3Table per3;
};
struct ApcComparison {
  int props = 0, points = 0;       // points where APC's table and the model both have a value
  double model_ct = 0, apc_ct = 0;  // median |x/UIUC - 1| of CT
  double model_cp = 0, apc_cp = 0;  // of CP
  double model_closer_ct = 0;       // share of points where the model's CT is at least as close
  double model_closer_cp = 0;
  std::vector<std::string> rows;    // per propeller: "10x5E | n | model CT | APC CT | model CP | APC CP"
};
ApcComparison CompareWithApc(const std::vector<ApcCase>& cases, const AirfoilPolar& polar);

}  // namespace dynosize
