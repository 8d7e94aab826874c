// The mission evaluator's construction (the parts, their masses, the data scenario and the
// assumed values), the battery at a capacity, and its entry points Solve and Simulate.
// The rest of MissionEvaluator, by what it does:
//   mission_eval_flight.cc       Run: the segments flown one after another (each segment's
//                                shaft point, the battery's sag, SOC, every constraint), and
//                                WithEndurance, the longest max_endurance stretch;
//   mission_eval_continuous.cc   the continuous variables (capacity, cruise airspeeds): a
//                                bracketed 1-D search, or a grid and COBYLA;
//   mission_eval_early_exits.cc  the search's early exits and bounds (EarlyExit and the proofs
//                                it rests on);
//   mission_eval_summary.cc      the designer's summary (hover, full throttle, climb rate) and
//                                the warnings.
#include "optimization/mission_eval.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.h"
#include "mission/flight.h"
#include "model/gear.h"
#include "model/physics.h"

namespace dynosize {

GroupParts FixedGroupParts(const Mission& m, const Catalog& cat, int g) {
  if (m.groups.empty() || !m.groups[g].fixed()) return {};
  const PropulsionGroup& grp = m.groups[g];
  auto look = [&](const char* key, const std::string& id, auto lookup) {
    try {
      return lookup(id);
    } catch (const Error& e) {
      throw DataError(m.file + ": $.propulsion." + grp.name + "." + key + ": \"" + id +
                      "\": not in the catalog (" + e.what() + ")");
    }
  };
  GroupParts p;
  p.motor = look("motor", grp.motor_id, [&](const std::string& id) { return &cat.motor(id); });
  p.esc = look("esc", grp.esc_id, [&](const std::string& id) { return &cat.esc(id); });
  p.prop = look("prop", grp.prop_id, [&](const std::string& id) { return &cat.prop(id); });
  return p;
}

MissionEvaluator::MissionEvaluator(const Mission& mission, const Combination& c,
                                   const PropModel* prop_model,
                                   const std::vector<const PropModel*>* group_prop_models)
    : m_(mission), c_(c) {
  const BatteryEntry& b = *c.battery;
  if (c.cells < 1 || c.cells % b.cells_series != 0) {
    throw UsageError("battery '" + b.id + "' has " + std::to_string(b.cells_series) +
                     " cells in series: --cells " + std::to_string(c.cells) +
                     " must be a positive multiple of it");
  }
  pack_base_ = MissionPackParams(m_.battery, b, c.cells);
  base_capacity_ah_ = pack_base_.cell_capacity_ah * pack_base_.n_parallel;
  for (const auto& k : pack_base_.assumed) assumed_.push_back("battery " + b.id + ": " + k);
  if (!b.mass_kg) throw DataError("battery '" + b.id + "' has no mass_kg: the mission needs it");
  if (!c.groups.empty() && static_cast<int>(c.groups.size()) != GroupCount(m_)) {
    throw UsageError("the combination has parts for " + std::to_string(c.groups.size()) +
                     " propulsion groups; the mission has " + std::to_string(GroupCount(m_)));
  }
  fixed_mass_kg_ = m_.vehicle.mass_kg;
  for (int g = 0; g < GroupCount(m_); ++g) {
    const GroupParts parts = c.Parts(g);
    if (!parts.motor || !parts.esc || !parts.prop) {
      throw UsageError("propulsion group '" + GroupName(m_, g) + "' has no motor, ESC or propeller");
    }
    // PropModels built by the caller: prop_model serves the group of c.prop, group_prop_models
    // the others; any group without one builds its own.
    const PropModel* given = prop_model && parts.prop == c.prop ? prop_model : nullptr;
    if (!given && group_prop_models && g < static_cast<int>(group_prop_models->size())) {
      given = (*group_prop_models)[g];
    }
    // The mission's data scenario (credibility.h): the motor's ratings estimated from its mass
    // when no source states them, the bands' ends in the pessimistic/optimistic scenarios.
    bool rating_estimated = false, motor_excluded = false;
    const MotorParams motor_params = ScenarioMotorParams(*parts.motor, m_, &rating_estimated, &motor_excluded);
    groups_.push_back(GroupDrive{parts, Drive(motor_params, ScenarioEscParams(*parts.esc, m_.objective.ranking)),
                                 given ? nullptr : std::make_unique<PropModel>(*parts.prop), nullptr, 0.0, {},
                                 false, false, false});
    GroupDrive& gd = groups_.back();
    gd.prop = given ? given : gd.owned_prop.get();
    gd.prop_adj = PropAdjustmentFor(*parts.prop, m_.objective.ranking);
    gd.folding_refused = FoldingPropRefused(*parts.prop, m_);
    gd.rating_estimated = rating_estimated;
    gd.motor_excluded = motor_excluded;
    if (rating_estimated) {
      assumed_.push_back("motor " + parts.motor->id +
                         (std::isfinite(parts.motor->params.max_power_w)
                              ? ": max_current_a (from mass and Kv)"
                              : ": max_power_w, max_current_a (from mass and Kv)"));
    }
    if (!parts.motor->mass_kg) {
      throw DataError("motor '" + parts.motor->id + "' has no mass_kg: the mission needs it");
    }
    const double motor_mass = *parts.motor->mass_kg;
    const ComponentMass esc_mass = EscMass(*parts.esc);
    if (esc_mass.assumed) assumed_.push_back("ESC " + parts.esc->id + ": mass_kg");
    const ComponentMass prop_mass = PropMass(*parts.prop);
    if (prop_mass.assumed) assumed_.push_back("propeller " + parts.prop->id + ": mass_kg");
    for (const auto& k : parts.motor->assumed_keys) assumed_.push_back("motor " + parts.motor->id + ": " + k);
    for (const auto& k : parts.esc->assumed_keys) assumed_.push_back("ESC " + parts.esc->id + ": " + k);
    for (const auto& k : parts.prop->assumed_keys) assumed_.push_back("propeller " + parts.prop->id + ": " + k);
    fixed_mass_kg_ += GroupRotors(m_, g) * (motor_mass + esc_mass.kg + prop_mass.kg);
    if (parts.motor->params.rth_k_per_w > 0) {
      gd.rth_k_per_w = parts.motor->params.rth_k_per_w;
    } else {
      gd.rth_k_per_w = AssumedMotorRthKPerW(motor_mass);
      assumed_.push_back("motor " + parts.motor->id + ": rth_k_per_w");
    }
  }
  lift_rotors_ = LiftRotors(m_);
  lift_group_ = std::max(0, LiftGroup(m_));
}

double MissionEvaluator::BatteryMassKg(double capacity_ah) const {
  return PackAt(capacity_ah).cell_mass_kg * pack_base_.n_series * pack_base_.n_parallel;
}

BatteryPackParams MissionEvaluator::PackAt(double capacity_ah) const {
  BatteryPackParams p = pack_base_;
  if (capacity_ah > 0) {
    // Sizing: the same cell technology at another capacity keeps its specific energy
    // (mass ~ capacity), its C-rate (current rating ~ capacity) and its R*capacity product.
    const double k = capacity_ah / base_capacity_ah_;
    p.cell_capacity_ah *= k;
    p.cell_mass_kg *= k;
    p.cell_ri_ohm /= k;
    p.cell_max_current_a *= k;
    p.cell_peak_current_a *= k;
  }
  return p;
}

double ObjectiveOfScore(ObjectiveType type, double score) {
  return type == ObjectiveType::kMinEnergy ? score : -score;
}

void MissionEvaluator::FillPropNotes(MissionResult* r) {
  for (SegmentResult& s : r->segments) {
    if (s.prop_edge && s.prop_note.empty()) s.prop_note = s.prop_edge_eval.Message();
  }
}

MissionResult MissionEvaluator::Solve(double cutoff_score, bool explain, bool decide, bool search) const {
  search_only_ = search && !explain;
  MissionResult r = SolveContinuous(cutoff_score, explain, decide && std::isfinite(cutoff_score), search);
  if (explain) FillPropNotes(&r);
  return r;
}

MissionResult MissionEvaluator::Simulate(const ContinuousVars& vars) const {
  MissionResult r = WithEndurance(vars);
  FillPropNotes(&r);
  Summarize(&r);
  AddWarnings(&r);
  return r;
}

double MissionEvaluator::WindingTempC(const OperatingPoint& p, int group) const {
  constexpr double kAlphaCuPerK = 0.00393;  // copper, at 20-25 C (IEC 60028)
  constexpr double kRmReferenceC = 25.0;    // datasheet resistance at room temperature (assumed)
  constexpr double kRunawayTempC = 1000.0;  // "no steady state": far above any limit, finite
  const MotorParams& mp = groups_[group].drive.motor();
  const double rth_k_per_w_ = groups_[group].rth_k_per_w;
  const double kp = MaxKtPerKe(mp.type);
  const double i = p.irms_a;
  const double p_cu_ref = kp * mp.rm_ohm * i * i;              // copper loss at Rm, W
  // The motor's own no-load loss: its shaft power is the propeller's plus the gear loss, which
  // heats the gearbox, not the winding (model/gear.h; direct drive: pmech_w itself).
  const Gear& gear = groups_[group].parts.motor->gear;
  const double p_shaft = gear.geared() ? MotorShaftOf(p.omega_rad_s, p.torque_nm, gear).power_w : p.pmech_w;
  const double p_other = std::max(0.0, p.pac_w - p_shaft - p_cu_ref);  // no-load loss, W
  const double t_air = m_.air_temperature_c;
  // T - t_air = Rth*(p_cu_ref*(1 + a*(T - T_ref)) + p_other), linear in T.
  const double denom = 1.0 - kAlphaCuPerK * rth_k_per_w_ * p_cu_ref;
  if (!(denom > 0.0)) return kRunawayTempC;
  const double rise = rth_k_per_w_ * (p_cu_ref * (1.0 + kAlphaCuPerK * (t_air - kRmReferenceC)) + p_other) / denom;
  return std::min(t_air + std::max(rise, 0.0), kRunawayTempC);
}

}  // namespace dynosize
