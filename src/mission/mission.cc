#include "mission/mission.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "common/atmosphere.h"
#include "common/error.h"
#include "common/units.h"

namespace dynosize {

const char* SegmentTypeName(SegmentType type) {
  switch (type) {
    case SegmentType::kHover: return "hover";
    case SegmentType::kClimb: return "climb";
    case SegmentType::kCruise: return "cruise";
    case SegmentType::kShaft: return "shaft";
  }
  return "?";
}

const char* ObjectiveTypeName(ObjectiveType type) {
  switch (type) {
    case ObjectiveType::kMaxEndurance: return "max_endurance";
    case ObjectiveType::kMinEnergy: return "min_energy";
    case ObjectiveType::kMaxEfficiency: return "max_efficiency";
  }
  return "?";
}

std::vector<PropSize> OfferedSizes(const Mission& m, const std::vector<PropSizing>& catalog_families, int g) {
  std::vector<PropSize> out;
  std::set<std::string> ids;
  for (const PropSize& s : GroupSizedProps(m, g)) {
    if (ids.insert(SizedPropId(s)).second) out.push_back(s);
  }
  if (!m.groups.empty() && m.groups[g].fixed()) return out;
  const std::optional<double> d_max = GroupMaxPropDiameterM(m, g);
  const std::optional<std::vector<PropSizing>>& own = GroupPropSizing(m, g);
  if (!own && !d_max) return out;
  for (const PropSizing& f : own ? *own : catalog_families) {
    for (const PropSize& s : SizingGrid(f, d_max.value_or(std::numeric_limits<double>::infinity()))) {
      if (ids.insert(SizedPropId(s)).second) out.push_back(s);
    }
  }
  return out;
}

double DisplayObjective(const Mission& m, double objective) {
  switch (m.objective.type) {
    case ObjectiveType::kMaxEndurance: return objective / 60.0;
    case ObjectiveType::kMinEnergy: return objective;
    case ObjectiveType::kMaxEfficiency: return 100.0 * objective;
  }
  return objective;
}

const char* DisplayUnit(const Mission& m) {
  switch (m.objective.type) {
    case ObjectiveType::kMaxEndurance: return " min";
    case ObjectiveType::kMinEnergy: return " Wh";
    case ObjectiveType::kMaxEfficiency: return " %";
  }
  return "";
}

namespace {

std::string ValueText(const Json& v) {
  std::string s = v.dump();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

// One object of the mission file at a JSON path, read strictly.
class Reader {
 public:
  Reader(const Json& obj, std::string file, std::string path)
      : obj_(obj), file_(std::move(file)), path_(std::move(path)) {
    if (!obj_.is_object()) Fail(path_, obj_, "must be an object");
  }

  [[noreturn]] void Fail(const std::string& path, const Json& value, const std::string& rule) const {
    throw DataError(file_ + ": " + path + " = " + ValueText(value) + ": " + rule);
  }
  [[noreturn]] void FailMissing(const std::string& key, const std::string& rule) const {
    throw DataError(file_ + ": " + Path(key) + ": missing (" + rule + ")");
  }
  std::string Path(const std::string& key) const { return path_ + "." + key; }
  const std::string& file() const { return file_; }

  // Unknown keys are an error, listed sorted, with the valid keys.
  void AllowOnly(std::initializer_list<const char*> keys) const {
    std::set<std::string> allowed(keys.begin(), keys.end());
    std::set<std::string> unknown;
    for (auto it = obj_.begin(); it != obj_.end(); ++it) {
      if (!allowed.count(it.key())) unknown.insert(it.key());
    }
    if (unknown.empty()) return;
    std::string u, v;
    for (const auto& k : unknown) u += (u.empty() ? "" : ", ") + k;
    for (const auto& k : allowed) v += (v.empty() ? "" : ", ") + k;
    throw DataError(file_ + ": " + path_ + ": unknown key(s) " + u + " (valid: " + v + ")");
  }

  bool Has(const std::string& key) const { return obj_.contains(key); }
  const Json& At(const std::string& key) const { return obj_.at(key); }

  double Number(const std::string& key, double min, double max, bool min_exclusive,
                std::optional<double> fallback = std::nullopt) const {
    if (!Has(key)) {
      if (fallback) return *fallback;
      FailMissing(key, "a number is required");
    }
    return CheckNumber(Path(key), At(key), min, max, min_exclusive);
  }
  std::optional<double> OptNumber(const std::string& key, double min, double max,
                                  bool min_exclusive) const {
    if (!Has(key)) return std::nullopt;
    return CheckNumber(Path(key), At(key), min, max, min_exclusive);
  }
  double CheckNumber(const std::string& path, const Json& v, double min, double max,
                     bool min_exclusive) const {
    if (!v.is_number()) Fail(path, v, "must be a number");
    const double x = v.get<double>();
    const bool below = min_exclusive ? !(x > min) : !(x >= min);
    if (!std::isfinite(x) || below || !(x <= max)) {
      std::ostringstream rule;
      rule << "must be a number " << (min_exclusive ? "> " : ">= ") << min;
      if (std::isfinite(max)) rule << " and <= " << max;
      Fail(path, v, rule.str());
    }
    return x;
  }
  int Integer(const std::string& key, int min, int max, std::optional<int> fallback) const {
    if (!Has(key)) {
      if (fallback) return *fallback;
      FailMissing(key, "an integer is required");
    }
    const Json& v = At(key);
    if (!v.is_number_integer() || v.get<long long>() < min || v.get<long long>() > max) {
      Fail(Path(key), v, "must be an integer in [" + std::to_string(min) + ", " +
                             std::to_string(max) + "]");
    }
    return static_cast<int>(v.get<long long>());
  }
  bool Bool(const std::string& key, bool fallback) const {
    if (!Has(key)) return fallback;
    if (!At(key).is_boolean()) Fail(Path(key), At(key), "must be true or false");
    return At(key).get<bool>();
  }
  std::string String(const std::string& key, std::optional<std::string> fallback) const {
    if (!Has(key)) {
      if (fallback) return *fallback;
      FailMissing(key, "a string is required");
    }
    if (!At(key).is_string() || At(key).get<std::string>().empty()) {
      Fail(Path(key), At(key), "must be a non-empty string");
    }
    return At(key).get<std::string>();
  }
  // A number or a two-element [lo, hi] array (a free range).
  Range NumberOrRange(const std::string& key, double min, double max, bool min_exclusive) const {
    if (!Has(key)) FailMissing(key, "a number or a [min, max] range is required");
    const Json& v = At(key);
    if (v.is_array()) {
      if (v.size() != 2) Fail(Path(key), v, "a range must be [min, max]");
      Range r{CheckNumber(Path(key) + "[0]", v[0], min, max, min_exclusive),
              CheckNumber(Path(key) + "[1]", v[1], min, max, min_exclusive)};
      if (!(r.hi >= r.lo)) Fail(Path(key), v, "a range must have min <= max");
      return r;
    }
    const double x = CheckNumber(Path(key), v, min, max, min_exclusive);
    return Range{x, x};
  }

 private:
  const Json& obj_;
  std::string file_;
  std::string path_;
};

Segment ReadSegment(const Reader& r, const std::string& path) {
  Segment s;
  s.name = r.String("name", std::nullopt);
  const std::string type = r.String("type", std::nullopt);
  if (type == "hover") s.type = SegmentType::kHover;
  else if (type == "climb") s.type = SegmentType::kClimb;
  else if (type == "cruise") s.type = SegmentType::kCruise;
  else if (type == "shaft") s.type = SegmentType::kShaft;
  else r.Fail(r.Path("type"), r.At("type"), "must be one of climb, cruise, hover, shaft");
  switch (s.type) {
    case SegmentType::kHover:
      r.AllowOnly({"name", "type", "duration_s", "rotors", "group"});
      break;
    case SegmentType::kClimb:
      r.AllowOnly({"name", "type", "duration_s", "distance_m", "rate_m_s", "rotors", "group"});
      s.climb_rate_m_s = r.Number("rate_m_s", -50.0, 50.0, false);
      if (s.climb_rate_m_s == 0.0) r.Fail(r.Path("rate_m_s"), r.At("rate_m_s"), "must not be 0 (use a hover segment)");
      break;
    case SegmentType::kCruise:
      r.AllowOnly({"name", "type", "duration_s", "distance_m", "airspeed_m_s", "lift_to_drag", "lift_to_drag_of",
                   "rotors", "group"});
      s.airspeed_m_s = r.NumberOrRange("airspeed_m_s", 0.0, 150.0, true);
      s.lift_to_drag = r.Number("lift_to_drag", 1.0, 50.0, false, 0.0);
      // Whose L/D it is (mission.h, LiftToDragOf): "aircraft" (default) or "wing"; only with a
      // lift_to_drag (a multirotor cruise has no L/D to qualify).
      if (r.Has("lift_to_drag_of")) {
        const std::string of = r.String("lift_to_drag_of", std::nullopt);
        if (!r.Has("lift_to_drag")) {
          r.Fail(r.Path("lift_to_drag_of"), r.At("lift_to_drag_of"), "needs lift_to_drag (a cruise without a wing has no L/D)");
        }
        if (of == "aircraft") s.lift_to_drag_of = LiftToDragOf::kAircraft;
        else if (of == "wing") s.lift_to_drag_of = LiftToDragOf::kWing;
        else r.Fail(r.Path("lift_to_drag_of"), r.At("lift_to_drag_of"), "must be one of aircraft, wing");
      }
      break;
    case SegmentType::kShaft: {
      r.AllowOnly({"name", "type", "duration_s", "power_w", "torque_nm", "rpm", "group"});
      s.shaft_power_w = r.OptNumber("power_w", 0.0, 1e7, true);
      s.shaft_torque_nm = r.OptNumber("torque_nm", 0.0, 1e5, true);
      if (s.shaft_power_w.has_value() == s.shaft_torque_nm.has_value()) {
        throw DataError(r.file() + ": " + path + ": give exactly one of power_w and torque_nm");
      }
      const Range rpm = r.NumberOrRange("rpm", 0.0, 1e6, true);
      s.shaft_omega_rad_s = Range{RpmToRadPerSec(rpm.lo), RpmToRadPerSec(rpm.hi)};
      break;
    }
  }
  s.rotors_active = r.Integer("rotors", 1, 64, 0);
  s.group_name = r.String("group", std::string());
  s.duration_s = r.OptNumber("duration_s", 0.0, 1e7, true);
  if (r.Has("distance_m")) s.distance_m = r.Number("distance_m", 0.0, 1e8, true);
  if (s.duration_s.has_value() == s.distance_m.has_value()) {
    throw DataError(r.file() + ": " + path + ": give exactly one of duration_s and distance_m");
  }
  if (s.type == SegmentType::kCruise && s.distance_m && s.airspeed_m_s.lo <= 0) {
    throw DataError(r.file() + ": " + path + ": a cruise by distance needs airspeed_m_s > 0");
  }
  return s;
}

}  // namespace

// A propeller from its size alone: "DxP[xB]" or {"param": "DxP[xB]", "family": F} (rotor/family.h).
static PropSize ReadSizedProp(const Json& v, const std::string& name, const std::string& path) {
  const std::string rule = "a size \"DxP[xB]\" (inches) or {\"param\": \"DxP[xB]\", \"family\": F}";
  std::string param, family;
  if (v.is_string()) {
    param = v.get<std::string>();
  } else if (v.is_object()) {
    const Reader r(v, name, path);
    r.AllowOnly({"param", "family", "comment"});
    param = r.String("param", std::nullopt);
    family = r.String("family", std::string());
  } else {
    throw DataError(name + ": " + path + ": must be " + rule);
  }
  PropSize size;
  try {
    size = ParsePropParam(param);
  } catch (const UsageError& e) {
    throw DataError(name + ": " + path + ": " + e.what());
  }
  if (!family.empty() && FindFamily(family) == nullptr) {
    throw DataError(name + ": " + path + ".family = \"" + family + "\": not a bundled family (known: " + KnownFamilyIds() + ")");
  }
  size.family = family;
  return size;
}

// "prop_sizing": [{"family": F, "diameter_m": [lo, hi], "pitch_ratio": [lo, hi], "blades": [2, 3]}]
// (rotor/family.h PropSizing); pitch_ratio defaults to the family's measured blades' range,
// blades to [2].
static std::vector<PropSizing> ReadPropSizing(const Json& v, const std::string& name, const std::string& path) {
  if (!v.is_array() || v.size() > 8) {
    throw DataError(name + ": " + path + ": must be an array of at most 8 families "
                    "({\"family\", \"diameter_m\": [min, max], \"pitch_ratio\", \"blades\"}; [] for none)");
  }
  std::vector<PropSizing> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string at = path + "[" + std::to_string(i) + "]";
    const Reader r(v[i], name, at);
    r.AllowOnly({"family", "diameter_m", "pitch_ratio", "blades", "comment"});
    PropSizing s;
    s.family = r.String("family", std::nullopt);
    const RotorFamily* family = FindFamily(s.family);
    if (family == nullptr) {
      r.Fail(at + ".family", r.At("family"), "must be a bundled family (" + KnownFamilyIds() + ")");
    }
    const Range d = r.NumberOrRange("diameter_m", 0.0, 10.0, true);
    const Range pd = r.Has("pitch_ratio") ? r.NumberOrRange("pitch_ratio", 0.0, 2.0, true)
                                          : Range{family->pd_min, family->pd_max};
    s.diameter_min_m = d.lo;
    s.diameter_max_m = d.hi;
    s.pitch_ratio_min = pd.lo;
    s.pitch_ratio_max = pd.hi;
    s.blades = {2};
    if (r.Has("blades")) {
      const Json& b = r.At("blades");
      if (!b.is_array() || b.empty() || b.size() > 8) r.Fail(at + ".blades", b, "must be an array of 1-8 blade counts");
      s.blades.clear();
      for (const Json& x : b) {
        if (!x.is_number_integer() || x.get<int>() < 1 || x.get<int>() > 8) {
          r.Fail(at + ".blades", b, "each blade count must be an integer 1-8");
        }
        s.blades.push_back(x.get<int>());
      }
    }
    try {
      CheckPropSizing(s);
    } catch (const UsageError& e) {
      throw DataError(name + ": " + at + ": " + e.what());
    }
    out.push_back(std::move(s));
  }
  return out;
}

// A searched group's (or the vehicle's) "sized_props" and "prop_sizing".
static void ReadPropOffer(const Reader& g, const std::string& name, const std::string& path,
                          std::vector<PropSize>* sized, std::optional<std::vector<PropSizing>>* sizing) {
  if (g.Has("sized_props")) {
    const Json& list = g.At("sized_props");
    if (!list.is_array() || list.empty() || list.size() > 64) {
      g.Fail(path + ".sized_props", list, "must be an array of 1-64 sizes (\"DxP[xB]\" or {\"param\", \"family\"})");
    }
    for (std::size_t i = 0; i < list.size(); ++i) {
      sized->push_back(ReadSizedProp(list[i], name, path + ".sized_props[" + std::to_string(i) + "]"));
    }
  }
  if (g.Has("prop_sizing")) *sizing = ReadPropSizing(g.At("prop_sizing"), name, path + ".prop_sizing");
}

// "propulsion": {"lift": {"rotors": 4, "max_prop_diameter_m": 0.33, "idle_drag_area_m2": 0.01,
//                "motor": ID, "esc": ID, "prop": ID}, ...}; sets m->groups and m->vehicle.rotors.
static void ReadPropulsion(const Reader& top, const std::string& name, Mission* m) {
  const Json& p = top.At("propulsion");
  if (!p.is_object() || p.empty()) top.Fail("$.propulsion", p, "must be an object of named groups");
  int total = 0;
  for (auto it = p.begin(); it != p.end(); ++it) {
    const std::string path = "$.propulsion." + it.key();
    const Reader g(it.value(), name, path);
    g.AllowOnly({"rotors", "max_prop_diameter_m", "idle_drag_area_m2", "motor", "esc", "prop", "sized_props",
                 "prop_sizing", "comment"});
    PropulsionGroup grp;
    grp.name = it.key();
    if (grp.name.empty()) top.Fail("$.propulsion", p, "a group name must not be empty");
    grp.rotors = g.Integer("rotors", 1, 64, std::nullopt);
    grp.max_prop_diameter_m = g.OptNumber("max_prop_diameter_m", 0.0, 100.0, true);
    grp.idle_drag_area_m2 = g.Number("idle_drag_area_m2", 0.0, 100.0, false, 0.0);
    grp.motor_id = g.String("motor", std::string());
    grp.esc_id = g.String("esc", std::string());
    if (g.Has("prop") && g.At("prop").is_object()) {
      grp.sized_props.push_back(ReadSizedProp(g.At("prop"), name, path + ".prop"));
      grp.prop_id = SizedPropId(grp.sized_props.back());
    } else {
      grp.prop_id = g.String("prop", std::string());
    }
    for (const char* key : {"sized_props", "prop_sizing"}) {
      if (g.Has(key) && !grp.prop_id.empty()) {
        g.Fail(path + "." + key, g.At(key), "a fixed group's propeller is its \"prop\"");
      }
    }
    ReadPropOffer(g, name, path, &grp.sized_props, &grp.prop_sizing);
    const int given = !grp.motor_id.empty() + !grp.esc_id.empty() + !grp.prop_id.empty();
    if (given != 0 && given != 3) {
      g.Fail(path, it.value(), "give all of motor, esc and prop (a fixed group) or none (a searched group)");
    }
    total += grp.rotors;
    m->groups.push_back(std::move(grp));
  }
  if (total > 64) top.Fail("$.propulsion", p, "more than 64 rotors in all");
  m->vehicle.rotors = total;
}

// "vehicle" (and "propulsion", which sets the rotor count).
static void ReadVehicle(const Reader& top, const std::string& name, Mission* m) {
  if (!top.Has("vehicle")) top.FailMissing("vehicle", "an object is required");
  const Reader v(top.At("vehicle"), name, "$.vehicle");
  v.AllowOnly({"mass_kg", "rotors", "coaxial", "drag_area_m2", "drag_coefficient", "avionics_power_w",
               "max_prop_diameter_m", "sized_props", "prop_sizing"});
  m->vehicle.mass_kg = v.Number("mass_kg", 0.0, 1e4, true);
  if (top.Has("propulsion")) {
    ReadPropulsion(top, name, m);
    if (v.Has("rotors") && v.Integer("rotors", 1, 64, std::nullopt) != m->vehicle.rotors) {
      v.Fail("$.vehicle.rotors", v.At("rotors"), "must be the sum of the propulsion groups' rotors (" +
                                                     std::to_string(m->vehicle.rotors) + ") or left out");
    }
    for (const char* key : {"max_prop_diameter_m", "sized_props", "prop_sizing"}) {
      if (v.Has(key)) v.Fail(std::string("$.vehicle.") + key, v.At(key), std::string("give ") + key + " per propulsion group");
    }
  } else {
    m->vehicle.rotors = v.Integer("rotors", 1, 64, std::nullopt);
    ReadPropOffer(v, name, "$.vehicle", &m->vehicle.sized_props, &m->vehicle.prop_sizing);
  }
  m->vehicle.coaxial = v.Bool("coaxial", false);
  if (m->vehicle.coaxial && m->vehicle.rotors % 2 != 0) {
    v.Fail("$.vehicle.rotors", v.At("rotors"), "must be even for a coaxial vehicle");
  }
  m->vehicle.drag_area_m2 = v.Number("drag_area_m2", 0.0, 100.0, false, 0.0);
  m->vehicle.drag_coefficient = v.Number("drag_coefficient", 0.0, 5.0, false, 0.0);
  m->vehicle.avionics_power_w = v.Number("avionics_power_w", 0.0, 1e5, false, 0.0);
  m->vehicle.max_prop_diameter_m = v.OptNumber("max_prop_diameter_m", 0.0, 100.0, true);
}

// "air": the density, given or from the ISA at an altitude and temperature.
static void ReadAir(const Reader& top, const std::string& name, Mission* m) {
  if (top.Has("air")) {
    const Reader a(top.At("air"), name, "$.air");
    a.AllowOnly({"density_kg_m3", "altitude_m", "temperature_c"});
    if (a.Has("density_kg_m3")) {
      if (a.Has("altitude_m") || a.Has("temperature_c")) {
        throw DataError(name + ": $.air: give density_kg_m3 or altitude_m/temperature_c, not both");
      }
      m->rho_kg_m3 = a.Number("density_kg_m3", 0.3, 1.6, false);
    } else {
      const double h = a.Number("altitude_m", -500.0, 10000.0, false, 0.0);
      const double t = a.Number("temperature_c", -60.0, 60.0, false, 15.0);
      m->rho_kg_m3 = AirDensityKgM3(h, t);
      m->air_temperature_c = t;
    }
  }
}

// "battery": catalog ids, cells (a number or a range), capacity, reserve, cut-off.
static void ReadBattery(const Reader& top, const std::string& name, Mission* m) {
  if (!top.Has("battery")) top.FailMissing("battery", "an object is required");
  const Reader b(top.At("battery"), name, "$.battery");
  b.AllowOnly({"id", "cells", "cells_parallel", "capacity_ah", "reserve_soc", "cutoff_cell_v",
               "mass_factor", "mass_factor_source"});
  if (!b.Has("id")) b.FailMissing("id", "a catalog battery id or an array of ids is required");
  if (b.At("id").is_array()) {
    if (b.At("id").empty()) b.Fail("$.battery.id", b.At("id"), "must list at least one id");
    for (std::size_t i = 0; i < b.At("id").size(); ++i) {
      const Json& e = b.At("id")[i];
      if (!e.is_string() || e.get<std::string>().empty()) {
        b.Fail("$.battery.id[" + std::to_string(i) + "]", e, "must be a non-empty string");
      }
      m->battery.ids.push_back(e.get<std::string>());
    }
  } else {
    m->battery.ids.push_back(b.String("id", std::nullopt));
  }
  const Range cells = b.NumberOrRange("cells", 1.0, kMaxCellsSeries, false);
  for (double c : {cells.lo, cells.hi}) {
    if (c != std::floor(c)) b.Fail("$.battery.cells", b.At("cells"), "cell counts must be integers");
  }
  m->battery.cells_min = static_cast<int>(cells.lo);
  m->battery.cells_max = static_cast<int>(cells.hi);
  if (b.Has("capacity_ah")) m->battery.capacity_ah = b.NumberOrRange("capacity_ah", 0.0, 1e4, true);
  m->battery.reserve_soc = b.Number("reserve_soc", 0.0, 0.9, false, 0.2);
  m->battery.cutoff_cell_v = b.OptNumber("cutoff_cell_v", 0.5, 4.5, true);
  m->battery.cells_parallel = b.Integer("cells_parallel", 1, 1000, 1);
  m->battery.mass_factor = b.Number("mass_factor", 1.0, 3.0, false, 1.0);
  m->battery.mass_factor_source = b.String("mass_factor_source", std::string());
  if (m->battery.mass_factor != 1.0 && m->battery.mass_factor_source.empty()) {
    b.FailMissing("mass_factor_source", "a mass_factor other than 1 must say where it comes from");
  }
}

// "constraints" with their documented defaults.
static void ReadConstraints(const Reader& top, const std::string& name, Mission* m) {
  if (top.Has("constraints")) {
    const Reader c(top.At("constraints"), name, "$.constraints");
    c.AllowOnly({"max_throttle", "min_hover_throttle", "current_margin", "allow_esc_saturation",
                 "enforce_motor_power", "max_figure_of_merit", "max_axial_figure_of_merit", "max_static_advance_ratio",
                 "min_thrust_to_weight", "max_winding_temp_c", "allow_folding_props_for_lift",
                 "unrated_motors", "prop_below_data_factor", "prop_above_data_factor", "max_tip_mach"});
    m->constraints.min_thrust_to_weight = c.Number("min_thrust_to_weight", 0.0, 50.0, false, 2.0);
    m->constraints.max_winding_temp_c = c.Number("max_winding_temp_c", 20.0, 400.0, false, 120.0);
    m->constraints.max_static_advance_ratio = c.Number("max_static_advance_ratio", 0.0, 5.0, false, 0.2);
    m->constraints.max_figure_of_merit = c.Number("max_figure_of_merit", 0.0, 1.0, true, 0.8);
    m->constraints.max_axial_figure_of_merit = c.Number("max_axial_figure_of_merit", 0.0, 1.0, true, 0.95);
    m->constraints.max_throttle = c.Number("max_throttle", 0.0, 1.0, true, 0.8);
    m->constraints.min_hover_throttle = c.Number("min_hover_throttle", 0.0, 1.0, false, 0.0);
    if (m->constraints.min_hover_throttle >= m->constraints.max_throttle) {
      c.Fail("$.constraints.min_hover_throttle", c.At("min_hover_throttle"),
             "must be below max_throttle");
    }
    m->constraints.current_margin = c.Number("current_margin", 0.0, 0.9, false, 0.1);
    m->constraints.prop_below_data_factor = c.Number("prop_below_data_factor", 0.0, 1.0, false, 0.6);
    m->constraints.prop_above_data_factor = c.Number("prop_above_data_factor", 0.0, 1e3, false, 1.5);
    m->constraints.max_tip_mach = c.Number("max_tip_mach", 0.0, 1.5, false, 0.7);
    if (m->constraints.prop_above_data_factor > 0.0 && m->constraints.prop_above_data_factor < 1.0) {
      c.Fail("$.constraints.prop_above_data_factor", c.At("prop_above_data_factor"),
             "must be 0 (not checked) or at least 1");
    }
    m->constraints.allow_esc_saturation = c.Bool("allow_esc_saturation", false);
    m->constraints.enforce_motor_power = c.Bool("enforce_motor_power", true);
    m->constraints.allow_folding_props_for_lift = c.Bool("allow_folding_props_for_lift", false);
    const std::string unrated = c.String("unrated_motors", std::string("estimate"));
    if (unrated != "estimate" && unrated != "exclude") {
      c.Fail("$.constraints.unrated_motors", c.At("unrated_motors"), "must be one of estimate, exclude");
    }
    m->constraints.estimate_unrated_motors = unrated == "estimate";
  }
}

// "segments": each read by ReadSegment, then tied to its propulsion group.
static void ReadSegments(const Reader& top, const std::string& name, Mission* m) {
  if (!top.Has("segments") || !top.At("segments").is_array() || top.At("segments").empty()) {
    top.Fail("$.segments", top.Has("segments") ? top.At("segments") : Json(nullptr),
             "must be a non-empty array of segments");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < top.At("segments").size(); ++i) {
    const std::string path = "$.segments[" + std::to_string(i) + "]";
    const Reader s(top.At("segments")[i], name, path);
    m->segments.push_back(ReadSegment(s, path));
    if (!names.insert(m->segments.back().name).second) {
      s.Fail(path + ".name", s.At("name"), "segment names must be unique");
    }
    Segment& seg = m->segments.back();
    if (!m->groups.empty()) {
      if (seg.group_name.empty()) s.FailMissing("group", "a mission with propulsion groups names each segment's group");
      auto it = std::find_if(m->groups.begin(), m->groups.end(), [&](const PropulsionGroup& g) { return g.name == seg.group_name; });
      if (it == m->groups.end()) {
        std::string names_list;
        for (const auto& g : m->groups) names_list += (names_list.empty() ? "" : ", ") + g.name;
        s.Fail(path + ".group", s.At("group"), "names no propulsion group (valid: " + names_list + ")");
      }
      seg.group = static_cast<int>(it - m->groups.begin());
    } else if (!seg.group_name.empty()) {
      s.Fail(path + ".group", s.At("group"), "needs a \"propulsion\" object naming the groups");
    }
    const int group_rotors = GroupRotors(*m, seg.group);
    if (seg.rotors_active > group_rotors) {
      s.Fail(path + ".rotors", s.At("rotors"), std::string("must be <= ") +
                                                   (m->groups.empty() ? "vehicle.rotors (" : "its group's rotors (") +
                                                   std::to_string(group_rotors) + ")");
    }
  }
  for (std::size_t g = 0; g < m->groups.size(); ++g) {
    const bool used = std::any_of(m->segments.begin(), m->segments.end(), [&](const Segment& x) { return x.group == static_cast<int>(g); });
    if (!used) {
      throw DataError(name + ": $.propulsion." + m->groups[g].name + ": \"" + m->groups[g].name +
                      "\": no segment uses this group (name it in a segment's \"group\" or remove it)");
    }
  }
}

// "objective": its type, ranking scenario and the segment it stretches or scores.
static void ReadObjective(const Reader& top, const std::string& name, Mission* m) {
  if (!top.Has("objective")) top.FailMissing("objective", "an object is required");
  const Reader o(top.At("objective"), name, "$.objective");
  o.AllowOnly({"type", "segment", "ranking"});
  const std::string ranking = o.String("ranking", std::string("credible"));
  if (ranking == "as_given") m->objective.ranking = DataScenario::kAsGiven;
  else if (ranking != "credible") o.Fail("$.objective.ranking", o.At("ranking"), "must be one of as_given, credible");
  const std::string type = o.String("type", std::nullopt);
  if (type == "max_endurance") m->objective.type = ObjectiveType::kMaxEndurance;
  else if (type == "min_energy") m->objective.type = ObjectiveType::kMinEnergy;
  else if (type == "max_efficiency") m->objective.type = ObjectiveType::kMaxEfficiency;
  else o.Fail("$.objective.type", o.At("type"), "must be one of max_efficiency, max_endurance, min_energy");
  m->objective.segment = o.String("segment", std::string());
  if (m->objective.segment.empty()) {
    if (m->objective.type == ObjectiveType::kMaxEfficiency) {
      o.FailMissing("segment", "max_efficiency needs the name of a segment");
    }
    if (m->objective.type == ObjectiveType::kMaxEndurance) {
      for (std::size_t i = 0; i < m->segments.size(); ++i) {
        if (m->segments[i].type == SegmentType::kHover) m->objective.segment_index = static_cast<int>(i);
      }
      if (m->objective.segment_index < 0) {
        o.FailMissing("segment", "max_endurance needs a hover or cruise segment to stretch");
      }
      m->objective.segment = m->segments[m->objective.segment_index].name;
    }
  } else {
    for (std::size_t i = 0; i < m->segments.size(); ++i) {
      if (m->segments[i].name == m->objective.segment) m->objective.segment_index = static_cast<int>(i);
    }
    if (m->objective.segment_index < 0) {
      o.Fail("$.objective.segment", o.At("segment"), "names no segment");
    }
    const SegmentType st = m->segments[m->objective.segment_index].type;
    if (m->objective.type == ObjectiveType::kMaxEndurance && st != SegmentType::kHover &&
        st != SegmentType::kCruise) {
      o.Fail("$.objective.segment", o.At("segment"), "max_endurance stretches a hover or cruise segment");
    }
  }
}

Mission ParseMission(const Json& doc, const std::string& name) {
  Mission m;
  m.file = name;
  const Reader top(doc, name, "$");
  top.AllowOnly({"name", "comment", "vehicle", "air", "battery", "constraints", "objective", "segments",
                 "propulsion"});
  m.name = top.String("name", std::string("mission"));
  if (top.Has("comment") && !top.At("comment").is_string()) {
    top.Fail("$.comment", top.At("comment"), "must be a string");
  }

  ReadVehicle(top, name, &m);
  ReadAir(top, name, &m);
  ReadBattery(top, name, &m);
  ReadConstraints(top, name, &m);
  ReadSegments(top, name, &m);
  ReadObjective(top, name, &m);
  return m;
}

Mission ReadMission(const std::string& path) {
  return ParseMission(ReadJsonFile(path), path);
}

}  // namespace dynosize
