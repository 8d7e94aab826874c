// The requirements no part of the catalog meets (no_design.h, which states each equation).
#include "optimization/no_design.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>
#include <tuple>

#include "common/units.h"
#include "mission/flight.h"
#include "model/drive.h"
#include "model/physics.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "optimization/mission_eval.h"
#include "optimization/search_stages.h"

namespace dynosize {

namespace {

using search_internal::BatteryOption;
using search_internal::kGrid;
using search_internal::PropGrid;

constexpr double kInf = std::numeric_limits<double>::infinity();

// The parts a group may fly (indices into the catalog's lists): its fixed parts, or every entry
// the search would consider (R0: not excluded, motors with a mass, propellers that fit the frame
// and are not folding for lift).
struct GroupCandidates {
  std::vector<int> motors, escs, props;
};

GroupCandidates CandidatesOf(const Mission& m, const Catalog& cat, const search_internal::SizedPropOffer& offer, int g,
                             bool lifts) {
  GroupCandidates c;
  auto index_of = [](const auto& list, const auto* entry) { return static_cast<int>(entry - list.data()); };
  if (!m.groups.empty() && m.groups[g].fixed()) {
    const GroupParts p = FixedGroupParts(m, cat, g);
    c.motors.push_back(index_of(cat.motors(), p.motor));
    c.escs.push_back(index_of(cat.escs(), p.esc));
    c.props.push_back(index_of(cat.props(), p.prop));
    return c;
  }
  for (std::size_t i = 0; i < cat.motors().size(); ++i) {
    const MotorEntry& mo = cat.motors()[i];
    if (mo.exclude_reason.empty() && mo.mass_kg) c.motors.push_back(static_cast<int>(i));
  }
  for (std::size_t i = 0; i < cat.escs().size(); ++i) {
    if (cat.escs()[i].exclude_reason.empty()) c.escs.push_back(static_cast<int>(i));
  }
  for (std::size_t i = 0; i < cat.props().size(); ++i) {
    if (!search_internal::PropFrameRule(m, offer, g, lifts, cat, i)) c.props.push_back(static_cast<int>(i));
  }
  return c;
}

// The lightest vehicle the catalog can build (no_design.h, m_min), kg.
double MassFloorKg(const Mission& m, const Catalog& cat, const std::vector<BatteryOption>& options,
                   const std::vector<GroupCandidates>& groups) {
  double pack_kg = kInf;
  for (const BatteryOption& o : options) pack_kg = std::min(pack_kg, o.mass_lo_kg);
  double kg = m.vehicle.mass_kg + (std::isfinite(pack_kg) ? pack_kg : 0.0);
  for (int g = 0; g < GroupCount(m); ++g) {
    const GroupCandidates& c = groups[static_cast<std::size_t>(g)];
    double motor_kg = kInf, esc_kg = kInf, prop_kg = kInf;
    for (const int i : c.motors) motor_kg = std::min(motor_kg, cat.motors()[i].mass_kg.value_or(0.0));
    for (const int i : c.escs) esc_kg = std::min(esc_kg, EscMassKg(cat.escs()[i]));
    for (const int i : c.props) prop_kg = std::min(prop_kg, PropMassKg(cat.props()[i]));
    for (const double part_kg : {motor_kg, esc_kg, prop_kg}) {
      if (std::isfinite(part_kg)) kg += GroupRotors(m, g) * part_kg;
    }
  }
  return kg;
}

std::string Fixed(double x, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << x;
  return o.str();
}

// R1 (docs/search.md#r1): every group's ESCs against the lowest full-charge OCV of the packs,
// and their least supply voltage against the highest cut-off (esc_min_voltage); the lift
// group's motors too (the search checks their voltage there only).
void VoltageRequirements(const Mission& m, const Catalog& cat, const std::vector<GroupCandidates>& groups,
                         int lift_group, double v_full_min_v, double v_cut_max_v, std::vector<UnmetRequirement>* out) {
  for (int g = 0; g < GroupCount(m); ++g) {
    const GroupCandidates& c = groups[static_cast<std::size_t>(g)];
    double esc_v = -kInf;
    std::string esc_id;
    for (const int i : c.escs) {
      if (cat.escs()[i].params.vdc_max_v > esc_v) {
        esc_v = cat.escs()[i].params.vdc_max_v;
        esc_id = cat.escs()[i].id;
      }
    }
    if (!c.escs.empty() && esc_v < v_full_min_v) {
      out->push_back({"controller_voltage", v_full_min_v, esc_v, "V", {esc_id},
                      "the ESC's voltage rating (vdc_max_v) against the full-charge voltage of the mission's "
                      "lowest-voltage pack",
                      "esc_voltage", GroupName(m, g)});
    }
    double esc_min_v = kInf;
    std::string esc_min_id;
    for (const int i : c.escs) {
      if (cat.escs()[i].params.vdc_min_v < esc_min_v) {
        esc_min_v = cat.escs()[i].params.vdc_min_v;
        esc_min_id = cat.escs()[i].id;
      }
    }
    if (!c.escs.empty() && esc_min_v > v_cut_max_v) {
      out->push_back({"controller_min_voltage", esc_min_v, v_cut_max_v, "V", {esc_min_id},
                      "the least supply voltage any ESC runs on (vdc_min_v) against the cut-off voltage of the "
                      "mission's highest-voltage pack, which the pack reaches at the end of the flight",
                      "esc_voltage", GroupName(m, g)});
    }
    if (g != lift_group) continue;
    double motor_v = -kInf;
    std::string motor_id;
    for (const int i : c.motors) {
      const double v = MotorMaxVoltageV(cat.motors()[i]);
      if (v > motor_v) {
        motor_v = v;
        motor_id = cat.motors()[i].id;
      }
    }
    if (!c.motors.empty() && motor_v < v_full_min_v) {
      out->push_back({"motor_voltage", v_full_min_v, motor_v, "V", {motor_id},
                      "the motor's voltage rating (cells_max x 4.2 V) against the full-charge voltage of the "
                      "mission's lowest-voltage pack",
                      "motor_voltage", GroupName(m, g)});
    }
  }
}

// R0 (docs/search.md#r0): no propeller fits the lift group's frame.
void FrameRequirement(const Mission& m, const Catalog& cat, int g, std::vector<UnmetRequirement>* out) {
  const std::optional<double> d_max_m = GroupMaxPropDiameterM(m, g);
  if (!d_max_m) return;
  double d_min_m = kInf;
  for (const PropEntry& p : cat.props()) {
    if (p.exclude_reason.empty() && !FoldingPropRefused(p, m)) d_min_m = std::min(d_min_m, p.diameter_m);
  }
  if (std::isfinite(d_min_m) && d_min_m > *d_max_m) {
    out->push_back({"frame_prop_diameter", d_min_m, *d_max_m, "m", {},
                    "the smallest usable propeller of the catalog against the frame's max_prop_diameter_m",
                    "prop_diameter", GroupName(m, g)});
  }
}

// The zero-resistance drives of the ESC classes among `escs` (distinct C1, C0, knee, slope): each
// bounds its members' throttle, currents and power from below (M2, docs/search.md#m2).
std::vector<EscParams> ZeroResistanceClasses(const Catalog& cat, const std::vector<int>& escs, DataScenario s) {
  std::vector<EscParams> out;
  for (const int i : escs) {
    const EscParams e = ScenarioEscParams(cat.escs()[i], s);
    const bool known = std::any_of(out.begin(), out.end(), [&](const EscParams& x) {
      return std::tie(x.c1, x.c0, x.tr_sat, x.sat_slope) == std::tie(e.c1, e.c0, e.tr_sat, e.sat_slope);
    });
    if (known) continue;
    search_internal::EscClass c;
    c.c1 = e.c1;
    c.c0 = e.c0;
    c.tr_sat = e.tr_sat;
    c.sat_slope = e.sat_slope;
    out.push_back(search_internal::ZeroResistanceEsc(c));
  }
  return out;
}

// A motor of the lift group with its drives, one per ESC class.
struct MotorDrives {
  int motor = 0;
  MotorParams params;
  std::vector<Drive> drives;
};

// Per propeller: the largest grid thrust at or below each grid speed, and the last grid index a
// feasible point can reach (max_rpm, R2; the data window's top, R12).
struct PropCeiling {
  int prop = 0, top = 0;
  double thrust_prefix_max_n[kGrid];
};

std::unique_ptr<PropCeiling> CeilingOf(const Mission& m, const PropEntry& entry, const PropModel& model,
                                       const PropGrid& g, int prop) {
  auto c = std::make_unique<PropCeiling>();
  c->prop = prop;
  double cap_rad_s = kInf;
  const MissionConstraints& k = m.constraints;
  if (const PropSpeedLimit lim = PropSpeedLimitOf(m, entry); lim.rule) cap_rad_s = RpmToRadPerSec(lim.rpm);
  if (k.prop_above_data_factor > 0) {
    cap_rad_s = std::min(cap_rad_s, RpmToRadPerSec(k.prop_above_data_factor * model.valid_range().rpm_hi));
  }
  c->top = static_cast<int>(std::lower_bound(g.omega, g.omega + kGrid, cap_rad_s) - g.omega);
  c->top = std::min(c->top, kGrid - 1);
  c->thrust_prefix_max_n[0] = g.thrust[0];
  for (int i = 1; i < kGrid; ++i) c->thrust_prefix_max_n[i] = std::max(c->thrust_prefix_max_n[i - 1], g.thrust[i]);
  return c;
}

// hover_thrust_per_rotor (no_design.h): the largest static thrust of any pair, found best
// propeller first and stopped once a pair reaches `needed_n` (then met). Returns the thrust and
// the pair's motor and propeller (-1 when no pair gives any).
struct ThrustCeiling {
  double thrust_n = -kInf;
  int motor = -1, prop = -1;
};

ThrustCeiling BestHoverThrust(const Mission& m, const Catalog& cat, const GroupCandidates& c, double v_full_max_v,
                              double needed_n) {
  const MissionConstraints& k = m.constraints;
  std::vector<PropGrid> grids;
  std::vector<std::unique_ptr<PropModel>> models;
  search_internal::BuildPropGrids(m, cat, &grids, &models);
  std::vector<std::unique_ptr<PropCeiling>> props;
  for (const int p : c.props) props.push_back(CeilingOf(m, cat.props()[p], *models[p], grids[p], p));
  std::sort(props.begin(), props.end(), [](const auto& a, const auto& b) {
    return a->thrust_prefix_max_n[a->top] > b->thrust_prefix_max_n[b->top];
  });
  const std::vector<EscParams> classes = ZeroResistanceClasses(cat, c.escs, m.objective.ranking);
  double esc_max_current_a = 0.0;  // no real ESC is rated above the highest rating
  for (const int i : c.escs) esc_max_current_a = std::max(esc_max_current_a, EscReachCurrentA(cat.escs()[i]));
  std::vector<MotorDrives> motors;
  for (const int i : c.motors) {
    bool excluded = false;
    MotorDrives md{i, ScenarioMotorParams(cat.motors()[i], m, nullptr, &excluded), {}};
    if (excluded) continue;  // motor_unrated (R0)
    for (const EscParams& e : classes) md.drives.emplace_back(md.params, e);
    motors.push_back(std::move(md));
  }
  ThrustCeiling best;
  for (const auto& pc : props) {
    const double* prefix = pc->thrust_prefix_max_n;
    if (!(prefix[pc->top] > best.thrust_n) || best.thrust_n >= needed_n) break;  // sorted: none left beats it
    const PropGrid& g = grids[pc->prop];
    for (const MotorDrives& md : motors) {
      for (const Drive& drive : md.drives) {
        const double tr_max = search_internal::ThrottleLimit(k, drive.esc().tr_sat);
        // R3 at grid index i: with the smallest torque at or above its speed, every real point
        // at or above that speed fails (M1, M2); failing is monotone in i.
        auto fails = [&](int i) {
          const double q_nm = g.torque_suffix_min[i], w_rad_s = g.omega[i];
          const Drive::InverseCurrents hi = drive.InverseLight(v_full_max_v, q_nm, w_rad_s);
          return search_internal::DriveRule(k, md.params, drive, v_full_max_v, hi, q_nm, w_rad_s, tr_max,
                                            esc_max_current_a) != nullptr;
        };
        // The pair's ceiling is prefix[j], j the first failing index (or top); it beats the best
        // so far only when nothing fails below the first index whose prefix beats it.
        const int beat = static_cast<int>(std::upper_bound(prefix, prefix + pc->top + 1, best.thrust_n) - prefix);
        if (beat > pc->top || (beat > 0 && fails(beat - 1))) continue;
        int lo = beat, hi = pc->top;  // the first failing index in [beat, top], else top
        while (lo < hi) {
          const int mid = (lo + hi) / 2;
          if (fails(mid)) hi = mid; else lo = mid + 1;
        }
        if (prefix[lo] > best.thrust_n) best = {prefix[lo], md.motor, pc->prop};
      }
    }
  }
  return best;
}

}  // namespace

namespace {

// The largest propeller of the candidates, its diameter in m (0 and -1 when none).
std::pair<double, int> LargestProp(const Catalog& cat, const GroupCandidates& c) {
  std::pair<double, int> best{0.0, -1};
  for (const int p : c.props) {
    if (cat.props()[p].diameter_m > best.first) best = {cat.props()[p].diameter_m, p};
  }
  return best;
}

// The most shaft power a motor can give within its ratings at the pack's highest voltage, W,
// the least of: its power rating when the mission enforces it (shaft power <= PAC <=
// max_power_w); and with U = kv*VDC*TR_eff <= kv*VDC (TR_eff <= 1) and U = R*I + KE*omega,
// R >= Rm (docs/model.md eq 48), Q*omega = KT*(I - Io)*omega <= (KT/KE)*I*(U - Rm*I) (eq 42),
// which is at most (KT/KE)*U*I_max at the margin-reduced current rating I_max (the motor's, and
// the highest ESC rating: Irms is held to both) and at most (KT/KE)*U^2/(4*Rm) at any current
// (the maximum-power point, eq 12).
double ShaftPowerCeilingW(const MissionConstraints& k, const MotorParams& mp, double v_full_max_v,
                          double esc_max_current_a) {
  double p_w = k.enforce_motor_power ? mp.max_power_w : kInf;
  if (!(mp.ke_v_s_per_rad > 0)) return p_w;
  const double u_v = Drive(mp, EscParams{}).volt_factor() * v_full_max_v;
  const double kt_per_ke = mp.kt_nm_per_a / mp.ke_v_s_per_rad;
  const double i_max_a = std::min(mp.max_current_a, esc_max_current_a);
  if (std::isfinite(i_max_a)) p_w = std::min(p_w, kt_per_ke * u_v * (1.0 - k.current_margin) * i_max_a);
  if (mp.rm_ohm > 0) p_w = std::min(p_w, kt_per_ke * u_v * u_v / (4.0 * mp.rm_ohm));
  return p_w;
}

// hover_thrust_per_rotor, motor_power_per_rotor and propeller_diameter for the lift group
// (no_design.h): thrust_n is T, the least a lift rotor gives in hover.
void LiftRequirements(const Mission& m, const Catalog& cat, const GroupCandidates& c, int g, double thrust_n,
                      double mass_kg, double v_full_max_v, std::vector<UnmetRequirement>* out) {
  const MissionConstraints& k = m.constraints;
  const std::string rotors = std::to_string(LiftRotors(m));
  const ThrustCeiling t = BestHoverThrust(m, cat, c, v_full_max_v, thrust_n);
  if (t.motor >= 0 && t.thrust_n < thrust_n) {
    out->push_back({"hover_thrust_per_rotor", thrust_n, t.thrust_n, "N",
                    {cat.motors()[t.motor].id, cat.props()[t.prop].id},
                    "static thrust per rotor at the hover-throttle limit (" +
                        Fixed(100 * std::min(k.max_throttle, 1.0), 0) + " %) on the pack's full charge (" +
                        Fixed(v_full_max_v, 1) + " V) within the motor's ratings and the propeller's speed limits, "
                        "against the weight of the lightest vehicle (" + Fixed(mass_kg, 2) + " kg) over " + rotors +
                        " rotors",
                    "throttle, motor_current, motor_power, prop_max_rpm", GroupName(m, g)});
  }
  const auto [d_max_m, d_prop] = LargestProp(cat, c);
  if (d_prop < 0) return;
  double esc_max_current_a = 0.0;
  for (const int i : c.escs) esc_max_current_a = std::max(esc_max_current_a, EscReachCurrentA(cat.escs()[i]));
  double p_max_w = -kInf;
  int p_motor = -1;
  for (const int i : c.motors) {
    bool excluded = false;
    const MotorParams mp = ScenarioMotorParams(cat.motors()[i], m, nullptr, &excluded);
    const double p_w = excluded ? -kInf : ShaftPowerCeilingW(k, mp, v_full_max_v, esc_max_current_a);
    if (p_w > p_max_w) {
      p_max_w = p_w;
      p_motor = i;
    }
  }
  const double fm_max = k.max_figure_of_merit;  // at rest (FigureOfMeritLimit, mission.h)
  // docs/model.md section 11: P_ideal = T^1.5/sqrt(2*rho*A); the evaluator holds P >= P_ideal/FM_max.
  const double p_needed_w = IdealRotorPowerW(thrust_n, d_max_m, m.rho_kg_m3) / fm_max;
  if (p_motor < 0 || !(p_max_w < p_needed_w)) return;
  out->push_back({"motor_power_per_rotor", p_needed_w, p_max_w, "W",
                  {cat.motors()[p_motor].id, cat.props()[d_prop].id},
                  "the motor's shaft power within its ratings and the highest ESC current rating at " +
                      Fixed(v_full_max_v, 1) +
                      " V against the momentum-theory hover power of the lightest vehicle's thrust per rotor on the "
                      "largest propeller that fits (ideal power / figure of merit " + Fixed(fm_max, 2) + ")",
                  "motor_power, motor_current, esc_current", GroupName(m, g)});
  // The same equation solved for the disk: A = T^3/(2*rho*(FM_max*P_max)^2), D = sqrt(4*A/pi).
  const double area_m2 = std::pow(thrust_n, 3) / (2.0 * m.rho_kg_m3 * std::pow(fm_max * p_max_w, 2));
  out->push_back({"propeller_diameter", std::sqrt(4.0 * area_m2 / kPi), d_max_m, "m",
                  {cat.props()[d_prop].id, cat.motors()[p_motor].id},
                  "the rotor diameter whose momentum-theory hover power (figure of merit " + Fixed(fm_max, 2) +
                      ") the most powerful motor gives, against the largest propeller that fits",
                  "motor_power, motor_current, esc_current", GroupName(m, g)});
}

// pack_energy (no_design.h): the segments' energy at momentum theory with no drive loss, J.
double EnergyFloorJ(const Mission& m, const Catalog& cat, const std::vector<GroupCandidates>& groups,
                    double mass_kg) {
  double e_j = 0.0;
  for (std::size_t i = 0; i < m.segments.size(); ++i) {
    const Segment& sg = m.segments[i];
    const bool stretched = static_cast<int>(i) == m.objective.segment_index &&
                           m.objective.type == ObjectiveType::kMaxEndurance;
    if (stretched) continue;
    const double t_s = SegmentDurationS(sg, sg.airspeed_m_s.hi);  // the shortest (cruise: fastest)
    e_j += m.vehicle.avionics_power_w * t_s;
    const bool lifting = sg.type == SegmentType::kHover || (sg.type == SegmentType::kClimb && sg.climb_rate_m_s > 0);
    if (!lifting) continue;
    const double d_m = LargestProp(cat, groups[static_cast<std::size_t>(sg.group)]).first;
    if (!(d_m > 0)) continue;
    const int rotors = sg.rotors_active > 0 ? sg.rotors_active : GroupRotors(m, sg.group);
    const double v_m_s = sg.type == SegmentType::kClimb ? sg.climb_rate_m_s : 0.0;
    // Hover: T = W; climb: T = W + drag >= W (mission/flight.h), in axial inflow V.
    const double t_n = mass_kg * kStandardGravity / rotors;
    const double fm_max = FigureOfMeritLimit(m.constraints, v_m_s);
    e_j += rotors * IdealRotorPowerW(t_n, d_m, m.rho_kg_m3, v_m_s) / fm_max * t_s;
  }
  return e_j;
}

void EnergyRequirement(const Mission& m, const Catalog& cat, const std::vector<GroupCandidates>& groups,
                       const std::vector<BatteryOption>& options, double mass_kg, std::vector<UnmetRequirement>* out) {
  double best_j = -kInf;
  const BatteryOption* best = nullptr;
  for (const BatteryOption& o : options) {
    const double e_j = o.ocv_integral_v * AhToCoulomb(o.capacity_hi_ah);  // R4's budget
    if (e_j > best_j) {
      best_j = e_j;
      best = &o;
    }
  }
  const double needed_j = EnergyFloorJ(m, cat, groups, mass_kg);
  if (!best || !(best_j < needed_j)) return;
  out->push_back({"pack_energy", needed_j, best_j, "J", {best->entry->id},
                  "the energy above the " + Fixed(100 * m.battery.reserve_soc, 0) +
                      " % reserve of the largest pack option (" + std::to_string(best->cells) +
                      "S) against what the segments the objective does not stretch need at least (momentum theory, "
                      "no drive loss, the lightest vehicle)",
                  "", ""});
}

}  // namespace

std::vector<UnmetRequirement> UnmetRequirements(const Mission& m, const Catalog& cat) {
  std::vector<UnmetRequirement> out;
  const std::vector<BatteryOption> options = search_internal::BatteryOptions(m, cat);
  if (options.empty()) return out;
  double v_full_min_v = kInf, v_full_max_v = 0.0, v_cut_max_v = 0.0;
  for (const BatteryOption& o : options) {
    v_full_min_v = std::min(v_full_min_v, o.v_full);
    v_full_max_v = std::max(v_full_max_v, o.v_full);
    v_cut_max_v = std::max(v_cut_max_v, o.v_cut);
  }
  const int lift_group = LiftGroup(m);
  std::vector<GroupCandidates> groups;
  const search_internal::SizedPropOffer offer(m, cat);
  for (int g = 0; g < GroupCount(m); ++g) groups.push_back(CandidatesOf(m, cat, offer, g, g == std::max(0, lift_group)));
  VoltageRequirements(m, cat, groups, lift_group, v_full_min_v, v_cut_max_v, &out);
  if (lift_group < 0) return out;  // a wing-borne cruise only: no hover to bound
  const GroupCandidates& lift = groups[static_cast<std::size_t>(lift_group)];
  if (lift.props.empty()) FrameRequirement(m, cat, lift_group, &out);
  const double mass_kg = MassFloorKg(m, cat, options, groups);
  const int rotors = LiftRotors(m);
  if (rotors > 0 && !lift.props.empty() && !lift.motors.empty()) {
    LiftRequirements(m, cat, lift, lift_group, mass_kg * kStandardGravity / rotors, mass_kg, v_full_max_v, &out);
  }
  EnergyRequirement(m, cat, groups, options, mass_kg, &out);
  return out;
}

std::string RequirementValueText(double value, const std::string& unit) {
  const bool joules = unit == "J";  // SI inside; Wh is what a pack's label says
  const double x = joules ? value / 3600.0 : value;
  std::ostringstream v;
  if (std::fabs(x) >= 1000) {
    v << std::fixed << std::setprecision(0) << x;
  } else {
    v << std::setprecision(4) << x;
  }
  v << " " << (joules ? "Wh" : unit);
  return v.str();
}

std::string UnmetRequirementText(const UnmetRequirement& r, const std::map<std::string, long long>* pruned_by) {
  std::ostringstream o;
  auto value = [&](double x) { return RequirementValueText(x, r.unit); };
  o << r.requirement;
  if (!r.group.empty()) o << " (group " << r.group << ")";
  o << ": needs at least " << value(r.needed) << ", the catalog's best gives at most " << value(r.best_available);
  if (!r.components.empty()) {
    o << " (";
    for (std::size_t i = 0; i < r.components.size(); ++i) o << (i ? ", " : "") << r.components[i];
    o << ")";
  }
  o << ": " << r.description;
  if (r.search_rule.empty()) return o.str();
  if (!pruned_by) {
    o << " [search rule " << r.search_rule << "]";
    return o.str();
  }
  o << " [the search's rules pruned:";
  std::istringstream rules(r.search_rule);
  bool first = true;
  for (std::string rule; std::getline(rules >> std::ws, rule, ',');) {
    const auto it = pruned_by->find(rule);
    o << (first ? " " : ", ") << rule << " " << (it == pruned_by->end() ? 0 : it->second);
    first = false;
  }
  o << "]";
  return o.str();
}

}  // namespace dynosize
