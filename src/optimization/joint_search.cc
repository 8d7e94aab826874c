#include "optimization/joint_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <queue>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/units.h"
#include "model/physics.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "optimization/top_results.h"

namespace dynosize {

// The rule (G2) and its proof are in search.cc's header comment, with R0-R11 and G1.

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMassCeilingKg = 1e5;  // MassFloorKg's search range: beyond any vehicle
constexpr double kRotorCeilingRadS = 1e5;  // RotorLowerBound's: ~1e6 rpm, beyond any motor

long long SaturatingProduct(std::initializer_list<long long> xs) {
  long long p = 1;
  for (long long x : xs) {
    if (__builtin_mul_overflow(p, x, &p)) return std::numeric_limits<long long>::max();
  }
  return p;
}

// x += y, held at the largest long long (counts of three or more free groups).
void AddCount(long long* x, long long y) {
  if (__builtin_add_overflow(*x, y, x)) *x = std::numeric_limits<long long>::max();
}

// Combinations of one free group per battery option: motors x ESCs x propellers.
long long GroupCombinations(const Catalog& cat) {
  return SaturatingProduct({static_cast<long long>(cat.motors().size()), static_cast<long long>(cat.escs().size()),
                            static_cast<long long>(cat.props().size())});
}


}  // namespace

int FreeGroupCount(const Mission& m) {
  if (m.groups.empty()) return 1;
  int n = 0;
  for (const PropulsionGroup& g : m.groups) n += g.fixed() ? 0 : 1;
  return n;
}

namespace search_internal {

RotorBound RotorLowerBound(const Mission& m, const Segment& sg, const PropEntry& prop, const PropModel& model,
                           double mass_kg) {
  RotorBound rb;
  const RotorLoad ld = SegmentRotorLoad(m, sg, mass_kg, sg.airspeed_m_s.lo);
  rb.rotors = ld.rotors;
  if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free()) {
    CruisePropBound pb{&prop, &model, PropAdjustmentFor(prop, m.objective.ranking), true};
    pb.with_prop_data = true;
    rb.free_cruise_lossy_w = FreeCruiseRotorPowerLowerBoundW(m, sg, pb, nullptr, mass_kg);
    return rb;
  }
  if (sg.type == SegmentType::kShaft) return rb;
  const double v = ld.axial_airspeed_m_s;
  // Bisection keeping thrust(lo) <= T (M1: thrust rises with speed), so lo is at or below the
  // evaluator's root; a propeller that cannot give T below the ceiling turns faster (and R3
  // then finds the throttle above one).
  double lo = 0.0, hi = kRotorCeilingRadS;
  if (model.Evaluate(hi, m.rho_kg_m3, v).thrust_n < ld.thrust_per_rotor_n) {
    lo = hi;
  } else {
    lo = BisectSpeedFromBelow(model, m.rho_kg_m3, ld.thrust_per_rotor_n, v, lo, hi, 60);
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

SegmentBound SegmentPowerBound(const Mission& m, std::size_t si, const GroupParts& parts, const MotorParams& mp,
                               const Drive& drive, double tr_max, double esc_max_current_a, const PropModel& model,
                               const BatteryOption& bo, double mass_kg, const RotorBound& rb) {
  const Segment& sg = m.segments[si];
  const MissionConstraints& k = m.constraints;
  SegmentBound b;
  b.power_w = m.vehicle.avionics_power_w;
  if (sg.type == SegmentType::kShaft) return b;
  const bool static_only = model.data_kind() != PropDataKind::kTables || parts.prop->j_tables.empty();
  if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free()) {
    // R7 over the range: a wing-borne cruise's inflow is its airspeed, at least lo, and the
    // shaft turns no faster than n_max (below), so J >= lo/(n_max*D) at every airspeed.
    const double n_max = drive.NoLoadSpeed(bo.v_full, 1.0) / (2.0 * kPi);
    if (static_only && sg.lift_to_drag > 0 && n_max > 0 &&
        sg.airspeed_m_s.lo / (n_max * parts.prop->diameter_m) > k.max_static_advance_ratio) {
      b.infeasible = "prop_no_forward_flight_data";
    }
    b.power_w += FreeCruisePowerLowerBoundW(m, sg, parts, model, mass_kg);
    return b;
  }
  if (!(rb.omega_rad_s > 0)) return b;
  // R3 at the bound point: the throttle, Irms and PAC of every real choice are at least these
  // (M2: zero or the real ESC resistance, the highest voltage the pack can have).
  const OperatingPoint hi = drive.Inverse(bo.v_full, rb.torque_nm, rb.omega_rad_s);
  const double margin = 1.0 - k.current_margin;
  b.irms_lb_a = hi.irms_a;
  if (hi.throttle > tr_max) {
    b.infeasible = "throttle";
  } else if (hi.irms_a > mp.max_current_a * margin) {
    b.infeasible = "motor_current";
  } else if (k.enforce_motor_power && hi.pac_w > mp.max_power_w) {
    b.infeasible = "motor_power";
  } else if (hi.irms_a > esc_max_current_a * margin) {
    b.infeasible = "esc_current";
  }
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
  const OperatingPoint lo = drive.Inverse(bo.v_cut, rb.torque_nm, rb.omega_rad_s);
  double pdc = rb.rotors * std::max(0.0, std::min(hi.pdc_w, lo.pdc_w));
  // Momentum theory: a feasible point's propeller data give P >= P_ideal/max_figure_of_merit
  // (the evaluator's prop_figure_of_merit, V_ax the inflow unless the data are static-only);
  // the scenario's power is at least P_ideal (credibility.h: raised, or capped at FM 1), so
  // P_ideal/max(1, max_figure_of_merit) bounds it in every scenario; and PDC >= Pmech when
  // neither the motor nor the ESC can create energy (model.md section 10).
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
  return PropFrameRule(m_, group, Lifts(group), p) == nullptr;
}

const char* JointBounds::PropRule(int prop) const {
  return PropFrameRule(m_, outer_, Lifts(outer_), cat_.props()[static_cast<std::size_t>(prop)]);
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

JointBounds::JointBounds(const Mission& m, const Catalog& cat, const PropGridCache& cache) : m_(m), cat_(cat) {
  for (const auto& p : cache.models) models_.push_back(p.get());
  lift_group_ = std::max(0, LiftGroup(m));
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
  for (const PropGrid& g : cache.grids) monotone_.push_back(g.monotone);
  mass_floor_kg_.assign(options_.size() * n_seg * cat.props().size(), -1.0);
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
  const std::size_t n_cache = options_.size() * n_seg * cat.props().size() * static_cast<std::size_t>(kFixedPowerMasses);
  rotor_cache_.assign(n_cache, RotorBound{});
  rotor_done_.assign(n_cache, 0);
  if (free.size() == 2 && m.objective.type == ObjectiveType::kMinEnergy) {
    inner_ = free[0] == outer_ ? free[1] : free[0];
    for (std::size_t o = 0; o < options_.size(); ++o) frontier_.push_back(InnerFrontier(o));
  }
}

// G2's coupled bound (min_energy, two free groups): the inner group's choices as a frontier of
// (extra mass over its lightest, least energy of its own segments at the vehicle with that mass
// and the outer group at its lightest), each choice that survives R0, R1, R3, R7 and the
// thrust-to-weight rule at that vehicle, taken lightest first and kept when its energy is below
// every lighter one's. Every feasible inner choice has a frontier point no heavier and with no
// more energy (M3). Choices whose floor (rotors*max(Q*omega, momentum) per segment) reaches the
// least energy so far are skipped when their drive cannot create energy (SegmentPowerBound).
std::vector<JointBounds::FrontierPoint> JointBounds::InnerFrontier(std::size_t o) {
  const auto& motors = cat_.motors();
  const auto& props = cat_.props();
  const BatteryOption& bo = options_[o];
  const double esc_min = std::isfinite(escs_.min_mass_kg[o]) ? escs_.min_mass_kg[o] : 0.0;
  const int rotors = m_.groups[static_cast<std::size_t>(inner_)].rotors;
  std::vector<std::size_t> segs;
  for (std::size_t si = 0; si < m_.segments.size(); ++si) {
    if (m_.segments[si].group == inner_) segs.push_back(si);
  }
  auto t_min = [&](std::size_t si) { return SegmentDurationS(m_.segments[si], m_.segments[si].airspeed_m_s.hi); };
  std::vector<double> floor_j(props.size(), kInf);  // per propeller at the lightest vehicle
  for (std::size_t pi = 0; pi < props.size(); ++pi) {
    if (!PropAllowed(inner_, props[pi])) continue;
    const bool static_only = models_[pi]->data_kind() != PropDataKind::kTables || props[pi].j_tables.empty();
    double e = 0;
    for (std::size_t si : segs) {
      const RotorBound& rb = OuterRotor(static_cast<int>(pi), si, o, mass_min_kg_[o]);
      const double p_ideal = rb.omega_rad_s > 0 ? IdealRotorPowerW(rb.thrust_n, props[pi].diameter_m, m_.rho_kg_m3,
                                                                   static_only ? 0.0 : rb.axial_airspeed_m_s)
                                                : 0.0;
      const double w = std::max(rb.torque_nm * rb.omega_rad_s, p_ideal / std::max(1.0, m_.constraints.max_figure_of_merit));
      e += (m_.vehicle.avionics_power_w + rb.rotors * w) * t_min(si);
    }
    floor_j[pi] = e;
  }
  std::vector<std::tuple<double, int, int>> by_mass;
  for (std::size_t mi = 0; mi < motors.size(); ++mi) {
    if (!motors[mi].mass_kg || !motors[mi].exclude_reason.empty()) continue;
    for (std::size_t pi = 0; pi < props.size(); ++pi) {
      if (!std::isfinite(floor_j[pi])) continue;
      const double kg = rotors * (*motors[mi].mass_kg + PropMassKg(props[pi]) + esc_min);
      if (kg >= inner_lightest_kg_[o]) by_mass.emplace_back(kg, static_cast<int>(mi), static_cast<int>(pi));
    }
  }
  std::sort(by_mass.begin(), by_mass.end());
  std::vector<FrontierPoint> front;
  double e_min = kInf;
  for (const auto& [kg, mi, pi] : by_mass) {
    const MotorEntry& mo = motors[static_cast<std::size_t>(mi)];
    bool excluded = false;
    const MotorParams mp = ScenarioMotorParams(mo, m_, nullptr, &excluded);
    if (Lifts(inner_) && (excluded || bo.v_full > MotorMaxVoltageV(mo))) continue;  // R0, R1
    const double vehicle_kg = mass_min_kg_[o] - inner_lightest_kg_[o] + kg;
    for (std::size_t c = 0; c < escs_.classes.size(); ++c) {
      if (escs_.per_option[o][c].empty()) continue;
      // SegmentPowerBound reads the ESC's C1 and C0 for a free-airspeed cruise
      // (FreeCruisePowerLowerBoundW): a member's, as MinFreeGroupPower does.
      const EscEntry& member = cat_.escs()[static_cast<std::size_t>(escs_.classes[c].members.front())];
      const GroupParts parts{&mo, &member, &props[static_cast<std::size_t>(pi)]};
      const EscClass& cls = escs_.classes[c];
      if (DriveIsLossy(mp, cls.c1, cls.c0) && floor_j[static_cast<std::size_t>(pi)] >= e_min) continue;
      const Drive d(mp, ZeroResistanceEsc(cls));
      if (!ReachesThrustToWeight(inner_, d, pi, vehicle_kg, o)) continue;
      double e = 0;
      for (std::size_t si : segs) {
        const RotorBound& rb = OuterRotor(pi, si, o, vehicle_kg);
        const SegmentBound b = SegmentPowerBound(m_, si, parts, mp, d, ThrottleLimit(m_.constraints, cls.tr_sat), kInf,
                                                 *models_[static_cast<std::size_t>(pi)], bo, vehicle_kg, rb);
        if (b.infeasible) {
          e = kInf;
          break;
        }
        e += b.power_w * t_min(si);
      }
      if (e < e_min) {
        e_min = e;
        front.push_back(FrontierPoint{kg - inner_lightest_kg_[o], e});
      }
    }
  }
  return front;
}

// R7's floor on one airspeed cell [v_a, v_b] (see MassFloorKg): kInf when no mass reaches the
// thrust, 0 when every mass does (or the inflow is 0).
double JointBounds::StaticAdvanceMassFloorKg(const PropModel& model, double diameter_m, const Segment& sg, double v_a,
                                             double v_b) const {
  const double v_ax = SegmentRotorLoad(m_, sg, 1.0, v_a).axial_airspeed_m_s;
  if (!(v_ax > 0)) return 0.0;
  const double omega_req = 2.0 * kPi * v_ax / (m_.constraints.max_static_advance_ratio * diameter_m);
  const double t_req = model.Evaluate(omega_req, m_.rho_kg_m3, 0.0).thrust_n;
  auto thrust_at = [&](double kg) { return SegmentRotorLoad(m_, sg, kg, v_b).thrust_per_rotor_n; };
  double lo = 0.0, hi = kMassCeilingKg;
  if (!(thrust_at(hi) >= t_req)) return kInf;
  if (!(thrust_at(lo) < t_req)) return 0.0;
  for (int it = 0; it < 60; ++it) {  // keeps thrust(lo) < T(n)
    const double mid = 0.5 * (lo + hi);
    (thrust_at(mid) < t_req ? lo : hi) = mid;
  }
  return lo;
}

// R7 as a mass floor: static-only data in axial flow V_ax pass the evaluator only at an advance
// ratio J = V_ax/(n*D) <= max_static_advance_ratio, so at a speed n >= V_ax/(J_max*D), where the
// static thrust (M1, the propeller's grid rising) is at least T(n); the segment's thrust rises
// with the vehicle's mass (M3), so a feasible vehicle weighs at least the mass whose thrust is
// T(n) (bisection, kept at or below it). kInf: no mass gives it; 0: no floor.
double JointBounds::MassFloorKg(int prop, std::size_t si, std::size_t o) {
  const std::size_t i = (o * m_.segments.size() + si) * cat_.props().size() + static_cast<std::size_t>(prop);
  if (mass_floor_kg_[i] >= 0) return mass_floor_kg_[i];
  const PropEntry& p = cat_.props()[static_cast<std::size_t>(prop)];
  const PropModel& model = *models_[static_cast<std::size_t>(prop)];
  const Segment& sg = m_.segments[si];
  double floor_kg = 0.0;
  const bool static_only = model.data_kind() != PropDataKind::kTables || p.j_tables.empty();
  const bool free_cruise = sg.type == SegmentType::kCruise && sg.airspeed_m_s.free();
  if (static_only && monotone_[static_cast<std::size_t>(prop)] && sg.type != SegmentType::kShaft &&
      (!free_cruise || sg.lift_to_drag > 0) && m_.constraints.max_static_advance_ratio > 0) {
    // A free (wing-borne) airspeed in cells [V_a, V_b]: the required speed and its static thrust
    // rise with V (M1), the segment's thrust at a mass is largest at V_b (flight.h), so a
    // vehicle flying the cell weighs at least the floor of (T(n(V_a)), thrust at V_b); the least
    // over the cells bounds the whole range. A fixed airspeed is one cell.
    const int cells = free_cruise ? kFreeCruiseFloorCells : 1;
    const double lo = sg.airspeed_m_s.lo, span = free_cruise ? sg.airspeed_m_s.hi - lo : 0.0;
    floor_kg = kInf;
    for (int c = 0; c < cells && floor_kg > 0; ++c) {
      const double v_a = lo + span * c / cells, v_b = lo + span * (c + 1) / cells;
      floor_kg = std::min(floor_kg, StaticAdvanceMassFloorKg(model, p.diameter_m, sg, v_a, v_b));
    }
  }  floor_kg = std::max(floor_kg, FigureOfMeritMassFloorKg(prop, si, o));
  mass_floor_kg_[i] = floor_kg;
  return floor_kg;
}

// R6 as a mass floor for the outer group (search.cc, G2): the lightest vehicle at which segment
// si (a fixed axial inflow) may pass prop_figure_of_merit on propeller `prop`, kg (a lower bound;
// 0 when nothing is proven). The evaluator's figure of merit is P_ideal(T, v)/P(omega), the
// propeller's power as given at the speed omega that gives the segment's thrust T (mission_eval.cc,
// PropellerPoint; model/physics.h). On a mass cell [M_a, M_b] the thrust is in [T(M_a), T(M_b)]
// (M3), the speed at or below omega_b, a speed whose thrust is at least T(M_b) (M1), so the
// power is at most P(omega_b) when the power rises with speed on the cell's speeds (checked at
// kFomSamples speeds, else nothing is proven there), and P_ideal rises with T: the figure of
// merit is at least P_ideal(T(M_a), v)/P(omega_b). Cells above the limit hold no feasible mass;
// the floor is the bottom of the first cell that is not proven so, scanning up from the
// option's lightest vehicle in cells kFomCellRatio wide (kFomCells of them).
double JointBounds::FigureOfMeritMassFloorKg(int prop, std::size_t si, std::size_t o) const {
  constexpr int kFomCells = 64, kFomSamples = 8, kSteps = 50;
  constexpr double kFomCellRatio = 1.03;
  const Segment& sg = m_.segments[si];
  const PropEntry& p = cat_.props()[static_cast<std::size_t>(prop)];
  const PropModel& model = *models_[static_cast<std::size_t>(prop)];
  const double limit = m_.constraints.max_figure_of_merit;
  // A fixed inflow: not a shaft segment, a free airspeed or a multirotor cruise (its inflow
  // changes with the mass, flight.h).
  const bool fixed_inflow = sg.type != SegmentType::kShaft &&
                            !(sg.type == SegmentType::kCruise && (sg.airspeed_m_s.free() || !(sg.lift_to_drag > 0)));
  if (!fixed_inflow || !(limit > 0) || !monotone_[static_cast<std::size_t>(prop)]) {
    return 0.0;
  }
  const bool static_only = model.data_kind() != PropDataKind::kTables || p.j_tables.empty();
  auto load_at = [&](double kg) { return SegmentRotorLoad(m_, sg, kg, sg.airspeed_m_s.lo); };
  const double v = load_at(1.0).axial_airspeed_m_s;
  if (v < 0) return 0.0;  // a descent: PropellerPoint's inflow differs
  const double v_fom = static_only ? 0.0 : v;  // PropellerPoint: static-only data held to the static bound
  const double v_eval = static_only ? 0.0 : v;  // static-only data are read at J = 0 in any inflow
  double kg = mass_min_kg_[o];
  for (int cell = 0; cell < kFomCells; ++cell) {
    const double kg_b = kg * kFomCellRatio;
    const double t_a = load_at(kg).thrust_per_rotor_n, t_b = load_at(kg_b).thrust_per_rotor_n;
    if (!(model.Evaluate(kRotorCeilingRadS, m_.rho_kg_m3, v_eval).thrust_n >= t_b)) return kg;
    // omega_b: thrust(hi) >= t_b kept through the bisection (M1).
    double lo = 0.0, hi = kRotorCeilingRadS;
    for (int it = 0; it < kSteps; ++it) {
      const double mid = 0.5 * (lo + hi);
      (model.Evaluate(mid, m_.rho_kg_m3, v_eval).thrust_n >= t_b ? hi : lo) = mid;
    }
    const double w_a = BisectSpeedFromBelow(model, m_.rho_kg_m3, t_a, v_eval, 0.0, hi, kSteps);
    double p_prev = -kInf, p_b = 0.0;
    bool rising = true;
    for (int k = 0; k <= kFomSamples && rising; ++k) {
      const double w = w_a + (hi - w_a) * k / kFomSamples;
      p_b = model.Evaluate(w, m_.rho_kg_m3, v_eval).power_w;
      rising = p_b >= p_prev;
      p_prev = p_b;
    }
    if (!rising || !(p_b > 0) || !(IdealRotorPowerW(t_a, p.diameter_m, m_.rho_kg_m3, v_fom) / p_b > limit)) return kg;
    kg = kg_b;
  }
  return kg;
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
  const int rotors = LiftRotors(m_);
  if (!Lifts(group) || !(k.min_thrust_to_weight > 0) || rotors <= 0 || !monotone_[static_cast<std::size_t>(prop)]) {
    return true;
  }
  const double w_nl = drive.NoLoadSpeed(options_[o].v_full, 1.0);
  if (!(w_nl > 0)) return false;
  const double t_max = models_[static_cast<std::size_t>(prop)]->Evaluate(w_nl, m_.rho_kg_m3, 0.0).thrust_n;
  return rotors * t_max >= k.min_thrust_to_weight * vehicle_kg * kStandardGravity;
}

double JointBounds::LightestSurvivorKg(int group, std::size_t o, double vehicle_kg) {
  const auto& motors = cat_.motors();
  const auto& props = cat_.props();
  std::vector<std::tuple<double, int, int>> by_mass;
  for (std::size_t mi = 0; mi < motors.size(); ++mi) {
    if (!motors[mi].mass_kg || !motors[mi].exclude_reason.empty()) continue;
    for (std::size_t pi = 0; pi < props.size(); ++pi) {
      if (PropAllowed(group, props[pi])) {
        by_mass.emplace_back(*motors[mi].mass_kg + PropMassKg(props[pi]), static_cast<int>(mi), static_cast<int>(pi));
      }
    }
  }
  std::sort(by_mass.begin(), by_mass.end());
  std::vector<std::size_t> segs;
  for (std::size_t si = 0; si < m_.segments.size(); ++si) {
    if (m_.segments[si].group == group) segs.push_back(si);
  }
  std::vector<RotorBound> rbs(props.size() * segs.size());
  std::vector<char> done(rbs.size(), 0);
  const BatteryOption& bo = options_[o];
  for (const auto& [kg, mi, pi] : by_mass) {
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

// G2: the least power bound over the group's (motor, ESC class, propeller) choices that survive
// R0, R1, R3 and R7 at this segment, at the lightest vehicle mass (M3: every heavier one draws
// no less). Propellers in order of their floor, rotors*max(Q*omega, momentum) + P_avionics (PDC
// >= Pmech for a drive that cannot create energy; SegmentPowerBound): once the floor reaches the least bound found, no energy-
// conserving drive on that propeller or a later one can go below it; drives that could create
// energy are checked on every propeller.
double JointBounds::MinFreeGroupPower(int group, std::size_t si, std::size_t o, double mass_kg) {
  const Mission& m = m_;
  const Segment& sg = m.segments[si];
  const BatteryOption& bo = options_[o];
  const auto& props = cat_.props();
  const auto& motors = cat_.motors();
  const std::vector<EscClass>& classes = escs_.classes;
  struct Cand {
    MotorParams mp;
    Drive drive;
    int cls;
    bool lossy;
    const MotorEntry* motor;
  };
  std::vector<Cand> cands;
  for (const MotorEntry& mo : motors) {
    if (!mo.exclude_reason.empty() || !mo.mass_kg) continue;
    bool excluded = false;
    const MotorParams mp = ScenarioMotorParams(mo, m, nullptr, &excluded);
    if (Lifts(group) && (excluded || bo.v_full > MotorMaxVoltageV(mo))) continue;  // R0, R1
    for (std::size_t c = 0; c < classes.size(); ++c) {
      if (escs_.per_option[o][c].empty()) continue;  // R1
      cands.push_back(Cand{mp, Drive(mp, ZeroResistanceEsc(classes[c])), static_cast<int>(c),
                           DriveIsLossy(mp, classes[c].c1, classes[c].c0), &mo});
    }
  }
  double best = kInf;
  if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free()) {
    // FreeCruisePowerLowerBoundW: momentum theory when the drive cannot create energy (the
    // class's catalog C0 is at most any scenario's), else none.
    for (const Cand& c : cands) {
      if (!c.lossy) return m.vehicle.avionics_power_w;
    }
    for (std::size_t pi = 0; pi < props.size(); ++pi) {
      if (!PropAllowed(group, props[pi]) || cands.empty()) continue;
      const Cand& c = cands.front();
      const GroupParts parts{c.motor, &cat_.escs()[static_cast<std::size_t>(classes[c.cls].members.front())], &props[pi]};
      best = std::min(best, m.vehicle.avionics_power_w + FreeCruisePowerLowerBoundW(m, sg, parts, *models_[pi], mass_kg));
    }
    return best;
  }
  if (sg.type == SegmentType::kShaft) return m.vehicle.avionics_power_w;
  struct PropFloor {
    double floor;
    std::size_t prop;
    RotorBound rb;
  };
  std::vector<PropFloor> floors;
  for (std::size_t pi = 0; pi < props.size(); ++pi) {
    if (!PropAllowed(group, props[pi])) continue;
    RotorBound rb = RotorLowerBound(m, sg, props[pi], *models_[pi], mass_kg);
    if (!(rb.omega_rad_s > 0)) return m.vehicle.avionics_power_w;  // no bound for this choice
    const bool static_only = models_[pi]->data_kind() != PropDataKind::kTables || props[pi].j_tables.empty();
    const double p_ideal = IdealRotorPowerW(rb.thrust_n, props[pi].diameter_m, m.rho_kg_m3,
                                            static_only ? 0.0 : rb.axial_airspeed_m_s);
    const double floor_w = std::max(rb.torque_nm * rb.omega_rad_s, p_ideal / std::max(1.0, m.constraints.max_figure_of_merit));
    floors.push_back({m.vehicle.avionics_power_w + rb.rotors * floor_w, pi, rb});
  }
  std::sort(floors.begin(), floors.end(), [](const PropFloor& a, const PropFloor& b) {
    return a.floor != b.floor ? a.floor < b.floor : a.prop < b.prop;
  });
  for (const PropFloor& f : floors) {
    const bool lossy_done = f.floor >= best;
    const GroupParts parts{nullptr, nullptr, &props[f.prop]};
    for (const Cand& c : cands) {
      if (lossy_done && c.lossy) continue;
      if (!ReachesThrustToWeight(group, c.drive, static_cast<int>(f.prop), mass_kg, o)) continue;
      const double tr_max = ThrottleLimit(m.constraints, classes[c.cls].tr_sat);
      const SegmentBound b = SegmentPowerBound(m, si, parts, c.mp, c.drive, tr_max, kInf, *models_[f.prop], bo,
                                               mass_kg, f.rb);
      if (!b.infeasible) best = std::min(best, b.power_w);
    }
  }
  return best;
}

const RotorBound& JointBounds::OuterRotor(int prop, std::size_t si, std::size_t o, double mass_kg) {
  // The grid mass at or below mass_kg (G1's geometric grid from the option's lightest vehicle).
  const double m0 = mass_min_kg_[o];
  int k = mass_kg > m0 ? static_cast<int>(std::floor(std::log(mass_kg / m0) / std::log(kFixedPowerMassStep))) : 0;
  k = std::clamp(k, 0, kFixedPowerMasses - 1);
  while (k > 0 && m0 * std::pow(kFixedPowerMassStep, k) > mass_kg) --k;
  const std::size_t i = ((o * m_.segments.size() + si) * cat_.props().size() + static_cast<std::size_t>(prop)) *
                            static_cast<std::size_t>(kFixedPowerMasses) + static_cast<std::size_t>(k);
  if (!rotor_done_[i]) {
    const double mk = k == 0 ? std::min(m0, mass_kg) : m0 * std::pow(kFixedPowerMassStep, k);
    rotor_cache_[i] = RotorLowerBound(m_, m_.segments[si], cat_.props()[static_cast<std::size_t>(prop)],
                                      *models_[static_cast<std::size_t>(prop)], mk);
    rotor_done_[i] = 1;
  }
  return rotor_cache_[i];
}

double JointBounds::OuterBound(const Drive& drive, const GroupParts& parts, double esc_max_a,
                               double tr_max, int prop, std::size_t o, double mass_kg, const char** why,
                               double* irms_lb) {
  const MotorParams& mp = drive.motor();
  scratch_ = other_power_w_[o];
  *irms_lb = 0;
  for (double p : scratch_) {
    if (!(p < kInf)) {  // another free group has no feasible choice with this option
      *why = "infeasible_bound";
      return kInf;
    }
  }
  const double raw_kg = mass_kg;
  for (std::size_t si : outer_segments_) mass_kg = std::max(mass_kg, MassFloorKg(prop, si, o));  // R7
  const double floor_kg = mass_kg;
  if (!(mass_kg < kInf)) {
    *why = "prop_no_forward_flight_data";
    return kInf;
  }
  if (!ReachesThrustToWeight(outer_, drive, prop, mass_kg, o)) {
    *why = "min_thrust_to_weight";
    return kInf;
  }
  // The coupled (lazy) stage only: a free-airspeed cruise's bound from the drive too, cell by
  // cell (FreeCruisePowerLowerBoundW with the drive: about 1,400 propeller evaluations, too many
  // for every pair's first bound). At mass_kg, so a floor for every heavier vehicle below (M3).
  // Every stage: the propeller's own data (RotorBound::free_cruise_lossy_w, cached per grid mass).
  cruise_floor_w_.assign(m_.segments.size(), 0.0);
  const bool lossy = DriveIsLossy(mp, drive.esc().c1, drive.esc().c0);
  for (std::size_t si : outer_segments_) {
    const Segment& sg = m_.segments[si];
    if (sg.type != SegmentType::kCruise || !sg.airspeed_m_s.free()) continue;
    if (lossy) {
      cruise_floor_w_[si] = m_.vehicle.avionics_power_w + OuterRotor(prop, si, o, mass_kg).free_cruise_lossy_w;
    }
    if (coupled_) {
      const CruiseDriveBound db{&drive, options_[o].v_full, options_[o].v_cut};
      cruise_floor_w_[si] = std::max(cruise_floor_w_[si], m_.vehicle.avionics_power_w +
                            FreeCruisePowerLowerBoundW(m_, sg, parts, *models_[static_cast<std::size_t>(prop)], mass_kg, &db));
    }
  }
  for (std::size_t si : outer_segments_) {
    const RotorBound& rb = OuterRotor(prop, si, o, mass_kg);
    const SegmentBound b = SegmentPowerBound(m_, si, parts, mp, drive, tr_max, esc_max_a,
                                             *models_[static_cast<std::size_t>(prop)], options_[o], mass_kg, rb);
    if (b.infeasible) {
      *why = b.infeasible;
      return kInf;
    }
    *irms_lb = std::max(*irms_lb, b.irms_lb_a);
    scratch_[si] = std::max(b.power_w, cruise_floor_w_[si]);
  }
  const double bound = ScoreFromSegmentPowers(m_, scratch_, options_[o]);
  if (!coupled_ || inner_ < 0) return bound;
  // The coupled bound (InnerFrontier): per frontier point, the outer group's segments at the
  // vehicle with that inner mass (and at least the R7 floor), the inner group's energy, the
  // other segments as above; the least over the points.
  auto t_min = [&](std::size_t si) { return SegmentDurationS(m_.segments[si], m_.segments[si].airspeed_m_s.hi); };
  double e_rest = 0;
  for (std::size_t si = 0; si < m_.segments.size(); ++si) {
    const int g = m_.segments[si].group;
    if (g != outer_ && g != inner_) e_rest += scratch_[si] * t_min(si);
  }
  double best = kInf;
  for (const FrontierPoint& f : frontier_[o]) {
    const double kg = std::max(raw_kg + f.extra_kg, floor_kg);
    double e = e_rest + f.energy_j;
    for (std::size_t si : outer_segments_) {
      const SegmentBound b = SegmentPowerBound(m_, si, parts, mp, drive, tr_max, esc_max_a,
                                               *models_[static_cast<std::size_t>(prop)], options_[o], kg,
                                               OuterRotor(prop, si, o, kg));
      if (b.infeasible) {
        e = kInf;
        break;
      }
      e += std::max(b.power_w, cruise_floor_w_[si]) * t_min(si);
    }
    best = std::min(best, e);
    if (!(best / 3600.0 > bound)) return bound;  // no better than the plain bound
  }
  if (!(best < kInf)) *why = "infeasible_bound";
  return std::max(bound, best / 3600.0);
}

double JointBounds::PairBound(int motor, int prop, std::size_t o, int esc_class, const char** why, double* irms_lb) {
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
  return OuterBound(d, parts, kInf, ThrottleLimit(m_.constraints, cls.tr_sat), prop, o, mass, why, irms_lb);
}

double JointBounds::TripleBound(int motor, int esc, int prop, std::size_t o, const char** why) {
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
                    prop, o, mass, why, &irms_lb);
}

namespace {

// Appends an inner search's results and counts to *out, its results to the top N (`top`).
void Merge(SearchResult&& r, TopResults* top, SearchResult* out) {
  out->searched += r.searched;
  for (const auto& [rule, n] : r.pruned_by) AddCount(&out->pruned_by[rule], n);
  out->evaluated_mass_objective.insert(out->evaluated_mass_objective.end(), r.evaluated_mass_objective.begin(),
                                       r.evaluated_mass_objective.end());
  out->candidate_pairs += r.candidate_pairs;
  out->candidate_seconds += r.candidate_seconds;
  out->virtual_evaluations += r.virtual_evaluations;
  out->candidate_batches += r.candidate_batches;
  AddCount(&out->unsettled, r.unsettled);
  for (RankedCombination& b : r.best) top->Add(std::move(b));
}

struct OuterPair {
  double bound;
  int motor, prop;
  std::size_t option;
};

// The outer group's (motor, propeller, option) pairs that survive R0, R1, R3 with their bound
// (the least over ESC classes), best first; the pruned ones counted (x `block`: the inner
// combinations of each).
std::vector<OuterPair> OuterPairs(const Catalog& cat, JointBounds* jb, long long block, SearchResult* out) {
  std::vector<OuterPair> pairs;
  const long long n_esc = static_cast<long long>(cat.escs().size());
  const long long n_prop = static_cast<long long>(cat.props().size());
  for (std::size_t mi = 0; mi < cat.motors().size(); ++mi) {
    if (!cat.motors()[mi].mass_kg) ++out->skipped_without_mass;
    for (std::size_t o = 0; o < jb->options().size(); ++o) {
      if (const char* rule = jb->MotorRule(static_cast<int>(mi), o)) {
        AddCount(&out->pruned_by[rule], SaturatingProduct({n_esc, n_prop, block}));
        continue;
      }
      for (std::size_t pi = 0; pi < cat.props().size(); ++pi) {
        if (const char* rule = jb->PropRule(static_cast<int>(pi))) {
          AddCount(&out->pruned_by[rule], SaturatingProduct({n_esc, block}));
          continue;
        }
        double best = kInf, irms = 0;
        const char* why = "throttle";
        for (std::size_t c = 0; c < jb->escs().classes.size(); ++c) {
          if (jb->escs().per_option[o][c].empty()) continue;
          const char* w = nullptr;
          const double b = jb->PairBound(static_cast<int>(mi), static_cast<int>(pi), o, static_cast<int>(c), &w, &irms);
          if (b < kInf) {
            best = std::min(best, b);
          } else if (w) {
            why = w;
          }
        }
        if (!(best < kInf)) {
          AddCount(&out->pruned_by[why], SaturatingProduct({n_esc, block}));
          continue;
        }
        pairs.push_back(OuterPair{best, static_cast<int>(mi), static_cast<int>(pi), o});
      }
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const OuterPair& a, const OuterPair& b) {
    if (a.bound != b.bound) return a.bound < b.bound;
    if (a.option != b.option) return a.option < b.option;
    if (a.motor != b.motor) return a.motor < b.motor;
    return a.prop < b.prop;
  });
  return pairs;
}

// The progress of the outer loop before pair `done` (SearchProgress): the share of the work, the
// inner searches' counts so far and the best so far.
void ReportProgress(const SearchOptions& opt, const std::vector<OuterPair>& pairs, std::size_t done,
                    const TopResults& top, const SearchResult& out) {
  if (!opt.progress) return;
  SearchProgress p;
  // As the one-group search's (search.cc, ReportProgress): the outer pairs taken against those
  // taken plus those left below the N-th best (they are sorted by bound).
  const double t = top.Threshold();
  const auto below = std::partition_point(pairs.begin(), pairs.end(), [t](const OuterPair& x) { return x.bound < t; });
  const double left = static_cast<double>(std::max<std::ptrdiff_t>(0, (below - pairs.begin()) - static_cast<std::ptrdiff_t>(done)));
  p.fraction = left == 0 ? 1.0 : static_cast<double>(done) / (static_cast<double>(done) + left);
  p.searched = out.searched;
  // The rules' counts overlap (an ESC over its voltage rating on a pair R0 removes is counted
  // by both, as in the one-group search): held to what is not yet searched.
  for (const auto& [rule, n] : out.pruned_by) AddCount(&p.pruned, n);
  p.pruned = std::min(p.pruned, out.combinations - out.searched);
  p.has_best = !top.empty();
  p.found = top.size();
  p.best_objective = top.best_objective();
  opt.progress(p);
}

// m with the outer group fixed to (pair's motor, ESC esc, pair's propeller) and the battery to
// the pair's option.
Mission SubMission(const Mission& m, const Catalog& cat, int outer, const OuterPair& pr, int esc,
                   const JointBounds& jb) {
  Mission sub = m;
  PropulsionGroup& g = sub.groups[static_cast<std::size_t>(outer)];
  g.motor_id = cat.motors()[static_cast<std::size_t>(pr.motor)].id;
  g.esc_id = cat.escs()[static_cast<std::size_t>(esc)].id;
  g.prop_id = cat.props()[static_cast<std::size_t>(pr.prop)].id;
  const BatteryOption& bo = jb.options()[pr.option];
  sub.battery.ids = {bo.entry->id};
  sub.battery.cells_min = sub.battery.cells_max = bo.cells;
  return sub;
}

// G3's limit: a virtual-ESC search that finds this many completions below the N-th best may have
// left some out (its own threshold fell below the cutoff); the class is then searched per ESC.
constexpr int kCompletionLimit = 512;
// G2's order: while no N-th best is known, an inner search that has not finished after this many
// solves is put back (an outer choice that no completion makes feasible would otherwise search
// the whole inner group without a cutoff: 18 s each on the full catalog's quadplane).
constexpr long long kFirstSearchBudget = 5000;

// G3 (search.cc): the class's real ESCs of one outer pair against the completions the virtual
// ESC's search found below the N-th best (`completions`, best first; that search's relaxed
// mission and the virtual ESC score no worse than the real ESC on the mission, M2, M3, so no
// other completion can beat the N-th best). Each (ESC, completion) is solved exactly, best
// virtual score first, until that score reaches the N-th best; the results join *out's top N.
// G3 (search.cc) for one real ESC e of an outer pair's class: (pair, e) with each completion the
// virtual ESC's search found below the N-th best (`completions`, best first; that search's relaxed
// mission and the virtual ESC score no worse than e on the mission, M2, M3, so no other
// completion scoring below the list's end can beat the N-th best), solved exactly, best virtual
// score first, until that score reaches the N-th best; the results join *out's top N. Returns
// the number of solves.
template <typename NthBest>
long long SolveAgainstCompletions(const Mission& sub, const Catalog& cat, int outer, int e,
                                  const std::vector<RankedCombination>& completions,
                                  const std::vector<const PropModel*>& group_models, const PropGridCache& cache,
                                  const NthBest& nth, TopResults* top, SearchResult* out) {
  long long solved = 0;
  for (const RankedCombination& done : completions) {
    const double cutoff = nth();
    if (!(done.result.score < cutoff)) break;  // every later completion scores no better
    Combination c = done.combination;
    c.groups[static_cast<std::size_t>(outer)].esc = &cat.escs()[static_cast<std::size_t>(e)];
    const PropModel* model = cache.models[static_cast<std::size_t>(c.prop - cat.props().data())].get();
    const MissionEvaluator eval(sub, c, model, &group_models);
    MissionResult res = eval.Solve(cutoff, false, false, true);  // search: the infeasibility exits too
    ++solved;
    if (res.bounded_out) continue;
    ++out->searched;
    if (!res.feasible) continue;
    out->evaluated_mass_objective.emplace_back(res.propulsion_mass_kg, res.objective);
    if (!(res.score < cutoff)) continue;
    res = eval.Solve(cutoff);  // explained, as the inner search explains its top N (same numbers)
    top->Add(RankedCombination{c, std::move(res), {}}, cutoff);
  }
  return solved;
}

}  // namespace

namespace {

// G2's loop over the outer group's pairs and triples (search.cc: order, R5, G3), best first from
// one queue, the inner searches merged into one top N.
class JointLoop {
 public:
  JointLoop(const Mission& m, const Catalog& cat, const SearchOptions& opt, double cutoff, PropGridCache* cache,
            JointBounds* jb, const std::vector<OuterPair>& pairs, long long block, SearchResult* out)
      : m_(m), cat_(cat), opt_(opt), cache_(cache), jb_(*jb), pairs_(pairs), block_(block),
        n_esc_(static_cast<long long>(cat.escs().size())), out_(*out), top_(opt.top_n, opt.distinct_designs, cutoff) {
    inner_opt_ = opt;
    inner_opt_.progress = nullptr;
    // The virtual ESC only with two free groups (the inner search is the one-group search) and
    // the catalog's ESC values as the ranking flies them (ScenarioEscParams leaves them).
    virtual_ok_ = FreeGroupCount(m) == 2 && m.objective.ranking != DataScenario::kPessimistic &&
                  m.objective.ranking != DataScenario::kOptimistic;
    relaxed_ = m;
    relaxed_.constraints.min_hover_throttle = 0.0;
    relaxed_.constraints.prop_below_data_factor = 0.0;  // as min_hover_throttle (search.cc R12)
  }

  // The whole loop; then out's best, N-th best and progress.
  void Run();

 private:
  // A pair (esc -1, under its coupled bound) or one ESC's inner search (under its triple bound).
  struct Queued {
    double bound;
    std::size_t pair;
    int esc;
    bool unlimited = false;  // taken before (put back): no budget now
    bool operator>(const Queued& o) const { return std::tie(bound, pair, esc) > std::tie(o.bound, o.pair, o.esc); }
  };
  double Nth() const { return top_.Threshold(); }
  void Progress(std::size_t done) const { ReportProgress(opt_, pairs_, done, top_, out_); }
  // The next pair of the list under its coupled bound (G2's order: the uncoupled one is lower).
  void Tighten();
  // The outer group fixed to (pair, ESC e), the battery to the pair's option: the inner search.
  // budgeted (only while there is no N-th best): an inner search that has not finished within
  // kFirstSearchBudget solves is dropped (false; its results unused) and taken again later.
  bool SearchTriple(const OuterPair& pr, int e, bool budgeted);
  // A pair's ESC classes: per class the bounds, the virtual ESC (R5, G3); the single ESCs left
  // go into the queue. False: the pair was put back (its first inner search over its budget).
  bool TakePair(const Queued& q);
  // One class with two or more ESCs below the N-th best (`cls`, best triple bound first): the
  // virtual ESC's completions, then each real ESC against them (G3) or its own inner search.
  void VirtualEscClass(const OuterPair& pr, std::size_t i, const std::vector<std::pair<double, int>>& cls);
  // Everything left is unsettled (a stop): the item being taken has bound `bound` and `left`
  // combinations not yet settled, the rest the queue's and the list's own bounds.
  void StopAll(double bound, long long left);
  long long QueuedCombinations(const Queued& q) const { return q.esc < 0 ? SaturatingProduct({n_esc_, block_}) : block_; }

  const Mission& m_;
  const Catalog& cat_;
  const SearchOptions& opt_;
  PropGridCache* cache_;
  JointBounds& jb_;
  const std::vector<OuterPair>& pairs_;
  const long long block_, n_esc_;
  SearchResult& out_;
  TopResults top_;  // top_results.h
  SearchOptions inner_opt_;
  bool virtual_ok_ = false;
  Mission relaxed_;
  std::priority_queue<Queued, std::vector<Queued>, std::greater<>> queue_;
  // Items whose budgeted inner search did not finish: back into the queue once an N-th best is
  // known (their bounds then prune most of them), or, when nothing else is left, unlimited.
  std::vector<Queued> deferred_;
  std::size_t next_ = 0;  // the list's next pair not yet in the queue
};

void JointLoop::Run() {
  std::size_t taken = 0;
  for (;;) {
    const bool drained = next_ == pairs_.size() && queue_.empty();
    if (!deferred_.empty() && (Nth() < kInf || drained)) {
      for (Queued d : deferred_) {
        d.unlimited = true;
        queue_.push(d);
      }
      deferred_.clear();
    }
    const bool from_list = next_ < pairs_.size() && (queue_.empty() || pairs_[next_].bound < queue_.top().bound);
    if (!from_list && queue_.empty()) break;
    const double least = from_list ? pairs_[next_].bound : queue_.top().bound;
    if (!(least < Nth())) {  // G2: every pair and triple left has a bound at least as bad
      long long left = SaturatingProduct({static_cast<long long>(pairs_.size() - next_), n_esc_, block_});
      for (; !queue_.empty(); queue_.pop()) AddCount(&left, QueuedCombinations(queue_.top()));
      AddCount(&out_.pruned_by["objective_bound"], left);
      break;
    }
    if (StopRequested(opt_)) {
      StopAll(least, 0);
      break;
    }
    if (from_list) {
      Tighten();
      continue;
    }
    const Queued q = queue_.top();
    queue_.pop();
    if (taken++ % 64 == 0) Progress(next_);
    const bool budgeted = !q.unlimited && !(Nth() < kInf);
    const bool done = q.esc >= 0 ? SearchTriple(pairs_[q.pair], q.esc, budgeted) : TakePair(q);
    if (!done) {
      deferred_.push_back(q);
      continue;
    }
    if (out_.interrupted) {  // stopped in this item's inner searches: the rest of it is unsettled
      StopAll(q.bound, QueuedCombinations(q));
      break;
    }
  }
  if (!out_.interrupted) Progress(pairs_.size());
  out_.best = top_.Sorted();
  out_.nth_best_score = top_.Threshold();
}

void JointLoop::Tighten() {
  const OuterPair& pr = pairs_[next_];
  double bound = kInf;
  for (std::size_t c = 0; c < jb_.escs().classes.size(); ++c) {
    if (jb_.escs().per_option[pr.option][c].empty()) continue;
    const char* why = nullptr;
    double irms_lb = 0;
    bound = std::min(bound, jb_.PairBound(pr.motor, pr.prop, pr.option, static_cast<int>(c), &why, &irms_lb));
  }
  if (bound < kInf) {
    queue_.push(Queued{std::max(bound, pr.bound), next_, -1});
  } else {
    AddCount(&out_.pruned_by["objective_bound"], SaturatingProduct({n_esc_, block_}));
  }
  ++next_;
}

bool JointLoop::SearchTriple(const OuterPair& pr, int e, bool budgeted) {
  const Mission sub = SubMission(m_, cat_, jb_.outer_group(), pr, e, jb_);
  SearchOptions o = inner_opt_;
  if (budgeted && FreeGroupCount(sub) == 1) o.evaluation_budget = kFirstSearchBudget;
  SearchResult r = FreeGroupCount(sub) > 1 ? JointSearch(sub, cat_, o, Nth(), cache_)
                                           : SearchOneGroup(sub, cat_, o, Nth(), cache_);
  if (r.interrupted && !StopRequested(opt_)) {  // over its budget: taken again later
    out_.virtual_evaluations += r.searched + r.virtual_evaluations;
    return false;
  }
  const bool stopped = r.interrupted;
  const double unsettled_bound = r.unsettled_bound_score;
  Merge(std::move(r), &top_, &out_);
  if (stopped) {
    out_.interrupted = true;
    out_.unsettled_bound_score = std::min(out_.unsettled_bound_score, unsettled_bound);
  }
  return true;
}

bool JointLoop::TakePair(const Queued& q) {
  const OuterPair& pr = pairs_[q.pair];
  const bool budgeted = !q.unlimited && !(Nth() < kInf);
  std::vector<std::pair<double, int>> triples, cls;
  bool started = false;  // work done on the pair: it may no longer be put back
  for (std::size_t c = 0; c < jb_.escs().classes.size() && !out_.interrupted; ++c) {
    const std::vector<int>& members = jb_.escs().per_option[pr.option][c];
    if (members.empty()) continue;
    const char* why = "objective_bound";
    double irms_lb = 0;
    const double cb = jb_.PairBound(pr.motor, pr.prop, pr.option, static_cast<int>(c), &why, &irms_lb);
    if (!(cb < Nth())) {
      AddCount(&out_.pruned_by[cb < kInf ? "objective_bound" : why],
               SaturatingProduct({static_cast<long long>(members.size()), block_}));
      continue;
    }
    cls.clear();
    for (int e : members) {
      const char* w = "objective_bound";
      const double tb = jb_.TripleBound(pr.motor, e, pr.prop, pr.option, &w);
      if (tb < Nth()) {
        cls.emplace_back(tb, e);
      } else {
        AddCount(&out_.pruned_by[tb < kInf ? "objective_bound" : w], block_);
      }
    }
    std::sort(cls.begin(), cls.end());
    if (cls.size() >= 2 && virtual_ok_ && !(Nth() < kInf)) {
      // No N-th best yet: the best-bound ESC's own search first, so that the virtual ESC's
      // search has a cutoff (without one it would list every completion). Put back only before
      // any other work on the pair (nothing of it may be taken twice).
      if (!SearchTriple(pr, cls.front().second, budgeted && !started)) return false;
      started = true;
      cls.erase(cls.begin());
      if (out_.interrupted) break;
    }
    if (cls.size() >= 2 && virtual_ok_) {
      started = true;
      VirtualEscClass(pr, q.pair, cls);
      continue;
    }
    triples.insert(triples.end(), cls.begin(), cls.end());
  }
  if (!out_.interrupted) {
    for (const auto& [tb, e] : triples) queue_.push(Queued{std::max(tb, q.bound), q.pair, e});
  }
  return true;
}

void JointLoop::VirtualEscClass(const OuterPair& pr, std::size_t i, const std::vector<std::pair<double, int>>& cls) {
  const auto& escs = cat_.escs();
  const int outer = jb_.outer_group();
  // R5 for the outer group: the class's virtual ESC (no resistance, the lightest of these ESCs'
  // mass, no current limit) scores no worse than any of them with every completion (M2, M3), on
  // the mission without min_hover_throttle (the one limit it may fail when a real ESC passes).
  // Nothing below the N-th best with it: nothing with them either.
  EscEntry virt;
  virt.id = "virtual";
  virt.params = escs[static_cast<std::size_t>(cls.front().second)].params;
  virt.params.resc_ohm = 0.0;
  virt.params.max_current_a = kInf;
  double kg = kInf;
  for (const auto& t : cls) kg = std::min(kg, EscMassKg(escs[static_cast<std::size_t>(t.second)]));
  virt.mass_kg = kg;
  std::vector<GroupParts> given(m_.groups.size());
  given[static_cast<std::size_t>(outer)] =
      GroupParts{&cat_.motors()[static_cast<std::size_t>(pr.motor)], &virt, &cat_.props()[static_cast<std::size_t>(pr.prop)]};
  Progress(i);
  // G3: every completion below the N-th best with the virtual ESC, up to kCompletionLimit.
  SearchOptions all_opt = inner_opt_;
  all_opt.top_n = kCompletionLimit;
  all_opt.distinct_designs = false;  // every completion, not one per design
  const SearchResult r = SearchOneGroup(SubMission(relaxed_, cat_, outer, pr, cls.front().second, jb_), cat_,
                                        all_opt, Nth(), cache_, &given);
  out_.virtual_evaluations += r.searched + r.virtual_evaluations;
  if (r.interrupted) {  // the pair is left unsettled (Run)
    out_.interrupted = true;
    return;
  }
  if (r.best.empty()) {
    AddCount(&out_.pruned_by["objective_bound"], SaturatingProduct({static_cast<long long>(cls.size()), block_}));
    return;
  }
  // Every completion not in r.best scores at least `complete_below` with the virtual ESC: while
  // the N-th best is at or below it, the list is every completion that can matter.
  const double complete_below = static_cast<int>(r.best.size()) < kCompletionLimit ? kInf : r.best.back().result.score;
  std::vector<const PropModel*> group_models(m_.groups.size(), nullptr);
  group_models[static_cast<std::size_t>(outer)] = cache_->models[static_cast<std::size_t>(pr.prop)].get();
  for (const auto& [tb, e] : cls) {
    if (out_.interrupted || StopRequested(opt_)) {
      out_.interrupted = true;
      return;
    }
    if (!(tb < Nth())) {
      AddCount(&out_.pruned_by["objective_bound"], block_);
    } else if (Nth() <= complete_below) {
      const long long solved = SolveAgainstCompletions(SubMission(m_, cat_, outer, pr, e, jb_), cat_, outer, e, r.best,
                                                       group_models, *cache_, [this]() { return Nth(); }, &top_, &out_);
      AddCount(&out_.pruned_by["objective_bound"], block_ - std::min(block_, solved));
    } else {
      SearchTriple(pr, e, false);
    }
  }
}

void JointLoop::StopAll(double bound, long long left) {
  out_.interrupted = true;
  double least = bound;
  if (next_ < pairs_.size()) least = std::min(least, pairs_[next_].bound);
  if (!queue_.empty()) least = std::min(least, queue_.top().bound);
  for (const Queued& d : deferred_) least = std::min(least, d.bound);
  out_.unsettled_bound_score = std::min(out_.unsettled_bound_score, least);
  AddCount(&out_.unsettled, left);
  AddCount(&out_.unsettled, SaturatingProduct({static_cast<long long>(pairs_.size() - next_), n_esc_, block_}));
  for (; !queue_.empty(); queue_.pop()) AddCount(&out_.unsettled, QueuedCombinations(queue_.top()));
  for (const Queued& d : deferred_) AddCount(&out_.unsettled, QueuedCombinations(d));
  deferred_.clear();
}

}  // namespace

SearchResult JointSearch(const Mission& m, const Catalog& cat, const SearchOptions& opt, double cutoff,
                         PropGridCache* cache) {
  const auto t0 = std::chrono::steady_clock::now();
  if (opt.top_n < 1) throw UsageError("--top " + std::to_string(opt.top_n) + ": must be >= 1");
  PropGridCache own;
  if (!cache) cache = &own;
  if (!cache->built) {
    BuildPropGrids(m, cat, &cache->grids, &cache->models);
    cache->built = true;
  }
  for (int g = 0; g < GroupCount(m); ++g) {  // a fixed id not in the catalog: the JSON path
    if (m.groups[g].fixed()) FixedGroupParts(m, cat, g);
  }
  JointBounds jb(m, cat, *cache);
  SearchResult out;
  const long long per_group = GroupCombinations(cat);
  long long block = 1;  // the inner combinations of one outer choice and option
  for (int i = 1; i < FreeGroupCount(m); ++i) block = SaturatingProduct({block, per_group});
  const long long n_motor = static_cast<long long>(cat.motors().size());
  const long long n_prop = static_cast<long long>(cat.props().size());
  out.combinations = SaturatingProduct({per_group, block, static_cast<long long>(jb.options().size())});
  AddCount(&out.pruned_by["esc_voltage"], SaturatingProduct({jb.escs().voltage_pruned, n_motor, n_prop, block}));
  if (jb.escs().excluded_pruned > 0) {
    AddCount(&out.pruned_by["catalog_exclude"], SaturatingProduct({jb.escs().excluded_pruned, n_motor, n_prop, block}));
  }
  const std::vector<OuterPair> pairs = OuterPairs(cat, &jb, block, &out);
  jb.set_coupled(true);  // the tighter bound for the pairs taken (G2)
  out.candidate_pairs = static_cast<long long>(pairs.size());
  out.candidate_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  JointLoop(m, cat, opt, cutoff, cache, &jb, pairs, block, &out).Run();
  out.pruned = out.combinations - out.searched - out.unsettled;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace search_internal
}  // namespace dynosize
