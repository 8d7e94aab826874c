#include "api/catalog_json.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "catalog/in_system.h"
#include "catalog/prop_credibility.h"
#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"
#include "rotor/family.h"

namespace dynosize::api {

namespace {

std::optional<double> Number(const Json& e, const char* key) {
  const auto it = e.find(key);
  if (it == e.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

}  // namespace

bool PassesListFilters(const CatalogListRequest& o, const Json& e) {
  auto within = [&](const char* key, std::optional<double> lo, std::optional<double> hi) {
    if (!lo && !hi) return true;
    const auto v = Number(e, key);
    return v && (!lo || *v >= *lo) && (!hi || *v <= *hi);
  };
  return within("kv_rpm_per_v", o.kv_min, o.kv_max) && within("mass_kg", std::nullopt, o.mass_max_kg) &&
         within("max_current_a", o.current_min_a, std::nullopt);
}

void CheckCatalogListRequest(const CatalogListRequest& o) {
  for (const auto& [flag, v] : {std::pair<const char*, std::optional<double>>{"--kv-min", o.kv_min},
                                {"--kv-max", o.kv_max},
                                {"--mass-max-kg", o.mass_max_kg},
                                {"--current-min-a", o.current_min_a}}) {
    if (v && !(std::isfinite(*v) && *v >= 0.0)) {
      std::ostringstream s;
      s << flag << " " << *v << ": must be a finite number >= 0";
      throw UsageError(s.str());
    }
  }
  if (o.kv_min && o.kv_max && *o.kv_min > *o.kv_max) {
    std::ostringstream s;
    s << "--kv-min " << *o.kv_min << " > --kv-max " << *o.kv_max << ": the range is empty";
    throw UsageError(s.str());
  }
  if ((o.kv_min || o.kv_max) && !o.kind.empty() && o.kind != "motors") {
    throw UsageError("--kv-min/--kv-max filter motors: use them with --kind motors");
  }
}

Json CatalogListJson(const Catalog& cat, const CatalogListRequest& o) {
  const bool all = o.kind.empty();
  const auto motors = SelectForList(cat.motors(), o);
  const auto escs = SelectForList(cat.escs(), o);
  const auto props = SelectForList(cat.props(), o);
  const auto batteries = SelectForList(cat.batteries(), o);
  const bool motor_filter = o.kv_min || o.kv_max;
  Json j;
  auto put = [&](const char* kind, const auto& entries) {
    if (!all && o.kind != kind) return;
    if (all && motor_filter && std::string(kind) != "motors") return;
    Json arr = Json::array();
    for (const auto* e : entries) arr.push_back(e->json);
    j[kind] = arr;
  };
  put("motors", motors);
  put("escs", escs);
  put("props", props);
  put("batteries", batteries);
  return j;
}

Json CatalogShowJson(const Catalog& cat, const std::string& id) {
  Json out;
  bool found = false;
  for (const auto& m : cat.motors()) {
    if (m.id != id) continue;
    found = true;
    out = m.json;
    Json si;
    si["ke_v_s_per_rad"] = m.params.ke_v_s_per_rad;
    si["kt_nm_per_a"] = m.params.kt_nm_per_a;
    si["kt_over_ke"] = m.params.kt_nm_per_a / m.params.ke_v_s_per_rad;
    si["kt_over_ke_ideal"] = m.params.type == MotorType::kBldc ? kPacPerVllIrms : 1.0;
    si["file"] = m.file;
    out["derived"] = si;
    // The in-system law (catalog/in_system.h): the file's numbers and the ones every command uses.
    if (m.datasheet_params) {
      const InSystemApplicability a = InSystemApplicabilityOf(m);
      const MotorParams& raw = *m.datasheet_params;
      Json law;
      law["law"] = {{"tier", TierName(m.tier)}, {"kind", a.law == &KdeDatasheetLaw() ? "KDE Direct datasheets" : "DriveCalc database"}, {"fitted_on", a.law->fitted_on}, {"motors", a.law->motors},
                    {"r_scale", a.law->r_scale}, {"r_add_ohm", a.law->r_add_ohm},
                    {"io_scale", a.law->io_scale}, {"io_speed", a.law->io_speed},
                    {"doc", "docs/in-system-law.md"}};
      law["applied_to"] = Json::array();
      if (a.r) law["applied_to"].push_back("rm_ohm");
      if (a.io) law["applied_to"].push_back("io_a");
      law["datasheet"] = {{"rm_ohm", raw.rm_ohm}, {"io_a", raw.io_a}, {"io1_a_s_per_rad", raw.io1_a_s_per_rad}};
      law["in_system"] = {{"rm_ohm", m.params.rm_ohm}, {"io_a", m.params.io_a},
                          {"io1_a_s_per_rad", m.params.io1_a_s_per_rad}};
      // One motor's scatter about the law, p10-p90 (the ranges of simulate, evaluate, optimize).
      const MotorParams lo = InSystemSpreadParams(m, false);
      const MotorParams hi = InSystemSpreadParams(m, true);
      law["in_system_p10_p90"] = {{"rm_ohm", {lo.rm_ohm, hi.rm_ohm}}, {"io_a", {lo.io_a, hi.io_a}}};
      out["in_system"] = law;
    }
  }
  for (const auto& e : cat.escs()) {
    if (e.id != id) continue;
    found = true;
    out = e.json;
    Json si;
    // Eq (62) at full throttle; the figure depends on the ESC alone, so any motor will do.
    si["esc_timing_figure_at_full_throttle"] = Drive(MotorParams{}, e.params).EscTimingFigure(1.0);
    si["file"] = e.file;
    out["derived"] = si;
  }
  for (const auto& p : cat.props()) {
    if (p.id != id) continue;
    found = true;
    out = p.json;
    const PropValidRange r = ValidRange(p);
    const PropFmScan s = ScanFigureOfMerit(p);
    const FmEnvelopeClass& env = FmEnvelopeFor(p.diameter_m);
    Json si;
    si["valid_rpm"] = {r.rpm_lo, r.rpm_hi};
    si["valid_rpm_assumed"] = r.rpm_assumed;
    si["valid_j_max"] = r.j_hi;
    si["static_fm"] = {{"min", s.fm_min}, {"median", s.fm_median}, {"max", s.fm_max},
                       {"rpm_at_max", s.rpm_at_max}};
    si["fm_envelope_of_class"] = {{"class", env.label}, {"measured_props", env.n_props},
                                  {"p10", env.p10}, {"p50", env.p50}, {"p90", env.p90},
                                  {"max", env.max}};
    si["file"] = p.file;
    out["derived"] = si;
  }
  for (const auto& b : cat.batteries()) {
    if (b.id != id) continue;
    found = true;
    out = b.json;
    out["derived"] = Json{{"file", b.file}};
  }
  // A propeller family the search sizes (catalog/prop_families.h): its ranges and its grid.
  for (const PropSizing& f : cat.prop_families()) {
    if (f.id != id) continue;
    found = true;
    const RotorFamily* family = FindFamily(f.family);
    out = {{"id", f.id}, {"family", f.family}, {"diameter_m", {f.diameter_min_m, f.diameter_max_m}},
           {"pitch_ratio", {f.pitch_ratio_min, f.pitch_ratio_max}}, {"blades", f.blades}, {"source", f.source}};
    out["derived"] = {{"family_description", family->description},
                      {"family_measured_diameter_in",
                       IsParametricFamily(*family) ? Json(nullptr) : Json{family->d_min_in, family->d_max_in}},
                      {"sizes_on_the_grid", SizingGrid(f, f.diameter_max_m).size()},
                      {"grid", "diameter every " + SignificantText(kSizingDiameterStepM, 2) + " m, pitch ratio every " +
                                   SignificantText(kSizingPitchRatioStep, 2) + "; offered within a mission group's "
                                   "max_prop_diameter_m (docs/missions.md, Sizing the rotor)"}};
  }
  if (!found) {
    // Ask the typed lookups for their "closest ids" message.
    try {
      cat.motor(id);
    } catch (const UsageError&) {
      throw UsageError("no catalog entry with id '" + id + "' (see 'dynosize catalog list')");
    }
  }
  return out;
}

}  // namespace dynosize::api
