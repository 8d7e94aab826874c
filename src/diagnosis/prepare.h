// The stages of `diagnose` before any candidate is scored: the log's rows and residual terms,
// the first-order model (what is free, starting values, scales, bounds), the cross-validation
// folds, the effective-variance weights and the outlier screen. Internal to src/diagnosis.
#pragma once

#include <cstddef>
#include <vector>

#include "calibration/calibrate.h"
#include "diagnosis/diagnosis_types.h"
#include "diagnosis/model_fit.h"

namespace dynosize::diagnosis::internal {

// Calibrate's fits of the log with diagnose's options (throttle map, speed and throttle floors, Kv
// label, ESC prior), from one run of calibrate (calibration::Calibrate with without_offset).
struct CalibrationFits {
  bool ok = false;         // calibrate ran and accepted the table
  bool has_entry = false;  // `entry` was fitted (DiagnoseOptions::calibration_entry)
  calibration::CalibrationOptions entry_options;  // calibrate's options with the throttle offset tested
  calibration::CalibrationResult base;   // without the throttle offset (a candidate here): the starts
  calibration::CalibrationResult entry;  // with the throttle offset tested: the entry (stage 11)
};
// None without calibrate's fits to use (a catalog motor is given: its values start the fit and
// the entry is diagnose's own).
CalibrationFits CalibrateForDiagnosis(const logs::SteadyTable& t, const DiagnoseOptions& o);
// Stage 1: what the log offers, and the rows and terms of the fit.
Prepared PrepareDiagnosisData(const logs::SteadyTable& t, const DiagnoseOptions& o, DiagnoseResult* res);
// Stage 2: the base (first-order) model: what is free, held values, starts, scales and bounds.
Model BuildBaseModel(const logs::SteadyTable& t, const DiagnoseOptions& o, const Prepared& p,
                     const CalibrationFits& cal, DiagnoseResult* res);
// Stage 4: cross-validation folds, seeded.
Folds AssignFolds(std::size_t n, const DiagnoseOptions& o);
// Stage 5: effective-variance weights (prepare.cc).
void ApplyEffectiveVarianceWeights(const std::vector<std::size_t>& used, const Model& base, Prepared* p);
// Stage 6: outlier screen with the union model (the base model plus every testable candidate).
// Returns the rows used by every later fit and score; fills res's outlier lists and row_used.
std::vector<std::size_t> ScreenWithUnionModel(const logs::SteadyTable& t, const DiagnoseOptions& o, const Data& d,
                                              const Model& base, const std::vector<Cause>& candidates,
                                              const std::vector<double>& knees, std::vector<std::size_t> used,
                                              DiagnoseResult* res);

}  // namespace dynosize::diagnosis::internal
