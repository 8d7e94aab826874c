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

#include "api/calibrate.h"
#include "calibration/catalog_output.h"
#include "calibration/drivecalc_refit.h"
#include "calibration/prop_static.h"
#include "common/units.h"
#include "fit/statistics.h"
#include "identification/verdict.h"
#include "catalog/catalog.h"
#include "commands.h"
#include "common/error.h"
#include "common/json_file.h"
#include "common/text_file.h"
#include "common/text_format.h"
#include "logs/log_reader.h"
#include "report/calibration_figures.h"

namespace dynosize::cli {

namespace {

using calibration::CalibrationOptions;
using calibration::CalibrationResult;

using fit::Median;
using fit::MedianAbs;

// One line: the held-out median |error| of the fitted model and of the plain DC model fitted on
// the same training rows (identification/dc_fit.h), the baseline to beat.
std::string HeldOutBesideDc(const calibration::CrossValidation& cv, bool label) {
  auto med = [](const std::vector<double>& e) {
    const double m = MedianAbs(e);
    return std::isfinite(m) ? FixedText(m, 2) + " %" : std::string("-");
  };
  const bool torque = !cv.omega_error_percent.empty();
  std::string s = "held out (" + std::to_string(cv.folds) + " folds), dynosize / plain DC model (" +
                  (label ? "label Kv; R, Io" : "Kv, R, Io") + " fitted on the same rows, the command through the "
                  "fit's throttle offset): ";
  if (torque) {
    s += "DC current " + med(cv.idc_error_percent) + " / " + med(cv.dc_idc_error_percent) + ", speed at the torque " +
         med(cv.omega_error_percent) + " / " + med(cv.dc_omega_error_percent);
  } else {
    s += "speed from the current " + med(cv.omega_from_idc_error_percent) + " / " + med(cv.dc_omega_from_idc_error_percent);
  }
  if (cv.dc_failed_folds > 0) {
    s += "; the plain DC model cannot be fitted on " + std::to_string(cv.dc_failed_folds) + " of " +
         std::to_string(cv.folds) + " folds (" + cv.dc_why + ")";
  }
  return s;
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
    loo["model"] = {{"idc_loaded", api::ErrorsJson(e.model_idc_loaded)}, {"omega_from_idc", api::ErrorsJson(e.model_omega)}};
    loo["baseline_u_n_kv_r_i"] = {{"idc_loaded", api::ErrorsJson(e.baseline_idc_loaded)},
                                  {"omega_from_idc", api::ErrorsJson(e.baseline_omega)}};
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
              << all.motors_too_few_points << " with too few points, " << all.failures.size() << " failed); "
              << motors.size() << " with status ok written -> " << out << "\n"
              << "median rmse: idc " << SignificantTextOr(Median(rmse_idc), "-", 3) << " %, no-load speed "
              << SignificantTextOr(Median(rmse_w), "-", 3) << " %\n";
    if (o.loo) std::cout << "leave-one-out: " << loo.dump() << "\n";
  }
  return 0;
}

}  // namespace

int RunCalibrate(const CalibrateOptions& o) {
  if (o.logs.empty()) throw UsageError("calibrate: give at least one LOG file");
  if (o.drivecalc_all) return RunDriveCalcAll(o);
  const api::CalibrateRequest request{o.logs,          o.motor_id,          o.esc_id,       o.input,
                                      o.drivecalc_motor, o.prior_motor,     o.prior_esc,    o.loo,
                                      o.kv_label,      o.rm_label,          o.io_label,     o.io_label_v,
                                      o.mass_kg,       o.max_current_a,     o.max_power_w,  o.esc_max_current_a,
                                      o.esc_vdc_max_v, o.esc_mass_kg,       o.prop_id,      o.prop_diameter_in,
                                      o.prop_pitch_in};
  const api::CalibrationLogs in = api::ReadCalibrationLogs(request);
  if (!o.json) {
    for (const auto& w : in.reader_warnings) std::cerr << w << "\n";
  }
  const logs::SteadyTable table = calibration::MergeLogs(in.tables);
  api::CheckCalibrateRequest(request);
  std::optional<Catalog> cat;
  if (!o.prior_motor.empty() || !o.prior_esc.empty()) cat = Catalog::Load(o.catalog);
  const CalibrationOptions co = api::CalibrationOptionsOf(request, cat ? &*cat : nullptr);
  const CalibrationResult r = calibration::Calibrate(table, co);
  // What was read (rows dropped and why), once the fit has run: a refusal stays one line.
  if (!o.json) {
    for (const auto& t : in.tables) std::cerr << t.BriefReport() << "\n";
  }
  if (const std::string bad = api::NonFiniteParameter(r); !bad.empty()) {
    // The fit failed: its status and message, no numbers; --out is not touched.
    if (o.json) {
      std::cout << DumpJson(api::FailedCalibrationJson(r, bad, in.reader_warnings));
    } else {
      std::cout << "calibrate (" << r.mode << "): FAILED: " << r.message << "\n";
    }
    throw DataError(api::FailedCalibrationMessage(request, r, bad, o.out));
  }
  const api::CalibrationOutcome out = api::JudgeCalibrationFit(request, table, co, r);
  const identification::Verdict& verdict = out.verdict;
  if (!o.plot_dir.empty()) {
    for (const auto& f : WriteCalibrationFigures(o.plot_dir, table, r)) {
      if (!o.json) std::cerr << "wrote " << f << "\n";
    }
  }
  if (o.json) {
    std::cout << DumpJson(api::CalibrationJson(request, out, r, in.reader_warnings));
  } else {
    std::cout << r.FullReport();
    if (o.loo) std::cout << "leave-one-out: " << out.loo.dump() << "\n";
    std::cout << HeldOutBesideDc(out.cv, co.labels.kv_rpm_per_v.has_value()) << "\n";
    std::cout << verdict.summary << "\n";
    if (!verdict.advice.empty()) std::cout << "next: " << verdict.advice << "\n";
  }
  if (!o.out.empty()) {
    // Only an entry with status ok is written; --force replaces ids, it never admits a refused fit.
    if (verdict.status != identification::Status::kOk) {
      const identification::Check* c = verdict.FirstFailed();
      std::ostringstream m;
      m << api::Datasets(o.logs) << ": " << o.out << " not written: status " << identification::StatusName(verdict.status);
      if (c != nullptr) m << ", check " << c->name << " failed (" << c->value << " vs limit " << c->limit << ")";
      throw DataError(m.str());
    }
    calibration::WriteCatalogEntries(o.out, {out.motor}, {out.esc}, o.force,
                                     "Entries fitted by dynosize calibrate from dynamometer logs.", out.props);
    if (!o.json) {
      std::cerr << "wrote " << o.motor_id << ", " << o.esc_id << (out.props.empty() ? "" : ", " + o.prop_id) << " to "
                << o.out << "\n";
    }
  }
  return 0;
}

}  // namespace dynosize::cli
