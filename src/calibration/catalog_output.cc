#include "calibration/catalog_output.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "catalog/catalog.h"
#include "common/error.h"
#include "common/text_file.h"
#include "common/units.h"

namespace dynosize::calibration {

namespace {


// Rounds to 6 significant digits: the fit's errors are far larger, and the files stay readable.
double Sig6(double v) {
  if (v == 0.0 || !std::isfinite(v)) return v;
  const double e = std::floor(std::log10(std::fabs(v))) - 5.0;
  const double f = std::pow(10.0, e);
  return std::round(v / f) * f;
}

std::string Method(const ParamEstimate& e) { return e.fitted ? "fitted" : "assumed"; }

// "held at prior" for every value the data could not identify (listed in the note).
std::string HeldNote(const CalibrationResult& r, const std::vector<Param>& ps) {
  std::string s;
  for (Param p : ps) {
    if (!r.param(p).fitted) s += std::string(s.empty() ? "" : ", ") + ParamName(p);
  }
  return s.empty() ? "" : "held at prior (not identifiable from this log): " + s;
}

std::string UnidentifiedNote(const CalibrationResult& r, const std::vector<Param>& ps) {
  std::string s;
  for (Param p : ps) {
    const auto& e = r.param(p);
    if (!e.identifiable) s += std::string(s.empty() ? "" : "; ") + ParamName(p) + ": " + e.note;
  }
  return s.empty() ? "" : "not identifiable from the data: " + s;
}

Json Source(const EntryProvenance& p, const Json& values, const std::string& auto_note) {
  Json src;
  src["dataset"] = p.dataset;
  if (!p.reference.empty()) src["reference"] = p.reference;
  src["values"] = values;
  std::string note = auto_note;
  if (!p.note.empty()) note = note.empty() ? p.note : p.note + "; " + note;
  if (!note.empty()) src["note"] = note;
  return src;
}

}  // namespace

Json ComponentEntryJson(const std::string& id, const std::string& name, const std::vector<EntryValue>& values,
                        const EntryProvenance& p, const std::string& auto_note, const std::string& kind) {
  Json e;
  e["id"] = id;
  e["name"] = name;
  Json v = Json::object();
  for (const auto& x : values) {
    if (x.text.empty()) {
      e[x.key] = Sig6(x.value);
    } else {
      e[x.key] = x.text;
    }
    v[x.key] = x.method;
  }
  e["source"] = Source(p, v, auto_note);
  CheckJsonFinite(e, kind + " entry " + id);
  return e;
}

Json MotorEntryJson(const std::string& id, const std::string& name, const CalibrationResult& r,
                    const EntryProvenance& p) {
  const std::vector<EntryValue> values = {
      {"type", 0.0, "assumed", "bldc"},
      {"ke_v_s_per_rad", r.motor.ke_v_s_per_rad, Method(r.param(Param::kKe)), ""},
      {"kt_nm_per_a", r.motor.kt_nm_per_a, r.param(Param::kKt).fitted ? "fitted" : "derived", ""},
      {"rm_ohm", r.motor.rm_ohm, Method(r.param(Param::kRm)), ""},
      {"io_a", r.motor.io_a, r.io_source == "label" ? "datasheet" : Method(r.param(Param::kIo)), ""},
      {"kv_rpm_per_v", kVllRmsPerVdc / (r.motor.ke_v_s_per_rad * kRadPerSecPerRpm), "derived", ""}};
  std::string note = HeldNote(r, {Param::kIo});
  const std::string un = UnidentifiedNote(r, {Param::kKe, Param::kKt, Param::kRm, Param::kIo});
  if (!un.empty()) note += (note.empty() ? "" : "; ") + un;
  return ComponentEntryJson(id, name, values, p, note, "motor");
}

Json EscEntryJson(const std::string& id, const std::string& name, const CalibrationResult& r,
                  const EntryProvenance& p) {
  std::vector<EntryValue> values = {{"resc_ohm", r.esc.resc_ohm, Method(r.param(Param::kResc)), ""},
                                    {"c1", r.esc.c1, Method(r.param(Param::kC1)), ""},
                                    {"c0", r.esc.c0, Method(r.param(Param::kC0)), ""},
                                    {"tr_sat", r.esc.tr_sat, Method(r.param(Param::kTrSat)), ""},
                                    {"sat_slope", r.esc.sat_slope, Method(r.param(Param::kSatSlope)), ""}};
  if (r.esc.deadband != 0.0 || r.param(Param::kDeadband).fitted) {
    values.push_back({"deadband", r.esc.deadband, Method(r.param(Param::kDeadband)), ""});
  }
  const std::vector<Param> ps = {Param::kResc, Param::kC1, Param::kC0, Param::kTrSat, Param::kSatSlope};
  std::string note = HeldNote(r, ps);
  const std::string un = UnidentifiedNote(r, ps);
  if (!un.empty()) note += (note.empty() ? "" : "; ") + un;
  return ComponentEntryJson(id, name, values, p, note, "ESC");
}

void WriteCatalogEntries(const std::string& path, const std::vector<Json>& motors, const std::vector<Json>& escs,
                         bool force, const std::string& comment, const std::vector<Json>& props) {
  // Read, merge and write under one lock: concurrent runs adding to the same catalog file take
  // turns (the write itself is atomic either way).
  const FileLock lock(path);
  Json doc;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    doc = ReadJsonFile(path);
    if (!doc.is_object()) throw DataError(path + ": not a catalog document (a JSON object)");
  } else {
    doc["comment"] = comment;
  }
  auto merge = [&](const char* array, const std::vector<Json>& entries) {
    if (entries.empty()) return;
    Json& arr = doc[array];
    if (arr.is_null()) arr = Json::array();
    if (!arr.is_array()) throw DataError(path + ": '" + array + "' is not an array");
    for (const Json& e : entries) {
      const std::string id = e.at("id").get<std::string>();
      bool replaced = false;
      for (Json& old : arr) {
        if (old.is_object() && old.contains("id") && old["id"] == id) {
          if (!force) {
            throw UsageError(path + ": " + array + " already has id '" + id +
                             "': use --force to replace it (the file was not changed)");
          }
          old = e;
          replaced = true;
        }
      }
      if (!replaced) arr.push_back(e);
    }
  };
  merge("motors", motors);
  merge("escs", escs);
  merge("props", props);
  Catalog check;
  std::vector<std::string> problems;
  check.AddDocument(doc, path, &problems);
  if (!problems.empty()) {
    std::string m = path + ": the catalog with the new entries would not load (file not changed):";
    for (std::size_t k = 0; k < problems.size() && k < 10; ++k) m += "\n  " + problems[k];
    throw DataError(m);
  }
  WriteFileAtomic(path, DumpJson(doc));
}

Json StandardErrorsJson(const CalibrationResult& r) {
  Json j = Json::object();
  for (int k = 0; k < kBaseParamCount; ++k) j[ParamName(static_cast<Param>(k))] = NumberOrNull(r.params[k].standard_error);
  j["r_total_ohm"] = NumberOrNull(r.r_total_standard_error);
  return j;
}

Json IdentifiableJson(const CalibrationResult& r) {
  Json j = Json::object();
  for (int k = 0; k < kBaseParamCount; ++k) j[ParamName(static_cast<Param>(k))] = r.params[k].identifiable;
  j["r_total_ohm"] = true;
  return j;
}

Json FitJson(const CalibrationResult& r) {
  Json j;
  j["mode"] = r.mode;
  j["converged"] = r.converged;
  j["message"] = r.message;
  j["points_used"] = r.points_used;
  j["points_dropped"] = r.points_dropped;
  Json d = Json::array();
  for (const auto& x : r.dropped) d.push_back({{"reason", x.reason}, {"count", x.count}});
  j["dropped"] = d;
  j["condition_number"] = NumberOrNull(r.condition_number);
  j["r_total_ohm"] = NumberOrNull(r.r_total_ohm);
  Json notes = Json::object();
  for (int k = 0; k < kBaseParamCount; ++k) {
    if (!r.params[k].note.empty()) notes[ParamName(static_cast<Param>(k))] = r.params[k].note;
  }
  j["parameter_notes"] = notes;
  Json cols = Json::object();
  for (const auto& f : r.fit) {
    cols[logs::ColumnName(f.column)] = {{"points", f.points},
                                        {"rmse", NumberOrNull(f.rmse)},
                                        {"rmse_percent", NumberOrNull(f.rmse_percent)},
                                        {"median_abs_percent", NumberOrNull(f.median_abs_percent)}};
  }
  j["columns"] = cols;
  j["unidentifiable_directions"] = r.unidentifiable_directions;
  return j;
}

}  // namespace dynosize::calibration

namespace dynosize::calibration {

void AddRatings(Json* entry, const EntryRatings& r) {
  // Json is an ordered map (a vector): adding a key to the entry may move "source", so the
  // reference to source.values is taken afresh after each insertion.
  auto set = [&](const char* key, const std::optional<double>& v) {
    if (!v) return;
    (*entry)[key] = *v;
    (*entry)["source"]["values"][key] = "datasheet";
  };
  set("mass_kg", r.mass_kg);
  set("max_current_a", r.max_current_a);
  set("max_power_w", r.max_power_w);
  set("kv_rpm_per_v", r.kv_label_rpm_per_v);
  set("vdc_max_v", r.vdc_max_v);
}

Json VerdictJson(const identification::Verdict& v) {
  Json j;
  j["status"] = identification::StatusName(v.status);
  j["summary"] = v.summary;
  j["advice"] = v.advice;
  Json checks = Json::array();
  for (const auto& c : v.checks) {
    checks.push_back({{"name", c.name}, {"passed", c.passed}, {"value", NumberOrNull(c.value)},
                      {"limit", NumberOrNull(c.limit)}, {"detail", c.detail}});
  }
  j["checks"] = checks;
  return j;
}

Json PropEntryJson(const std::string& id, const std::string& name, const PropStaticTable& t,
                   const PropStaticOptions& o, const EntryProvenance& p) {
  Json e;
  e["id"] = id;
  e["name"] = name;
  e["diameter_m"] = Sig6(o.diameter_m);
  Json v;
  v["diameter_m"] = "datasheet";
  if (o.pitch_m > 0.0) {
    e["pitch_m"] = Sig6(o.pitch_m);
    v["pitch_m"] = "datasheet";
  }
  Json rpm = Json::array(), ct = Json::array(), cp = Json::array();
  for (std::size_t k = 0; k < t.rpm.size(); ++k) {
    rpm.push_back(Sig6(t.rpm[k]));
    ct.push_back(Sig6(t.ct[k]));
    cp.push_back(Sig6(t.cp[k]));
  }
  e["static_table"] = {{"rpm", rpm}, {"ct", ct}, {"cp", cp}};
  v["static_table"] = "measured";
  std::ostringstream note;
  note << "static CT = T/(rho n^2 D^4), CP = Q*omega/(rho n^3 D^5) from " << t.rows_used
       << " log rows (rows within 1 % in speed averaged); rho = " << o.rho_kg_m3
       << " kg/m^3 assumed (ISA sea level, not recorded in the log); largest figure of merit " << Sig6(t.max_figure_of_merit);
  e["source"] = Source(p, v, note.str());
  CheckJsonFinite(e, "propeller entry " + id);
  return e;
}

}  // namespace dynosize::calibration
