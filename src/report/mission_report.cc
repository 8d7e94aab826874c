#include "report/mission_report.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "common/numbers.h"
#include "common/text_file.h"
#include "common/text_format.h"
#include "common/units.h"
#include "mission/flight.h"
#include "model/drive.h"
#include "model/gear.h"
#include "model/physics.h"
#include "optimization/no_design.h"
#include "prop/prop_model.h"
#include "report/gnuplot.h"
#include "rotor/family.h"

namespace dynosize {

std::string ObjectiveLabel(const Mission& m) {
  switch (m.objective.type) {
    case ObjectiveType::kMaxEndurance: return "endurance [min]";
    case ObjectiveType::kMinEnergy: return "energy drawn [Wh]";
    case ObjectiveType::kMaxEfficiency: return "system efficiency in '" + m.objective.segment + "' [%]";
  }
  return "objective";
}

namespace {

double Display(const Mission& m, double objective) { return DisplayObjective(m, objective); }

// "Name (id)" for a figure title; the id alone when the entry has no name.
std::string PartName(const EntryBase& e) {
  return e.name.empty() || e.name == e.id ? e.id : e.name + " (" + e.id + ")";
}

// objective_range, the ranking, the tiers and the motor rating (optimization/credibility.h).
void AddCredibilityJson(const Mission& m, const MissionResult& r, Json* j) {
  const ObjectiveRange& g = r.range;
  (*j)["ranking"] = m.objective.ranking == DataScenario::kAsGiven ? "as_given" : "credible";
  if (!g.computed) return;
  // An end that cannot fly has no value (null), not the headline's.
  (*j)["objective_range"] = {g.low_flies ? Json(g.low) : Json(nullptr), g.high_flies ? Json(g.high) : Json(nullptr)};
  // An infeasible result's objective is not a value of the range (it flew part of the mission).
  (*j)["objective_in_range"] = r.feasible;
  (*j)["objective_range_basis"] = g.basis;
  (*j)["objective_range_complete"] = g.complete;
  if (!g.low_breaks.empty()) (*j)["objective_range_low_breaks"] = g.low_breaks;
  if (!g.high_breaks.empty()) (*j)["objective_range_high_breaks"] = g.high_breaks;
  // null when the data as given break a limit (the number is then not an objective).
  (*j)["objective_as_given"] = g.as_given_feasible ? Json(g.as_given) : Json(nullptr);
  if (!g.as_given_feasible) (*j)["objective_as_given_breaks"] = g.as_given_breaks;
  Json t = Json::object();
  for (const PartTier& p : g.tiers) t[p.part] = {{"id", p.id}, {"tier", TierName(p.tier)}, {"set_by", p.why}};
  (*j)["tiers"] = t;
  (*j)["motor_rating"] = g.motor_rating;
}

// A sized propeller (rotor/family.h): its size, blades, family and how far the family's data
// reach; null for a catalog propeller.
Json SizedPropOf(const PropEntry& p) {
  const RotorFamily* f = FamilyOfSizedPropId(p.id);
  if (f == nullptr) return nullptr;
  return {{"diameter_m", p.diameter_m}, {"pitch_m", p.pitch_m.value_or(0.0)}, {"blades", p.blades.value_or(2)},
          {"family", f->id}, {"family_description", f->description},
          {"family_measured_diameter_in", IsParametricFamily(*f) ? Json(nullptr) : Json{f->d_min_in, f->d_max_in}},
          {"reach", FamilyReachText(*f, p.diameter_m)}};
}

// "  sized propeller (lift): 1.630 m, pitch 0.533 m (64.17 x 20.99 in), 2 blades, family ...".
std::string SizedPropText(const Mission& m, const Combination& c) {
  std::string out;
  for (int g = 0; g < GroupCount(m); ++g) {
    const PropEntry& p = *c.Parts(g).prop;
    const RotorFamily* f = FamilyOfSizedPropId(p.id);
    if (f == nullptr) continue;
    const double pitch_m = p.pitch_m.value_or(0.0);
    out += "  sized propeller" + (m.groups.empty() ? std::string() : " (" + m.groups[g].name + ")") + ": " +
           FixedText(p.diameter_m, 3) + " m, pitch " + FixedText(pitch_m, 3) + " m (" + SignificantText(p.diameter_m / 0.0254, 4) +
           " x " + SignificantText(pitch_m / 0.0254, 4) + " in), " + std::to_string(p.blades.value_or(2)) + " blades, family " +
           f->id + ", blade-element estimate; " + FamilyReachText(*f, p.diameter_m) + "\n";
  }
  return out;
}

std::string CredibilityText(const Mission& m, const MissionResult& r) {
  const ObjectiveRange& g = r.range;
  if (!g.computed) return "";
  const bool credible = m.objective.ranking != DataScenario::kAsGiven;
  const char* unit = DisplayUnit(m);
  std::ostringstream o;
  const auto end = [&](bool flies, double v) { return flies ? FixedText(Display(m, v), 2) : std::string("(cannot fly)"); };
  o << "  " << (credible ? "credible " : "data as given: ");
  if (r.feasible) {
    o << FixedText(Display(m, r.objective), 2) << unit << ", ";
  } else {
    // An infeasible run's objective is what it flew before it broke a limit: not a point of the range.
    o << "infeasible; ";
  }
  o << end(g.low_flies, g.low) << "-" << end(g.high_flies, g.high) << unit << " with the spread of the data ("
    << g.basis << ")";
  if (credible) {
    o << "; data as given: "
      << (g.as_given_feasible ? FixedText(Display(m, g.as_given), 2) + unit : "infeasible (breaks " + g.as_given_breaks + ")");
  }
  if (!g.low_breaks.empty()) o << "\n  at the low end it breaks " << g.low_breaks << " (limits relaxed for the number)";
  if (!g.high_breaks.empty()) o << "\n  at the high end it breaks " << g.high_breaks << " (limits relaxed for the number)";
  if (!g.complete) o << "\n  the range is incomplete: one end cannot fly even with the limits relaxed";
  o << "\n  data tiers:";
  for (const PartTier& p : g.tiers) o << " " << p.part << " " << TierName(p.tier) << " (" << p.why << ");";
  o << " motor rating: " << g.motor_rating << "\n";
  return o.str();
}

// The widths of the segment table's name and group columns: each segment's whole name (names
// never run together) and its group's.
struct SegmentColumns {
  int name = 7, group = 5;  // "segment", "group"
};
SegmentColumns SegmentColumnsOf(const Mission& m, const MissionResult& r) {
  SegmentColumns c;
  for (const SegmentResult& s : r.segments) {
    c.name = std::max(c.name, static_cast<int>(s.name.size()));
    if (!m.groups.empty()) c.group = std::max(c.group, static_cast<int>(m.groups[s.group].name.size()));
  }
  return c;
}

// Two header lines: what the columns hold, then their names (widths as the rows').
std::string SegmentTableHeader(const Mission& m, const MissionResult& r) {
  const SegmentColumns c = SegmentColumnsOf(m, r);
  std::ostringstream o;
  o << "  each segment at its end (the worst case: lowest voltage, highest throttle); throttle: the command;"
       " effective: the throttle the ESC delivers (less above its saturation knee);"
       " efficiencies eta: motor, ESC, motor and ESC together\n";
  o << "  " << std::left << std::setw(c.name) << "segment";
  if (!m.groups.empty()) o << "  " << std::setw(c.group) << "group";
  o << "  " << std::setw(6) << "type" << std::right << std::setw(7) << "s" << std::setw(8) << "rpm" << std::setw(12)
    << "throttle %" << std::setw(13) << "effective %" << std::setw(11) << "torque N*m" << std::setw(8) << "Irms A"
    << std::setw(7) << "IDC A" << std::setw(8) << "VDC V" << std::setw(8) << "PDC W" << std::setw(8) << "PESC W"
    << std::setw(9) << "eta_mot" << std::setw(9) << "eta_esc" << std::setw(9) << "eta_sys" << "  limit\n";
  return o.str();
}

}  // namespace

Json MissionResultJson(const Mission& m, const Combination& c, const MissionResult& r) {
  Json j;
  j["motor"] = c.motor->id;
  j["esc"] = c.esc->id;
  j["prop"] = c.prop->id;
  if (!m.groups.empty()) {
    Json groups = Json::object();
    for (int g = 0; g < GroupCount(m); ++g) {
      const GroupParts p = c.Parts(g);
      Json x = {{"motor", p.motor->id}, {"esc", p.esc->id}, {"prop", p.prop->id}, {"rotors", GroupRotors(m, g)},
                {"fixed", m.groups[g].fixed()}};
      if (g == LiftGroup(m)) x["thrust_to_weight"] = r.thrust_to_weight;
      if (const Json sized = SizedPropOf(*p.prop); !sized.is_null()) x["sized_prop"] = sized;
      groups[m.groups[g].name] = x;
    }
    j["groups"] = groups;
  }
  if (m.groups.empty()) {
    if (const Json sized = SizedPropOf(*c.prop); !sized.is_null()) j["sized_prop"] = sized;
  }
  j["battery"] = c.battery->id;
  j["cells"] = c.cells;
  j["objective"] = r.objective;
  j["objective_type"] = ObjectiveTypeName(m.objective.type);
  j["objective_unit"] = r.objective_unit;
  j["feasible"] = r.feasible;
  j["endurance_s"] = r.endurance_s;
  j["energy_wh"] = r.energy_wh;
  j["final_soc"] = r.final_soc;
  j["capacity_ah"] = r.capacity_ah;
  j["propulsion_mass_kg"] = r.propulsion_mass_kg;
  j["total_mass_kg"] = r.total_mass_kg;
  j["lift_rotors"] = r.lift_rotors;
  j["thrust_to_weight"] = r.thrust_to_weight;
  if (r.summary.valid) {
    const DesignSummary& d = r.summary;
    // A pack that cannot hover has no hover endurance (null, can_hover false).
    const auto hover_only = [&](double v) { return d.can_hover ? Json(v) : Json(nullptr); };
    j["summary"] = {{"can_hover", d.can_hover},
                    {"hover_throttle", d.hover_throttle},
                    {"hover_battery_current_a", hover_only(d.hover_battery_current_a)},
                    {"hover_endurance_s", hover_only(d.hover_endurance_s)},
                    {"full_throttle_battery_current_a", d.full_throttle_battery_current_a},
                    {"full_throttle_endurance_s", hover_only(d.full_throttle_endurance_s)},
                    {"reserve_hover_s", hover_only(d.reserve_hover_s)},
                    {"full_throttle_thrust_n", d.full_throttle_thrust_n},
                    {"full_throttle_current_limited", d.full_throttle_current_limited},
                    {"max_climb_rate_m_s", d.max_climb_rate_m_s},
                    {"winding_temp_max_c", d.winding_temp_max_c},
                    {"at", "SOC 0.5 with sag; endurances from full to the reserve SOC"}};
  }
  Json segs = Json::array();
  for (const SegmentResult& s : r.segments) {
    // A geared motor: the motor's shaft in rpm, torque, pmech and the efficiencies, the
    // propeller's beside them (model/gear.h); direct drive: the one shaft.
    const Gear& gear = c.Parts(s.group).motor->gear;
    const OperatingPoint p = MotorSidePoint(s.point, gear);
    Json g;
    g["name"] = s.name;
    g["type"] = SegmentTypeName(s.type);
    if (!m.groups.empty()) g["group"] = m.groups[s.group].name;
    g["point"] = "end (worst case: lowest voltage, highest throttle)";
    g["duration_s"] = s.duration_s;
    if (s.type == SegmentType::kCruise) g["airspeed_m_s"] = s.airspeed_m_s;
    if (s.type != SegmentType::kShaft) {
      g["thrust_per_rotor_n"] = s.thrust_per_rotor_n;
      g["tilt_deg"] = s.tilt_deg;
    }
    g["rotors"] = s.rotors;
    g["rpm"] = p.rpm;
    g["throttle"] = p.throttle;
    g["throttle_effective"] = p.throttle_effective;
    g["torque_nm"] = p.torque_nm;
    g["irms_a"] = p.irms_a;
    g["idc_a"] = p.idc_a;
    g["vdc_v"] = p.vdc_v;
    g["pdc_w"] = p.pdc_w;
    g["pesc_w"] = p.pesc_w;
    g["pmech_w"] = p.pmech_w;
    g["eta_motor"] = p.eta_motor;
    g["eta_esc"] = p.eta_esc;
    g["eta_system"] = p.eta_system;
    if (gear.geared()) {
      const MotorShaft shaft = MotorShaftOf(s.point.omega_rad_s, s.point.torque_nm, gear);
      g["gear_ratio"] = gear.ratio;
      g["gear_efficiency"] = gear.efficiency;
      g["prop_rpm"] = s.point.rpm;
      g["prop_torque_nm"] = s.point.torque_nm;
      g["prop_power_w"] = s.point.pmech_w;
      g["gear_loss_w"] = shaft.gear_loss_w;
    }
    g["eta_system_average"] = s.eta_average;
    g["winding_temp_c"] = s.winding_temp_c;
    if (s.type == SegmentType::kHover && s.point.pmech_w > 0) {  // of the power flown (credibility.h)
      g["figure_of_merit"] = IdealRotorPowerW(s.thrust_per_rotor_n, c.Parts(s.group).prop->diameter_m, m.rho_kg_m3) / s.point.pmech_w;
    }
    g["battery_current_a"] = s.battery_current_a;
    g["soc_start"] = s.soc_start;
    g["soc_end"] = s.soc_end;
    g["energy_wh"] = s.energy_j / 3600.0;
    g["active_limit"] = s.active_limit.empty() ? Json(nullptr) : Json(s.active_limit);
    if (!s.active_limit.empty()) g["active_limit_slack"] = s.active_limit_slack;
    g["range"] = {{"vdc_v", {s.vdc_min_v, s.vdc_max_v}},
                  {"throttle", {s.throttle_min, s.throttle_max}},
                  {"idc_a", {s.idc_min_a, s.idc_max_a}}};
    if (!s.prop_note.empty()) g["prop_note"] = s.prop_note;
    if (!s.shaft_solver.empty()) g["shaft_solver"] = s.shaft_solver;
    segs.push_back(g);
  }
  j["segments"] = segs;
  Json v = Json::array();
  for (const Violation& x : r.violations) {
    v.push_back({{"constraint", x.constraint}, {"segment", x.segment}, {"value", x.value},
                 {"limit", x.limit}, {"excess", x.excess()}, {"unit", x.unit}});
  }
  j["violations"] = v;
  j["warnings"] = r.warnings;
  j["assumed"] = r.assumed;
  if (!r.solver.empty()) j["solver"] = r.solver;
  AddCredibilityJson(m, r, &j);
  return j;
}

std::string MissionResultText(const Mission& m, const Combination& c, const MissionResult& r) {
  std::ostringstream o;
  if (m.groups.empty()) {
    o << "motor " << c.motor->id << " + ESC " << c.esc->id << " + prop " << c.prop->id << " + "
      << c.cells << "S " << c.battery->id << " (" << FixedText(r.capacity_ah, 2) << " Ah)\n";
  } else {
    o << c.cells << "S " << c.battery->id << " (" << FixedText(r.capacity_ah, 2) << " Ah)";
    for (int g = 0; g < GroupCount(m); ++g) {
      const GroupParts p = c.Parts(g);
      o << (g ? "; " : " with ") << m.groups[g].name << " " << m.groups[g].rotors << " x motor " << p.motor->id
        << " + ESC " << p.esc->id << " + prop " << p.prop->id << (m.groups[g].fixed() ? " (fixed)" : "");
    }
    o << "\n";
  }
  o << "  " << (r.feasible ? "feasible" : "INFEASIBLE") << "; " << ObjectiveLabel(m) << " "
    << FixedText(Display(m, r.objective), 2) << "; mission " << FixedText(r.endurance_s / 60.0, 2)
    << " min, " << FixedText(r.energy_wh, 2) << " Wh, final SOC " << FixedText(100 * r.final_soc, 1)
    << " %; mass " << FixedText(r.total_mass_kg, 3) << " kg (propulsion " << FixedText(r.propulsion_mass_kg, 3)
    << " kg)\n";
  if (r.summary.valid) {
    const DesignSummary& d = r.summary;
    o << "  thrust/weight " << FixedText(r.thrust_to_weight, 2) << " (" << r.lift_rotors
      << (m.groups.empty() ? " lift rotors" : " rotors of group " + m.groups[std::max(0, LiftGroup(m))].name) << ", full throttle at the mission's end); at half charge: ";
    if (d.can_hover) {
      o << "hover throttle " << FixedText(100 * d.hover_throttle, 1) << " %, hover " << FixedText(d.hover_endurance_s / 60.0, 1)
        << " min, full throttle " << FixedText(d.full_throttle_endurance_s / 60.0, 1) << " min ("
        << FixedText(d.full_throttle_battery_current_a, 1) << " A" << (d.full_throttle_current_limited ? ", at the current rating" : "")
        << "), climb up to " << FixedText(d.max_climb_rate_m_s, 1) << " m/s; reserve at landing "
        << FixedText(d.reserve_hover_s / 60.0, 1) << " min of hover";
    } else {
      const double weight_n = r.total_mass_kg * kStandardGravity;
      o << "it cannot hover (";
      if (d.full_throttle_thrust_n < weight_n) {
        o << "full-throttle thrust " << FixedText(d.full_throttle_thrust_n, 1) << " N for a weight of "
          << FixedText(weight_n, 1) << " N";
      } else {
        o << "it needs " << FixedText(100 * d.hover_throttle, 1) << " % throttle";
      }
      o << "): no hover endurance";
    }
    o << "; winding up to " << FixedText(d.winding_temp_max_c, 0) << " C\n";
  }
  o << SizedPropText(m, c);
  o << CredibilityText(m, r);
  o << SegmentTableHeader(m, r);
  const SegmentColumns cols = SegmentColumnsOf(m, r);
  for (const SegmentResult& s : r.segments) {
    const Gear& gear = c.Parts(s.group).motor->gear;
    const OperatingPoint p = MotorSidePoint(s.point, gear);  // the motor's shaft (model/gear.h)
    o << "  " << std::left << std::setw(cols.name) << s.name;
    if (!m.groups.empty()) o << "  " << std::setw(cols.group) << m.groups[s.group].name;
    o << "  " << std::setw(6) << SegmentTypeName(s.type) << std::right << std::setw(7) << FixedText(s.duration_s, 0)
      << std::setw(8) << FixedText(p.rpm, 0) << std::setw(12) << FixedText(100 * p.throttle, 1)
      << std::setw(13) << FixedText(100 * p.throttle_effective, 1) << std::setw(11)
      << FixedText(p.torque_nm, 5) << std::setw(8) << FixedText(p.irms_a, 2) << std::setw(7)
      << FixedText(p.idc_a, 2) << std::setw(8) << FixedText(p.vdc_v, 3) << std::setw(8)
      << FixedText(p.pdc_w, 1) << std::setw(8) << FixedText(p.pesc_w, 2) << std::setw(9)
      << FixedText(p.eta_motor, 3) << std::setw(9) << FixedText(p.eta_esc, 3) << std::setw(9)
      << FixedText(p.eta_system, 3) << "  " << (s.active_limit.empty() ? "-" : s.active_limit) << "\n";
    o << "      over the segment: VDC " << FixedText(s.vdc_max_v, 2) << " -> " << FixedText(s.vdc_min_v, 2)
      << " V, throttle " << FixedText(100 * s.throttle_min, 1) << "-" << FixedText(100 * s.throttle_max, 1)
      << " %, IDC " << FixedText(s.idc_min_a, 2) << "-" << FixedText(s.idc_max_a, 2) << " A, SOC "
      << FixedText(100 * s.soc_start, 1) << " -> " << FixedText(100 * s.soc_end, 1) << " %, winding "
      << FixedText(s.winding_temp_c, 0) << " C";
    if (s.type == SegmentType::kCruise) o << ", airspeed " << FixedText(s.airspeed_m_s, 2) << " m/s";
    if (gear.geared()) {
      const MotorShaft shaft = MotorShaftOf(s.point.omega_rad_s, s.point.torque_nm, gear);
      o << "\n      geared " << FixedText(gear.ratio, 2) << ":1 (efficiency " << FixedText(gear.efficiency, 3)
        << "; the row is the motor's shaft): propeller " << FixedText(s.point.rpm, 0) << " rpm, "
        << FixedText(s.point.torque_nm, 4) << " N*m, " << FixedText(s.point.pmech_w, 1) << " W; gear loss "
        << FixedText(shaft.gear_loss_w, 1) << " W";
    }
    o << "\n";
  }
  for (const Violation& v : r.violations) {
    const std::string unit = v.unit.empty() ? "" : " " + v.unit;  // throttle, SOC: no unit
    o << "  fails " << v.constraint << (v.segment.empty() ? "" : " in '" + v.segment + "'") << ": "
      << v.value << unit << " vs limit " << v.limit << unit << " (by " << v.excess() << unit << ")\n";
  }
  for (const std::string& w : r.warnings) o << "  warning: " << w << "\n";
  if (!r.solver.empty()) o << "  continuous variables: " << r.solver << "\n";
  return o.str();
}

std::vector<std::vector<int>> IndistinguishableRanks(const SearchResult& s) {
  std::vector<std::vector<int>> out(s.best.size());
  for (std::size_t i = 0; i < s.best.size(); ++i) {
    for (std::size_t j = 0; j < s.best.size(); ++j) {
      const ObjectiveRange& a = s.best[i].result.range;
      const ObjectiveRange& b = s.best[j].result.range;
      // Closed ranges (low <= high, credibility.h) overlap when neither lies wholly below the other.
      if (i != j && a.computed && b.computed && !(a.high < b.low) && !(b.high < a.low)) {
        out[i].push_back(static_cast<int>(j) + 1);
      }
    }
  }
  return out;
}

namespace {

// "ESC e" or "lift ESC e, cruise ESC f" (the groups whose ESC differs from the result's), then the
// pack when it differs (entry, cells or the capacity flown).
std::string AlternativeParts(const Mission& m, const Combination& best, double best_capacity_ah, const Alternative& a) {
  std::string out;
  for (int g = 0; g < std::max(1, GroupCount(m)); ++g) {
    const EscEntry* e = a.combination.Parts(g).esc;
    if (e == best.Parts(g).esc) continue;
    out += (out.empty() ? "" : ", ") + (m.groups.empty() ? std::string() : m.groups[g].name + " ") + "ESC " + e->id;
  }
  if (a.combination.battery != best.battery || a.combination.cells != best.cells || a.capacity_ah != best_capacity_ah) {
    out += (out.empty() ? "" : ", ") + std::to_string(a.combination.cells) + "S " + a.combination.battery->id + " (" +
           FixedText(a.capacity_ah, 2) + " Ah)";
  }
  return out.empty() ? "the same parts" : out;
}

}  // namespace

std::string AlternativesText(const Mission& m, const RankedCombination& r, const std::vector<int>& tied) {
  constexpr std::size_t kListed = 5;  // in the text; JSON lists them all
  std::ostringstream o;
  if (!r.alternatives.empty()) {
    o << "  other ESCs and packs of this design (" << r.alternatives.size() << "):";
    for (std::size_t k = 0; k < r.alternatives.size() && k < kListed; ++k) {
      const Alternative& a = r.alternatives[k];
      o << (k ? "; " : " ") << AlternativeParts(m, r.combination, r.result.capacity_ah, a) << " "
        << FixedText(DisplayObjective(m, a.objective), 2) << DisplayUnit(m);
    }
    if (r.alternatives.size() > kListed) o << "; and " << r.alternatives.size() - kListed << " more (--json lists them)";
    o << "\n";
  }
  if (!tied.empty()) {
    o << "  not distinguishable on the data from";
    for (std::size_t k = 0; k < tied.size(); ++k) o << (k ? ", #" : " #") << tied[k];
    o << ": their objective ranges overlap this one's\n";
  }
  return o.str();
}

std::string InterruptedText(const Mission& m, const SearchResult& s, int top_n) {
  if (!s.interrupted) return "";
  std::ostringstream o;
  const char* unit = DisplayUnit(m);
  const bool larger_better = m.objective.type != ObjectiveType::kMinEnergy;
  o << "interrupted after " << FixedText(s.seconds, 2) << " s: the best found so far, not proven the best ("
    << s.unsettled << " combinations not yet settled)\n";
  if (!std::isfinite(s.unsettled_bound_score)) {
    if (m.objective.type == ObjectiveType::kMaxEfficiency) {
      o << "bound gap: unknown (the objective " << ObjectiveTypeName(m.objective.type)
        << " has no bound on what is left)\n";
    } else {  // the joint search stopped in its first pass (docs/joint-search.md#dive)
      o << "bound gap: unknown (stopped before every choice of the outer group was bounded; a longer "
           "time limit gives one)\n";
    }
    return o.str();
  }
  const double bound = DisplayObjective(m, ObjectiveOfScore(m.objective.type, s.unsettled_bound_score));
  o << "bound gap: nothing left unsettled can " << (larger_better ? "exceed " : "go below ") << FixedText(bound, 2)
    << unit;
  if (std::isfinite(s.nth_best_score)) {
    const double nth = DisplayObjective(m, ObjectiveOfScore(m.objective.type, s.nth_best_score));
    o << "; the " << top_n << (top_n == 1 ? "st" : top_n == 2 ? "nd" : top_n == 3 ? "rd" : "th") << " best found is "
      << FixedText(nth, 2) << unit << " (gap " << FixedText(std::fabs(bound - nth), 2) << unit << ")";
  } else {
    o << "; fewer than " << top_n << " results found so far";
  }
  o << "\n";
  return o.str();
}

Json SearchResultJson(const Mission& m, const SearchResult& s) {
  Json j;
  Json results = Json::array();
  const std::vector<std::vector<int>> tied = IndistinguishableRanks(s);
  for (std::size_t i = 0; i < s.best.size(); ++i) {
    const RankedCombination& b = s.best[i];
    Json r = MissionResultJson(m, b.combination, b.result);
    Json alt = Json::array();
    for (const Alternative& a : b.alternatives) {
      Json x = {{"battery", a.combination.battery->id}, {"cells", a.combination.cells},
                {"capacity_ah", a.capacity_ah}, {"objective", a.objective}};
      if (m.groups.empty()) {
        x["esc"] = a.combination.esc->id;
      } else {
        Json g = Json::object();
        for (int k = 0; k < GroupCount(m); ++k) g[m.groups[k].name] = a.combination.Parts(k).esc->id;
        x["esc"] = g;
      }
      alt.push_back(x);
    }
    r["alternatives"] = alt;
    r["indistinguishable_from"] = tied[i];
    results.push_back(r);
  }
  j["results"] = results;
  j["interrupted"] = s.interrupted;
  if (s.interrupted) {
    const auto value = [&](double score) {
      return std::isfinite(score) ? Json(ObjectiveOfScore(m.objective.type, score)) : Json(nullptr);
    };
    const bool both = std::isfinite(s.unsettled_bound_score) && std::isfinite(s.nth_best_score);
    j["bound_gap"] = {{"unsettled_bound", value(s.unsettled_bound_score)},
                      {"nth_best", value(s.nth_best_score)},
                      {"gap", both ? Json(std::fabs(s.nth_best_score - s.unsettled_bound_score)) : Json(nullptr)}};
  }
  j["searched"] = s.searched;
  j["pruned"] = s.pruned;
  j["unsettled"] = s.unsettled;
  j["combinations"] = s.combinations;
  Json by = Json::object();
  for (const auto& [rule, n] : s.pruned_by) by[rule] = n;
  j["pruned_by"] = by;
  j["seconds"] = s.seconds;
  if (!s.relaxed_constraint.empty()) j["relaxed_constraint"] = s.relaxed_constraint;
  j["no_design_because"] = UnmetRequirementsJson(s.no_design_because);
  return j;
}

Json UnmetRequirementsJson(const std::vector<UnmetRequirement>& reasons) {
  Json out = Json::array();
  const auto number = [](double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); };
  for (const UnmetRequirement& r : reasons) {
    out.push_back({{"requirement", r.requirement},
                   {"needed", number(r.needed)},
                   {"best_available", number(r.best_available)},
                   {"unit", r.unit},
                   {"components", r.components},
                   {"description", r.description},
                   {"search_rule", r.search_rule},
                   {"group", r.group}});
  }
  return out;
}

std::string NoDesignText(const SearchResult& s) {
  if (!s.best.empty() || s.interrupted) return "";
  if (s.no_design_because.empty()) {
    return "  each requirement checked alone (docs/search.md#why-nothing-flies) is met by some part of the catalog: "
           "the parts fail together (the counts above say by which rules)\n";
  }
  std::string out;
  for (const UnmetRequirement& r : s.no_design_because) out += "  " + UnmetRequirementText(r, &s.pruned_by) + "\n";
  return out;
}

ParetoPoints ParetoPointsOf(const Mission& m, const SearchResult& s) {
  ParetoPoints out;
  for (const auto& p : s.evaluated_mass_objective) out.all.emplace_back(p.first, Display(m, p.second));
  const bool larger_better = m.objective.type != ObjectiveType::kMinEnergy;
  std::sort(out.all.begin(), out.all.end());
  double best = larger_better ? -1e300 : 1e300;
  for (const auto& p : out.all) {
    const bool better = larger_better ? p.second > best : p.second < best;
    if (better) {  // non-dominated: lighter ones are all worse
      best = p.second;
      out.front.push_back(p);
    }
  }
  return out;
}

std::string WriteParetoFigure(const Mission& m, const SearchResult& s, const std::string& dir) {
  MakeOutputDir(dir);
  const ParetoPoints pareto = ParetoPointsOf(m, s);
  DataBlock all{"all", {}, false}, front{"front", {}, false}, top{"top", {}, false};
  std::vector<double> ax, ay, fx, fy, tx, ty;
  for (const auto& p : pareto.all) {
    ax.push_back(p.first);
    ay.push_back(p.second);
  }
  for (const auto& p : pareto.front) {
    fx.push_back(p.first);
    fy.push_back(p.second);
  }
  std::vector<double> tlo, thi;  // objective_range of the picks (credibility.h)
  for (const auto& b : s.best) {
    tx.push_back(b.result.propulsion_mass_kg);
    ty.push_back(Display(m, b.result.objective));
    const bool ranged = b.result.range.computed;
    tlo.push_back(Display(m, ranged ? std::min(b.result.range.low, b.result.range.high) : b.result.objective));
    thi.push_back(Display(m, ranged ? std::max(b.result.range.low, b.result.range.high) : b.result.objective));
  }
  if (ax.empty()) { ax.push_back(kNaN); ay.push_back(kNaN); }
  if (fx.empty()) { fx.push_back(kNaN); fy.push_back(kNaN); }
  if (tx.empty()) { tx.push_back(kNaN); ty.push_back(kNaN); tlo.push_back(kNaN); thi.push_back(kNaN); }
  all.series.push_back({ax, ay});
  front.series.push_back({fx, fy});
  top.series.push_back({tx, ty, tlo, thi});
  std::ostringstream g;
  g << "set title \"" << m.name << ": " << ObjectiveLabel(m) << " vs propulsion mass\\n"
    << s.searched << " combinations evaluated exactly, " << s.pruned << " pruned\" noenhanced\n"
    << "set xlabel 'propulsion mass (motors, ESCs, propellers, battery) [kg]'\nset ylabel \""
    << ObjectiveLabel(m) << "\" noenhanced\nset grid\nset key bottom right\n"
    << "plot $all using 1:2 with points pt 7 ps 0.5 lc rgb '#9a9a9a' title 'evaluated', "
    << "$front using 1:2 with linespoints pt 7 ps 1 lw 2 lc rgb '#d62728' title 'Pareto front', "
    << "$top using 1:2:3:4 with yerrorbars pt 6 ps 2.5 lw 2 lc rgb '#1f77b4' "
    << "title 'top picks (range)'\n";
  const std::string path = dir + "/pareto_front.png";
  RenderPng(path, {all, front, top}, g.str(), 1000, 700);
  return path;
}

std::vector<std::string> WriteSegmentMaps(const Mission& m, const Combination& c,
                                          const MissionResult& r, const std::string& dir) {
  MakeOutputDir(dir);
  std::vector<std::string> paths;
  for (std::size_t si = 0; si < r.segments.size(); ++si) {
    const SegmentResult& s = r.segments[si];
    DataBlock pts{"pts", {}, false};  // every segment flown by this drive (its group)
    {
      std::vector<double> rpm, q;
      for (const SegmentResult& x : r.segments) {
        if (x.group != s.group) continue;
        rpm.push_back(x.point.rpm);
        q.push_back(x.point.torque_nm);
      }
      pts.series.push_back({rpm, q});
    }
    const GroupParts parts = c.Parts(s.group);
    // At the propeller shaft, as the segment's point (model/gear.h; direct drive: the motor's).
    const Drive d(MotorAtPropellerShaft(parts.motor->params, parts.motor->gear), parts.esc->params);
    const PropModel prop(*parts.prop);
    const double vdc = s.point.vdc_v;
    const double w_max = d.NoLoadSpeed(vdc, 1.0);
    double q_top = 0;
    for (const SegmentResult& x : r.segments) {
      if (x.group == s.group) q_top = std::max(q_top, x.point.torque_nm);
    }
    q_top *= 2.0;
    const double i_lim = std::isfinite(parts.motor->params.max_current_a) ? parts.motor->params.max_current_a : 1e300;
    DataBlock map{"map", {}, true};
    const int n = 100;
    for (int i = 0; i <= n; ++i) {
      const double w = w_max * i / n;
      std::vector<double> rpm, q, eta;
      for (int j = 0; j <= n; ++j) {
        const double torque = q_top * j / n;
        const OperatingPoint p = d.Inverse(vdc, torque, w);
        const bool ok = p.throttle >= 0.0 && p.throttle <= 1.0 && p.irms_a <= i_lim;
        rpm.push_back(RadPerSecToRpm(w));
        q.push_back(torque);
        eta.push_back(ok ? 100 * p.eta_system : kNaN);
      }
      map.series.push_back({rpm, q, eta});
    }
    DataBlock me{"me", {}, false};
    me.series.push_back({{s.point.rpm}, {s.point.torque_nm}});
    DataBlock lim{"lim", {}, false};
    {
      // The mission's throttle limit line.
      std::vector<double> rpm, q;
      for (int j = 0; j <= 40; ++j) {
        const double torque = q_top * j / 40;
        const OperatingPoint p = d.AtTorque(vdc, m.constraints.max_throttle, torque);
        if (p.omega_rad_s <= 0) break;
        rpm.push_back(p.rpm);
        q.push_back(torque);
      }
      if (rpm.empty()) { rpm.push_back(kNaN); q.push_back(kNaN); }
      lim.series.push_back({rpm, q});
    }
    DataBlock load{"load", {}, false};
    {
      // The propeller's load line in this segment's inflow: the torque it asks at each speed,
      // on which the operating point moves as the throttle changes.
      std::vector<double> rpm, q;
      if (s.type != SegmentType::kShaft) {
        const double v_ax = SegmentRotorLoad(m, m.segments[si], r.total_mass_kg, s.airspeed_m_s).axial_airspeed_m_s;
        // The scenario's propeller, as the evaluator flies it (optimization/credibility.h).
        const PropAdjustment adj = PropAdjustmentFor(*parts.prop, m.objective.ranking);
        for (int j = 1; j <= 60; ++j) {
          const double w = w_max * j / 60;
          PropEvaluation ev = prop.Evaluate(w, m.rho_kg_m3, v_ax);
          AdjustPropEvaluation(adj, parts.prop->diameter_m, &ev);
          const double torque = ev.torque_nm;
          if (torque > q_top) break;
          rpm.push_back(RadPerSecToRpm(w));
          q.push_back(torque);
        }
      }
      if (rpm.empty()) { rpm.push_back(kNaN); q.push_back(kNaN); }
      load.series.push_back({rpm, q});
    }
    std::ostringstream g;
    g << "set title \"" << PartName(*parts.motor) << " + " << PartName(*parts.esc) << " + " << PartName(*parts.prop)
      << "\\nsegment '" << s.name << "' (" << SegmentTypeName(s.type) << ") at VDC = " << FixedText(vdc, 2)
      << " V (its end)\" noenhanced\n"
      << "set xlabel 'speed [rpm]'\nset ylabel 'torque [N m]'\nset view map\n"
      << "set palette defined (0 '#2b083b', 0.35 '#3b528b', 0.6 '#21918c', 0.8 '#5ec962', 1 '#fde725')\n"
      << "set cbrange [0:100]\nset cblabel 'system efficiency Pmech/PDC [%]'\n"
      << "set key outside bottom center horizontal noenhanced\n"
      << "set contour base\nset cntrparam levels discrete 40,60,70,80,85,90\n"
      << "set xrange [0:" << RadPerSecToRpm(w_max) << "]\nset yrange [0:" << q_top << "]\n"
      << "unset surface\nset table $contours\nsplot $map using 1:2:3 with lines\nunset table\n"
      << "unset contour\nset surface\n"
      << "plot $map using 1:2:3 with image notitle, "
      << "$contours using 1:2 with lines lc rgb 'white' lw 1 notitle, "
      // White on the map, invisible in the white key: the key shows them in grey (keyentry).
      << "keyentry with lines lc rgb '#909090' lw 1 title 'contours 40-90 % (white)', "
      << "$lim using 1:2 with lines lw 2 dt 2 lc rgb 'black' title 'throttle limit "
      << FixedText(100 * m.constraints.max_throttle, 0) << " %', "
      << "$load using 1:2 with lines lw 2 lc rgb '#ff7f0e' title 'propeller load line', "
      << "$pts using 1:2 with points pt 6 ps 2 lw 2 lc rgb 'white' notitle, "
      << "keyentry with points pt 6 ps 2 lw 2 lc rgb '#909090' title 'all segments (white rings)', "
      << "$me using 1:2 with points pt 7 ps 2.5 lc rgb 'red' title 'this segment'\n";
    std::string safe = s.name;
    for (char& ch : safe) if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    const std::string path = dir + "/efficiency_map_" + safe + ".png";
    RenderPng(path, {map, me, lim, load, pts}, g.str(), 1000, 800);
    paths.push_back(path);
  }
  return paths;
}

}  // namespace dynosize
