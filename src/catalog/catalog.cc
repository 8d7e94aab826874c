#include "catalog/catalog.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <set>
#include <sstream>

#include "catalog/conventions.h"
#include "catalog/prop_families.h"
#include "catalog/esc_prior.h"
#include "catalog/motor_credibility.h"
#include "catalog/in_system.h"
#include "catalog/prop_credibility.h"
#include "catalog/schema.h"
#include "common/error.h"
#include "common/units.h"
#include "model/physics.h"

namespace dynosize {

namespace {

constexpr std::size_t kMaxProblemsInError = 20;
// Relative rounding of a ratio of two numbers written with 6 significant digits (each within
// 5e-6 of its value): 1e-5.
constexpr double kCatalogRoundingRel = 1e-5;

std::string ValueText(const Json& v) {
  std::string s = v.dump();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

bool ValidId(const std::string& id) {
  if (id.empty() || id.size() > 120) return false;
  return std::all_of(id.begin(), id.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
           c == '+';
  });
}

bool TypeMatches(const KeySpec& spec, const Json& v) {
  switch (spec.type) {
    case ValueType::kNumber: return v.is_number();
    case ValueType::kInteger:
      return v.is_number_integer() ||
             (v.is_number_float() && std::floor(v.get<double>()) == v.get<double>());
    case ValueType::kString: return v.is_string();
    case ValueType::kBool: return v.is_boolean();
    case ValueType::kObject: return v.is_object();
    case ValueType::kArray: return v.is_array();
  }
  return false;
}

// Checks one value against its spec; returns the violated rule or "".
std::string CheckValue(const KeySpec& spec, const Json& v) {
  if (!TypeMatches(spec, v)) return "must be " + DescribeRule(spec);
  if (spec.type == ValueType::kNumber || spec.type == ValueType::kInteger) {
    const double x = v.get<double>();
    const bool below = spec.min_exclusive ? !(x > spec.min) : !(x >= spec.min);
    const bool above = spec.max_exclusive ? !(x < spec.max) : !(x <= spec.max);
    if (!std::isfinite(x) || below || above) return "must be " + DescribeRule(spec);
  }
  if (spec.type == ValueType::kString && !spec.choices.empty() &&
      std::find(spec.choices.begin(), spec.choices.end(), v.get<std::string>()) ==
          spec.choices.end()) {
    return "must be " + DescribeRule(spec);
  }
  return "";
}

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t sub = prev[j - 1] + (std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

double Get(const Json& e, const char* key, double fallback) {
  const auto it = e.find(key);
  return it == e.end() ? fallback : it->get<double>();
}

std::optional<double> GetOpt(const Json& e, const char* key) {
  const auto it = e.find(key);
  if (it == e.end()) return std::nullopt;
  return it->get<double>();
}

// Checks a numeric array; returns the violated rule or "".
std::string CheckNumberArray(const Json& a, bool increasing, double min_value) {
  if (!a.is_array() || a.empty()) return "must be a non-empty array of numbers";
  double prev = -1e300;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_number()) return "element " + std::to_string(i) + " must be a number";
    const double x = a[i].get<double>();
    if (!std::isfinite(x)) return "element " + std::to_string(i) + " must be finite";
    if (x < min_value) {
      return "element " + std::to_string(i) + " = " + ValueText(a[i]) + " must be >= " +
             ValueText(Json(min_value));
    }
    if (increasing && i > 0 && !(x > prev)) {
      return "element " + std::to_string(i) + " = " + ValueText(a[i]) +
             " must be greater than the one before (strictly increasing)";
    }
    prev = x;
  }
  return "";
}

// Validates {"rpm"|"j": [...], "ct": [...], "cp": [...]} (+ "rpm": number for a sweep);
// `bad(key, rule)` records problems under `path`.
template <typename Bad>
void CheckCoefficientTable(const Json& t, const std::string& path, bool sweep, Bad bad) {
  const char* axis = sweep ? "j" : "rpm";
  for (auto k = t.begin(); k != t.end(); ++k) {
    if (k.key() != axis && k.key() != "ct" && k.key() != "cp" && !(sweep && k.key() == "rpm")) {
      bad(path + "." + k.key(), std::string("unknown key: allowed are ") +
                                    (sweep ? "rpm, j, ct, cp" : "rpm, ct, cp"));
    }
  }
  if (sweep) {
    const auto r = t.find("rpm");
    if (r == t.end() || !r->is_number() || !(r->get<double>() > 0)) {
      bad(path + ".rpm", "must be a number > 0 (the speed of the sweep)");
    }
  }
  std::size_t n = 0;
  for (const char* key : {axis, "ct", "cp"}) {
    const auto a = t.find(key);
    if (a == t.end()) {
      bad(path + "." + key, "missing");
      continue;
    }
    const bool is_axis = std::string(key) == axis;
    const std::string rule = CheckNumberArray(*a, is_axis, is_axis ? 0.0 : -10.0);
    if (!rule.empty()) {
      bad(path + "." + key, rule);
    } else if (n == 0) {
      n = a->size();
    } else if (a->size() != n) {
      bad(path + "." + key, "must have as many elements as " + std::string(axis) + " (" +
                                std::to_string(n) + "), has " + std::to_string(a->size()));
    }
  }
}

DataTier InferTierFromValues(ComponentKind kind, const Json& src);

DataTier TierFromName(const std::string& name) {
  const auto& names = TierNames();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<DataTier>(i);
  }
  return DataTier::kAssumed;
}

// The tier of an entry that does not state one: from how its performance numbers were obtained
// (source.values of the key that carries the performance): measured/fitted -> measured,
// computed -> manufacturer_computed, datasheet/derived -> manufacturer_stated, assumed or not
// stated -> assumed. DriveCalc's numbers are user submissions whatever the method (its
// measurement points included): a data set that names DriveCalc is at best user_contributed.
DataTier InferTier(ComponentKind kind, const Json& src) {
  DataTier t = InferTierFromValues(kind, src);
  const std::string dataset = src.value("dataset", std::string());
  if (dataset.find("DriveCalc") != std::string::npos && t < DataTier::kUserContributed) {
    t = DataTier::kUserContributed;
  }
  return t;
}

// An entry's assumed keys and tier from its (valid) source object: the tier stated, else inferred.
void FillSourceFields(ComponentKind kind, const Json& src, EntryBase* base) {
  if (const auto vals = src.find("values"); vals != src.end()) {
    for (auto m = vals->begin(); m != vals->end(); ++m) {
      if (m->get<std::string>() == "assumed") base->assumed_keys.push_back(m.key());
    }
  }
  if (const auto t = src.find("tier"); t != src.end()) {
    base->tier = TierFromName(t->get<std::string>());
    base->tier_stated = true;
  } else {
    base->tier = InferTier(kind, src);
  }
}

DataTier InferTierFromValues(ComponentKind kind, const Json& src) {
  const auto vals = src.find("values");
  if (vals == src.end() || !vals->is_object()) return DataTier::kAssumed;
  std::vector<const char*> keys;
  switch (kind) {
    case ComponentKind::kMotor: keys = {"rm_ohm", "ke_v_s_per_rad", "kv_rpm_per_v"}; break;
    case ComponentKind::kEsc: keys = {"c1", "resc_ohm"}; break;
    case ComponentKind::kProp:
      keys = {"static_table", "j_tables", "ct_static", "thrust_law_n"};
      break;
    case ComponentKind::kBattery: keys = {"ri_ohm", "capacity_ah"}; break;
  }
  for (const char* k : keys) {
    const auto m = vals->find(k);
    if (m == vals->end() || !m->is_string()) continue;
    return MethodTier(m->get<std::string>());
  }
  return DataTier::kAssumed;
}

MotorEntry MotorFromJson(const Json& e, EntryBase base) {
  MotorEntry m;
  static_cast<EntryBase&>(m) = std::move(base);
  MotorParams& p = m.params;
  p.type = e["type"].get<std::string>() == "brushed" ? MotorType::kBrushed : MotorType::kBldc;
  m.kv_rpm_per_v = GetOpt(e, "kv_rpm_per_v");
  const double ke_from_kv =
      m.kv_rpm_per_v ? (p.type == MotorType::kBldc ? KeFromKvBldc(*m.kv_rpm_per_v)
                                                   : KeFromKvBrushed(*m.kv_rpm_per_v))
                     : 0.0;
  p.ke_v_s_per_rad = Get(e, "ke_v_s_per_rad", ke_from_kv);
  // Section 5: ideal waveforms give KT = sqrt(27/10)*KE; a DC machine KT = KE (SI).
  p.kt_nm_per_a = Get(e, "kt_nm_per_a", p.type == MotorType::kBldc
                                            ? kPacPerVllIrms * p.ke_v_s_per_rad
                                            : p.ke_v_s_per_rad);
  p.rm_ohm = e["rm_ohm"].get<double>();
  p.io_a = e["io_a"].get<double>();
  p.max_current_a = Get(e, "max_current_a", p.max_current_a);
  p.max_power_w = Get(e, "max_power_w", p.max_power_w);
  // Peak ratings with their duration (issue 51): read by a mission through ApplyPeakRatings only.
  p.peak_current_a = Get(e, "peak_current_a", 0.0);
  p.peak_power_w = Get(e, "peak_power_w", 0.0);
  p.peak_duration_s = Get(e, "peak_duration_s", 0.0);
  p.io1_a_s_per_rad = Get(e, "io1_a_s_per_rad", 0.0);
  p.rth_k_per_w = Get(e, "rth_k_per_w", 0.0);
  p.kt_droop_per_a = Get(e, "kt_droop_per_a", 0.0);
  m.mass_kg = GetOpt(e, "mass_kg");
  m.loss_torque_nm = GetOpt(e, "loss_torque_nm");
  m.loss_torque_per_omega_nm_s_per_rad = GetOpt(e, "loss_torque_per_omega_nm_s_per_rad");
  m.gear.ratio = Get(e, "gear_ratio", 1.0);
  m.gear.efficiency = Get(e, "gear_efficiency", 1.0);
  if (const auto r = e.find("estimate_ranges"); r != e.end() && r->is_object()) {
    auto range = [&](const char* key) -> std::optional<std::pair<double, double>> {
      const auto k = r->find(key);
      if (k == r->end()) return std::nullopt;
      return std::make_pair((*k)[0].get<double>(), (*k)[1].get<double>());
    };
    m.rm_range_ohm = range("rm_ohm");
    m.io_range_a = range("io_a");
    m.kv_range_rpm_per_v = range("kv_rpm_per_v");
  }
  return m;
}

EscEntry EscFromJson(const Json& e, EntryBase base) {
  EscEntry x;
  static_cast<EntryBase&>(x) = std::move(base);
  EscParams& p = x.params;
  p.resc_ohm = e["resc_ohm"].get<double>();
  p.c1 = e["c1"].get<double>();
  p.c0 = e["c0"].get<double>();
  p.tr_sat = e["tr_sat"].get<double>();
  p.sat_slope = e["sat_slope"].get<double>();
  p.max_current_a = Get(e, "max_current_a", p.max_current_a);
  if (e.contains("vdc_max_v")) {
    p.vdc_max_v = e["vdc_max_v"].get<double>();
  } else if (e.contains("cells_max")) {
    p.vdc_max_v = kLipoFullCellV * e["cells_max"].get<double>();  // its largest LiPo pack, full
  } else {
    p.vdc_max_v = DefaultEscPrior().unrated_vdc_max_v;
    x.assumed_keys.push_back("vdc_max_v");
  }
  p.vdc_min_v = Get(e, "vdc_min_v", 0.0);
  p.peak_current_a = Get(e, "ipeak_a", 0.0);
  p.peak_duration_s = Get(e, "peak_duration_s", 0.0);
  p.deadband = Get(e, "deadband", 0.0);
  p.rsupply_ohm = Get(e, "rsupply_ohm", 0.0);
  x.mass_kg = GetOpt(e, "mass_kg");
  return x;
}

PropEntry PropFromJson(const Json& e, EntryBase base) {
  PropEntry x;
  static_cast<EntryBase&>(x) = std::move(base);
  x.diameter_m = e["diameter_m"].get<double>();
  x.pitch_m = GetOpt(e, "pitch_m");
  x.mass_kg = GetOpt(e, "mass_kg");
  if (const auto b = e.find("blades"); b != e.end()) x.blades = b->get<int>();
  x.max_rpm = GetOpt(e, "max_rpm");
  x.rpm_min = GetOpt(e, "rpm_min");
  x.rpm_max = GetOpt(e, "rpm_max");
  if (const auto f = e.find("folding"); f != e.end()) x.folding = f->get<bool>();
  x.power_derate_factor = Get(e, "power_derate_factor", 1.0);
  if (e.contains("thrust_law_n")) {
    PropPowerLaw law;
    law.thrust_law_n = e["thrust_law_n"].get<double>();
    law.thrust_law_exp = e["thrust_law_exp"].get<double>();
    law.power_law_w = e["power_law_w"].get<double>();
    law.power_law_exp = e["power_law_exp"].get<double>();
    law.rho_kg_m3 = e["law_rho_kg_m3"].get<double>();
    x.power_law = law;
  }
  x.ct_static = GetOpt(e, "ct_static");
  x.cp_static = GetOpt(e, "cp_static");
  if (const auto st = e.find("static_table"); st != e.end()) {
    x.static_table.rpm = (*st)["rpm"].get<std::vector<double>>();
    x.static_table.ct = (*st)["ct"].get<std::vector<double>>();
    x.static_table.cp = (*st)["cp"].get<std::vector<double>>();
  }
  if (const auto jt = e.find("j_tables"); jt != e.end()) {
    for (const Json& t : *jt) {
      PropSweep sw;
      sw.rpm = t["rpm"].get<double>();
      sw.j = t["j"].get<std::vector<double>>();
      sw.ct = t["ct"].get<std::vector<double>>();
      sw.cp = t["cp"].get<std::vector<double>>();
      x.j_tables.push_back(std::move(sw));
    }
  }
  return x;
}

BatteryEntry BatteryFromJson(const Json& e, EntryBase base) {
  BatteryEntry x;
  static_cast<EntryBase&>(x) = std::move(base);
  x.mass_kg = GetOpt(e, "mass_kg");
  static const std::pair<const char*, BatteryChemistry> kChem[] = {
      {"lipo", BatteryChemistry::kLiPo}, {"liion", BatteryChemistry::kLiIon},
      {"lifepo4", BatteryChemistry::kLiFePo4}, {"nimh", BatteryChemistry::kNiMh},
      {"nicd", BatteryChemistry::kNiCd}};
  const std::string chem = e["chemistry"].get<std::string>();
  for (const auto& [name, value] : kChem) {
    if (chem == name) x.chemistry = value;
  }
  x.cells_series = e["cells_series"].get<int>();
  if (const auto p = e.find("cells_parallel"); p != e.end()) x.cells_parallel = p->get<int>();
  x.capacity_ah = e["capacity_ah"].get<double>();
  x.voltage_nominal_v = e["voltage_nominal_v"].get<double>();
  x.ri_ohm = GetOpt(e, "ri_ohm");
  x.max_current_a = GetOpt(e, "max_current_a");
  x.peak_current_a = GetOpt(e, "peak_current_a");
  return x;
}

// source: {dataset (required), reference, values: {key: method}, note, tier}.
template <typename Bad>
void CheckSource(const Json& e, const Json* src, Bad bad) {
  for (auto k = src->begin(); k != src->end(); ++k) {
    const std::string& sk = k.key();
    if (sk == "dataset" || sk == "reference" || sk == "note") {
      if (!k->is_string()) bad("source." + sk, "must be a string", &*k);
    } else if (sk == "values") {
      if (!k->is_object()) {
        bad("source.values", "must be an object {key: method}");
        continue;
      }
      for (auto m = k->begin(); m != k->end(); ++m) {
        const auto& methods = ProvenanceMethods();
        if (!e.contains(m.key())) {
          bad("source.values." + m.key(), "names a key the entry does not have");
        } else if (!m->is_string() ||
                   std::find(methods.begin(), methods.end(), m->get<std::string>()) ==
                       methods.end()) {
          bad("source.values." + m.key(),
              "must be one of datasheet, measured, computed, fitted, derived, assumed", &*m);
        }
      }
    } else if (sk == "tier") {
      const auto& tiers = TierNames();
      if (!k->is_string() ||
          std::find(tiers.begin(), tiers.end(), k->get<std::string>()) == tiers.end()) {
        bad("source.tier",
            "must be one of measured, manufacturer_computed, manufacturer_stated, "
            "user_contributed, assumed",
            &*k);
      }
    } else {
      bad("source." + sk,
          "unknown key: allowed are dataset, reference, values, note, tier", &*k);
    }
  }
  if (!src->contains("dataset")) bad("source.dataset", "missing (required)");
}

// Performance data and tables of a propeller; `problems` gets lines under `where`.
template <typename Bad>
void CheckPropKeys(const Json& e, const std::string& where, Bad bad,
                   std::vector<std::string>* problems) {
  auto bad_path = [&](const std::string& key, const std::string& rule) {
    problems->push_back(where + ": key '" + key + "': " + rule);
  };
  if (const auto st = e.find("static_table"); st != e.end() && st->is_object()) {
    CheckCoefficientTable(*st, "static_table", false, bad_path);
  }
  if (const auto jt = e.find("j_tables"); jt != e.end() && jt->is_array()) {
    double prev_rpm = 0.0;
    for (std::size_t k = 0; k < jt->size(); ++k) {
      const std::string path = "j_tables[" + std::to_string(k) + "]";
      const Json& t = (*jt)[k];
      if (!t.is_object()) {
        bad_path(path, "must be an object {rpm, j, ct, cp}");
        continue;
      }
      CheckCoefficientTable(t, path, true, bad_path);
      const auto r = t.find("rpm");
      if (r != t.end() && r->is_number()) {
        if (!(r->get<double>() > prev_rpm)) {
          bad_path(path + ".rpm", "sweeps must be sorted by strictly increasing rpm");
        }
        prev_rpm = r->get<double>();
      }
    }
  }
  const bool t_law = e.contains("thrust_law_n"), p_law = e.contains("power_law_w");
  for (const char* k : {"thrust_law_exp", "power_law_exp", "law_rho_kg_m3"}) {
    if ((t_law || p_law) && !e.contains(k)) bad(k, "missing: the power laws need it");
  }
  if (t_law != p_law) bad(t_law ? "power_law_w" : "thrust_law_n",
                          "missing: thrust and power laws come together");
  if (e.contains("ct_static") != e.contains("cp_static")) {
    bad(e.contains("ct_static") ? "cp_static" : "ct_static",
        "missing: ct_static and cp_static come together");
  }
  if (!t_law && !e.contains("ct_static") && !e.contains("static_table") &&
      !e.contains("j_tables")) {
    bad("thrust_law_n", "missing: a propeller needs performance data (power laws, "
                        "ct_static/cp_static, static_table or j_tables)");
  }
}

// gear_ratio and gear_efficiency of a motor (model/gear.h): an efficiency only with a gear, a
// gear only with its efficiency, and a geared entry's Kv the motor's (motor_credibility.h,
// kGearedKmRatioMax).
template <typename Bad>
void CheckGear(const Json& e, Bad bad) {
  auto num = [&e](const char* k) {
    const auto it = e.find(k);
    return it != e.end() && it->is_number() ? std::optional<double>(it->get<double>()) : std::nullopt;
  };
  const std::optional<double> ratio = num("gear_ratio"), eta = num("gear_efficiency");
  const bool geared = ratio && *ratio > 1.0;
  if (geared && !eta) bad("gear_efficiency", "missing: a motor with gear_ratio > 1 needs its gearbox's efficiency");
  if (!geared && eta && *eta != 1.0) bad("gear_efficiency", "must be 1 without a gear (gear_ratio 1 or absent)");
  if (!geared) return;
  const std::optional<double> kv = num("kv_rpm_per_v"), mass = num("mass_kg");
  std::optional<double> r_dc = num("rm_dc_ohm");
  if (!r_dc && num("rm_ohm") && e.value("type", std::string()) == "bldc") r_dc = *num("rm_ohm") / kRmsPerDcResistance;
  if (!kv || !r_dc || !mass) return;
  const double k = GearedKmRatio(*kv, *r_dc, *mass);
  if (k > kGearedKmRatioMax) {
    std::ostringstream rule;
    rule << std::setprecision(3) << "a geared motor's Kv must be the motor's, not the output shaft's: its motor constant Km = "
         << MotorConstantDc(*kv, *r_dc) << " N*m/sqrt(W) is " << k << " x a typical motor of its mass (at most " << kGearedKmRatioMax
         << " x; an output-shaft Kv makes it gear_ratio times too large: motor_credibility.h)";
    bad("kv_rpm_per_v", rule.str());
  }
}

// estimate_ranges of a motor: {"rm_ohm" | "io_a" | "kv_rpm_per_v": [p10, p90]}, finite,
// 0 < p10 <= the entry's value <= p90.
template <typename Bad>
void CheckEstimateRanges(const Json& e, Bad bad) {
  const auto r = e.find("estimate_ranges");
  if (r == e.end()) return;
  if (!r->is_object()) {
    bad("estimate_ranges", "must be an object {key: [p10, p90]}");
    return;
  }
  for (auto f = r->begin(); f != r->end(); ++f) {
    const std::string path = "estimate_ranges." + f.key();
    if (f.key() != "rm_ohm" && f.key() != "io_a" && f.key() != "kv_rpm_per_v") {
      bad(path, "unknown key: allowed are rm_ohm, io_a, kv_rpm_per_v");
      continue;
    }
    const auto v = e.find(f.key());
    const bool pair = f->is_array() && f->size() == 2 && (*f)[0].is_number() && (*f)[1].is_number();
    if (!pair || v == e.end() || !v->is_number() || !((*f)[0].get<double>() > 0) ||
        !((*f)[0].get<double>() <= v->get<double>()) || !(v->get<double>() <= (*f)[1].get<double>()) ||
        !std::isfinite((*f)[1].get<double>())) {
      bad(path, "must be [p10, p90] with 0 < p10 <= " + f.key() + " <= p90, found " + ValueText(*f));
    }
  }
}

// test_points of a motor (published operating points).
template <typename Bad>
void CheckTestPoints(const Json& e, Bad bad) {
  if (const auto tp = e.find("test_points"); tp != e.end() && tp->is_array()) {
    for (std::size_t k = 0; k < tp->size(); ++k) {
      const std::string path = "test_points[" + std::to_string(k) + "]";
      const Json& pt = (*tp)[k];
      if (!pt.is_object()) {
        bad(path, "must be an object {vdc_v, idc_a, throttle, rpm, torque_nm, thrust_n, prop}");
        continue;
      }
      for (const char* req : {"vdc_v", "idc_a"}) {
        if (!pt.contains(req)) bad(path + "." + req, "missing (required)");
      }
      for (auto f = pt.begin(); f != pt.end(); ++f) {
        const std::string& fk = f.key();
        if (fk == "prop") {
          if (!f->is_string()) bad(path + ".prop", "must be a string");
          continue;
        }
        double lo = 0, hi = 1e7;
        if (fk == "throttle") hi = 1;
        else if (fk != "vdc_v" && fk != "idc_a" && fk != "rpm" && fk != "torque_nm" &&
                 fk != "thrust_n") {
          bad(path + "." + fk, "unknown key: allowed are vdc_v, idc_a, throttle, rpm, "
                               "torque_nm, thrust_n, prop");
          continue;
        }
        if (!f->is_number() || !std::isfinite(f->get<double>()) || f->get<double>() < lo ||
            f->get<double>() > hi) {
          std::ostringstream rule;
          rule << "must be a number in [" << lo << ", " << hi << "], found "
               << ValueText(*f);
          bad(path + "." + fk, rule.str());
        }
      }
    }
  }
}

}  // namespace

PropEntry PropEntryFromJson(const Json& e) {
  EntryBase base;
  base.id = e.value("id", std::string());
  base.name = e.value("name", std::string());
  base.json = e;
  if (const auto src = e.find("source"); src != e.end() && src->is_object()) {
    FillSourceFields(ComponentKind::kProp, *src, &base);
  }
  return PropFromJson(e, std::move(base));
}

template <typename Entry>
void Catalog::Put(std::vector<Entry>* entries, ComponentKind kind, Entry entry) {
  const auto it = index_.find(entry.id);
  if (it != index_.end() && it->second.first == kind) {
    (*entries)[it->second.second] = std::move(entry);  // an override (AddDocument checked it)
    return;
  }
  index_[entry.id] = {kind, entries->size()};
  entries->push_back(std::move(entry));
}

// Physics at the door (docs/model.md section 10, model/physics.h, catalog/prop_credibility.h): an
// entry that creates energy or beats momentum theory is refused, whatever its source.
std::string Catalog::AddEntry(ComponentKind kind, const Json& e, EntryBase base) {
  const std::string id = base.id;
  switch (kind) {
    case ComponentKind::kMotor: {
      MotorEntry m = MotorFromJson(e, std::move(base));
      // Catalog numbers carry 6 significant digits: a KT written as sqrt(27/10)*KE may exceed
      // it by the rounding of two numbers (< 1e-5 relative). Such a KT is on the boundary of
      // docs/model.md section 10, and is set exactly onto it so that no point can gain energy from
      // the last digit.
      MotorParams& p = m.params;
      const double kt_max = MaxKtPerKe(p.type) * p.ke_v_s_per_rad;
      if (p.kt_nm_per_a > kt_max && p.kt_nm_per_a <= kt_max * (1.0 + kCatalogRoundingRel)) {
        p.kt_nm_per_a = kt_max;
      }
      const std::string v = MotorEnergyViolation(p);
      if (!v.empty()) return "creates energy: " + v;
      if (in_system_law_) {
        const InSystemApplicability a = InSystemApplicabilityOf(m);
        if (a.any()) {
          m.datasheet_params = p;
          p = InSystemMotorParams(p, a.datasheet, *a.law, a.r, a.io);
        }
      }
      Put(&motors_, kind, std::move(m));
      break;
    }
    case ComponentKind::kEsc: {
      EscEntry x = EscFromJson(e, std::move(base));
      const std::string v = EscEnergyViolation(x.params);
      if (!v.empty()) return "creates energy: " + v;
      Put(&escs_, kind, std::move(x));
      break;
    }
    case ComponentKind::kProp: {
      PropEntry x = PropFromJson(e, std::move(base));
      if (x.rpm_min && x.rpm_max && !(*x.rpm_max >= *x.rpm_min)) {
        return "key 'rpm_max' = " + ValueText(e["rpm_max"]) + ": must be >= rpm_min " +
               ValueText(e["rpm_min"]);
      }
      const std::string v = PropMomentumViolation(x);
      if (!v.empty()) return v;
      Put(&props_, kind, std::move(x));
      break;
    }
    case ComponentKind::kBattery: {
      BatteryEntry x = BatteryFromJson(e, std::move(base));
      Put(&batteries_, kind, std::move(x));
      break;
    }
  }
  return "";
}

// An id read a second time: within one folder always a duplicate; from a later folder (one the
// user added on top) an error naming both files unless overrides are allowed, and then only by an
// entry of the same kind. "" when the new entry may replace the earlier one.
std::string Catalog::ClashRule(const IdOrigin& prev, ComponentKind kind, const std::string& id) const {
  if (prev.folder == folder_) return "duplicate id: already used in " + prev.where;
  if (!override_ids_) {
    return "clashes with " + prev.where + " (a folder added on top may not redefine an id: rename "
           "one of them, or let the added entry win with --override)";
  }
  const ComponentKind prev_kind = index_.at(id).first;
  if (prev_kind != kind) {
    return "cannot override " + prev.where + ": " + KindNoun(prev_kind) + " there, " + KindNoun(kind) +
           " here (an override must be of the same kind)";
  }
  return "";
}

void Catalog::AddDocument(const Json& doc, const std::string& file,
                          std::vector<std::string>* problems) {
  if (!doc.is_object()) {
    problems->push_back(file + ": the top level must be an object with arrays \"motors\", "
                               "\"escs\", \"props\" and/or \"batteries\"");
    return;
  }
  static const ComponentKind kKinds[] = {ComponentKind::kMotor, ComponentKind::kEsc,
                                         ComponentKind::kProp, ComponentKind::kBattery};
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    const bool known = std::any_of(std::begin(kKinds), std::end(kKinds), [&](ComponentKind k) {
      return it.key() == KindArrayName(k);
    });
    if (!known && it.key() != "comment" && it.key() != "prop_families") {
      problems->push_back(file + ": unknown top-level key \"" + it.key() +
                          "\": allowed are motors, escs, props, batteries, prop_families, comment");
    }
  }
  if (const auto fam = doc.find("prop_families"); fam != doc.end()) ReadPropFamilies(*fam, file, &prop_families_, problems);
  for (ComponentKind kind : kKinds) {
    const auto arr = doc.find(KindArrayName(kind));
    if (arr == doc.end()) continue;
    if (!arr->is_array()) {
      problems->push_back(file + ": \"" + KindArrayName(kind) + "\" must be an array");
      continue;
    }
    const auto& schema = SchemaFor(kind);
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const Json& e = (*arr)[i];
      std::string where = file + ": " + KindArrayName(kind) + "[" + std::to_string(i) + "]";
      if (!e.is_object()) {
        problems->push_back(where + ": must be an object, found " + ValueText(e));
        continue;
      }
      const auto id_it = e.find("id");
      std::string id;
      if (id_it != e.end() && id_it->is_string()) {
        id = id_it->get<std::string>();
        where += " id=" + id;
      }
      const std::size_t before = problems->size();
      // One problem line: file, entry, key, value (when present) and the rule.
      auto bad = [&](const std::string& key, const std::string& rule, const Json* value = nullptr) {
        if (!value && e.contains(key)) value = &e[key];
        problems->push_back(where + ": key '" + key + "'" +
                            (value ? " = " + ValueText(*value) : std::string()) + ": " + rule);
      };
      // Unknown keys, listed sorted.
      std::set<std::string> unknown;
      for (auto k = e.begin(); k != e.end(); ++k) {
        const bool in_schema = std::any_of(schema.begin(), schema.end(),
                                           [&](const KeySpec& s) { return s.key == k.key(); });
        if (!in_schema) unknown.insert(k.key());
      }
      for (const auto& k : unknown) bad(k, std::string("unknown key for a ") + KindNoun(kind));
      for (const KeySpec& spec : schema) {
        const auto v = e.find(spec.key);
        if (v == e.end()) {
          if (spec.required) bad(spec.key, "missing (required: " + spec.doc + ")");
          continue;
        }
        const std::string rule = CheckValue(spec, *v);
        if (!rule.empty()) bad(spec.key, rule);
      }
      if (id_it != e.end() && id_it->is_string() && !ValidId(id)) {
        bad("id", "must be 1-120 characters of letters, digits, _ - . +");
      }
      // source: {dataset (required), reference, values: {key: method}, note}.
      const auto src = e.find("source");
      if (src != e.end() && src->is_object()) CheckSource(e, &*src, bad);
      if (kind == ComponentKind::kMotor && !e.contains("ke_v_s_per_rad") &&
          !e.contains("kv_rpm_per_v")) {
        bad("ke_v_s_per_rad", "missing: a motor needs ke_v_s_per_rad or kv_rpm_per_v");
      }
      if (kind == ComponentKind::kProp) CheckPropKeys(e, where, bad, problems);
      if (kind == ComponentKind::kMotor) {
        CheckTestPoints(e, bad);
        CheckEstimateRanges(e, bad);
        CheckGear(e, bad);
      }
      if (kind == ComponentKind::kBattery) {
        const auto s_it = e.find("cells_series");
        const auto v_it = e.find("voltage_nominal_v");
        if (s_it != e.end() && v_it != e.end() && s_it->is_number() && v_it->is_number()) {
          const double per_cell = v_it->get<double>() / s_it->get<double>();
          if (per_cell < 0.9 || per_cell > 4.5) {
            bad("voltage_nominal_v", "gives " + ValueText(Json(per_cell)) +
                                         " V per cell: must be 0.9-4.5 V per cell in series");
          }
        }
      }
      std::optional<IdOrigin> replaced;
      if (!id.empty()) {
        if (const auto prev = id_file_.find(id); prev != id_file_.end()) {
          const std::string clash = ClashRule(prev->second, kind, id);
          if (clash.empty()) replaced = prev->second; else bad("id", clash);
        }
      }
      if (problems->size() != before) continue;

      // The entry is valid: convert it once, here, to SI parameters.
      id_file_[id] = IdOrigin{where, folder_};
      EntryBase base;
      base.id = id;
      base.name = e["name"].get<std::string>();
      base.file = file;
      base.json = e;
      FillSourceFields(kind, *src, &base);
      if (const auto x = e.find("exclude"); x != e.end()) base.exclude_reason = x->get<std::string>();
      const std::string violation = AddEntry(kind, e, std::move(base));
      if (!violation.empty()) {
        problems->push_back(where + ": " + violation);
        if (replaced) id_file_[id] = *replaced; else id_file_.erase(id);
      }
    }
  }
}

namespace {

std::vector<std::string> CatalogFiles(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw NoInputError(dir + ": no such catalog folder");
  std::vector<std::string> files;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    if (it->is_regular_file() && it->path().extension() == ".json") {
      files.push_back(it->path().string());
    }
  }
  if (ec) throw NoInputError(dir + ": cannot list the catalog folder: " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

std::vector<std::string> Catalog::Validate(const std::string& dir) {
  return Validate(CatalogFolders{dir, {}, false});
}

std::vector<std::string> Catalog::Validate(const CatalogFolders& folders) {
  Catalog catalog;
  std::vector<std::string> problems;
  catalog.AddFolders(folders, &problems);
  return problems;
}

void Catalog::AddFolders(const CatalogFolders& folders, std::vector<std::string>* problems) {
  override_ids_ = folders.override_ids;
  std::vector<std::string> dirs = {folders.base};
  dirs.insert(dirs.end(), folders.added.begin(), folders.added.end());
  // Every folder is listed before any is read, so that a missing one is reported first.
  std::vector<std::vector<std::string>> files;
  for (const auto& dir : dirs) files.push_back(CatalogFiles(dir));
  for (folder_ = 0; folder_ < dirs.size(); ++folder_) {
    if (files[folder_].empty()) {
      problems->push_back(dirs[folder_] + ": the catalog folder holds no .json file");
    }
    for (const auto& file : files[folder_]) {
      try {
        AddDocument(ReadJsonFile(file), file, problems);
      } catch (const DataError& e) {
        problems->push_back(e.what());
      }
    }
  }
  folder_ = 0;
}

Catalog Catalog::Load(const std::string& dir, bool in_system_law) {
  return Load(CatalogFolders{dir, {}, false}, in_system_law);
}

Catalog Catalog::Load(const CatalogFolders& folders, bool in_system_law) {
  Catalog catalog;
  catalog.in_system_law_ = in_system_law;
  std::vector<std::string> problems;
  catalog.AddFolders(folders, &problems);
  const std::string& dir = folders.base;
  if (!problems.empty()) {
    std::ostringstream msg;
    for (std::size_t i = 0; i < problems.size() && i < kMaxProblemsInError; ++i) {
      msg << (i ? "\n" : "") << problems[i];
    }
    if (problems.size() > kMaxProblemsInError) {
      msg << "\n(and " << problems.size() - kMaxProblemsInError
          << " more; run 'dynosize catalog validate"
          << (folders.added.empty() ? " " + dir : std::string(" with the same catalog flags"))
          << "' for all)";
    }
    throw DataError(msg.str());
  }
  return catalog;
}

template <typename Entry>
const Entry& Catalog::Find(const std::vector<Entry>& entries, ComponentKind kind,
                           const std::string& id) const {
  const auto it = index_.find(id);
  if (it != index_.end() && it->second.first == kind) return entries[it->second.second];
  std::string msg = std::string("unknown ") + KindNoun(kind) + " id '" + id + "'";
  if (it != index_.end()) {
    msg += ": that id is a " + std::string(KindNoun(it->second.first));
  } else if (!entries.empty()) {
    std::vector<std::pair<std::size_t, std::string>> near;
    for (const auto& e : entries) near.emplace_back(EditDistance(id, e.id), e.id);
    const std::size_t k = std::min<std::size_t>(3, near.size());
    std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(k), near.end());
    msg += "; closest: ";
    for (std::size_t i = 0; i < k; ++i) msg += (i ? ", " : "") + near[i].second;
    msg += " (see 'dynosize catalog list --kind " + std::string(KindArrayName(kind)) + "')";
  } else {
    msg += std::string(": the catalog has no ") + KindArrayName(kind);
  }
  throw UsageError(msg);
}

const MotorEntry& Catalog::motor(const std::string& id) const {
  return Find(motors_, ComponentKind::kMotor, id);
}
const EscEntry& Catalog::esc(const std::string& id) const {
  return Find(escs_, ComponentKind::kEsc, id);
}
const PropEntry& Catalog::prop(const std::string& id) const {
  return Find(props_, ComponentKind::kProp, id);
}
const BatteryEntry& Catalog::battery(const std::string& id) const {
  return Find(batteries_, ComponentKind::kBattery, id);
}

}  // namespace dynosize
