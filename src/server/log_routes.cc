#include "server/log_routes.h"

#include <vector>

#include "api/calibrate.h"
#include "api/diagnose.h"
#include "api/log_input.h"
#include "common/error.h"
#include "server/request_body.h"
#include "server/uploads.h"

namespace dynosize::server {

namespace {

const std::vector<std::string> kLogOptionKeys = {"format", "map", "drop_incomplete_rows", "decimal_comma",
                                                 "where", "esc_min_us", "esc_max_us"};

std::vector<std::string> KeysWithLogOptions(std::vector<std::string> keys) {
  keys.insert(keys.end(), kLogOptionKeys.begin(), kLogOptionKeys.end());
  return keys;
}

api::LogInputOptions LogInputOf(const RequestBody& b) {
  api::LogInputOptions in;
  if (const std::string f = b.Text("format"); !f.empty()) in.format = f;
  in.column_map = b.Texts("map");
  in.drop_incomplete_rows = b.Flag("drop_incomplete_rows");
  in.decimal_comma = b.Flag("decimal_comma");
  in.where = b.Texts("where");
  in.esc_min_us = b.Number("esc_min_us").value_or(in.esc_min_us);
  in.esc_max_us = b.Number("esc_max_us").value_or(in.esc_max_us);
  return in;
}

// {"name": ..., "text": ...} or {"name": ..., "base64": ...}.
UploadedLog LogOf(const Json& v, const std::string& what) {
  if (!v.is_object()) throw UsageError(what + ": must be an object {\"name\": ..., \"text\": ...}");
  for (auto it = v.begin(); it != v.end(); ++it) {
    if (it.key() != "name" && it.key() != "text" && it.key() != "base64") {
      throw UsageError(what + ": unknown key '" + it.key() + "' (valid: base64, name, text)");
    }
  }
  const auto name = v.find("name");
  if (name == v.end() || !name->is_string()) throw UsageError(what + ": 'name' (the log's file name) is required");
  UploadedLog log;
  log.name = CheckedLogName(name->get<std::string>(), what + ".name");
  const auto text = v.find("text");
  const auto b64 = v.find("base64");
  if ((text == v.end()) == (b64 == v.end())) throw UsageError(what + ": give one of 'text' and 'base64'");
  const Json& content = text != v.end() ? *text : *b64;
  if (!content.is_string()) throw UsageError(what + ": the log's content must be a string");
  log.bytes = text != v.end() ? content.get<std::string>() : DecodeBase64(content.get<std::string>(), what + ".base64");
  return log;
}

// The document with the upload folder's path removed (the logs named as the user named them);
// an error's message likewise.
template <typename Run>
Json Stripped(const UploadFolder& folder, Run run) {
  try {
    return Json::parse(folder.Strip(run().dump()));
  } catch (const Error& e) {
    throw Error(e.code(), folder.Strip(e.what()));
  }
}

}  // namespace

Json CalibrateRoute(const ApiContext& context, const std::string& body) {
  const RequestBody b(body, "calibrate",
                      KeysWithLogOptions({"logs", "motor_id", "esc_id", "prior_motor", "prior_esc", "loo", "kv_label",
                                          "rm_label", "io_label", "io_label_v", "mass_kg", "max_current_a",
                                          "max_power_w", "esc_max_current_a", "esc_vdc_max_v", "esc_mass_kg",
                                          "prop_id", "prop_diameter_in", "prop_pitch_in"}));
  const Json* logs = b.Find("logs");
  if (!logs || !logs->is_array() || logs->empty()) {
    throw UsageError("calibrate: 'logs' is required: [{\"name\": \"log.csv\", \"text\": \"...\"}, ...]");
  }
  UploadFolder folder;
  api::CalibrateRequest r;
  for (std::size_t i = 0; i < logs->size(); ++i) {
    r.logs.push_back(folder.Write(LogOf((*logs)[i], "calibrate: logs[" + std::to_string(i) + "]")));
  }
  r.motor_id = b.Text("motor_id");
  r.esc_id = b.Text("esc_id");
  r.input = LogInputOf(b);
  r.prior_motor = b.Text("prior_motor");
  r.prior_esc = b.Text("prior_esc");
  r.loo = b.Flag("loo");
  r.kv_label = b.Number("kv_label");
  r.rm_label = b.Number("rm_label");
  r.io_label = b.Number("io_label");
  r.io_label_v = b.Number("io_label_v");
  r.mass_kg = b.Number("mass_kg");
  r.max_current_a = b.Number("max_current_a");
  r.max_power_w = b.Number("max_power_w");
  r.esc_max_current_a = b.Number("esc_max_current_a");
  r.esc_vdc_max_v = b.Number("esc_vdc_max_v");
  r.esc_mass_kg = b.Number("esc_mass_kg");
  r.prop_id = b.Text("prop_id");
  r.prop_diameter_in = b.Number("prop_diameter_in");
  r.prop_pitch_in = b.Number("prop_pitch_in");
  const bool priors = !r.prior_motor.empty() || !r.prior_esc.empty();
  return Stripped(folder, [&] { return api::CalibrateLogs(r, priors ? context.catalog : nullptr); });
}

Json DiagnoseRoute(const ApiContext& context, const std::string& body) {
  const RequestBody b(body, "diagnose", KeysWithLogOptions({"log", "motor", "esc", "folds", "alpha", "kv_label"}));
  const Json* log = b.Find("log");
  if (!log) throw UsageError("diagnose: 'log' is required: {\"name\": \"log.csv\", \"text\": \"...\"}");
  UploadFolder folder;
  api::DiagnoseRequest r;
  r.log = folder.Write(LogOf(*log, "diagnose: log"));
  r.motor_id = b.Text("motor");
  r.esc_id = b.Text("esc");
  r.input = LogInputOf(b);
  const long long folds = b.Integer("folds").value_or(5);
  if (folds < 2 || folds > 1000) throw UsageError("--folds " + std::to_string(folds) + ": must be in [2 - 1000]");
  r.folds = static_cast<int>(folds);
  r.alpha = b.Number("alpha").value_or(r.alpha);
  r.kv_label = b.Number("kv_label");
  api::CheckDiagnoseRequest(r);
  const bool entries = !r.motor_id.empty() || !r.esc_id.empty();
  return Stripped(folder, [&] { return api::DiagnoseLog(r, entries ? context.catalog : nullptr); });
}

}  // namespace dynosize::server
