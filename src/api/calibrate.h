// `calibrate` (fitting motor + ESC entries to logs) as a library call: the request, the fit's
// verdict and entries, and the document that --json prints. The CLI (apps/cmd_calibrate.cc, which
// also writes --out and figures) and the Python module (python/) share them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "api/log_input.h"
#include "calibration/calibrate.h"
#include "catalog/catalog.h"
#include "common/json_file.h"
#include "identification/verdict.h"
#include "logs/steady_table.h"

namespace dynosize::api {

struct CalibrateRequest {
  std::vector<std::string> logs;
  std::string motor_id, esc_id;        // ids of the fitted entries
  LogInputOptions input;
  long long drivecalc_motor = -1;      // drivecalc: one motor id
  std::string prior_motor, prior_esc;  // catalog ids anchoring / filling in the fit
  bool loo = false;                    // also the leave-one-out errors
  std::optional<double> kv_label, rm_label, io_label, io_label_v;
  std::optional<double> mass_kg, max_current_a, max_power_w;
  std::optional<double> esc_max_current_a, esc_vdc_max_v, esc_mass_kg;
  std::string prop_id;                 // also a static propeller entry
  std::optional<double> prop_diameter_in, prop_pitch_in;
};

// The logs read, and the reader's warnings (a missing throttle column) to say first. Throws
// UsageError for a request without logs or ids, and the readers' errors.
struct CalibrationLogs {
  std::vector<logs::SteadyTable> tables;
  std::vector<std::string> reader_warnings;
};
CalibrationLogs ReadCalibrationLogs(const CalibrateRequest& request);

// Throws UsageError for labels or propeller options that break a rule (the CLI's messages).
void CheckCalibrateRequest(const CalibrateRequest& request);

// The fit's options: labels, and the priors' catalog entries (`catalog` may be null when no
// prior is named).
calibration::CalibrationOptions CalibrationOptionsOf(const CalibrateRequest& request, const Catalog* catalog);

// The logs' file names, comma-separated (the entries' dataset).
std::string Datasets(const std::vector<std::string>& logs);

// {"median_abs_percent": x, "points": n} of a list of errors in percent.
Json ErrorsJson(const std::vector<double>& errors_percent);

// "" when every fitted parameter is finite, else the first that is not.
std::string NonFiniteParameter(const calibration::CalibrationResult& r);
// The --json document of a failed fit, and the DataError message (out: the --out file, or "").
Json FailedCalibrationJson(const calibration::CalibrationResult& r, const std::string& bad,
                           const std::vector<std::string>& reader_warnings);
std::string FailedCalibrationMessage(const CalibrateRequest& request, const calibration::CalibrationResult& r,
                                     const std::string& bad, const std::string& out);

// The status contract and the entries of a fit with finite parameters.
struct CalibrationOutcome {
  calibration::CrossValidation cv;
  identification::Verdict verdict;
  Json motor, esc;
  std::vector<Json> props;
  Json loo;  // with request.loo
};
CalibrationOutcome JudgeCalibrationFit(const CalibrateRequest& request, const logs::SteadyTable& table,
                                       const calibration::CalibrationOptions& co,
                                       const calibration::CalibrationResult& r);

// calibrate --json.
Json CalibrationJson(const CalibrateRequest& request, const CalibrationOutcome& out,
                     const calibration::CalibrationResult& r, const std::vector<std::string>& reader_warnings);

// The whole request as calibrate --json runs it (no figures, no files). A fit without finite
// parameters throws DataError (FailedCalibrationMessage).
Json CalibrateLogs(const CalibrateRequest& request, const Catalog* catalog);

}  // namespace dynosize::api
