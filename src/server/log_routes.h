// POST /api/calibrate and POST /api/diagnose of `dynosize serve`: the logs travel in the JSON
// body as {"name": "dyno_log.csv", "text": "..."} (or "base64": "..." for bytes that are not
// UTF-8, a spreadsheet's Latin-1 re-save), are written to a private temporary folder
// (server/uploads.h) and read by the CLI's readers; the answer is calibrate --json or diagnose
// --json of a file of that name (api/calibrate.h CalibrateLogs, api/diagnose.h DiagnoseLog).
//
//   POST /api/calibrate {"logs": [{"name", "text" | "base64"}, ...], "motor_id", "esc_id",
//                        "prior_motor", "prior_esc", "loo", "kv_label", "rm_label", "io_label",
//                        "io_label_v", "mass_kg", "max_current_a", "max_power_w",
//                        "esc_max_current_a", "esc_vdc_max_v", "esc_mass_kg", "prop_id",
//                        "prop_diameter_in", "prop_pitch_in", and the log options below}
//   POST /api/diagnose  {"log": {"name", "text" | "base64"}, "motor", "esc", "folds", "alpha",
//                        "kv_label", and the log options below}
//   log options (the CLI's flags): "format", "map", "drop_incomplete_rows", "decimal_comma",
//                        "where", "esc_min_us", "esc_max_us"
#pragma once

#include <string>

#include "common/json_file.h"
#include "server/api_context.h"

namespace dynosize::server {

Json CalibrateRoute(const ApiContext& context, const std::string& body);
Json DiagnoseRoute(const ApiContext& context, const std::string& body);

}  // namespace dynosize::server
