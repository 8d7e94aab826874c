#include "api/calibrate.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "calibration/catalog_output.h"
#include "calibration/prop_static.h"
#include "common/error.h"
#include "common/units.h"
#include "fit/statistics.h"
#include "logs/log_reader.h"

namespace dynosize::api {

using fit::MedianAbs;

namespace {

std::string BaseName(const std::string& p) { return std::filesystem::path(p).filename().string(); }



// {"median_abs_percent": x, "points": n}

// The reader's warnings (a missing throttle column) ahead of the fit's.
std::vector<std::string> WithReaderWarnings(std::vector<std::string> reader, const std::vector<std::string>& fit) {
  reader.insert(reader.end(), fit.begin(), fit.end());
  return reader;
}

void CheckPropOptions(const CalibrateRequest& o) {
  if (o.prop_id.empty()) {
    if (o.prop_diameter_in || o.prop_pitch_in) throw UsageError("calibrate: --prop-diameter-in/--prop-pitch-in need --prop-id");
    return;
  }
  if (!o.prop_diameter_in || !(*o.prop_diameter_in > 0.0)) {
    throw UsageError("calibrate: --prop-id needs --prop-diameter-in > 0 (inch)");
  }
  if (o.prop_pitch_in && !(*o.prop_pitch_in > 0.0)) throw UsageError("calibrate: --prop-pitch-in must be > 0 (inch)");
}

// The static propeller entry of --prop-id (calibration/prop_static.h).
Json PropEntry(const CalibrateRequest& o, const logs::SteadyTable& table, const calibration::EntryProvenance& prov) {
  calibration::PropStaticOptions po;
  po.diameter_m = InchToMeter(*o.prop_diameter_in);
  if (o.prop_pitch_in) po.pitch_m = InchToMeter(*o.prop_pitch_in);
  const calibration::PropStaticTable pt = calibration::FitPropStatic(table, po);
  return calibration::PropEntryJson(o.prop_id, o.prop_id + " (measured)", pt, po, prov);
}

}  // namespace

std::string Datasets(const std::vector<std::string>& logs) {
  std::string s;
  for (const auto& l : logs) s += (s.empty() ? "" : ", ") + BaseName(l);
  return s;
}

Json ErrorsJson(const std::vector<double>& e) {
  return {{"median_abs_percent", NumberOrNull(MedianAbs(e))}, {"points", e.size()}};
}

// Numerical guard, independent of the solver's own claim: every reported parameter finite.
// Returns "" or the first non-finite parameter.
std::string NonFiniteParameter(const calibration::CalibrationResult& r) {
  for (int k = 0; k < calibration::kBaseParamCount; ++k) {
    if (!std::isfinite(r.params[k].value)) return calibration::ParamName(static_cast<calibration::Param>(k));
  }
  if (!std::isfinite(r.r_total_ohm)) return "r_total_ohm";
  return "";
}

CalibrationLogs ReadCalibrationLogs(const CalibrateRequest& o) {
  if (o.logs.empty()) throw UsageError("calibrate: give at least one LOG file");
  if (o.motor_id.empty() || o.esc_id.empty()) {
    throw UsageError("calibrate: --motor-id and --esc-id are required (ids of the fitted entries)");
  }
  logs::LogReadOptions ro = ToLogReadOptions(o.input);
  ro.drivecalc_motor_id = o.drivecalc_motor;
  ro.drivecalc_keep_no_load_without_speed = true;
  if (std::string why; !ro.IsValid(&why)) throw UsageError(why);
  CalibrationLogs in;
  for (const auto& l : o.logs) in.tables.push_back(logs::ReadLog(l, ro));
  // A log without a throttle column says so first, before any fit advice.
  for (const auto& t : in.tables) {
    if (std::string w = MissingThrottleLine(t); !w.empty()) in.reader_warnings.push_back(std::move(w));
  }
  return in;
}

namespace {

identification::LabelPriors LabelsOf(const CalibrateRequest& o) {
  identification::LabelPriors labels;
  labels.kv_rpm_per_v = o.kv_label;
  labels.rm_ohm = o.rm_label;
  labels.io_a = o.io_label;
  labels.io_v = o.io_label_v;
  return labels;
}

}  // namespace

void CheckCalibrateRequest(const CalibrateRequest& o) {
  if (std::string e; !LabelsOf(o).IsValid(&e)) throw UsageError("calibrate: " + e);
  CheckPropOptions(o);
}

calibration::CalibrationOptions CalibrationOptionsOf(const CalibrateRequest& o, const Catalog* cat) {
  CheckCalibrateRequest(o);
  calibration::CalibrationOptions co;
  co.labels = LabelsOf(o);
  if (cat != nullptr) {
    if (!o.prior_motor.empty()) co.motor_prior = cat->motor(o.prior_motor).params;
    if (!o.prior_esc.empty()) co.esc_prior = cat->esc(o.prior_esc).params;
  }
  return co;
}

Json FailedCalibrationJson(const calibration::CalibrationResult& r, const std::string& bad,
                           const std::vector<std::string>& reader_warnings) {
  Json j;
  j["status"] = "failed";
  j["motor"] = nullptr;
  j["esc"] = nullptr;
  j["fit"] = {{"mode", r.mode}, {"converged", false}, {"message", r.message},
              {"points_used", r.points_used}, {"non_finite_parameter", bad}};
  j["warnings"] = WithReaderWarnings(reader_warnings, r.warnings);
  return j;
}

std::string FailedCalibrationMessage(const CalibrateRequest& o, const calibration::CalibrationResult& r,
                                     const std::string& bad, const std::string& out) {
  return Datasets(o.logs) + ": the fit failed (" + bad + " is not a finite number; solver: " + r.message +
         "): no parameters reported" + (out.empty() ? std::string() : ", " + out + " not changed");
}

CalibrationOutcome JudgeCalibrationFit(const CalibrateRequest& o, const logs::SteadyTable& table,
                                       const calibration::CalibrationOptions& co,
                                       const calibration::CalibrationResult& r) {
  CalibrationOutcome out;
  // The status contract: checks over the fit, the label and the held-out (cross-validated) error.
  out.cv = calibration::CrossValidateForVerdict(table, co);
  out.verdict = calibration::JudgeCalibration(r, table, co, &out.cv);
  calibration::EntryProvenance prov;
  prov.dataset = Datasets(o.logs);
  std::ostringstream ref;
  ref << "dynosize calibrate (" << r.mode << "), " << r.points_used << " points, status "
      << identification::StatusName(out.verdict.status);
  prov.reference = ref.str();
  out.motor = calibration::MotorEntryJson(o.motor_id, o.motor_id + " (fitted)", r, prov);
  out.esc = calibration::EscEntryJson(o.esc_id, o.esc_id + " (fitted)", r, prov);
  calibration::AddRatings(&out.motor, {o.mass_kg, o.max_current_a, o.max_power_w, o.kv_label, std::nullopt});
  calibration::AddRatings(&out.esc, {o.esc_mass_kg, o.esc_max_current_a, std::nullopt, std::nullopt, o.esc_vdc_max_v});
  if (!o.prop_id.empty()) out.props.push_back(PropEntry(o, table, prov));
  if (o.loo) {
    const auto lcv = calibration::LeaveOneOut(table, co, true);
    out.loo["by"] = table.Has(logs::Column::kThrottle) ? "throttle level" : "row";
    out.loo["folds"] = lcv.folds;
    out.loo["failed_folds"] = lcv.failed_folds;
    out.loo["idc"] = ErrorsJson(lcv.idc_error_percent);
    out.loo["omega_at_torque"] = ErrorsJson(lcv.omega_error_percent);
    out.loo["omega_from_idc"] = ErrorsJson(lcv.omega_from_idc_error_percent);
  }
  return out;
}

Json CalibrationJson(const CalibrateRequest& o, const CalibrationOutcome& out,
                     const calibration::CalibrationResult& r, const std::vector<std::string>& reader_warnings) {
  const calibration::CrossValidation& cv = out.cv;
  Json j = calibration::VerdictJson(out.verdict);
  j["motor"] = out.motor;
  j["esc"] = out.esc;
  if (!out.props.empty()) j["prop"] = out.props[0];
  j["stderr"] = calibration::StandardErrorsJson(r);
  j["identifiable"] = calibration::IdentifiableJson(r);
  j["fit"] = calibration::FitJson(r);
  j["io_source"] = r.io_source;
  j["warnings"] = WithReaderWarnings(reader_warnings, r.warnings);
  j["held_out"] = {{"leave_one_out", cv.leave_one_out},
                   {"folds", cv.folds},
                   {"failed_folds", cv.failed_folds},
                   {"idc", ErrorsJson(cv.idc_error_percent)},
                   {"omega_at_torque", ErrorsJson(cv.omega_error_percent)},
                   {"omega_from_idc", ErrorsJson(cv.omega_from_idc_error_percent)},
                   {"dc_baseline", {{"idc", ErrorsJson(cv.dc_idc_error_percent)},
                                    {"omega_at_torque", ErrorsJson(cv.dc_omega_error_percent)},
                                    {"omega_from_idc", ErrorsJson(cv.dc_omega_from_idc_error_percent)},
                                    {"failed_folds", cv.dc_failed_folds},
                                    {"why", cv.dc_why.empty() ? Json(nullptr) : Json(cv.dc_why)}}}};
  Json dropped = Json::array();
  for (const auto& d : r.dropped_rows) dropped.push_back({{"line", d.source_line}, {"reason", d.reason}});
  j["dropped_rows"] = dropped;
  if (o.loo) j["leave_one_out"] = out.loo;
  return j;
}

Json CalibrateLogs(const CalibrateRequest& o, const Catalog* catalog) {
  const CalibrationLogs in = ReadCalibrationLogs(o);
  const logs::SteadyTable table = calibration::MergeLogs(in.tables);
  const calibration::CalibrationOptions co = CalibrationOptionsOf(o, catalog);
  const calibration::CalibrationResult r = calibration::Calibrate(table, co);
  if (const std::string bad = NonFiniteParameter(r); !bad.empty()) {
    throw DataError(FailedCalibrationMessage(o, r, bad, ""));
  }
  return CalibrationJson(o, JudgeCalibrationFit(o, table, co, r), r, in.reader_warnings);
}

}  // namespace dynosize::api
