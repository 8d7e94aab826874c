// The joint search's bounds (joint_search.h; G2, docs/search.md#g2): a rotor's and a segment's
// power from below, the score assembled from them, the rules and mass floors of the outer and
// inner groups, and an outer pair's or triple's bound. The other free groups' least power and
// the coupled frontier: joint_frontier.cc.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/units.h"
#include "model/physics.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "optimization/joint_search.h"
#include "optimization/mass_floors.h"
#include "optimization/prop_bounds.h"

namespace dynosize::search_internal {

namespace {

// G2's inner filter's outer energy (JointBounds::OuterEnergy): e_outer_at (the outer segments'
// energy at a vehicle of a mass, a bound at every heavier one) at floor_kg and at each grid mass
// of G1's geometric grid from m0 above it up to top_kg; an infeasible mass ends the list (every
// heavier vehicle is infeasible too, M3).
template <typename EnergyAt>
JointBounds::OuterEnergy OuterEnergyByMass(double raw_kg, double floor_kg, double m0, double top_kg, double rest_j,
                                           EnergyAt&& e_outer_at) {
  JointBounds::OuterEnergy out;
  out.valid = true;
  out.raw_kg = raw_kg;
  out.rest_j = rest_j;
  out.outer_j_by_kg.emplace_back(floor_kg, e_outer_at(floor_kg));
  int k = floor_kg > m0 ? static_cast<int>(std::floor(std::log(floor_kg / m0) / std::log(kFixedPowerMassStep))) + 1 : 1;
  for (; k < kFixedPowerMasses && std::isfinite(out.outer_j_by_kg.back().second); ++k) {
    const double kg = m0 * std::pow(kFixedPowerMassStep, k);
    if (kg > top_kg) break;
    if (kg <= out.outer_j_by_kg.back().first) continue;
    out.outer_j_by_kg.emplace_back(kg, e_outer_at(kg));
  }
  return out;
}

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRotorCeilingRadS = 1e5;  // RotorLowerBound's: ~1e6 rpm, beyond any motor
constexpr std::size_t kNoIndex = std::numeric_limits<std::size_t>::max();  // OuterBound's: not a free cruise

}  // namespace

RotorBound RotorLowerBound(const Mission& m, const Segment& sg, const PropEntry& prop, const PropModel& model,
                           double mass_kg) {
  RotorBound rb;
  const RotorLoad ld = SegmentRotorLoad(m, sg, mass_kg, sg.airspeed_m_s.lo);
  rb.rotors = ld.rotors;
  // A free cruise's speeds are its samples' (JointBounds::OuterCruise); a shaft has none.
  if ((sg.type == SegmentType::kCruise && sg.airspeed_m_s.free()) || sg.type == SegmentType::kShaft) return rb;
  const double v = ld.axial_airspeed_m_s;
  // A speed from below keeping thrust(lo) <= T (M1: thrust rises with speed), so lo is at or below the
  // evaluator's root; a propeller that cannot give T below the ceiling turns faster (and R3
  // then finds the throttle above one).
  double lo = 0.0, hi = kRotorCeilingRadS;
  if (model.Evaluate(hi, m.rho_kg_m3, v).thrust_n < ld.thrust_per_rotor_n) {
    lo = hi;
  } else {
    lo = SpeedFromBelow(model, m.rho_kg_m3, ld.thrust_per_rotor_n, v, lo, hi, 60);
  }
  if (!(lo > 0)) return rb;
  rb.thrust_n = ld.thrust_per_rotor_n;
  rb.axial_airspeed_m_s = v;
  PropEvaluation ev = model.Evaluate(lo, m.rho_kg_m3, v);
  // The scenario's load, as the evaluator flies it (it keeps rising with speed: M1).
  AdjustPropEvaluation(PropAdjustmentFor(prop, m.objective.ranking), prop.diameter_m, &ev);
  if (!(ev.torque_nm > 0)) return rb;
  rb.omega_rad_s = lo;
  rb.torque_nm = ev.torque_nm;
  return rb;
}

SegmentBound FreeCruiseSegmentBound(const Mission& m, std::size_t si, const GroupParts& parts, const Drive& drive,
                                    const PropModel& model, const BatteryOption& bo, double mass_kg, bool with_power) {
  const Segment& sg = m.segments[si];
  SegmentBound b;
  b.power_w = m.vehicle.avionics_power_w;
  // R7 over the range: a wing-borne cruise's inflow is its airspeed, at least lo, and the
  // shaft turns no faster than n_max (below), so J >= lo/(n_max*D) at every airspeed.
  const bool static_only = model.data_kind() != PropDataKind::kTables || parts.prop->j_tables.empty();
  const double n_max = drive.NoLoadSpeed(bo.v_full, 1.0) / (2.0 * kPi);
  if (static_only && sg.lift_to_drag > 0 && n_max > 0 &&
      sg.airspeed_m_s.lo / (n_max * parts.prop->diameter_m) > m.constraints.max_static_advance_ratio) {
    b.infeasible = "prop_no_forward_flight_data";
  }
  if (with_power) b.power_w += FreeCruisePowerLowerBoundW(m, sg, parts, model, mass_kg);
  return b;
}

SegmentBound SegmentPowerBound(const Mission& m, std::size_t si, const GroupParts& parts, const MotorParams& mp,
                               const Drive& drive, double tr_max, double esc_max_current_a, const PropModel& model,
                               const BatteryOption& bo, double mass_kg, const RotorBound& rb) {
  const Segment& sg = m.segments[si];
  const MissionConstraints& k = m.constraints;
  SegmentBound b;
  b.power_w = m.vehicle.avionics_power_w;
  if (sg.type == SegmentType::kShaft) return b;
  if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free()) {
    return FreeCruiseSegmentBound(m, si, parts, drive, model, bo, mass_kg, true);
  }
  const bool static_only = model.data_kind() != PropDataKind::kTables || parts.prop->j_tables.empty();
  if (!(rb.omega_rad_s > 0)) return b;
  // R3 at the bound point.
  const Drive::InverseCurrents hi = drive.InverseLight(bo.v_full, rb.torque_nm, rb.omega_rad_s);
  b.irms_lb_a = hi.irms_a;
  b.infeasible = DriveRule(k, mp, drive, bo.v_full, hi, rb.torque_nm, rb.omega_rad_s, tr_max, esc_max_current_a);
  // R7: static-only data in axial flow. The shaft turns no faster than the drive's no-load
  // speed at full throttle and the full-charge voltage (M2), so J >= V_ax/(n_max*D); above the
  // mission's max_static_advance_ratio the evaluator fails prop_no_forward_flight_data.
  if (!b.infeasible && static_only && rb.axial_airspeed_m_s > 0) {
    const double n_max = drive.NoLoadSpeed(bo.v_full, 1.0) / (2.0 * kPi);
    if (n_max > 0 && rb.axial_airspeed_m_s / (n_max * parts.prop->diameter_m) > k.max_static_advance_ratio) {
      b.infeasible = "prop_no_forward_flight_data";
    }
  }
  // PDC is linear in VDC (eqs 57, 59): the smaller of the two ends bounds every voltage between.
  // (Each end's PDC = VDC*IDC from InverseLight, Inverse's bit for bit.)
  const double pdc_hi_w = bo.v_full * hi.idc_a;
  double pdc = rb.rotors * std::max(0.0, std::min(pdc_hi_w, drive.InversePdcW(bo.v_cut, rb.torque_nm, rb.omega_rad_s)));
  // Momentum theory: a feasible point's propeller data give P >= P_ideal/max_figure_of_merit
  // (the evaluator's prop_figure_of_merit, V_ax the inflow unless the data are static-only);
  // the scenario's power is at least P_ideal (credibility.h: raised, or capped at FM 1), so
  // P_ideal/max(1, max_figure_of_merit) bounds it in every scenario; and PDC >= Pmech when
  // neither the motor nor the ESC can create energy (docs/model.md section 10).
  if (DriveIsLossy(drive.motor(), drive.esc().c1, drive.esc().c0)) {
    const double p_ideal = IdealRotorPowerW(rb.thrust_n, parts.prop->diameter_m, m.rho_kg_m3,
                                            static_only ? 0.0 : rb.axial_airspeed_m_s);
    pdc = std::max(pdc, rb.rotors * p_ideal / std::max(1.0, k.max_figure_of_merit));
  }
  b.power_w += pdc;
  return b;
}

double ScoreFromSegmentPowers(const Mission& m, const std::vector<double>& p_lb_w, const BatteryOption& bo) {
  auto t_min = [](const Segment& sg) { return SegmentDurationS(sg, sg.airspeed_m_s.hi); };
  if (m.objective.type == ObjectiveType::kMinEnergy) {
    double e = 0;
    for (std::size_t si = 0; si < m.segments.size(); ++si) e += p_lb_w[si] * t_min(m.segments[si]);
    return e / 3600.0;
  }
  if (m.objective.type != ObjectiveType::kMaxEndurance || m.objective.segment_index < 0) return -kInf;
  const std::size_t ist = static_cast<std::size_t>(m.objective.segment_index);
  const Segment& st = m.segments[ist];
  // A stretched segment needs a power bound that holds at every instant: constant thrust.
  if (st.type == SegmentType::kCruise && st.airspeed_m_s.free()) return -kInf;
  double e_other = 0;
  for (std::size_t si = 0; si < m.segments.size(); ++si) {
    if (si != ist) e_other += p_lb_w[si] * t_min(m.segments[si]);
  }
  const double e_max = bo.ocv_integral_v * AhToCoulomb(bo.capacity_hi_ah);
  return BudgetScore(LongestFixedDurationS(m), e_max, e_other, p_lb_w[ist]);
}

bool JointBounds::PropAllowed(int group, const PropEntry& p) const {
  return PropFrameRule(m_, offer_, group, Lifts(group), cat_, static_cast<std::size_t>(&p - cat_.props().data())) == nullptr;
}

const char* JointBounds::PropRule(int prop) const {
  return PropFrameRule(m_, offer_, outer_, Lifts(outer_), cat_, static_cast<std::size_t>(prop));
}

const char* JointBounds::MotorRule(int motor, std::size_t o) const {
  const MotorEntry& mo = cat_.motors()[static_cast<std::size_t>(motor)];
  if (!mo.exclude_reason.empty()) return "catalog_exclude";
  if (!mo.mass_kg) return "motor_without_mass";
  if (Lifts(outer_)) {
    bool excluded = false;
    ScenarioMotorParams(mo, m_, nullptr, &excluded);
    if (excluded) return "motor_unrated";
    if (options_[o].v_full > MotorMaxVoltageV(mo)) return "motor_voltage";
  }
  return nullptr;
}

JointBounds::JointBounds(const Mission& m, const Catalog& cat, const PropGridCache& cache)
    : m_(m), cat_(cat), offer_(m, cat) {
  for (const auto& p : cache.models) models_.push_back(p.get());
  for (const PropEntry& p : cat.props()) adjustments_.push_back(PropAdjustmentFor(p, m.objective.ranking));
  lift_group_ = std::max(0, LiftGroup(m));
  lift_rotors_ = LiftRotors(m);
  // The outer group: a free group that does not lift the vehicle, so that the innermost search
  // is the lift group's, whose hover gives R2-R4 their grip.
  std::vector<int> free;
  for (int g = 0; g < GroupCount(m); ++g) {
    if (!m.groups[g].fixed()) free.push_back(g);
  }
  if (free.size() < 2) throw std::logic_error("JointBounds: needs two or more free groups");
  outer_ = free.front() == lift_group_ ? free[1] : free.front();
  options_ = BatteryOptions(m, cat);
  escs_ = BuildEscTable(cat, options_);
  const std::size_t n_seg = m.segments.size();
  for (std::size_t si = 0; si < n_seg; ++si) {
    if (m.segments[si].group == outer_) outer_segments_.push_back(si);
  }
  // Every group's lightest: fixed groups exactly, free ones from the catalog's lightest motor,
  // propeller (R0 for the group) and ESC (R1 for the option), then LightestSurvivorKg.
  double motor_min = kInf;
  for (const MotorEntry& mo : cat.motors()) {
    if (mo.mass_kg && mo.exclude_reason.empty()) motor_min = std::min(motor_min, *mo.mass_kg);
  }
  if (!std::isfinite(motor_min)) motor_min = 0.0;
  std::vector<double> prop_min(m.groups.size(), kInf);
  for (int g : free) {
    for (const PropEntry& p : cat.props()) {
      if (PropAllowed(g, p)) prop_min[g] = std::min(prop_min[g], PropMassKg(p));
    }
    if (!std::isfinite(prop_min[g])) prop_min[g] = 0.0;
  }
  double fixed_kg = 0;
  std::vector<GroupParts> fixed(m.groups.size());
  for (int g = 0; g < GroupCount(m); ++g) {
    if (!m.groups[g].fixed()) continue;
    fixed[g] = FixedGroupParts(m, cat, g);
    if (!fixed[g].motor->mass_kg) throw DataError("motor '" + fixed[g].motor->id + "' has no mass_kg: the mission needs it");
    fixed_kg += m.groups[g].rotors * (*fixed[g].motor->mass_kg + EscMassKg(*fixed[g].esc) + PropMassKg(*fixed[g].prop));
  }
  std::vector<std::unique_ptr<PropModel>> fixed_models(m.groups.size());
  for (int g = 0; g < GroupCount(m); ++g) {
    if (m.groups[g].fixed()) fixed_models[g] = std::make_unique<PropModel>(*fixed[g].prop);
  }
  grids_ = &cache.grids;
  for (std::size_t o = 0; o < options_.size(); ++o) {
    const BatteryOption& bo = options_[o];
    const double esc_min = std::isfinite(escs_.min_mass_kg[o]) ? escs_.min_mass_kg[o] : 0.0;
    const double base = m.vehicle.mass_kg + bo.mass_lo_kg + fixed_kg;
    std::vector<double> lightest(m.groups.size(), 0.0);
    for (int g : free) {
      lightest[g] = m.groups[g].rotors * (motor_min + prop_min[g] + esc_min);
    }
    // The lightest choice of each free group that can fly its own segments (R0, R1, R3, R7 at
    // the lightest vehicle): a feasible choice survives them at its true mass, so at any lighter
    // one (M1-M3), and so at the lightest vehicle found so far; each pass can only raise the
    // lightest vehicle, and every pass keeps it a lower bound.
    auto total = [&]() {
      double x = base;
      for (int g : free) x += lightest[g];
      return x;
    };
    for (int pass = 0; pass < 2; ++pass) {
      const double vehicle_kg = total();
      for (int g : free) {
        const double parts_kg = LightestSurvivorKg(g, o, vehicle_kg);
        lightest[g] = std::max(lightest[g], std::isfinite(parts_kg) ? m.groups[g].rotors * (parts_kg + esc_min)
                                                                   : lightest[g]);
      }
    }
    const double mass = total();
    if (o + 1 == options_.size()) {  // the ctor's only
      std::vector<std::vector<std::pair<double, int>>>().swap(props_by_mass_);
      std::vector<std::pair<double, int>>().swap(motors_by_mass_);
    }
    outer_lightest_kg_.push_back(lightest[outer_]);
    if (free.size() == 2) inner_lightest_kg_.push_back(lightest[free[0] == outer_ ? free[1] : free[0]]);
    mass_min_kg_.push_back(mass);
    std::vector<double> p(n_seg, m.vehicle.avionics_power_w);
    for (std::size_t si = 0; si < n_seg; ++si) {
      const Segment& sg = m.segments[si];
      if (sg.group == outer_) continue;
      if (m.groups[sg.group].fixed()) {  // G1's bound with the group's own drive
        const GroupParts& parts = fixed[sg.group];
        const MotorParams mp = ScenarioMotorParams(*parts.motor, m);
        const Drive d(mp, ScenarioEscParams(*parts.esc, m.objective.ranking));
        const RotorBound rb = RotorLowerBound(m, sg, *parts.prop, *fixed_models[sg.group], mass);
        // Feasibility is the evaluator's to judge for a fixed group (no rating check here).
        p[si] = SegmentPowerBound(m, si, parts, mp, d, kInf, kInf, *fixed_models[sg.group], bo, mass, rb).power_w;
        continue;
      }
      p[si] = MinFreeGroupPower(sg.group, si, o, mass);
    }
    other_power_w_.push_back(std::move(p));
  }
  // G1's grid masses per option (RotorCacheIndex), computed once.
  grid_kg_.assign(options_.size() * static_cast<std::size_t>(kFixedPowerMasses), 0.0);
  for (std::size_t o = 0; o < options_.size(); ++o) {
    for (int k = 0; k < kFixedPowerMasses; ++k) {
      grid_kg_[o * static_cast<std::size_t>(kFixedPowerMasses) + static_cast<std::size_t>(k)] =
          mass_min_kg_[o] * std::pow(kFixedPowerMassStep, k);
    }
  }
  const std::size_t n_cache = options_.size() * n_seg * cat.props().size() * static_cast<std::size_t>(kFixedPowerMasses);
  rotor_cache_.assign(n_cache, RotorBound{});
  rotor_done_.assign(n_cache, 0);
  mass_floor_kg_.assign(n_cache, -1.0);
  cruise_index_.assign(n_cache, -1);
  for (std::size_t si : outer_segments_) {
    const Segment& sg = m.segments[si];
    if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free()) cruise_momentum_w_.assign(n_cache, kNaN);
  }
  if (free.size() == 2 && m.objective.type == ObjectiveType::kMinEnergy) {
    inner_ = free[0] == outer_ ? free[1] : free[0];
    frontier_.assign(options_.size(), std::vector<std::vector<FrontierPoint>>(kFrontierLevels));
    frontier_done_.assign(options_.size(), std::vector<char>(kFrontierLevels, 0));
    inner_floors_.assign(options_.size(), std::vector<std::vector<std::uint16_t>>(kFrontierLevels));
    for (std::size_t o = 0; o < options_.size(); ++o) Frontier(o, 0.0);
  }
}

// R7 and R6 as mass floors of the outer group's segment si on `prop` (mass_floors.h) for a
// vehicle of at least mass_kg: scanned up from the grid mass at or below it (RotorCacheIndex; a
// floor found from a lighter grid mass that reaches this one serves), kept per grid mass. kInf:
// no mass passes; at most the grid mass: no floor above it.
double JointBounds::MassFloorKg(int prop, std::size_t si, std::size_t o, double mass_kg) {
  double grid_kg = 0;
  const std::size_t i = RotorCacheIndex(prop, si, o, mass_kg, &grid_kg);
  if (mass_floor_kg_[i] >= 0) return mass_floor_kg_[i];
  const std::size_t k = i % static_cast<std::size_t>(kFixedPowerMasses);
  if (k > 0 && mass_floor_kg_[i - 1] >= grid_kg) {
    mass_floor_kg_[i] = mass_floor_kg_[i - 1];
  } else {
    mass_floor_kg_[i] = SegmentMassFloorKg(m_, m_.segments[si], cat_.props()[static_cast<std::size_t>(prop)],
                                           *models_[static_cast<std::size_t>(prop)],
                                           (*grids_)[static_cast<std::size_t>(prop)].monotone, grid_kg)
                            .kg;
  }
  return mass_floor_kg_[i];
}

// Thrust-to-weight (checked on the lift group at full throttle): the full-throttle speed is
// below the drive's no-load speed at full throttle and the full-charge voltage (eqs 42, 48;
// zero or the real ESC resistance only lowers it), so, the static thrust rising with speed (M1,
// the propeller's grid checked), the lift rotors give at most T(omega_nl) each; a choice whose
// T(omega_nl) is below min_thrust_to_weight x the lightest weight fails the limit whatever else
// is chosen.
bool JointBounds::ReachesThrustToWeight(int group, const Drive& drive, int prop, double vehicle_kg,
                                        std::size_t o) const {
  const MissionConstraints& k = m_.constraints;
  const int rotors = lift_rotors_;
  const PropGrid& g = (*grids_)[static_cast<std::size_t>(prop)];
  if (!Lifts(group) || !(k.min_thrust_to_weight > 0) || rotors <= 0 || !g.monotone) return true;
  const double w_nl = drive.NoLoadSpeed(options_[o].v_full, 1.0);
  if (!(w_nl > 0)) return false;
  const double need_n = k.min_thrust_to_weight * vehicle_kg * kStandardGravity;
  // The static grid's thrust at its last speed at or below w_nl is at most the thrust at w_nl
  // (M1, the grid rises): when it is enough, so is the propeller's at w_nl. Else the model is
  // read at w_nl itself, so a refusal never rests on the grid.
  const std::ptrdiff_t i = std::upper_bound(g.omega, g.omega + kGrid, w_nl) - g.omega - 1;
  if (i >= 0 && rotors * g.thrust[i] >= need_n) return true;
  const double t_max = models_[static_cast<std::size_t>(prop)]->Evaluate(w_nl, m_.rho_kg_m3, 0.0).thrust_n;
  return rotors * t_max >= need_n;
}

double JointBounds::LightestSurvivorKg(int group, std::size_t o, double vehicle_kg) {
  const auto& motors = cat_.motors();
  const auto& props = cat_.props();
  // The usable motors by mass, once; the group's propellers by mass, once per group (the same
  // lists for every option and pass).
  if (props_by_mass_.size() != m_.groups.size()) props_by_mass_.resize(m_.groups.size());
  if (motors_by_mass_.empty()) {
    for (std::size_t mi = 0; mi < motors.size(); ++mi) {
      if (motors[mi].mass_kg && motors[mi].exclude_reason.empty()) {
        motors_by_mass_.emplace_back(*motors[mi].mass_kg, static_cast<int>(mi));
      }
    }
    std::sort(motors_by_mass_.begin(), motors_by_mass_.end());
  }
  std::vector<std::pair<double, int>>& props_by_mass = props_by_mass_[static_cast<std::size_t>(group)];
  if (props_by_mass.empty()) {
    for (std::size_t pi = 0; pi < props.size(); ++pi) {
      if (PropAllowed(group, props[pi])) props_by_mass.emplace_back(PropMassKg(props[pi]), static_cast<int>(pi));
    }
    std::sort(props_by_mass.begin(), props_by_mass.end());
  }
  if (props_by_mass.empty()) return kInf;
  // The (motor, propeller) pairs in ascending motor + propeller mass, merged lazily: a heap
  // holds each motor's next propeller (by position in props_by_mass), so the walk pays for the
  // pairs it reaches, not for sorting every pair. The first pair that survives is the lightest
  // that does (ties in mass: the same mass, whichever is taken first).
  using Next = std::tuple<double, std::size_t, std::size_t>;  // (kg, motor position, propeller position)
  std::vector<Next> heap;
  heap.reserve(motors_by_mass_.size());
  for (std::size_t a = 0; a < motors_by_mass_.size(); ++a) {
    heap.emplace_back(motors_by_mass_[a].first + props_by_mass[0].first, a, 0);
  }
  std::make_heap(heap.begin(), heap.end(), std::greater<>());
  std::vector<std::size_t> segs;
  for (std::size_t si = 0; si < m_.segments.size(); ++si) {
    if (m_.segments[si].group == group) segs.push_back(si);
  }
  std::vector<RotorBound> rbs(props.size() * segs.size());
  std::vector<char> done(rbs.size(), 0);
  const BatteryOption& bo = options_[o];
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), std::greater<>());
    const auto [kg, a, b] = heap.back();
    heap.pop_back();
    if (b + 1 < props_by_mass.size()) {
      heap.emplace_back(motors_by_mass_[a].first + props_by_mass[b + 1].first, a, b + 1);
      std::push_heap(heap.begin(), heap.end(), std::greater<>());
    }
    const int mi = motors_by_mass_[a].second, pi = props_by_mass[b].second;
    const MotorEntry& mo = motors[static_cast<std::size_t>(mi)];
    bool excluded = false;
    const MotorParams mp = ScenarioMotorParams(mo, m_, nullptr, &excluded);
    if (Lifts(group) && (excluded || bo.v_full > MotorMaxVoltageV(mo))) continue;  // R0, R1
    for (std::size_t c = 0; c < escs_.classes.size(); ++c) {
      if (escs_.per_option[o][c].empty()) continue;
      // SegmentPowerBound reads the ESC's C1 and C0 for a free-airspeed cruise
      // (FreeCruisePowerLowerBoundW): a member's, as MinFreeGroupPower does.
      const EscEntry& member = cat_.escs()[static_cast<std::size_t>(escs_.classes[c].members.front())];
      const GroupParts parts{&mo, &member, &props[static_cast<std::size_t>(pi)]};
      const Drive d(mp, ZeroResistanceEsc(escs_.classes[c]));
      bool ok = ReachesThrustToWeight(group, d, pi, vehicle_kg, o);
      for (std::size_t k = 0; k < segs.size() && ok; ++k) {
        const std::size_t j = static_cast<std::size_t>(pi) * segs.size() + k;
        if (!done[j]) {
          rbs[j] = RotorLowerBound(m_, m_.segments[segs[k]], props[static_cast<std::size_t>(pi)],
                                   *models_[static_cast<std::size_t>(pi)], vehicle_kg);
          done[j] = 1;
        }
        ok = !SegmentPowerBound(m_, segs[k], parts, mp, d, ThrottleLimit(m_.constraints, escs_.classes[c].tr_sat), kInf,
                                *models_[static_cast<std::size_t>(pi)], bo, vehicle_kg, rbs[j]).infeasible;
      }
      if (ok) return kg;
    }
  }
  return kInf;
}

std::size_t JointBounds::RotorCacheIndex(int prop, std::size_t si, std::size_t o, double mass_kg,
                                         double* grid_kg) const {
  // The grid mass at or below mass_kg (G1's geometric grid from the option's lightest vehicle).
  const double m0 = mass_min_kg_[o];
  const double* grid = &grid_kg_[o * static_cast<std::size_t>(kFixedPowerMasses)];
  // The last grid mass at or below mass_kg (binary search on the tabulated grid; 0 below it).
  const int k = std::max(0, static_cast<int>(std::upper_bound(grid, grid + kFixedPowerMasses, mass_kg) - grid) - 1);
  *grid_kg = k == 0 ? std::min(m0, mass_kg) : grid[k];
  return ((o * m_.segments.size() + si) * cat_.props().size() + static_cast<std::size_t>(prop)) *
             static_cast<std::size_t>(kFixedPowerMasses) + static_cast<std::size_t>(k);
}

const RotorBound& JointBounds::OuterRotor(int prop, std::size_t si, std::size_t o, double mass_kg) {
  double mk = 0;
  const std::size_t i = RotorCacheIndex(prop, si, o, mass_kg, &mk);
  if (!rotor_done_[i]) {
    rotor_cache_[i] = RotorLowerBound(m_, m_.segments[si], cat_.props()[static_cast<std::size_t>(prop)],
                                      *models_[static_cast<std::size_t>(prop)], mk);
    rotor_done_[i] = 1;
  }
  return rotor_cache_[i];
}

double JointBounds::CruiseMomentumAboveW(int prop, std::size_t si, std::size_t o, double mass_kg) {
  double grid_kg = 0;
  const std::size_t at = RotorCacheIndex(prop, si, o, mass_kg, &grid_kg);
  // The first grid mass at or above mass_kg, from the one after RotorCacheIndex's.
  const std::size_t n = static_cast<std::size_t>(kFixedPowerMasses);
  const double* grid = &grid_kg_[o * n];
  std::size_t k = at % n + 1;
  while (k < n && grid[k] < mass_kg) ++k;
  if (k == n) return kInf;  // above the grid's top
  const std::size_t i = at - at % n + k;
  if (std::isnan(cruise_momentum_w_[i])) {
    const double above_kg = grid[k];
    const std::size_t pi = static_cast<std::size_t>(prop);
    const CruisePropBound pb{&cat_.props()[pi], models_[pi], adjustments_[pi], true};
    cruise_momentum_w_[i] = FreeCruiseRotorPowerLowerBoundW(m_, m_.segments[si], pb, nullptr, above_kg);
  }
  return cruise_momentum_w_[i];
}

SegmentBound JointBounds::OuterSegmentBound(std::size_t si, const GroupParts& parts, const Drive& drive, double tr_max,
                                            double esc_max_a, int prop, std::size_t o, double mass_kg, double known_w) {
  const Segment& sg = m_.segments[si];
  const PropModel& model = *models_[static_cast<std::size_t>(prop)];
  if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free() && !cruise_momentum_w_.empty()) {
    // Held 1e-9 above: the momentum bound rises with the mass, but not to the last bit.
    const double above_w = m_.vehicle.avionics_power_w + CruiseMomentumAboveW(prop, si, o, mass_kg) * (1.0 + 1e-9);
    return FreeCruiseSegmentBound(m_, si, parts, drive, model, options_[o], mass_kg, !(above_w < known_w));
  }
  return SegmentPowerBound(m_, si, parts, drive.motor(), drive, tr_max, esc_max_a, model, options_[o], mass_kg,
                           OuterRotor(prop, si, o, mass_kg));
}

const FreeCruiseSamples& JointBounds::OuterCruise(int prop, std::size_t si, std::size_t o, double mass_kg) {
  double mk = 0;
  const std::size_t i = RotorCacheIndex(prop, si, o, mass_kg, &mk);
  if (cruise_index_[i] < 0) {
    const std::size_t pi = static_cast<std::size_t>(prop);
    const CruisePropBound pb{&cat_.props()[pi], models_[pi], adjustments_[pi], true};
    cruise_index_[i] = static_cast<int>(cruise_samples_.size());
    cruise_samples_.push_back(SampleFreeCruise(m_, m_.segments[si], pb, mk, true));
  }
  return cruise_samples_[static_cast<std::size_t>(cruise_index_[i])];
}

double JointBounds::OuterCruiseFloorW(const Drive& drive, int prop, std::size_t si, std::size_t o, double mass_kg) {
  const std::size_t pi = static_cast<std::size_t>(prop);
  const MotorParams& mp = drive.motor();
  // The drive's own ESC values decide whether a stage can create energy: a class's catalog C1,
  // C0 (each real member's scenario values only raise C0) or the real ESC's scenario values.
  CruisePropBound pb{&cat_.props()[pi], models_[pi], adjustments_[pi], DriveIsLossy(mp, drive.esc().c1, drive.esc().c0)};
  pb.with_prop_data = true;
  const MotorLossFloor loss = LossFloorOf(mp);
  const CruiseDriveBound db{&drive, options_[o].v_full, options_[o].v_cut};
  return m_.vehicle.avionics_power_w +
         FreeCruiseRotorPowerFromSamples(m_, m_.segments[si], pb, OuterCruise(prop, si, o, mass_kg),
                                         coupled_ ? &db : nullptr, &loss);
}

const char* JointBounds::VoltageLeftRule(const Drive& drive, int prop, std::size_t o, double mass_kg, double tr_max) {
  const BatteryOption& bo = options_[o];
  const double q_c = AhToCoulomb(bo.capacity_hi_ah);
  const int stretch = m_.objective.type == ObjectiveType::kMaxEndurance ? m_.objective.segment_index : -1;
  double charge_c = 0;
  for (std::size_t si = 0; si < m_.segments.size(); ++si) {
    const Segment& sg = m_.segments[si];
    // The terminal current is at least the power bound over the full-charge OCV, so the charge
    // drawn by the segment's end is at least the sum's (R10, coulomb counting).
    const double t_min = static_cast<int>(si) == stretch ? 0.0 : SegmentDurationS(sg, sg.airspeed_m_s.hi);
    charge_c += kChargeAllowance * scratch_[si] * t_min / bo.v_full;
    const double soc = 1.0 - charge_c / q_c;
    if (soc < m_.battery.reserve_soc) return "reserve_soc";  // the SOC only falls
    if (sg.group != outer_ || sg.type == SegmentType::kShaft || (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free())) {
      continue;
    }
    const RotorBound& rb = OuterRotor(prop, si, o, mass_kg);
    if (!(rb.omega_rad_s > 0)) continue;
    // At the segment's end the terminal voltage is at most OCV(soc) less the least current's
    // drop on the pack's least resistance; the throttle that holds the point falls as the
    // voltage rises (M2), and the point is at or below the segment's own (M1, M3).
    const double v_ub = bo.OcvV(soc) - scratch_[si] / bo.v_full * bo.ri_at_hi_ohm;
    if (!(v_ub > 0) || drive.InverseLight(v_ub, rb.torque_nm, rb.omega_rad_s).throttle > tr_max) return "throttle";
  }
  return nullptr;
}

double JointBounds::OuterBound(const Drive& drive, const GroupParts& parts, double esc_max_a,
                               double tr_max, int prop, std::size_t o, double mass_kg, const char** why,
                               double* irms_lb, OuterEnergy* outer_energy) {
  if (outer_energy) outer_energy->valid = false;
  scratch_ = other_power_w_[o];
  *irms_lb = 0;
  for (double p : scratch_) {
    if (!(p < kInf)) {  // another free group has no feasible choice with this option
      *why = "infeasible_bound";
      return kInf;
    }
  }
  const double raw_kg = mass_kg;
  // R7, R6: the floors scanned from the pair's own mass in the coupled stage (the pairs taken),
  // from the option's lightest vehicle before it (every pair: one scan per propeller).
  const double scan_from_kg = coupled_ ? raw_kg : mass_min_kg_[o];
  for (std::size_t si : outer_segments_) mass_kg = std::max(mass_kg, MassFloorKg(prop, si, o, scan_from_kg));
  const double floor_kg = mass_kg;
  if (!(mass_kg < kInf)) {
    *why = "prop_no_forward_flight_data";
    return kInf;
  }
  if (!ReachesThrustToWeight(outer_, drive, prop, mass_kg, o)) {
    *why = "min_thrust_to_weight";
    return kInf;
  }
  // A free-airspeed cruise's bound from the propeller's samples at the grid mass at or below
  // mass_kg (OuterCruiseFloorW: momentum theory, the shaft power and the motor's loss floor; the
  // coupled stage also the drive's PDC), so a floor for every heavier vehicle below (M3;
  // docs/search.md#g2-free-cruise).
  // Only the outer segments' entries are read (cruise_point_w_ after cruise_point_at_ is set).
  cruise_floor_w_.resize(m_.segments.size());
  cruise_point_at_.resize(m_.segments.size());
  cruise_point_w_.resize(m_.segments.size());
  for (std::size_t si : outer_segments_) {
    cruise_floor_w_[si] = 0.0;
    cruise_point_at_[si] = kNoIndex;
  }
  for (std::size_t si : outer_segments_) {
    const Segment& sg = m_.segments[si];
    if (sg.type != SegmentType::kCruise || !sg.airspeed_m_s.free()) continue;
    cruise_floor_w_[si] = OuterCruiseFloorW(drive, prop, si, o, mass_kg);
    cruise_point_at_[si] = kNoIndex - 1;  // a free cruise: read again per frontier point
    // R2, R12's top and R3 over the airspeed range (docs/search.md#g2-free-cruise, #g1-torque-floor):
    // every airspeed's point is at least the floor point, and the samples' first when their
    // speeds and torques rise.
    const FreeCruiseSamples& s = OuterCruise(prop, si, o, mass_kg);
    if (const char* rule = FreeCruiseRangeRule(m_.constraints, drive, s, options_[o].v_full, tr_max, esc_max_a, irms_lb)) {
      *why = rule;
      return kInf;
    }
  }
  for (std::size_t si : outer_segments_) {
    const SegmentBound b = OuterSegmentBound(si, parts, drive, tr_max, esc_max_a, prop, o, mass_kg, cruise_floor_w_[si]);
    if (b.infeasible) {
      *why = b.infeasible;
      return kInf;
    }
    *irms_lb = std::max(*irms_lb, b.irms_lb_a);
    scratch_[si] = std::max(b.power_w, cruise_floor_w_[si]);
  }
  if (const char* rule = VoltageLeftRule(drive, prop, o, mass_kg, tr_max)) {
    *why = rule;
    return kInf;
  }
  const double bound = ScoreFromSegmentPowers(m_, scratch_, options_[o]);
  if (!coupled_ || inner_ < 0) return bound;
  // The coupled bound (InnerFrontier): per frontier point of the level at or below this outer
  // choice's extra mass (Frontier), the outer group's segments at the vehicle with that inner
  // mass (and at least the R7 floor), the inner group's energy, the other segments as above; the
  // least over the points.
  auto t_min = [&](std::size_t si) { return SegmentDurationS(m_.segments[si], m_.segments[si].airspeed_m_s.hi); };
  double e_rest = 0;
  for (std::size_t si = 0; si < m_.segments.size(); ++si) {
    const int g = m_.segments[si].group;
    if (g != outer_ && g != inner_) e_rest += scratch_[si] * t_min(si);
  }
  // The outer segments' energy at a vehicle of kg (at least raw_kg): a bound at every heavier
  // vehicle (M3). A free cruise reads its samples at the grid mass at or below kg, once per grid
  // mass (the masses asked rise).
  auto e_outer_at = [&](double kg) {
    double e = 0;
    for (std::size_t si : outer_segments_) {
      double floor_w = cruise_floor_w_[si];  // at raw_kg <= kg
      if (cruise_point_at_[si] != kNoIndex) {
        double grid_kg = 0;
        const std::size_t i = RotorCacheIndex(prop, si, o, kg, &grid_kg);
        if (i != cruise_point_at_[si]) {
          cruise_point_at_[si] = i;
          cruise_point_w_[si] = OuterCruiseFloorW(drive, prop, si, o, kg);
        }
        floor_w = std::max(floor_w, cruise_point_w_[si]);
      }
      const SegmentBound b = OuterSegmentBound(si, parts, drive, tr_max, esc_max_a, prop, o, kg, floor_w);
      if (b.infeasible) return kInf;
      e += std::max(b.power_w, floor_w) * t_min(si);
    }
    return e;
  };
  if (outer_energy) {  // up to the vehicle with the inner group's heaviest pair
    const double top_kg = raw_kg + (inner_pair_kg_.empty() ? 0.0 : InnerExtraKg(o, inner_pair_kg_.back()));
    *outer_energy = OuterEnergyByMass(raw_kg, floor_kg, mass_min_kg_[o], top_kg, e_rest, e_outer_at);
  }
  double best = kInf;
  // The outer segments' energy depends on kg only through OuterRotor's grid mass (a free-airspeed
  // cruise reads kg itself): points on one grid mass share it. Energy of an infeasible point is
  // kInf, shared too: the same rotor bound fails the same way.
  bool reuse = !outer_segments_.empty();
  for (std::size_t si : outer_segments_) {
    reuse = reuse && !(m_.segments[si].type == SegmentType::kCruise && m_.segments[si].airspeed_m_s.free());
  }
  const RotorBound* last_rb = nullptr;
  double e_outer = 0;
  for (const FrontierPoint& f : Frontier(o, raw_kg - mass_min_kg_[o])) {
    const double kg = std::max(raw_kg + f.extra_kg, floor_kg);
    const RotorBound* rb0 = reuse ? &OuterRotor(prop, outer_segments_.front(), o, kg) : nullptr;
    if (!rb0 || rb0 != last_rb) {
      e_outer = e_outer_at(kg);
      last_rb = rb0;
    }
    const double e = e_rest + f.energy_j + e_outer;
    best = std::min(best, e);
    if (!(best / 3600.0 > bound)) return bound;  // no better than the plain bound
  }
  if (!(best < kInf)) *why = "infeasible_bound";
  return std::max(bound, best / 3600.0);
}

double JointBounds::PairBound(int motor, int prop, std::size_t o, int esc_class, const char** why, double* irms_lb,
                              OuterEnergy* outer_energy) {
  if (outer_energy) outer_energy->valid = false;
  const MotorEntry& mo = cat_.motors()[static_cast<std::size_t>(motor)];
  const EscClass& cls = escs_.classes[static_cast<std::size_t>(esc_class)];
  const std::vector<int>& members = escs_.per_option[o][static_cast<std::size_t>(esc_class)];
  if (members.empty()) {
    *why = "esc_voltage";
    return kInf;
  }
  const MotorParams mp = ScenarioMotorParams(mo, m_);
  const Drive d(mp, ZeroResistanceEsc(cls));
  // FreeCruisePowerLowerBoundW reads the ESC's C1, C0: a member's, when the class's catalog
  // values cannot create energy (a scenario only raises C0); else none of the class is lossy
  // for certain, and a synthetic member with a negative C0 gives no momentum bound.
  EscEntry none;
  none.params = ZeroResistanceEsc(cls);
  none.params.c0 = -1.0;
  const EscEntry* esc = DriveIsLossy(mp, cls.c1, cls.c0) ? &cat_.escs()[static_cast<std::size_t>(members.front())] : &none;
  const GroupParts parts{&mo, esc, &cat_.props()[static_cast<std::size_t>(prop)]};
  const double mass = mass_min_kg_[o] - outer_lightest_kg_[o] +
                      m_.groups[outer_].rotors * (*mo.mass_kg + PropMassKg(cat_.props()[static_cast<std::size_t>(prop)]) +
                                                  escs_.min_mass_kg[o]);
  return OuterBound(d, parts, kInf, ThrottleLimit(m_.constraints, cls.tr_sat), prop, o, mass, why, irms_lb,
                    outer_energy);
}

double JointBounds::TripleBound(int motor, int esc, int prop, std::size_t o, const char** why,
                                OuterEnergy* outer_energy) {
  const MotorEntry& mo = cat_.motors()[static_cast<std::size_t>(motor)];
  const EscEntry& e = cat_.escs()[static_cast<std::size_t>(esc)];
  const PropEntry& p = cat_.props()[static_cast<std::size_t>(prop)];
  const MotorParams mp = ScenarioMotorParams(mo, m_);
  const EscParams ep = ScenarioEscParams(e, m_.objective.ranking);
  const Drive d(mp, ep);
  const double mass = mass_min_kg_[o] - outer_lightest_kg_[o] +
                      m_.groups[outer_].rotors * (*mo.mass_kg + PropMassKg(p) + EscMassKg(e));
  double irms_lb = 0;
  return OuterBound(d, GroupParts{&mo, &e, &p}, ep.max_current_a, ThrottleLimit(m_.constraints, ep.tr_sat),
                    prop, o, mass, why, &irms_lb, outer_energy);
}

}  // namespace dynosize::search_internal
