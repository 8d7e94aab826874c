// `dynosize calibrate`: fit motor + ESC catalog entries to dynamometer / thrust-stand logs
// (src/calibration), or refit every DriveCalc motor from MData.csv (--drivecalc-all).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "calibration/catalog_output.h"
#include "calibration/drivecalc_refit.h"
#include "calibration/prop_static.h"
#include "common/units.h"
#include "fit/statistics.h"
#include "identification/verdict.h"
#include "catalog/catalog.h"
#include "commands.h"
#include "log_input.h"
#include "common/error.h"
#include "common/json_file.h"
#include "common/text_file.h"
#include "logs/log_reader.h"
#include "report/calibration_figures.h"

namespace dynosize::cli {

namespace {

using calibration::CalibrationOptions;
using calibration::CalibrationResult;

std::string BaseName(const std::string& p) { return std::filesystem::path(p).filename().string(); }

std::string Datasets(const std::vector<std::string>& logs) {
  std::string s;
  for (const auto& l : logs) s += (s.empty() ? "" : ", ") + BaseName(l);
  return s;
}

using fit::Median;
using fit::MedianAbs;


// A percentage for the text report: "-" when there is none (never "nan").
std::string PercentText(double v) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::setprecision(3) << v;
  return s.str();
}

// Numerical guard, independent of the solver's own claim: every reported parameter finite.
// Returns "" or the first non-finite parameter.
std::string NonFiniteParameter(const CalibrationResult& r) {
  for (int k = 0; k < calibration::kParamCount; ++k) {
    if (!std::isfinite(r.params[k].value)) return calibration::ParamName(static_cast<calibration::Param>(k));
  }
  if (!std::isfinite(r.r_total_ohm)) return "r_total_ohm";
  return "";
}

// {"median_abs_percent": x, "points": n}
Json ErrJson(const std::vector<double>& e) {
  return {{"median_abs_percent", NumberOrNull(MedianAbs(e))}, {"points", e.size()}};
}

// One line: the held-out median |error| of the fitted model and of the plain DC model fitted on
// the same training rows (identification/dc_fit.h), the baseline to beat.
std::string HeldOutBesideDc(const calibration::CrossValidation& cv, bool label) {
  auto med = [](const std::vector<double>& e) {
    const double m = MedianAbs(e);
    std::ostringstream o;
    o << std::fixed << std::setprecision(2) << m << " %";
    return std::isfinite(m) ? o.str() : std::string("-");
  };
  const bool torque = !cv.omega_error_percent.empty();
  std::string s = "held out (" + std::to_string(cv.folds) + " folds), dynosize / plain DC model (" +
                  (label ? "label Kv; R, Io" : "Kv, R, Io") + " fitted on the same rows): ";
  if (torque) {
    s += "DC current " + med(cv.idc_error_percent) + " / " + med(cv.dc_idc_error_percent) + ", speed at the torque " +
         med(cv.omega_error_percent) + " / " + med(cv.dc_omega_error_percent);
  } else {
    s += "speed from the current " + med(cv.omega_from_idc_error_percent) + " / " + med(cv.dc_omega_from_idc_error_percent);
  }
  return s;
}

// The reader's warnings (a missing throttle column) ahead of the fit's.
std::vector<std::string> WithReaderWarnings(std::vector<std::string> reader, const std::vector<std::string>& fit) {
  reader.insert(reader.end(), fit.begin(), fit.end());
  return reader;
}

void CheckPropOptions(const CalibrateOptions& o) {
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
Json PropEntry(const CalibrateOptions& o, const logs::SteadyTable& table, const calibration::EntryProvenance& prov) {
  calibration::PropStaticOptions po;
  po.diameter_m = InchToMeter(*o.prop_diameter_in);
  if (o.prop_pitch_in) po.pitch_m = InchToMeter(*o.prop_pitch_in);
  const calibration::PropStaticTable pt = calibration::FitPropStatic(table, po);
  return calibration::PropEntryJson(o.prop_id, o.prop_id + " (measured)", pt, po, prov);
}

int RunDriveCalcAll(const CalibrateOptions& o) {
  if (o.logs.size() != 1) throw UsageError("--drivecalc-all takes one log: DriveCalc's MData.csv");
  logs::LogReadOptions ro;
  ro.format = logs::LogFormat::kDriveCalc;
  ro.drivecalc_keep_no_load_without_speed = true;  // their no-load current still fixes Io
  const logs::SteadyTable t = logs::ReadLog(o.logs[0], ro);
  const calibration::DriveCalcRefit all = calibration::RefitDriveCalc(t);
  // Names from the imported DriveCalc catalog (dc_m_<id>) when it is there.
  std::optional<Catalog> cat;
  try {
    cat = Catalog::Load(o.catalog);
  } catch (const Error&) {
  }
  std::vector<Json> motors;
  std::map<std::string, std::size_t> held_back;  // motors not written, by failed check
  std::vector<double> rmse_idc, rmse_w;
  for (const auto& f : all.fits) {
    const auto& r = f.result;
    const std::string base = "dc_m_" + std::to_string(f.motor_id);
    std::string name = "DriveCalc motor " + std::to_string(f.motor_id);
    if (cat) {
      for (const auto& m : cat->motors()) {
        if (m.id == base) name = m.name;
      }
    }
    calibration::EntryProvenance p;
    p.dataset = "DriveCalc MData";
    std::ostringstream ref;
    ref << "MData.csv motor_id " << f.motor_id << ": " << f.loaded_points << " loaded + " << f.no_load_points
        << " no-load points, dynosize calibrate --drivecalc-all";
    p.reference = ref.str();
    p.note = "full-throttle points with an ideal ESC assumed: rm_ohm is the whole series resistance of "
             "DriveCalc's set-up (motor + ESC + wiring) in the rms circuit of eq (48), R = 0.749*R_dc; "
             "io_a = Io_dc/1.1095";
    // The status contract without the (costly, per-motor) held-out check: only an "ok" motor is
    // written; the others are counted by their first failed check.
    const identification::Verdict v = calibration::JudgeCalibration(r, t, calibration::CalibrationOptions(), nullptr);
    if (v.status != identification::Status::kOk) {
      const identification::Check* c = v.FirstFailed();
      ++held_back[c != nullptr ? c->name : identification::StatusName(v.status)];
    } else {
      Json e = calibration::MotorEntryJson(base + "_fit", name + " (refit)", r, p);
      motors.push_back(e);
    }
    for (const auto& c : r.fit) {
      if (c.column == logs::Column::kIdcA) rmse_idc.push_back(c.rmse_percent);
      if (c.column == logs::Column::kOmegaRadS) rmse_w.push_back(c.rmse_percent);
    }
  }
  Json loo;
  if (o.loo) {
    const auto e = calibration::DriveCalcLeaveOneOut(t, all);
    loo["model"] = {{"idc_loaded", ErrJson(e.model_idc_loaded)}, {"omega_from_idc", ErrJson(e.model_omega)}};
    loo["baseline_u_n_kv_r_i"] = {{"idc_loaded", ErrJson(e.baseline_idc_loaded)},
                                  {"omega_from_idc", ErrJson(e.baseline_omega)}};
  }
  const std::string out = o.out.empty() ? o.catalog.base + "/drivecalc_fitted.json" : o.out;
  const std::string comment =
      "Generated by 'dynosize calibrate --drivecalc-all shared/data/drivecalc/MData.csv': DriveCalc motors "
      "(drivecalc.de database, user-contributed, redistribution terms unclear) refitted from their own "
      "measurement points (MData), every motor with >= 1 no-load point with rpm and >= 3 loaded points. "
      "Each point is taken at full throttle with an ideal ESC (calibration/calibrate.h, no-throttle mode): "
      "ke from U = R_dc*I + n/Kv, rm_ohm = the whole series resistance (motor + ESC + wiring) in the rms "
      "circuit, io_a from the no-load points. Do not edit by hand.";
  if (std::filesystem::exists(out) && o.force) {
    // A regeneration replaces the generated file as a whole.
    const FileLock lock(out);
    Json doc;
    doc["comment"] = comment;
    doc["motors"] = motors;
    Catalog check;
    std::vector<std::string> problems;
    check.AddDocument(doc, out, &problems);
    if (!problems.empty()) throw DataError(out + ": generated entries do not load: " + problems[0]);
    WriteFileAtomic(out, DumpJson(doc));
  } else {
    calibration::WriteCatalogEntries(out, motors, {}, o.force, comment);
  }
  if (o.json) {
    Json j;
    j["out"] = out;
    j["motors_seen"] = all.motors_seen;
    j["motors_fitted"] = all.fits.size();
    j["motors_written"] = motors.size();
    Json hb = Json::object();
    for (const auto& [k, n] : held_back) hb[k] = n;
    j["motors_not_ok"] = hb;
    j["motors_too_few_points"] = all.motors_too_few_points;
    j["failures"] = all.failures;
    j["median_idc_rmse_percent"] = rmse_idc.empty() ? Json(nullptr) : Json(Median(rmse_idc));
    j["median_omega_rmse_percent"] = rmse_w.empty() ? Json(nullptr) : Json(Median(rmse_w));
    if (o.loo) j["leave_one_out"] = loo;
    std::cout << DumpJson(j);
  } else {
    std::cout << "refitted " << all.fits.size() << " of " << all.motors_seen << " DriveCalc motors ("
              << all.motors_too_few_points << " with too few points, " << all.failures.size()
              << " failed); " << motors.size() << " with status ok written -> " << out << "\n"
              << "median rmse: idc " << PercentText(Median(rmse_idc)) << " %, no-load speed "
              << PercentText(Median(rmse_w)) << " %\n";
    if (o.loo) std::cout << "leave-one-out: " << loo.dump() << "\n";
  }
  return 0;
}

}  // namespace

int RunCalibrate(const CalibrateOptions& o) {
  if (o.logs.empty()) throw UsageError("calibrate: give at least one LOG file");
  if (o.drivecalc_all) return RunDriveCalcAll(o);
  if (o.motor_id.empty() || o.esc_id.empty()) {
    throw UsageError("calibrate: --motor-id and --esc-id are required (ids of the fitted entries)");
  }
  logs::LogReadOptions ro = ToLogReadOptions(o.input);
  ro.drivecalc_motor_id = o.drivecalc_motor;
  ro.drivecalc_keep_no_load_without_speed = true;
  if (const std::string e = ro.Validate(); !e.empty()) throw UsageError(e);
  std::vector<logs::SteadyTable> tables;
  for (const auto& l : o.logs) tables.push_back(logs::ReadLog(l, ro));
  // A log without a throttle column says so first, before any fit advice.
  std::vector<std::string> reader_warnings;
  for (const auto& t : tables) {
    if (std::string w = MissingThrottleLine(t); !w.empty()) reader_warnings.push_back(std::move(w));
  }
  if (!o.json) {
    for (const auto& w : reader_warnings) std::cerr << w << "\n";
  }
  const logs::SteadyTable table = calibration::MergeLogs(tables);
  CalibrationOptions co;
  co.labels.kv_rpm_per_v = o.kv_label;
  co.labels.rm_ohm = o.rm_label;
  co.labels.io_a = o.io_label;
  co.labels.io_v = o.io_label_v;
  if (const std::string e = co.labels.Validate(); !e.empty()) throw UsageError("calibrate: " + e);
  CheckPropOptions(o);
  if (!o.prior_motor.empty() || !o.prior_esc.empty()) {
    const Catalog cat = Catalog::Load(o.catalog);
    if (!o.prior_motor.empty()) co.motor_prior = cat.motor(o.prior_motor).params;
    if (!o.prior_esc.empty()) co.esc_prior = cat.esc(o.prior_esc).params;
  }
  const CalibrationResult r = calibration::Calibrate(table, co);
  // What was read (rows dropped and why), once the fit has run: a refusal stays one line.
  if (!o.json) {
    for (const auto& t : tables) std::cerr << t.BriefReport() << "\n";
  }
  if (const std::string bad = NonFiniteParameter(r); !bad.empty()) {
    // The fit failed: its status and message, no numbers; --out is not touched.
    if (o.json) {
      Json j;
      j["status"] = "failed";
      j["motor"] = nullptr;
      j["esc"] = nullptr;
      j["fit"] = {{"mode", r.mode}, {"converged", false}, {"message", r.message},
                  {"points_used", r.points_used}, {"non_finite_parameter", bad}};
      j["warnings"] = WithReaderWarnings(reader_warnings, r.warnings);
      std::cout << DumpJson(j);
    } else {
      std::cout << "calibrate (" << r.mode << "): FAILED: " << r.message << "\n";
    }
    throw DataError(Datasets(o.logs) + ": the fit failed (" + bad + " is not a finite number; solver: " +
                    r.message + "): no parameters reported" +
                    (o.out.empty() ? std::string() : ", " + o.out + " not changed"));
  }
  // The status contract: checks over the fit, the label and the held-out (cross-validated) error.
  const calibration::CrossValidation cv = calibration::CrossValidateForVerdict(table, co);
  const identification::Verdict verdict = calibration::JudgeCalibration(r, table, co, &cv);

  calibration::EntryProvenance prov;
  prov.dataset = Datasets(o.logs);
  std::ostringstream ref;
  ref << "dynosize calibrate (" << r.mode << "), " << r.points_used << " points, status "
      << identification::StatusName(verdict.status);
  prov.reference = ref.str();
  Json motor = calibration::MotorEntryJson(o.motor_id, o.motor_id + " (fitted)", r, prov);
  Json esc = calibration::EscEntryJson(o.esc_id, o.esc_id + " (fitted)", r, prov);
  calibration::AddRatings(&motor, {o.mass_kg, o.max_current_a, o.max_power_w, o.kv_label, std::nullopt});
  calibration::AddRatings(&esc, {o.esc_mass_kg, o.esc_max_current_a, std::nullopt, std::nullopt, o.esc_vdc_max_v});
  std::vector<Json> props;
  if (!o.prop_id.empty()) props.push_back(PropEntry(o, table, prov));

  Json loo;
  if (o.loo) {
    const auto lcv = calibration::LeaveOneOut(table, co, true);
    loo["by"] = table.Has(logs::Column::kThrottle) ? "throttle level" : "row";
    loo["folds"] = lcv.folds;
    loo["failed_folds"] = lcv.failed_folds;
    loo["idc"] = ErrJson(lcv.idc_error_percent);
    loo["omega_at_torque"] = ErrJson(lcv.omega_error_percent);
    loo["omega_from_idc"] = ErrJson(lcv.omega_from_idc_error_percent);
  }
  if (!o.plot_dir.empty()) {
    for (const auto& f : WriteCalibrationFigures(o.plot_dir, table, r)) {
      if (!o.json) std::cerr << "wrote " << f << "\n";
    }
  }
  if (o.json) {
    Json j = calibration::VerdictJson(verdict);
    j["motor"] = motor;
    j["esc"] = esc;
    if (!props.empty()) j["prop"] = props[0];
    j["stderr"] = calibration::StandardErrorsJson(r);
    j["identifiable"] = calibration::IdentifiableJson(r);
    j["fit"] = calibration::FitJson(r);
    j["io_source"] = r.io_source;
    j["warnings"] = WithReaderWarnings(reader_warnings, r.warnings);
    j["held_out"] = {{"leave_one_out", cv.leave_one_out},
                     {"folds", cv.folds},
                     {"failed_folds", cv.failed_folds},
                     {"idc", ErrJson(cv.idc_error_percent)},
                     {"omega_at_torque", ErrJson(cv.omega_error_percent)},
                     {"omega_from_idc", ErrJson(cv.omega_from_idc_error_percent)},
                     {"dc_baseline", {{"idc", ErrJson(cv.dc_idc_error_percent)},
                                      {"omega_at_torque", ErrJson(cv.dc_omega_error_percent)},
                                      {"omega_from_idc", ErrJson(cv.dc_omega_from_idc_error_percent)}}}};
    Json dropped = Json::array();
    for (const auto& d : r.dropped_rows) dropped.push_back({{"line", d.source_line}, {"reason", d.reason}});
    j["dropped_rows"] = dropped;
    if (o.loo) j["leave_one_out"] = loo;
    std::cout << DumpJson(j);
  } else {
    std::cout << r.FullReport();
    if (o.loo) std::cout << "leave-one-out: " << loo.dump() << "\n";
    std::cout << HeldOutBesideDc(cv, co.labels.kv_rpm_per_v.has_value()) << "\n";
    std::cout << verdict.summary << "\n";
    if (!verdict.advice.empty()) std::cout << "next: " << verdict.advice << "\n";
  }
  if (!o.out.empty()) {
    // Only an entry with status ok is written; --force replaces ids, it never admits a refused fit.
    if (verdict.status != identification::Status::kOk) {
      const identification::Check* c = verdict.FirstFailed();
      std::ostringstream m;
      m << Datasets(o.logs) << ": " << o.out << " not written: status " << identification::StatusName(verdict.status);
      if (c != nullptr) m << ", check " << c->name << " failed (" << c->value << " vs limit " << c->limit << ")";
      throw DataError(m.str());
    }
    calibration::WriteCatalogEntries(o.out, {motor}, {esc}, o.force,
                                     "Entries fitted by dynosize calibrate from dynamometer logs.", props);
    if (!o.json) {
      std::cerr << "wrote " << o.motor_id << ", " << o.esc_id << (props.empty() ? "" : ", " + o.prop_id) << " to "
                << o.out << "\n";
    }
  }
  return 0;
}

}  // namespace dynosize::cli
