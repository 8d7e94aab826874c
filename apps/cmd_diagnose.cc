// `dynosize diagnose LOG`: what the first-order model gets wrong in a measured log, the named
// cause, the extended model and the cross-validated gain (src/diagnosis/diagnose.h).
#include <cctype>
#include <cmath>
#include <sstream>
#include <iostream>

#include <filesystem>

#include "calibration/catalog_output.h"
#include "catalog/catalog.h"
#include "commands.h"
#include "log_input.h"
#include "common/error.h"
#include "common/json_file.h"
#include "diagnosis/diagnose.h"
#include "logs/log_reader.h"
#include "report/diagnosis_figures.h"

namespace dynosize::cli {

namespace {

using diagnosis::CauseId;
using diagnosis::ColumnError;


Json CvJson(const std::vector<ColumnError>& cv, bool percent) {
  Json j = Json::object();
  for (const auto& c : cv) j[logs::ColumnName(c.column)] = NumberOrNull(percent ? c.rmse_percent : c.rmse);
  return j;
}

Json MapJson(const std::map<std::string, double>& m) {
  Json j = Json::object();
  for (const auto& [k, v] : m) j[k] = NumberOrNull(v);
  return j;
}

// Catalog-style entry values (SI, catalog keys) of the extended model.
Json MotorJson(const MotorParams& m) {
  Json j;
  j["type"] = m.type == MotorType::kBldc ? "bldc" : "brushed";
  j["ke_v_s_per_rad"] = m.ke_v_s_per_rad;
  j["kt_nm_per_a"] = m.kt_nm_per_a;
  j["rm_ohm"] = m.rm_ohm;
  j["io_a"] = m.io_a;
  j["io1_a_s_per_rad"] = m.io1_a_s_per_rad;
  j["rth_k_per_w"] = m.rth_k_per_w;
  j["kt_droop_per_a"] = m.kt_droop_per_a;
  return j;
}

Json EscJson(const EscParams& e) {
  Json j;
  j["resc_ohm"] = e.resc_ohm;
  j["c1"] = e.c1;
  j["c0"] = e.c0;
  j["tr_sat"] = e.tr_sat;
  j["sat_slope"] = e.sat_slope;
  j["deadband"] = e.deadband;
  j["rsupply_ohm"] = e.rsupply_ohm;
  return j;
}

Json ScoreJson(const diagnosis::CandidateScore& s) {
  Json j;
  j["cause"] = CauseId(s.cause);
  j["parameters"] = MapJson(s.parameters);
  j["f_statistic"] = NumberOrNull(s.f_statistic);
  j["p_value"] = NumberOrNull(s.p_value);
  j["delta_aicc"] = NumberOrNull(s.delta_aicc);
  j["cv_rms_percent"] = s.cv_rms_percent > 0.0 ? NumberOrNull(s.cv_rms_percent) : Json(nullptr);
  j["gain_percent"] = NumberOrNull(s.gain_percent);
  j["significant"] = s.significant;
  if (!s.note.empty()) j["note"] = s.note;
  return j;
}

// A catalog id from a file name: [A-Za-z0-9_.+-] kept, anything else '_'.
std::string IdFrom(const std::string& path) {
  std::string stem = std::filesystem::path(path).stem().string();
  for (char& c : stem) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '+' || c == '-';
    if (!ok) c = '_';
  }
  if (stem.empty()) stem = "diagnosed";
  return stem.substr(0, 100);
}

// The extended model as catalog entries: fitted values say "fitted", values held at a default
// or at the --motor/--esc entry say "assumed", KT tied to KE says "derived".
void WriteExtendedEntries(const DiagnoseCliOptions& o, const diagnosis::DiagnoseResult& r) {
  const std::string id = o.id.empty() ? IdFrom(o.log) : o.id;
  auto fitted = [&](const std::string& key) {
    for (const auto& f : r.base_free_parameters) {
      if (f == key) return true;
    }
    for (const auto& f : r.findings) {
      if (f.parameters.count(key)) return true;
    }
    return false;
  };
  std::ostringstream ref;
  ref << "dynosize diagnose (" << r.mode << "), " << r.points_used << " points; findings:";
  for (const auto& f : r.findings) ref << " " << CauseId(f.cause);
  if (r.findings.empty()) ref << " none";
  auto method = [&](const std::string& key) -> std::string {
    if (key == "kt_nm_per_a" && !fitted(key)) return "derived";
    return fitted(key) ? "fitted" : "assumed";
  };
  std::vector<calibration::EntryValue> mv = {{"type", 0.0, "assumed",
                                              r.extended_motor.type == MotorType::kBldc ? "bldc" : "brushed"}};
  const Json motor = MotorJson(r.extended_motor);
  for (auto it = motor.begin(); it != motor.end(); ++it) {
    if (it.key() != "type") mv.push_back({it.key(), it.value().get<double>(), method(it.key()), ""});
  }
  std::vector<calibration::EntryValue> ev;
  const Json esc = EscJson(r.extended_esc);
  for (auto it = esc.begin(); it != esc.end(); ++it) ev.push_back({it.key(), it.value().get<double>(), method(it.key()), ""});
  calibration::EntryProvenance prov;
  prov.dataset = std::filesystem::path(o.log).filename().string();
  prov.reference = ref.str();
  std::string note;
  for (const auto& w : r.warnings) note += (note.empty() ? "" : "; ") + w;
  const Json m = calibration::ComponentEntryJson(id + "_motor", id + " motor (diagnosed, extended model)", mv, prov,
                                                 note, "motor");
  const Json e = calibration::ComponentEntryJson(id + "_esc", id + " ESC (diagnosed, extended model)", ev, prov,
                                                 note, "ESC");
  calibration::WriteCatalogEntries(o.out, {m}, {e}, o.force,
                                   "Extended models fitted by dynosize diagnose from dynamometer logs.");
  if (!o.json) std::cerr << "wrote " << id << "_motor, " << id << "_esc to " << o.out << "\n";
}

// --out writes the extended model only when its status is ok (the same rule as calibrate):
// otherwise exit 65 with one line naming the failed check, and the file is not touched.
void WriteIfOk(const DiagnoseCliOptions& o, const diagnosis::DiagnoseResult& r) {
  if (o.out.empty()) return;
  if (r.verdict.status != identification::Status::kOk) {
    const identification::Check* c = r.verdict.FirstFailed();
    std::ostringstream m;
    m << o.log << ": " << o.out << " not written: status " << identification::StatusName(r.verdict.status);
    if (c != nullptr) m << ", check " << c->name << " failed (" << c->value << " vs limit " << c->limit << ")";
    throw DataError(m.str());
  }
  WriteExtendedEntries(o, r);
}

}  // namespace

int RunDiagnose(const DiagnoseCliOptions& o) {
  const logs::LogReadOptions ro = ToLogReadOptions(o.input);
  diagnosis::DiagnoseOptions opt;
  opt.folds = o.folds;
  opt.alpha = o.alpha;
  opt.kv_label_rpm_per_v = o.kv_label;
  if (o.kv_label && !(*o.kv_label > 0.0)) throw UsageError("diagnose: --kv-label must be > 0 (rpm per volt)");
  if (!o.motor_id.empty() || !o.esc_id.empty()) {
    const Catalog cat = Catalog::Load(o.catalog);
    if (!o.motor_id.empty()) opt.motor = cat.motor(o.motor_id).params;
    if (!o.esc_id.empty()) opt.esc = cat.esc(o.esc_id).params;
  }
  std::string why;
  if (!opt.IsValid(&why)) throw UsageError("diagnose: " + why);
  const logs::SteadyTable table = logs::ReadLog(o.log, ro);
  const std::string no_throttle = MissingThrottleLine(table);
  if (!o.json && !no_throttle.empty()) std::cerr << no_throttle << "\n";
  if (!o.json) std::cerr << table.BriefReport() << "\n";
  const diagnosis::DiagnoseResult r = diagnosis::Diagnose(table, opt);
  if (!o.plot_dir.empty()) {
    for (const auto& f : WriteDiagnosisFigures(o.plot_dir, table, r)) {
      if (!o.json) std::cerr << "wrote " << f << "\n";
    }
  }
  if (!o.json) {
    std::cout << r.FullReport();
    WriteIfOk(o, r);
    return 0;
  }
  Json j = calibration::VerdictJson(r.verdict);
  j["file"] = r.file;
  j["mode"] = r.mode;
  j["entry_from_calibration"] = r.entry_from_calibration;
  j["points_used"] = r.points_used;
  j["outlier_rows"] = r.outlier_rows.size();
  j["baseline"] = {{"cv_rmse", CvJson(r.baseline_cv, false)},
                   {"cv_rmse_percent", CvJson(r.baseline_cv, true)},
                   {"cv_rms_percent_all", NumberOrNull(r.baseline_cv_rms_percent)},
                   {"free_parameters", r.base_free_parameters},
                   {"motor", MotorJson(r.base_motor)},
                   {"esc", EscJson(r.base_esc)}};
  Json worst = Json::array();
  for (const auto& w : r.worst_points) {
    worst.push_back({{"line", w.source_line}, {"column", logs::ColumnName(w.column)}, {"measured", w.measured},
                     {"predicted", w.predicted}, {"error_percent", w.error_percent}});
  }
  j["baseline"]["worst_points"] = worst;
  Json trends = Json::array();
  for (const auto& t : r.residual_trends) {
    trends.push_back({{"column", logs::ColumnName(t.column)}, {"variable", t.variable}, {"r2", NumberOrNull(t.r2)},
                      {"p_value", NumberOrNull(t.p_value)}, {"slope_percent_per_range", NumberOrNull(t.slope_percent_per_range)},
                      {"structured", t.structured}});
  }
  j["baseline"]["residual_structure"] = trends;
  Json findings = Json::array();
  for (const auto& f : r.findings) {
    Json fj;
    fj["cause"] = CauseId(f.cause);
    fj["description"] = f.description;
    fj["parameters"] = MapJson(f.parameters);
    fj["stderr"] = MapJson(f.stderrs);
    fj["cv_rmse_after"] = CvJson(f.cv_after, false);
    fj["cv_rmse_percent_after"] = CvJson(f.cv_after, true);
    fj["gain_percent"] = NumberOrNull(f.gain_percent);
    Json steps = Json::array();
    for (const auto& s : f.step_scores) steps.push_back(ScoreJson(s));
    fj["evidence"] = {{"f_statistic", NumberOrNull(f.f_statistic)},
                      {"p_value", NumberOrNull(f.p_value)},
                      {"delta_aicc", NumberOrNull(f.delta_aicc)},
                      {"max_abs_correlation_with_base", NumberOrNull(f.max_abs_correlation)},
                      {"most_correlated_with", f.most_correlated_with},
                      {"candidates", steps}};
    findings.push_back(fj);
  }
  j["findings"] = findings;
  Json last = Json::array();
  for (const auto& s : r.last_step_scores) last.push_back(ScoreJson(s));
  j["rejected_candidates"] = last;
  Json amb = Json::array();
  for (const auto& a : r.ambiguous) {
    Json causes = Json::array();
    for (auto c : a.causes) causes.push_back(CauseId(c));
    amb.push_back({{"causes", causes}, {"reason", a.reason}, {"measurement", a.measurement}});
  }
  j["ambiguous"] = amb;
  Json nt = Json::array();
  for (const auto& s : r.not_testable) nt.push_back({{"cause", CauseId(s.cause)}, {"reason", s.not_testable_reason}});
  j["not_testable"] = nt;
  j["extended_model"] = {{"motor", MotorJson(r.extended_motor)},
                         {"esc", EscJson(r.extended_esc)},
                         {"cv_rmse", CvJson(r.extended_cv, false)},
                         {"cv_rmse_percent", CvJson(r.extended_cv, true)},
                         {"cv_rms_percent_all", NumberOrNull(r.extended_cv_rms_percent)}};
  j["warnings"] = r.warnings;
  if (!no_throttle.empty()) j["warnings"].insert(j["warnings"].begin(), no_throttle);
  j["dropped_rows"] = r.outlier_reasons;
  j["cross_validation"] = {{"folds", r.cv_folds}, {"leave_one_out", r.leave_one_out},
                           {"baseline_failed_folds", r.baseline_cv_failed_folds},
                           {"extended_failed_folds", r.extended_cv_failed_folds}};
  std::cout << DumpJson(j);
  WriteIfOk(o, r);
  return 0;
}

}  // namespace dynosize::cli
