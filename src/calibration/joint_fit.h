// Calibrate's joint fit: the bounded Levenberg-Marquardt solve of src/fit with the Gaussian
// priors (labels, motor prior), the saturation knee profiled over a grid and kept by an F test,
// the throttle offset tested the same way, the robust outlier pass, and the standard errors of
// the physical KT and c1. Internal to src/calibration.
#pragma once

#include <string>
#include <vector>

#include "calibration/prepare.h"

namespace dynosize::calibration::internal {

struct SolveOutcome {
  std::array<double, kBaseParamCount> params{};
  LevenbergMarquardtSummary summary;
  double cost = std::numeric_limits<double>::infinity();
  int free_count = 0;
};

// Largest |residual| of each fit row at parameters p.
std::vector<double> RowResidualMax(const Prepared& pr, const Params& p);
// "" when the free ESC slots (excess s, c0) of a solve are determined, else why not.
std::string EscUndetermined(const LevenbergMarquardtSummary& s);
// True when parameter k carries a Gaussian prior in the fit.
bool HasPrior(const CalibrationOptions& o, int k);
// FitWithOffset's note on the offset with fit_throttle_offset off.
inline constexpr const char* kOffsetNotTestedNote = "not tested (fit_throttle_offset off)";

// The fit without the throttle offset that FitWithOffset compares with (its knee profile and
// knee note): what FitWithOffset returns with fit_throttle_offset off.
struct OffsetFreeFit {
  SolveOutcome outcome;
  bool knee_found = false;
  std::string knee_note;
};
// The base fit with its knee profile, and with three or more throttle levels the same with the
// throttle offset / dead band free, kept when it beats "no offset" by the F test. The fit
// without the offset goes to *offset_free when given.
SolveOutcome FitWithOffset(const Prepared& pr, const CalibrationOptions& o, bool* knee_found, std::string* knee_note,
                           bool* offset_found, std::string* offset_note, OffsetFreeFit* offset_free = nullptr);
// Rows whose largest residual exceeds outlier_sigmas robust standard deviations (joint_fit.cc).
std::vector<DroppedRow> SelectOutliers(const Prepared& pr, const Params& p, const logs::SteadyTable& t,
                                       const CalibrationOptions& o, int nfree);
// Standard errors and values of the physical KT and C1 from the internal ratio f and excess s
// (delta method on the covariance).
void TransformStandardErrors(bool tie_kt, const std::vector<int>& slots, const LevenbergMarquardtSummary& s,
                             CalibrationResult* out);

}  // namespace dynosize::calibration::internal
