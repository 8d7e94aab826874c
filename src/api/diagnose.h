// `diagnose` as a library call: the options of a request (checked, catalog entries looked up) and
// the document that --json prints; the CLI (apps/cmd_diagnose.cc) and the Python module (python/)
// share them.
#pragma once

#include <optional>
#include <string>

#include "api/log_input.h"
#include "catalog/catalog.h"
#include "common/json_file.h"
#include "diagnosis/diagnose.h"

namespace dynosize::api {

struct DiagnoseRequest {
  std::string log;
  std::string motor_id, esc_id;  // catalog entries to start from (optional)
  LogInputOptions input;
  int folds = 5;
  double alpha = 1e-3;
  std::optional<double> kv_label;  // the motor's label Kv, rpm/V
};

// Throws UsageError for a label Kv that is not > 0 (the CLI's message).
void CheckDiagnoseRequest(const DiagnoseRequest& request);

// The diagnosis options of the request; `catalog` (may be null when no entry is named) gives the
// --motor/--esc entries. Throws UsageError naming the rule (diagnosis::DiagnoseOptions::IsValid).
diagnosis::DiagnoseOptions DiagnoseOptionsOf(const DiagnoseRequest& request, const Catalog* catalog);

// Catalog-style values (SI, catalog keys) of a motor's and an ESC's model.
Json MotorValuesJson(const MotorParams& m);
Json EscValuesJson(const EscParams& e);

// diagnose --json: the verdict, baseline, findings, ambiguous, extended_model, ...; no_throttle
// is api::MissingThrottleLine of the log (first of the warnings when not empty).
Json DiagnoseJson(const diagnosis::DiagnoseResult& r, const std::string& no_throttle);

// The whole request as diagnose --json runs it (without figures or files): read the log,
// diagnose, the document.
Json DiagnoseLog(const DiagnoseRequest& request, const Catalog* catalog);

}  // namespace dynosize::api
