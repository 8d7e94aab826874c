#include "api/diagnose.h"

#include "calibration/catalog_output.h"
#include "common/error.h"
#include "logs/log_reader.h"

namespace dynosize::api {

using diagnosis::CauseId;
using diagnosis::ColumnError;

namespace {

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

}  // namespace

// Catalog-style entry values (SI, catalog keys) of the extended model.
Json MotorValuesJson(const MotorParams& m) {
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

Json EscValuesJson(const EscParams& e) {
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

namespace {

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

}  // namespace

void CheckDiagnoseRequest(const DiagnoseRequest& o) {
  if (o.kv_label && !(*o.kv_label > 0.0)) throw UsageError("diagnose: --kv-label must be > 0 (rpm per volt)");
}

diagnosis::DiagnoseOptions DiagnoseOptionsOf(const DiagnoseRequest& o, const Catalog* cat) {
  CheckDiagnoseRequest(o);
  diagnosis::DiagnoseOptions opt;
  opt.folds = o.folds;
  opt.alpha = o.alpha;
  opt.kv_label_rpm_per_v = o.kv_label;
  if (cat != nullptr) {
    if (!o.motor_id.empty()) opt.motor = cat->motor(o.motor_id).params;
    if (!o.esc_id.empty()) opt.esc = cat->esc(o.esc_id).params;
  }
  std::string why;
  if (!opt.IsValid(&why)) throw UsageError("diagnose: " + why);
  return opt;
}

Json DiagnoseJson(const diagnosis::DiagnoseResult& r, const std::string& no_throttle) {
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
                   {"motor", MotorValuesJson(r.base_motor)},
                   {"esc", EscValuesJson(r.base_esc)}};
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
  Json remaining = Json::array();
  for (const auto& t : r.remaining_trends) {
    const identification::TrendAttribution& a = t.attribution;
    Json sigs = Json::array();
    for (const auto& g : a.signatures) {
      Json gj = {{"mechanism", g.mechanism}, {"r2", NumberOrNull(g.r2)}, {"p_value", NumberOrNull(g.p_value)},
                 {"change_percent", NumberOrNull(g.change_percent)}};
      if (g.mechanism == "heating") gj["tau_s"] = g.tau_s;
      sigs.push_back(gj);
    }
    remaining.push_back({{"column", logs::ColumnName(t.column)}, {"follows", a.signatures.front().mechanism},
                         {"separable", a.separable}, {"rival", a.rival},
                         {"rival_correlation", NumberOrNull(a.rival_correlation)}, {"text", a.text},
                         {"measurement", a.measurement}, {"signatures", sigs}});
  }
  j["remaining_trends"] = remaining;
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
  j["extended_model"] = {{"motor", MotorValuesJson(r.extended_motor)},
                         {"esc", EscValuesJson(r.extended_esc)},
                         {"cv_rmse", CvJson(r.extended_cv, false)},
                         {"cv_rmse_percent", CvJson(r.extended_cv, true)},
                         {"cv_rms_percent_all", NumberOrNull(r.extended_cv_rms_percent)}};
  j["warnings"] = r.warnings;
  if (!no_throttle.empty()) j["warnings"].insert(j["warnings"].begin(), no_throttle);
  j["dropped_rows"] = r.outlier_reasons;
  j["cross_validation"] = {{"folds", r.cv_folds}, {"leave_one_out", r.leave_one_out},
                           {"baseline_failed_folds", r.baseline_cv_failed_folds},
                           {"extended_failed_folds", r.extended_cv_failed_folds}};
  return j;
}

Json DiagnoseLog(const DiagnoseRequest& request, const Catalog* catalog) {
  const logs::LogReadOptions ro = ToLogReadOptions(request.input);
  const diagnosis::DiagnoseOptions opt = DiagnoseOptionsOf(request, catalog);
  const logs::SteadyTable table = logs::ReadLog(request.log, ro);
  const diagnosis::DiagnoseResult r = diagnosis::Diagnose(table, opt);
  return DiagnoseJson(r, MissingThrottleLine(table));
}

}  // namespace dynosize::api
