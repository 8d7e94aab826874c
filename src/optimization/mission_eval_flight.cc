// Run: one combination flying the mission's segments with fixed continuous variables. Per
// segment the shaft point (the propeller's speed for the thrust, or Ipopt's shaft speed), then
// the battery's sag and SOC sub-step by sub-step with every constraint checked; at the end the
// reserve, the thrust-to-weight and the objective. WithEndurance finds the longest feasible
// max_endurance stretch. (MissionEvaluator's other files: mission_eval.cc.)
#include <algorithm>
#include <cmath>
#include <string>

#include "common/units.h"
#include "mission/flight.h"
#include "model/physics.h"
#include "optimization/mission_eval.h"
#include "optimization/mission_eval_internal.h"
#include "optimization/prop_speed.h"
#include "optimization/shaft.h"

namespace dynosize {

namespace {

using eval_internal::kInf;
constexpr int kSubsteps = 8;           // per fixed segment (midpoint rule in SOC)
constexpr int kStretchSubsteps = 16;   // for the stretched max_endurance segment
// An active limit is named when its relative slack is below this.
constexpr double kActiveSlack = 0.10;

// For the report of a point that creates energy: the efficiency (> 1) of the stage that does,
// eta_esc = PAC/PDC or eta_motor = Pmech/PAC; when that stage's input is not positive,
// 1 + output/|output| = 2 (a finite stand-in for "power out of nothing").
double CreatedEnergyRatio(const OperatingPoint& op) {
  auto ratio = [](double out_w, double in_w) { return in_w > 0 ? out_w / in_w : 2.0; };
  double r = 1.0;
  if (op.pesc_w < 0) r = std::max(r, ratio(op.pac_w, op.pdc_w));
  if (op.pmech_w > op.pac_w) r = std::max(r, ratio(op.pmech_w, op.pac_w));
  return r;
}

}  // namespace

namespace eval_internal {

// Tracks slacks and violations of one simulation.
class Tracker {
 public:
  // stretch_phase (RunState::in_stretch): when set, the checks also go into stretch_slacks.
  explicit Tracker(MissionResult* r, const bool* stretch_phase = nullptr) : r_(r), stretch_phase_(stretch_phase) {}
  // value <= limit (or >= when `at_least`); relative slack (limit - value)/|limit|.
  // `name` and `unit` are literals: no string is built unless the check fails.
  inline void Check(const char* name, const std::string& segment, double value, double limit,
                    const char* unit, bool at_least = false, SegmentResult* seg = nullptr) {
    if (!std::isfinite(limit)) return;
    double slack = (limit - value) / std::max(std::fabs(limit), 1e-12);
    if (at_least) slack = -slack;
    if (std::isnan(slack)) slack = -kInf;
    r_->min_slack = std::min(r_->min_slack, slack);
    if (stretch_phase_ && *stretch_phase_) r_->stretch_slacks.Add(name, slack);
    if (seg && slack < seg->active_limit_slack) {
      seg->active_limit_slack = slack;
      seg->active_limit_id = name;
    }
    if (slack < 0) Fail(name, segment, value, limit, unit, at_least, slack);
  }

 private:
  // A failed check: kept when it is the constraint's first or worst so far (out of line: the
  // passing checks, nearly all of them, stay small enough to inline).
  [[gnu::noinline]] void Fail(const char* name, const std::string& segment, double value, double limit,
                              const char* unit, bool at_least, double slack) {
    for (Violation& v : r_->violations) {
      if (v.constraint == name) {
        const double rel_old = std::fabs(v.excess()) / std::max(std::fabs(v.limit), 1e-12);
        if (-slack > rel_old) v = Violation{name, segment, value, limit, unit, at_least};
        return;
      }
    }
    r_->violations.push_back(Violation{name, segment, value, limit, unit, at_least});
  }

  MissionResult* r_;
  const bool* stretch_phase_;
};

}  // namespace eval_internal

namespace {

using eval_internal::Tracker;

// A propeller segment's shaft point: the speed where the propeller gives the required thrust
// per rotor (static or in the axial inflow), its torque, and the propeller's own checks (data
// held at an edge, static-only data in inflow, momentum theory, max rpm, the hover throttle at
// full charge). False when even four times the motor's no-load speed does not give the thrust
// (a "thrust" violation is recorded).
bool PropellerPoint(const Mission& m, const Segment& s, const RotorLoad& load, const Drive& drive,
                    const PropModel& prop, const PropEntry& prop_entry, const PropAdjustment& adj,
                    double v_full, double w_motor_max, Tracker* track, SegmentResult* seg, double* omega,
                    double* torque) {
  const MissionConstraints& k = m.constraints;
  PropEvaluation ev;
  const double w_hi = 4.0 * w_motor_max;
  if (!PropSpeedForThrust(prop, load.thrust_per_rotor_n, m.rho_kg_m3,
                          load.axial_airspeed_m_s, w_hi, omega, &ev)) {
    // Even four times the motor's no-load speed does not give the thrust.
    const PropEvaluation at_nl = prop.Evaluate(w_motor_max, m.rho_kg_m3, load.axial_airspeed_m_s);
    track->Check("thrust", s.name, load.thrust_per_rotor_n, at_nl.thrust_n, "N", false, seg);
    return false;
  }
  if (!ev.InData()) {  // the note is written from these numbers when read (FillPropNotes)
    seg->prop_edge = true;
    seg->prop_edge_eval = ev;
  }
  // Static-only data (DriveCalc power laws, static coefficients) say nothing about the
  // thrust lost to inflow; held at J = 0 they grossly over-state a propeller in fast axial
  // flow. Up to the mission's max_static_advance_ratio (default 0.2) the static values
  // are accepted as an approximation (and noted); beyond it the point fails.
  if (ev.no_forward_flight_data) {
    track->Check("prop_no_forward_flight_data", s.name, ev.j, k.max_static_advance_ratio, "", false, seg);
  }
  // Momentum theory bounds a rotor's shaft power from below: an actuator disk of area A in
  // axial flow V needs P_ideal = T*(V/2 + sqrt((V/2)^2 + T/(2*rho*A))) (Leishman,
  // Principles of Helicopter Aerodynamics, 2nd ed., eqs 2.14 and 2.91; figure of merit
  // <= 1). Propeller data below it are not physical (some DriveCalc power laws are), and
  // would fly on impossible efficiency. The ratio P_ideal/P is the figure of merit (static) or
  // its axial-flow analogue; above the mission's limit (FigureOfMeritLimit: 0.8 at rest, small
  // propellers measure 0.5-0.75, Brandt & Selig 2011; 0.95 in axial flow read from
  // forward-flight data, docs/model.md section 11) the point fails "prop_figure_of_merit".
  {
    // Static-only data evaluated in axial flow (flagged in prop_note) are held to the
    // static bound: they cannot see the climb power, which the note says.
    const double v_ax = ev.no_forward_flight_data ? 0.0 : load.axial_airspeed_m_s;
    // Positive thrust for no power: 1e3, far above any limit (a finite value to print).
    const double fom = ev.power_w > 0 ? FigureOfMerit(load.thrust_per_rotor_n, ev.power_w, prop_entry.diameter_m,
                                                      m.rho_kg_m3, v_ax)
                                      : (load.thrust_per_rotor_n > 0 ? 1e3 : 0.0);
    track->Check("prop_figure_of_merit", s.name, fom, FigureOfMeritLimit(k, v_ax), "", false, seg);
  }
  // The scenario's propeller power (credibility.h: the credible value by default), after the
  // momentum-theory check, which judges the data as given.
  AdjustPropEvaluation(adj, prop_entry.diameter_m, &ev);
  *torque = ev.torque_nm;
  if (const PropSpeedLimit lim = PropSpeedLimitOf(m, prop_entry); lim.rule) {
    track->Check(lim.rule, s.name, RadPerSecToRpm(*omega), lim.rpm, "rpm", false, seg);
  }
  // The propeller's speed window around its data (mission.h): beyond it the data do not rank.
  // The bottom is not checked in a descent (a climb segment with a negative rate): the rotors
  // unload below the weight for the seconds of a landing, a dip the Reynolds correction covers,
  // and a limit there would exclude a propeller for its landing, not for what it is ranked on.
  const PropValidRange& data = prop.valid_range();
  if (k.prop_below_data_factor > 0 && !(s.type == SegmentType::kClimb && s.climb_rate_m_s < 0)) {
    track->Check("prop_below_data", s.name, RadPerSecToRpm(*omega), k.prop_below_data_factor * data.rpm_lo, "rpm",
                 true, seg);
  }
  if (k.prop_above_data_factor > 0) {
    track->Check("prop_above_data", s.name, RadPerSecToRpm(*omega), k.prop_above_data_factor * data.rpm_hi, "rpm",
                 false, seg);
  }
  if (s.type == SegmentType::kHover && k.min_hover_throttle > 0) {
    // At the full-charge voltage without sag: the lowest throttle this hover can need, and
    // the same at every moment of the mission (so the stretch stays monotone).
    const OperatingPoint full = drive.Inverse(v_full, *torque, *omega);
    track->Check("min_hover_throttle", s.name, full.throttle, k.min_hover_throttle, "", true, seg);
  }
  return true;
}

}  // namespace

// Mission-wide checks of the parts: ESC voltage, the frame, and the lift group's credibility
// checks (credibility.h).
void MissionEvaluator::CheckParts(const RunState& st, eval_internal::Tracker* track) const {
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    const GroupDrive& gd = groups_[g];
    track->Check("esc_voltage", "", st.v_full, gd.drive.esc().vdc_max_v, "V");
    // The pack may be run down to its cut-off: the controller must still run there.
    if (gd.drive.esc().vdc_min_v > 0) track->Check("esc_min_voltage", "", st.cutoff_v, gd.drive.esc().vdc_min_v, "V", true);
    if (const auto d_max = GroupMaxPropDiameterM(m_, g)) {
      track->Check("prop_diameter", "", gd.parts.prop->diameter_m, *d_max, "m");
    }
    if (g != lift_group_) continue;  // credibility.h: the lift group's parts only
    if (gd.folding_refused) track->Check("prop_folding", "", 1.0, 0.0, "");
    if (gd.motor_excluded) track->Check("motor_unrated", "", 1.0, 0.0, "");
    track->Check("motor_voltage", "", st.v_full, MotorMaxVoltageV(*gd.parts.motor), "V");
  }
}

// The shaft's speed and torque of segment si (shaft segments: Ipopt; propeller segments:
// PropellerPoint). False when the propeller cannot give the thrust.
bool MissionEvaluator::SegmentShaftPoint(std::size_t si, const RunState& st, const RotorLoad& load,
                                         eval_internal::Tracker* track, SegmentResult* seg, double* omega,
                                         double* torque) const {
  const Segment& s = m_.segments[si];
  const GroupDrive& gd = groups_[s.group];
  const Drive& drive = gd.drive;
  const MissionConstraints& k = m_.constraints;
  if (s.type == SegmentType::kShaft) {
    const MotorParams& mp = drive.motor();
    const EscParams& ep = drive.esc();
    ShaftRequest q;
    q.vdc_v = st.v_full;
    q.power_w = s.shaft_power_w;
    q.torque_nm = s.shaft_torque_nm;
    q.omega_rad_s = s.shaft_omega_rad_s;
    q.max_throttle = std::min(k.max_throttle, k.allow_esc_saturation ? 1.0 : ep.tr_sat);
    const double lim = std::min(mp.max_current_a, ep.max_current_a) * st.current_factor;
    q.max_current_a = std::isfinite(lim) ? lim : 1e300;
    const ShaftSolution sol = SolveShaftSpeed(drive, q, "ipopt");
    *omega = sol.omega_rad_s;
    *torque = sol.point.torque_nm;
    seg->shaft_solver = sol.algorithm + ": " + sol.message;
    return true;
  }
  const double w_motor_max = std::max(drive.NoLoadSpeed(st.v_full, 1.0), 1.0);
  return PropellerPoint(m_, s, load, drive, *gd.prop, *gd.parts.prop, gd.prop_adj, st.v_full, w_motor_max, track,
                        seg, omega, torque);
}

// Flies segment si at the shaft point (omega, torque) from st.soc: the pack's sag per instant,
// the constraints at every sub-step's end, SOC by the midpoint rule. False when the pack cannot
// deliver the power (a battery_power violation is recorded).
bool MissionEvaluator::IntegrateSegment(std::size_t si, bool stretched, double omega, double torque,
                                        RunState* st, eval_internal::Tracker* track, SegmentResult* seg) const {
  const Segment& s = m_.segments[si];
  const GroupDrive& gd = groups_[s.group];
  const Drive& drive = gd.drive;
  const MotorParams& mp = gd.drive.motor();  // the scenario's (credibility.h)
  const EscParams& ep = gd.drive.esc();
  const MissionConstraints& k = m_.constraints;
  const BatteryPack& pack = st->pack;
  const int n_active = seg->rotors;
  double last_sag_v = 0.0;
  // The power asked of the pack at the last voltage tried, and the most it can give then
  // (a source OCV behind R delivers at most OCV^2/(4*R)).
  double demanded_w = 0.0, deliverable_w = 0.0;
  // The operating point at a state of charge: the terminal voltage V solves
  //   V = OCV(soc) - R*I_batt,  V*I_batt = N*PDC(V) + P_avionics.
  // PDC = C1*U*Irms/kv + C0*VDC*Irms (eqs 57, 59) depends on V only through the C0 term (and
  // saturation), so each step solves the quadratic V^2 - OCV*V + R*P = 0 for its upper (stable)
  // root with P at the current V: exact in one step when C0 = 0, a fast contraction otherwise.
  // No real root: the pack cannot deliver the power.
  // The iteration needs only IDC (Drive::InverseLight, the same numbers as Inverse); the whole
  // point is computed once, at the voltage of the last one, and only when op is not null (the
  // midpoints need IDC alone: the shaft point, hence Pmech, is the segment's).
  auto point_at = [&](double soc_now, OperatingPoint* op, double* v, double* i_batt) {
    const double ocv = pack.OcvV(soc_now);
    const double r_pack = pack.ri_ohm();
    // Warm start from the previous instant's sag (the current changes little in a segment).
    double vv = last_sag_v > 0 && last_sag_v < 0.5 * ocv ? ocv - last_sag_v : ocv;
    double v_op = vv, idc_op = 0.0;  // the last InverseLight's voltage and IDC
    for (int it = 0; it < 30; ++it) {
      idc_op = drive.InverseLight(vv, torque, omega).idc_a;
      v_op = vv;
      const double p_w = n_active * idc_op * vv + m_.vehicle.avionics_power_w;
      const double disc = ocv * ocv - 4.0 * r_pack * p_w;
      demanded_w = p_w;
      deliverable_w = ocv * ocv / (4.0 * r_pack);
      if (!(disc >= 0.0)) {
        if (op) *op = drive.Inverse(v_op, torque, omega);
        return false;
      }
      const double next = 0.5 * (ocv + std::sqrt(disc));
      // Converged: the point at vv, whose IDC was just computed; the pack's equation holds
      // there to 1e-10 of the OCV.
      if (std::fabs(next - vv) < 1e-10 * ocv) break;
      vv = next;
    }
    if (op) {
      *op = drive.Inverse(v_op, torque, omega);
      idc_op = op->idc_a;
    }
    *i_batt = n_active * idc_op + m_.vehicle.avionics_power_w / vv;
    *v = vv;
    last_sag_v = ocv - vv;
    return true;
  };
  auto check_point = [&](const OperatingPoint& op, double v, double i_batt) {
    track->Check("max_throttle", s.name, op.throttle, k.max_throttle, "", false, seg);
    if (!k.allow_esc_saturation) track->Check("esc_saturation", s.name, op.throttle, ep.tr_sat, "", false, seg);
    const double i = std::max(op.idc_a, op.irms_a);
    // The peak ratings for a segment no longer than their duration, else the continuous ones (issue 51).
    const double t_s = seg->duration_s;
    track->Check("motor_current", s.name, i,
                 SegmentRating(mp.max_current_a, mp.continuous_current_a, mp.peak_duration_s, t_s) * st->current_factor,
                 "A", false, seg);
    track->Check("esc_current", s.name, i,
                 SegmentRating(ep.max_current_a, ep.continuous_current_a, ep.peak_duration_s, t_s) * st->current_factor,
                 "A", false, seg);
    if (k.enforce_motor_power) {
      track->Check("motor_power", s.name, op.pac_w,
                   SegmentRating(mp.max_power_w, mp.continuous_power_w, mp.peak_duration_s, t_s), "W", false, seg);
    }
    track->Check("battery_current", s.name, i_batt, pack.max_current_a() * st->current_factor, "A", false, seg);
    track->Check("battery_cutoff", s.name, v, st->cutoff_v, "V", true, seg);
    const double temp_c = WindingTempC(op, s.group);
    seg->winding_temp_c = std::max(seg->winding_temp_c, temp_c);
    track->Check("max_winding_temp_c", s.name, temp_c, k.max_winding_temp_c, "C", false, seg);
    // Physics is the contract: a point where the ESC or the motor puts out more power than
    // it takes in (docs/model.md section 10; Drive::Flag sets the bit through model/physics.h)
    // is never feasible, whatever the objective gains from it.
    if (op.limits & kLimitCreatesEnergy) {
      track->Check("creates_energy", s.name, CreatedEnergyRatio(op), 1.0, "", false, seg);
    }
  };
  double& soc = st->soc;
  seg->soc_start = soc;
  OperatingPoint op;
  double v = 0, ib = 0;
  bool ok = point_at(soc, &op, &v, &ib);
  if (ok) check_point(op, v, ib);
  // From here on the checks depend on the stretch's duration (WithEndurance's root function).
  if (stretched) st->in_stretch = true;
  seg->battery_current_start_a = ib;
  seg->vdc_min_v = seg->vdc_max_v = v;
  seg->throttle_min = seg->throttle_max = op.throttle;
  seg->idc_min_a = seg->idc_max_a = op.idc_a;
  const int steps = stretched ? kStretchSubsteps : kSubsteps;
  const double dt = seg->duration_s / steps;
  double e_seg = 0, e_mech = 0;
  // Pmech = KT(I)*(I - Io)*omega at the segment's fixed shaft point (eqs 42, 50): the same at
  // every voltage, so the midpoints take it from the first point.
  const double pmech_w = op.pmech_w;
  for (int j = 0; ok && j < steps && dt > 0; ++j) {
    // Midpoint rule: predict SOC at mid-step with the start current, draw the mid current.
    double vm = 0, im = 0;
    ok = point_at(soc - 0.5 * ib * dt / st->q_c, nullptr, &vm, &im);
    if (!ok) break;
    soc -= im * dt / st->q_c;
    e_seg += vm * im * dt;
    e_mech += n_active * pmech_w * dt;
    ok = point_at(soc, &op, &v, &ib);
    if (!ok) break;
    check_point(op, v, ib);
    seg->vdc_min_v = std::min(seg->vdc_min_v, v);
    seg->vdc_max_v = std::max(seg->vdc_max_v, v);
    seg->throttle_min = std::min(seg->throttle_min, op.throttle);
    seg->throttle_max = std::max(seg->throttle_max, op.throttle);
    seg->idc_min_a = std::min(seg->idc_min_a, op.idc_a);
    seg->idc_max_a = std::max(seg->idc_max_a, op.idc_a);
  }
  if (!ok) {
    // The pack cannot deliver this power.
    track->Check("battery_power", s.name, demanded_w, deliverable_w, "W", false, seg);
    return false;
  }
  seg->point = op;
  seg->battery_current_a = ib;
  seg->soc_end = soc;
  seg->energy_j = e_seg;
  seg->eta_average = e_seg > 0 ? e_mech / (e_seg - m_.vehicle.avionics_power_w * seg->duration_s) : op.eta_system;
  if (dt <= 0) seg->eta_average = op.eta_system;
  if (seg->active_limit_slack > kActiveSlack) seg->active_limit_id = nullptr;
  st->time_s += seg->duration_s;
  st->energy_j += e_seg;
  return true;
}

// After the last segment: the reserve, the thrust-to-weight, the objective and the score.
void MissionEvaluator::FinishRun(const RunState& st, eval_internal::Tracker* track, MissionResult* out) const {
  MissionResult& r = *out;
  const MissionConstraints& k = m_.constraints;
  r.final_soc = st.soc;
  track->Check("reserve_soc", "", st.soc, m_.battery.reserve_soc, "", true);
  // Thrust-to-weight at full throttle on the lowest pack voltage of the mission (its end: the
  // SOC only falls) with the sag at that current. Falls as the stretch lengthens (less charge,
  // lower OCV), so the stretch's slack stays monotone.
  r.lift_rotors = lift_rotors_;
  if (k.min_thrust_to_weight > 0 && lift_rotors_ > 0) {
    const double weight_n = r.total_mass_kg * kStandardGravity;
    // A search's evaluation (Solve's `search`: only the score and the feasibility are read),
    // outside a max-endurance stretch (whose root function reads this check's slack): when a
    // lower bound of the thrust-to-weight meets the limit with a relative slack no smaller than
    // the run's least so far (and not negative), the exact check could change neither the least
    // slack nor the violations, and is not computed. The result then holds the bound.
    const double floor_tw = search_only_ && !st.in_stretch ? lift_rotors_ * ThrustFloorN(st.soc) / weight_n : 0.0;
    const double floor_slack = (floor_tw - k.min_thrust_to_weight) / k.min_thrust_to_weight;
    if (floor_tw > 0 && floor_slack >= std::max(0.0, r.min_slack)) {
      r.thrust_to_weight = floor_tw;
    } else {
      FullThrottle ft;
      r.thrust_to_weight =
          FullThrottleAt(st.pack, st.soc, &ft) ? lift_rotors_ * ft.thrust_per_rotor_n / weight_n : 0.0;
      track->Check("min_thrust_to_weight", "", r.thrust_to_weight, k.min_thrust_to_weight, "", true);
    }
  }
  r.endurance_s = st.time_s;
  r.energy_wh = st.energy_j / 3600.0;
  r.feasible = r.min_slack >= 0;
  switch (m_.objective.type) {
    case ObjectiveType::kMaxEndurance:
      r.objective = st.time_s;
      r.objective_unit = "s";
      r.score = -st.time_s;
      break;
    case ObjectiveType::kMinEnergy:
      r.objective = r.energy_wh;
      r.objective_unit = "Wh";
      r.score = r.energy_wh;
      break;
    case ObjectiveType::kMaxEfficiency:
      r.objective = r.segments[m_.objective.segment_index].eta_average;
      r.objective_unit = "";
      r.score = -r.objective;
      break;
  }
  if (!r.feasible) r.score = kInf;
}

MissionEvaluator::RunPrefix MissionEvaluator::RunUpTo(const ContinuousVars& vars, std::size_t end, bool screen) const {
  RunPrefix p{MissionResult{}, RunState{BatteryPack(PackAt(vars.capacity_ah))}, 0, false};
  MissionResult& r = p.r;
  RunState& st = p.st;
  r.min_slack = kInf;
  r.segments.reserve(m_.segments.size());
  Tracker track(&r);
  const BatteryPack& pack = st.pack;
  r.capacity_ah = pack.capacity_ah();
  r.total_mass_kg = fixed_mass_kg_ + pack.mass_kg();
  r.propulsion_mass_kg = r.total_mass_kg - m_.vehicle.mass_kg;
  DischargeOptions dopt;
  if (m_.battery.cutoff_cell_v) dopt.cutoff_cell_v = *m_.battery.cutoff_cell_v;
  st.cutoff_v = pack.cutoff_v(dopt);
  st.v_full = pack.OcvV(1.0);
  st.q_c = AhToCoulomb(pack.capacity_ah());
  st.current_factor = 1.0 - m_.constraints.current_margin;
  CheckParts(st, &track);
  RunSegments(vars, 0.0, screen, end, &p);
  return p;
}

// Flies the segments from p->next up to `end` (exclusive); sets p->finished when the run ends
// early (a segment that cannot be flown, or a violation when screening).
void MissionEvaluator::RunSegments(const ContinuousVars& vars, double stretch_s, bool screen, std::size_t end,
                                   RunPrefix* p) const {
  MissionResult& r = p->r;
  Tracker track(&r, &p->st.in_stretch);
  for (std::size_t si = p->next; si < end && !p->finished; ++si) {
    const Segment& s = m_.segments[si];
    SegmentResult seg;
    seg.group = s.group;
    seg.name = s.name;
    seg.type = s.type;
    seg.active_limit_slack = kInf;
    seg.winding_temp_c = m_.air_temperature_c;
    seg.airspeed_m_s = s.type == SegmentType::kCruise
                           ? (si < vars.airspeed_m_s.size() && vars.airspeed_m_s[si] > 0
                                  ? vars.airspeed_m_s[si]
                                  : s.airspeed_m_s.lo)
                           : 0.0;
    const bool stretched = m_.objective.type == ObjectiveType::kMaxEndurance &&
                           static_cast<int>(si) == m_.objective.segment_index;
    seg.duration_s = stretched ? stretch_s : SegmentDurationS(s, seg.airspeed_m_s);
    const RotorLoad load = SegmentRotorLoad(m_, s, r.total_mass_kg, seg.airspeed_m_s);
    seg.rotors = load.rotors;
    seg.thrust_per_rotor_n = s.type == SegmentType::kShaft ? 0.0 : load.thrust_per_rotor_n;
    seg.tilt_deg = load.tilt_rad * 180.0 / kPi;
    double omega = 0, torque = 0;
    const bool ok = SegmentShaftPoint(si, p->st, load, &track, &seg, &omega, &torque) &&
                    IntegrateSegment(si, stretched, omega, torque, &p->st, &track, &seg);
    if (seg.active_limit_id) seg.active_limit = seg.active_limit_id;
    r.segments.push_back(std::move(seg));
    p->next = si + 1;
    // Not ok: even four times the motor's no-load speed does not give the thrust, or the pack
    // cannot deliver the power.
    if (!ok || (screen && !r.violations.empty())) {
      r.feasible = false;
      r.score = kInf;
      p->finished = true;
    }
  }
}

MissionResult MissionEvaluator::RunFrom(RunPrefix p, const ContinuousVars& vars, double stretch_s, bool screen) const {
  RunSegments(vars, stretch_s, screen, m_.segments.size(), &p);
  if (p.finished) return std::move(p.r);
  Tracker track(&p.r, &p.st.in_stretch);
  FinishRun(p.st, &track, &p.r);
  return std::move(p.r);
}

MissionResult MissionEvaluator::Run(const ContinuousVars& vars, double stretch_s, bool screen) const {
  return RunFrom(RunUpTo(vars, 0, screen), vars, stretch_s, screen);
}

double MissionEvaluator::StretchStartCurrent(const MissionResult& r) const {
  return r.segments[m_.objective.segment_index].battery_current_start_a;
}

MissionResult MissionEvaluator::WithEndurance(ContinuousVars vars, double decide_cutoff) const {
  if (m_.objective.type != ObjectiveType::kMaxEndurance) return Run(vars, 0.0);
  // The longest stretch that keeps every constraint. Feasibility at T rests on the checks
  // before the stretch and at its first point, which do not depend on T (the segments before
  // it, the shaft points, the full-charge hover throttle), and on the rest, each of whose
  // slacks falls with T (SOC and voltage only fall). Once the first part holds (at T = 0),
  // the end of the feasible stretches is bracketed and closed in on by Illinois regula falsi
  // on the slack of one constraint: the one that fails worst at the bracket's infeasible end
  // (switched when a probe fails by another). That slack is smooth in T; the smallest slack
  // of all is not: a limit that does not move with T sits as a floor near 0 on the feasible
  // side (a thrust-to-weight held at the current rating, the class ESC's voltage limit, which
  // is exactly the pack's) and slows the regula falsi below a bisection.
  // The segments before the stretch do not depend on it: flown once.
  const RunPrefix prefix = RunUpTo(vars, static_cast<std::size_t>(m_.objective.segment_index), false);
  auto run = [&](double t) { return RunFrom(prefix, vars, t, false); };
  auto flown = [&](const MissionResult& r) { return r.segments.size() == m_.segments.size(); };
  // The watched constraint's slack; -1 where the pack gave out (no slack to read).
  const char* watch = nullptr;
  auto slack = [&](const MissionResult& r) { return flown(r) ? r.stretch_slacks.Of(watch) : -1.0; };
  MissionResult lo_r = run(0.0);
  if (lo_r.min_slack < 0 || !flown(lo_r)) return lo_r;
  // lo_r is feasible from here on and its stretch only grows (its score only falls).
  auto decided = [&]() { return lo_r.feasible && lo_r.score < decide_cutoff; };
  if (decided()) return lo_r;
  double lo = 0.0;
  // First guess: the charge left above the reserve at the stretched segment's start current.
  // The stretched segment draws at least its start current (the voltage only falls, the power
  // does not), so the charge above the reserve lasts at most this long: an infeasible end.
  const double q_c = AhToCoulomb(lo_r.capacity_ah);
  const double i_start = std::max(StretchStartCurrent(lo_r), 1e-9);
  double hi = std::max(1.0, q_c * std::max(lo_r.final_soc - m_.battery.reserve_soc, 1e-4) / i_start * 1.0001);
  MissionResult hi_r = run(hi);
  for (int i = 0; i < 40 && hi_r.feasible; ++i) {
    lo = hi; lo_r = std::move(hi_r);
    if (decided()) return lo_r;
    hi *= 2;
    hi_r = run(hi);
  }
  watch = hi_r.stretch_slacks.Worst();
  double f_lo = slack(lo_r), f_hi = slack(hi_r);
  int side = 0;
  for (int it = 0; it < 60 && hi - lo > 1e-6 * hi; ++it) {
    double t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    MissionResult tr = run(t);
    if (tr.feasible) {
      lo = t; f_lo = slack(tr); lo_r = std::move(tr);
      if (decided()) return lo_r;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else if (const char* fails = tr.stretch_slacks.Worst(); flown(tr) && !SameConstraint(fails, watch)) {
      watch = fails;  // another limit ends the stretch first: follow it from here
      hi = t; f_hi = slack(tr); f_lo = slack(lo_r);
      side = 0;
    } else {
      hi = t; f_hi = slack(tr);
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return lo_r;
}

}  // namespace dynosize
