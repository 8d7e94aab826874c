// The search's early exits and bounds of the mission evaluator: EarlyExit and the proofs it
// rests on (the propeller data window, the hover throttle and thrust-to-weight over the
// capacity range, the endurance upper bound, the min_energy lower bound). Each decides a
// candidate without the full solve, with the same answer to the search's question.
// (MissionEvaluator's other files: mission_eval.cc.)
#include <algorithm>
#include <cmath>
#include <string>

#include "common/units.h"
#include "mission/flight.h"
#include "model/physics.h"
#include "optimization/mission_eval.h"
#include "optimization/mission_eval_internal.h"
#include "optimization/needed_capacity.h"
#include "optimization/prop_bounds.h"
#include "optimization/prop_speed.h"

namespace dynosize {

using eval_internal::kInf;

namespace {

// A voltage at or below the lowest at which `drive` holds (torque, omega) with a throttle of at
// most t_max (< 1): the throttle that holds a point falls as the voltage rises (eq 48: the
// ESC must give U = (Rm + RESC)*I + KE*omega, U = kv*VDC*TR_eff, TR rising with TR_eff), so
// bisection keeps throttle(lo) > t_max. Returns v_hi when even v_hi needs more than t_max, 0
// when nothing is known.
double MinVoltageForThrottle(const Drive& drive, double torque_nm, double omega_rad_s, double v_hi, double t_max) {
  if (!(v_hi > 0) || !(drive.InverseLight(v_hi, torque_nm, omega_rad_s).throttle <= t_max)) return v_hi;
  double lo = 0.0, hi = v_hi;
  for (int i = 0; i < 50 && hi - lo > 1e-9 * v_hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (drive.InverseLight(mid, torque_nm, omega_rad_s).throttle > t_max ? lo : hi) = mid;
  }
  return lo;
}

// An SOC at or below the lowest SOC in [floor_soc, 1] whose OCV (rising with SOC) reaches v:
// bisection keeping OCV(lo) < v; floor_soc when OCV(floor_soc) >= v already.
double SocBelowOcv(const BatteryPack& pack, double v, double floor_soc) {
  if (pack.OcvV(floor_soc) >= v) return floor_soc;
  if (pack.OcvV(1.0) < v) return 1.0;
  double lo = floor_soc, hi = 1.0;
  for (int i = 0; i < 50 && hi - lo > 1e-9; ++i) {
    const double mid = 0.5 * (lo + hi);
    (pack.OcvV(mid) < v ? lo : hi) = mid;
  }
  return lo;
}

// Constraints that cannot recover with a larger capacity: the ESC voltage and the frame do not
// depend on it, and the thrust, propeller speed and PAC = sqrt(27/10)*(Rm*I + KE*omega)*I
// (eqs 41, 42, 47, 48) depend only on the shaft's speed and torque, which rise with the mass
// (search.cc, M3); so does the winding temperature (its losses kp*Rm*I^2 + KT*Io*omega depend
// only on them). Violated at one capacity, they are violated at every larger one. Throttle
// and IDC are not in the list: a larger pack also sags less, which lowers both.
bool RisesWithMass(const std::string& constraint) {
  static const char* const kNames[] = {"esc_voltage", "esc_min_voltage", "prop_diameter", "thrust", "motor_power", "prop_max_rpm", "prop_tip_mach",
                                       "prop_above_data",
                                       "max_winding_temp_c", "prop_folding", "motor_unrated",
                                       "motor_voltage"};
  for (const char* name : kNames) {
    if (constraint == name) return true;
  }
  return false;
}

// EnduranceUpperBound's first pieces of a capacity range, and the Runs it may take.
constexpr int kEnduranceBoundPieces = 2;
// Capacity-sized quadcopter, --top 5 (one thread, instructions of the search): halving the
// worst piece, 8 runs, 13.74 G; split where the run stops proving, 8, 12, 16, 24 runs:
// 12.53, 12.38, 12.41, 12.85 G, the same results (docs/joint-search.md, session 45).
constexpr int kEnduranceBoundRuns = 12;

// The largest budget capacity (Ah) at which t_fixed + (Q(cb)*integral_v - e_j)/p < target,
// given room_j = (target - t_fixed)*p: Q(cb)*integral_v = room_j + e_j (EnduranceUpperBound).
double BudgetReachAh(double room_j, double integral_v, double e_j) {
  return integral_v > 0 ? (room_j + e_j) / AhToCoulomb(integral_v) : kInf;
}

}  // namespace

// max_endurance with the stretched segment at a fixed airspeed (hover, or cruise with one
// airspeed): over capacities C in a piece [C_a, C_b] of the range,
//   t_total(C) <= t_fixed_max + Q(C_b)*integral of OCV over [reserve, 1] / P_stretch(C_a)
// because more capacity means more mass and so no less power in every segment (M3 of
// search.cc), and the terminal energy is at most the OCV-weighted charge above the reserve.
// P_stretch(C_a) is the terminal power at the start of the stretch, from one Run, less the
// part of it that may fall as the voltage sags (voltage_dependent_w below: with C0 > 0 or
// a supply resistance, eqs 57, 59), so that it is the least power over the stretch and over
// the larger capacities.
// When the ESC has C0 = 0 and no supply resistance, every segment's terminal power
// N*PDC + P_avionics = N*C1*U*Irms/kv + P_avionics (eqs 48, 57, 59) does not depend on the
// voltage, so the other segments' energy at C_a, E_other(C_a), is a lower bound of theirs at
// any larger capacity (M3), and the stretch gets only what is left of the budget:
//   t_total(C) <= t_fixed_max + (Q(C_b)*integral of OCV - E_other(C_a)) / P_stretch(C_a).
// The OCV curve per SOC does not depend on the capacity (PackAt scales charge, mass,
// resistance and rating only), so the integral is computed once.
// The range starts in kEnduranceBoundPieces pieces; while the largest piece bound is at least
// `target_s`, that piece is split where its own run stops proving the target out (split_at
// below; one more Run), up to kEnduranceBoundRuns Runs: the bound only tightens as far as it takes
// to prove "cannot reach target_s", and stops as soon as no split can.
double MissionEvaluator::EnduranceUpperBound(double target_s, double from_ah, double to_ah,
                                             const MissionResult* run_at_lo) const {
  const Segment& st = m_.segments[m_.objective.segment_index];
  if (st.type == SegmentType::kCruise && st.airspeed_m_s.free()) return kInf;
  const double t_fixed_max = LongestFixedDurationS(m_);
  const bool free_c = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  double c_lo = m_.battery.capacity_ah ? m_.battery.capacity_ah->lo : base_capacity_ah_;
  double c_hi = m_.battery.capacity_ah ? m_.battery.capacity_ah->hi : base_capacity_ah_;
  if (free_c && to_ah > 0) {  // a part of the range (SolveOneVariable's bracket)
    c_lo = std::max(c_lo, from_ah);
    c_hi = std::min(c_hi, to_ah);
  }
  const double ocv_integral_v = OcvIntegralUpperBound(BatteryPack(PackAt(c_lo)), m_.battery.reserve_soc);
  bool energy_fixed = true;
  for (const GroupDrive& g : groups_) {
    energy_fixed &= g.drive.esc().c0 == 0.0 && g.drive.esc().rsupply_ohm == 0.0;
  }
  int runs = 0;
  double infeasible_from = kInf;  // every capacity from here up breaks a RisesWithMass constraint
  // Throttle floor (a second bound per piece): every checked point of the stretch holds the
  // stretch's (torque, speed), which rise with the mass (M3), within the throttle limit t_max
  // (max_throttle, and the ESC's knee when saturation is not allowed), and the throttle needed
  // for a (torque, speed) falls as the voltage rises (M2). So the terminal voltage at the
  // stretch's end is at least V_min, where the drive at C_a's point needs exactly t_max
  // (MinVoltageForThrottle), and at least the cut-off; the OCV (rising with SOC) is above the
  // terminal voltage, so the stretch ends at an SOC s >= s_min with OCV(s_min) = V_min. Up to
  // that end the pack gives at most Q(C_b)*integral of OCV over [s_min, 1], of which the
  // segments before the stretch take at least E_before(C_a) (energy_fixed, as above):
  //   t_total(C) <= t_fixed_max + (Q(C_b)*integral of OCV over [s_min, 1] - E_before(C_a)) / P_stretch(C_a).
  const GroupDrive& stretch_drive = groups_[st.group];
  double t_max = m_.constraints.max_throttle;
  if (!m_.constraints.allow_esc_saturation) t_max = std::min(t_max, stretch_drive.drive.esc().tr_sat);
  const BatteryPack pack_lo(PackAt(c_lo));
  DischargeOptions dopt;
  if (m_.battery.cutoff_cell_v) dopt.cutoff_cell_v = *m_.battery.cutoff_cell_v;
  const double v_cut = pack_lo.cutoff_v(dopt);
  // The part of one rotor's PDC at the stretch's start point that may fall as the pack sags or
  // with a larger, stiffer pack. The stretch holds one (torque, speed), so U and Irms are fixed
  // (eqs 42, 48), and PDC = VDC*(C1*TR_eff + C0)*I with U = kv*(VDC - rsupply*IDC)*TR_eff
  // (eqs 47, 57, 59, section 9) is C1*U*I/kv + C1*TR_eff*rsupply*IDC*I + C0*VDC*I: the first
  // term is fixed (and rises with the mass, M3), the second is left out, the third is counted
  // at the cut-off (every checked point has VDC >= v_cut, battery_cutoff). 0 for C0 = 0 and no
  // supply resistance, where the start power is the least.
  const EscParams& stretch_esc = stretch_drive.drive.esc();
  auto voltage_dependent_w = [&](const OperatingPoint& op) {
    double w = stretch_esc.c0 * op.irms_a * std::max(0.0, op.vdc_v - v_cut);
    if (stretch_esc.rsupply_ohm != 0.0) {
      w += stretch_esc.c1 * op.throttle_effective * stretch_esc.rsupply_ohm * op.idc_a * op.irms_a;
    }
    return w;
  };
  struct Piece {
    double ca, cb, p_ca, e_other_ca, e_before_ca = 0;
    double torque_nm = 0, omega_rad_s = 0;  // the stretch's point at C_a
    bool floor_done = false;                 // the throttle floor is computed only when needed
    double ocv_integral_smin_v = kInf;
  };
  // The piece [c, cb] (P_stretch and E_other at c; P = 0 when no bound can be given there);
  // sets infeasible_from.
  auto piece_at = [&](double c, double cb) {
    Piece pc{c, cb, 0.0, 0.0};
    ContinuousVars v;
    v.capacity_ah = c;
    v.airspeed_m_s.assign(m_.segments.size(), 0.0);
    for (std::size_t k = 0; k < m_.segments.size(); ++k) v.airspeed_m_s[k] = m_.segments[k].airspeed_m_s.lo;
    ++runs;
    // Without energy_fixed only the stretch's start is read: the segments after it are not
    // flown (their violations would only add to infeasible_from, which may miss some). With it,
    // the caller's run at the lowest capacity is this one (the same variables: a cruise's
    // airspeed 0 in a run's variables means its lowest).
    const bool reuse = energy_fixed && run_at_lo && c == c_lo && !(to_ah > 0);
    MissionResult flown;
    if (!reuse) {
      const std::size_t stretch_end = static_cast<std::size_t>(m_.objective.segment_index) + 1;
      flown = energy_fixed ? Run(v, 0.0) : RunUpTo(v, stretch_end, false).r;
    }
    const MissionResult& r = reuse ? *run_at_lo : flown;
    for (const Violation& x : r.violations) {
      if (RisesWithMass(x.constraint)) infeasible_from = std::min(infeasible_from, c);
    }
    if (r.segments.size() <= static_cast<std::size_t>(m_.objective.segment_index)) return pc;
    const SegmentResult& s = r.segments[m_.objective.segment_index];
    const double p = s.battery_current_start_a * s.vdc_max_v - s.rotors * voltage_dependent_w(s.point);
    pc.p_ca = p > 0 ? p : 0.0;
    if (energy_fixed && r.segments.size() == m_.segments.size()) {
      for (const SegmentResult& x : r.segments) pc.e_other_ca += x.energy_j;  // the stretch: 0 s
      for (int k = 0; k < m_.objective.segment_index; ++k) pc.e_before_ca += r.segments[k].energy_j;
    }
    pc.torque_nm = s.point.torque_nm;
    pc.omega_rad_s = s.point.omega_rad_s;
    return pc;
  };
  // The piece's throttle floor (its OCV integral from s_min), computed once and only when needed.
  auto throttle_floor = [&](Piece& pc) {
    if (!pc.floor_done && t_max < 1.0 && pc.omega_rad_s > 0) {
      const double v_min = std::max(v_cut, MinVoltageForThrottle(stretch_drive.drive, pc.torque_nm, pc.omega_rad_s,
                                                                 pack_lo.OcvV(1.0), t_max));
      pc.ocv_integral_smin_v = OcvIntegralUpperBound(pack_lo, SocBelowOcv(pack_lo, v_min, m_.battery.reserve_soc));
    }
    pc.floor_done = true;
  };
  // The piece's bound with its budget at capacity cb (>= pc.ca): the smaller of the reserve's
  // and the throttle floor's, each t_fixed_max + (Q(cb)*integral of OCV - E)/P_stretch(C_a).
  auto bound_to = [&](Piece& pc, double cb) {
    if (pc.ca >= infeasible_from) return -kInf;
    if (!(pc.p_ca > 0)) return kInf;
    const double by_reserve = t_fixed_max + std::max(0.0, ocv_integral_v * AhToCoulomb(cb) - pc.e_other_ca) / pc.p_ca;
    if (by_reserve < target_s) return by_reserve;  // enough: the floor could only lower it
    throttle_floor(pc);
    if (!std::isfinite(pc.ocv_integral_smin_v)) return by_reserve;
    const double by_throttle =
        t_fixed_max + std::max(0.0, pc.ocv_integral_smin_v * AhToCoulomb(cb) - pc.e_before_ca) / pc.p_ca;
    return std::min(by_reserve, by_throttle);
  };
  // Where to split a piece [C_a, C_b] whose bound reaches target_s: the largest capacity up to which
  // its run at C_a proves the target out (both bounds are linear in Q(cb): a closed form). No more
  // than C_a when no budget above Q(C_a) proves it: then no split can (every piece from C_a has at
  // least that bound). It only chooses where the next run goes; a wrong split costs runs, not a proof.
  auto split_at = [&](Piece& pc) {
    if (!(pc.p_ca > 0) || !(target_s > t_fixed_max)) return pc.ca;
    const double room_j = (target_s - t_fixed_max) * pc.p_ca;  // the energy a bound below target_s allows
    double reach = BudgetReachAh(room_j, ocv_integral_v, pc.e_other_ca);
    throttle_floor(pc);
    if (std::isfinite(pc.ocv_integral_smin_v)) {
      reach = std::max(reach, BudgetReachAh(room_j, pc.ocv_integral_smin_v, pc.e_before_ca));
    }
    double s = std::min(pc.ca + (reach - pc.ca) * (1.0 - 1e-9), pc.cb);  // strictly below target_s, not at it
    for (int i = 0; i < 4 && s > pc.ca && !(bound_to(pc, s) < target_s); ++i) s = pc.ca + 0.5 * (s - pc.ca);
    return bound_to(pc, s) < target_s ? s : pc.ca;
  };
  std::vector<Piece> pieces;
  const int n0 = free_c ? kEnduranceBoundPieces : 1;
  for (int i = 0; i < n0; ++i) {
    const double ca = c_lo + (c_hi - c_lo) * i / n0;
    const double cb = c_lo + (c_hi - c_lo) * (i + 1) / n0;
    pieces.push_back(piece_at(ca, cb));
  }
  while (true) {
    std::size_t worst = 0;
    for (std::size_t i = 1; i < pieces.size(); ++i) {
      if (bound_to(pieces[i], pieces[i].cb) > bound_to(pieces[worst], pieces[worst].cb)) worst = i;
    }
    const double ub = bound_to(pieces[worst], pieces[worst].cb);
    if (!free_c || ub < target_s || runs >= kEnduranceBoundRuns || !std::isfinite(ub)) return ub;
    const double cut = split_at(pieces[worst]);
    if (!(cut > pieces[worst].ca)) return ub;  // no split can prove it
    const double cb = pieces[worst].cb;
    pieces[worst].cb = cut;
    pieces.push_back(piece_at(cut, cb));
  }
}

// The propeller data window (PropellerPoint's prop_above_data, prop_below_data) decided without
// a solve. The speed of a segment at a fixed inflow rises with the vehicle's mass (its thrust
// per rotor does, M3 of search.cc, and the speed that gives it, M1). So a segment above the
// window at the lightest vehicle the continuous variables allow (the smallest capacity of a
// range, else the mission's) is above it at every capacity (prop_above_data is in RisesWithMass),
// and a hover below it at the heaviest (the largest capacity of a free range) is below it at
// every capacity. Segments with a free airspeed are left to the full solve (their inflow is not
// fixed). In the search many propellers hover inside their data and climb or cruise above it,
// or hover below it, each for a whole solve before.
bool MissionEvaluator::DataWindowRefuses(bool below_too, MissionResult* out) const {
  const MissionConstraints& k = m_.constraints;
  const bool free_capacity = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  for (int pass = 0; pass < 2; ++pass) {
    const bool above = pass == 0;
    if (above ? !(k.prop_above_data_factor > 0) : !(below_too && k.prop_below_data_factor > 0)) continue;
    const double capacity_ah = !m_.battery.capacity_ah         ? 0.0
                               : (!above && free_capacity) ? m_.battery.capacity_ah->hi
                                                           : m_.battery.capacity_ah->lo;
    const BatteryPack pack(PackAt(capacity_ah));
    const double mass_kg = fixed_mass_kg_ + pack.mass_kg();
    const double v_full = pack.OcvV(1.0);
    for (const Segment& s : m_.segments) {
      if (s.type == SegmentType::kShaft || (s.type == SegmentType::kCruise && s.airspeed_m_s.free())) continue;
      if (!above && s.type != SegmentType::kHover) continue;
      const GroupDrive& gd = groups_[s.group];
      const RotorLoad load = SegmentRotorLoad(m_, s, mass_kg, s.type == SegmentType::kCruise ? s.airspeed_m_s.lo : 0.0);
      double omega = 0;
      PropEvaluation ev;
      const double w_motor_max = std::max(gd.drive.NoLoadSpeed(v_full, 1.0), 1.0);
      if (!PropSpeedForThrust(*gd.prop, load.thrust_per_rotor_n, m_.rho_kg_m3, load.axial_airspeed_m_s,
                              4.0 * w_motor_max, &omega, &ev)) {
        continue;  // the full solve names the thrust
      }
      const double rpm = RadPerSecToRpm(omega);
      const double limit = above ? k.prop_above_data_factor * gd.prop->valid_range().rpm_hi
                                 : k.prop_below_data_factor * gd.prop->valid_range().rpm_lo;
      if (above ? rpm > limit : rpm < limit) {
        MissionResult r;
        r.capacity_ah = pack.capacity_ah();
        r.total_mass_kg = mass_kg;
        r.propulsion_mass_kg = mass_kg - m_.vehicle.mass_kg;
        r.violations.push_back(Violation{above ? "prop_above_data" : "prop_below_data", s.name, rpm, limit, "rpm", !above});
        r.min_slack = (above ? limit - rpm : rpm - limit) / limit;
        r.feasible = false;
        r.score = kInf;
        r.violations_everywhere = true;  // at every capacity and airspeed (above)
        *out = std::move(r);
        return true;
      }
    }
  }
  return false;
}

// The lightest capacity of [c_lo, c_hi] whose vehicle weighs at least mass_kg, by bisection
// keeping that side (the pack's mass rises with the capacity, PackAt); c_hi when none is lighter.
double MissionEvaluator::LightestCapacityAtLeastKg(double mass_kg, double c_lo, double c_hi) const {
  double lo = c_lo, hi = c_hi;
  for (int i = 0; i < 60 && hi - lo > 1e-12 * c_hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (fixed_mass_kg_ + BatteryMassKg(mid) >= mass_kg ? hi : lo) = mid;
  }
  return hi;
}

// A run at the smallest capacity (r) that breaks a constraint no larger capacity can cure
// (RisesWithMass) in a segment flown before the first cruise with a free airspeed: that
// segment's shaft points, state of charge and winding temperature depend on the capacity and
// the segments before it only, so the airspeeds do not reach it, and every point of the ranges
// breaks it too.
bool MissionEvaluator::BreaksBeforeFreeAirspeeds(const MissionResult& r) const {
  std::size_t first_free = m_.segments.size();
  for (std::size_t i = 0; i < m_.segments.size() && first_free == m_.segments.size(); ++i) {
    if (m_.segments[i].type == SegmentType::kCruise && m_.segments[i].airspeed_m_s.free()) first_free = i;
  }
  for (const Violation& v : r.violations) {
    if (!RisesWithMass(v.constraint)) continue;
    for (std::size_t i = 0; i < first_free; ++i) {
      if (m_.segments[i].name == v.segment) return true;
    }
  }
  return false;
}

// min_hover_throttle from below and min_thrust_to_weight from above, without a run (EarlyExit;
// only in a search: the result is infeasible, as the full search's would be, and says so with
// the constraint the proof rests on).
// min_hover_throttle is checked at the full-charge OCV (PropellerPoint), which does not depend
// on the capacity, with the hover's torque and speed, which rise with the mass (M3 of
// search.cc); the throttle that holds them rises with them (M2). So the hover throttle rises
// with the capacity: below the limit at a capacity C_h, it is below it at every capacity up to
// C_h. Without a capacity range the check at the mission's capacity decides it outright: the
// hover's mass, thrust and full-charge OCV depend on nothing else that is free (the stretch's
// duration and the cruise airspeeds do not enter them). In the search nearly every real ESC that
// passes the virtual one's bound fails this limit (96 % of the quadcopter's real-ESC
// evaluations), each for a whole 1-D search before.
// min_thrust_to_weight is checked at the run's end (FinishRun) with the lift rotors' thrust at
// full throttle at the terminal voltage there, which is at most the full-charge OCV (the OCV
// rises with the SOC, the sag only lowers it); that thrust rises with the voltage
// (ThrustToWeightMassCeilingKg), so every vehicle heavier than the ceiling m_t fails it, at any
// capacity, stretch and airspeed. The two together: when the hover throttle is below its limit
// at C_h, the lightest capacity whose vehicle weighs at least m_t (or the range's top, when none
// does), every capacity up to C_h fails the first and every capacity above it the second (its
// vehicle is heavier than m_t: the pack's mass rises with the capacity, PackAt). (The capacity-
// sized quadcopter's search: 3,834 of its 3,950 solves whose every point was infeasible failed
// both, each a whole 1-D search of infeasible points before.)
// with_weight = false: min_hover_throttle at the range's top alone (C_h = the top).
bool MissionEvaluator::HoverOrWeightRefuses(bool with_weight, MissionResult* out) const {
  const bool capacity_free = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  // The range's ends (the mission's own capacity, as Run flies it, without a range).
  const double c_lo = !m_.battery.capacity_ah ? 0.0 : m_.battery.capacity_ah->lo;
  const double c_hi = !m_.battery.capacity_ah ? 0.0 : capacity_free ? m_.battery.capacity_ah->hi : c_lo;
  auto refuse = [&](double capacity_ah, Violation v, bool everywhere) {
    MissionResult r;
    r.violations_everywhere = everywhere;
    const BatteryPack pack(PackAt(capacity_ah));
    r.capacity_ah = pack.capacity_ah();
    r.total_mass_kg = fixed_mass_kg_ + pack.mass_kg();
    r.propulsion_mass_kg = r.total_mass_kg - m_.vehicle.mass_kg;
    r.min_slack = v.at_least ? (v.value - v.limit) / v.limit : (v.limit - v.value) / v.limit;
    r.violations.push_back(std::move(v));
    r.feasible = false;
    r.score = kInf;
    *out = std::move(r);
    return true;
  };
  const double m_t = with_weight ? ThrustToWeightMassCeilingKg() : kInf;
  if (with_weight && !std::isfinite(m_t)) return false;  // the check below was made without it
  if (fixed_mass_kg_ + BatteryMassKg(c_lo) > m_t) {  // every capacity's vehicle is too heavy
    const double mass_kg = fixed_mass_kg_ + BatteryMassKg(c_lo);
    const double limit = m_.constraints.min_thrust_to_weight;
    return refuse(c_lo, Violation{"min_thrust_to_weight", "", limit * m_t / mass_kg, limit, "", true}, true);
  }
  if (!(m_.constraints.min_hover_throttle > 0)) return false;
  // C_h: the range's top, or the lightest capacity of the range whose vehicle weighs at least
  // m_t (bisection keeping that side; the pack's mass rises with the capacity).
  double c_h = c_hi;
  if (capacity_free && fixed_mass_kg_ + BatteryMassKg(c_hi) > m_t) {
    c_h = LightestCapacityAtLeastKg(m_t, c_lo, c_hi);
  } else if (with_weight) {
    return false;  // C_h is the top, where the check was made without the weight
  }
  const BatteryPack pack(PackAt(c_h));
  const double mass_kg = fixed_mass_kg_ + pack.mass_kg();
  const double v_full = pack.OcvV(1.0);
  for (const Segment& s : m_.segments) {
    if (s.type != SegmentType::kHover) continue;
    const GroupDrive& gd = groups_[s.group];
    const RotorLoad load = SegmentRotorLoad(m_, s, mass_kg, 0.0);
    double omega = 0;
    PropEvaluation ev;
    const double w_motor_max = std::max(gd.drive.NoLoadSpeed(v_full, 1.0), 1.0);
    if (!PropSpeedForThrust(*gd.prop, load.thrust_per_rotor_n, m_.rho_kg_m3, load.axial_airspeed_m_s,
                            4.0 * w_motor_max, &omega, &ev)) {
      continue;  // no hover point: the check says nothing here
    }
    AdjustPropEvaluation(gd.prop_adj, gd.parts.prop->diameter_m, &ev);
    const double throttle = gd.drive.Inverse(v_full, ev.torque_nm, omega).throttle;
    if (throttle < m_.constraints.min_hover_throttle) {
      // Above C_h (with_weight) the vehicle fails min_thrust_to_weight instead, not this one.
      return refuse(c_h, Violation{"min_hover_throttle", s.name, throttle, m_.constraints.min_hover_throttle, "", true},
                    c_h >= c_hi);
    }
  }
  return false;
}

// The lift rotors' full-throttle thrust (FullThrottleAt) rises with the terminal voltage v: the
// throttle that holds a (torque, speed) falls as v rises (M2 of search.cc), so at full throttle
// the motor holds at least the torque at every speed from a higher v, and the equilibrium with
// the propeller's torque, which rises with the speed (M1), moves to a higher speed. Where the
// current rating caps it, the capped speed rises too: along the propeller's curve Irms depends
// only on the torque (eq 48) and IDC = PDC/VDC = C1*U*Irms/(kv*VDC) + C0*Irms (eqs 57, 59; no
// supply resistance) falls as VDC rises. The thrust rises with the speed (M1). The terminal
// voltage at every state of charge is at most the full-charge OCV, so the thrust from that OCV
// with no sag (times 1 + kCeilingMargin against the root finders' tolerance, 1e-10 of the
// speed) bounds the thrust-to-weight check of every run from above.
// Kept once computed: EarlyExit reads it twice with a capacity range (HoverOrWeightRefuses and
// the min_energy bound's range top).
double MissionEvaluator::ThrustToWeightMassCeilingKg() const {
  constexpr double kCeilingMargin = 1e-6;
  if (mass_ceiling_kg_ >= 0) return mass_ceiling_kg_;
  mass_ceiling_kg_ = kInf;
  if (!(m_.constraints.min_thrust_to_weight > 0) || lift_rotors_ <= 0 ||
      groups_[lift_group_].drive.esc().rsupply_ohm != 0.0) {
    return mass_ceiling_kg_;
  }
  FullThrottle ft;
  if (!FullThrottleFrom(BatteryPack(pack_base_).OcvV(1.0), 0.0, &ft)) return mass_ceiling_kg_;
  mass_ceiling_kg_ = lift_rotors_ * ft.thrust_per_rotor_n * (1.0 + kCeilingMargin) /
                     (kStandardGravity * m_.constraints.min_thrust_to_weight);
  return mass_ceiling_kg_;
}

// FinishRun checks min_thrust_to_weight with the lift rotors' thrust at full throttle from the
// run's end: OCV(SOC) behind the pack's resistance R (FullThrottleAt). That thrust rises with
// the terminal voltage (ThrustToWeightMassCeilingKg), and the full-throttle terminal voltage
// V = OCV - R*I_batt, the upper root of V^2 - OCV*V + R*P = 0 with P the power drawn (rising with
// V), rises with the OCV and falls with R. A run that ends at an SOC of at least s_j has an OCV of
// at least OCV(s_j) (the OCV rises with the SOC), and every pack of a capacity range has a
// resistance at most its smallest pack's (PackAt: R*capacity is kept). So the thrust from
// OCV(s_j) behind the smallest pack's resistance, times 1 - kFloorMargin against the root
// finders' tolerance (1e-10 of the speed), is at or below the check's thrust of every such run.
// The levels s_j = j/kThrustFloorLevels (the highest at or below soc is read), each computed when
// first read, from an evaluator's second run on. None (0) with a supply resistance, as for the
// ceiling.
double MissionEvaluator::ThrustFloorN(double soc) const {
  constexpr double kFloorMargin = 1e-6;
  if (++runs_finished_ < 2 || !(soc >= 0)) return 0.0;
  const int j = std::min(kThrustFloorLevels - 1, static_cast<int>(std::floor(soc * kThrustFloorLevels)));
  double& floor_n = thrust_floor_n_[static_cast<std::size_t>(j)];
  if (floor_n >= 0) return floor_n;
  floor_n = 0.0;
  if (lift_rotors_ <= 0 || groups_[lift_group_].drive.esc().rsupply_ohm != 0.0) return floor_n;
  const BatteryPack pack(PackAt(m_.battery.capacity_ah ? m_.battery.capacity_ah->lo : 0.0));
  FullThrottle ft;
  if (FullThrottleFrom(pack.OcvV(static_cast<double>(j) / kThrustFloorLevels), pack.ri_ohm(), &ft)) {
    floor_n = std::max(0.0, ft.thrust_per_rotor_n * (1.0 - kFloorMargin));
  }
  return floor_n;
}

// min_energy with free cruise airspeeds (EarlyExit): every other segment's energy does not
// depend on them (terminal power N*PDC + P_avionics, and PDC = C1*U*I/kv does not depend on the
// voltage when C0 = 0, eqs 57, 59), and a wing-borne cruise needs at least the propulsive work
// T*d (electrical >= shaft >= thrust power) plus the avionics, T = W/(L/D) plus the added drag
// at the lowest airspeed of the range (flight.h: the least thrust of the range). r: a Run at
// `vars` (free airspeeds unset) that reached the last segment.
double MissionEvaluator::MinEnergyLowerBoundJ(const MissionResult& r, const ContinuousVars& vars) const {
  double e_lb = 0;
  for (std::size_t i = 0; i < m_.segments.size(); ++i) {
    const Segment& s = m_.segments[i];
    if (!(s.type == SegmentType::kCruise && s.airspeed_m_s.free())) {
      e_lb += r.segments[i].energy_j;
      continue;
    }
    const double d = s.distance_m ? *s.distance_m : *s.duration_s * s.airspeed_m_s.lo;
    const double t_min = s.distance_m ? d / s.airspeed_m_s.hi : *s.duration_s;
    const double thrust =
        s.lift_to_drag > 0 ? SegmentRotorLoad(m_, s, r.total_mass_kg, s.airspeed_m_s.lo).thrust_total_n : 0.0;
    double e_prop = thrust * d + m_.vehicle.avionics_power_w * t_min;
    const GroupDrive& gd = groups_[s.group];
    const MotorParams& mp = gd.drive.motor();
    const EscParams& ep = gd.drive.esc();
    // Tighter, cell by cell over the airspeed range (prop_bounds.h): momentum theory when no
    // stage creates energy, and this group's own drive at the pack's voltage range; at the
    // run's mass, which every larger pack only adds to (M3).
    const bool lossy = mp.kt_nm_per_a <= MaxKtPerKe(mp.type) * mp.ke_v_s_per_rad && mp.rm_ohm >= 0 &&
                       mp.io_a >= 0 && mp.io1_a_s_per_rad >= 0 && ep.c0 >= 0 &&
                       ep.c1 + ep.c0 >= IdealIdcPerIrmsPerThrottle(mp.type);
    const CruisePropBound pb{gd.parts.prop, gd.prop, gd.prop_adj, lossy};
    const BatteryPack pack(PackAt(vars.capacity_ah));
    DischargeOptions dopt;
    if (m_.battery.cutoff_cell_v) dopt.cutoff_cell_v = *m_.battery.cutoff_cell_v;
    const CruiseDriveBound db{&gd.drive, pack.OcvV(1.0), pack.cutoff_v(dopt)};
    const double p_rotors = FreeCruiseRotorPowerLowerBoundW(m_, s, pb, &db, r.total_mass_kg);
    e_lb += std::max(e_prop, (p_rotors + m_.vehicle.avionics_power_w) * t_min);
  }
  return e_lb;
}

// The early exits of a search (a finite cutoff, or `search`), each a proof stated at its block: a
// result (bounded out, infeasible, or the answer itself) in *out and true, or false to go on.
// The exits that end in an infeasible result need no cutoff, only a caller that reads nothing
// of an infeasible result but the constraint (Solve's search); the bounds need a finite cutoff.
bool MissionEvaluator::EarlyExit(double cutoff_score, bool explain, bool search, MissionResult* out) const {
  const bool capacity_free = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  const bool bounds = std::isfinite(cutoff_score);
  const bool screens = bounds || search;
  if (screens && DataWindowRefuses(true, out)) return true;
  if (screens && HoverOrWeightRefuses(false, out)) return true;
  // max_endurance's screening run at the smallest capacity (none run: empty); a feasible one was
  // flown in full (a screening run stops only at a violation) and is EnduranceUpperBound's first.
  MissionResult screen_run;
  if (screens && m_.objective.type == ObjectiveType::kMaxEndurance) {
    // One simulation decides most candidates of a search: infeasible before any stretch.
    // With a capacity range it is run at the smallest capacity (the lightest vehicle), and
    // decides only through constraints that no larger capacity can cure (RisesWithMass).
    ContinuousVars v0;
    v0.airspeed_m_s.assign(m_.segments.size(), 0.0);
    if (m_.battery.capacity_ah) v0.capacity_ah = m_.battery.capacity_ah->lo;
    bool airspeed_free = false;
    for (const Segment& s : m_.segments) airspeed_free |= s.type == SegmentType::kCruise && s.airspeed_m_s.free();
    if (!airspeed_free) {
      screen_run = Run(v0, 0.0, true);
      if (!screen_run.feasible) {
        if (!capacity_free) {
          screen_run.violations_everywhere = true;  // nothing free: the one point
          *out = std::move(screen_run);
          return true;
        }
        for (const Violation& v : screen_run.violations) {
          if (RisesWithMass(v.constraint)) {  // it holds at every capacity
            *out = screen_run;
            out->violations_everywhere = true;
            return true;
          }
        }
      }
    }
  }
  // After the screening above, whose exits through constraints that a heavier ESC cannot cure
  // let the search skip the ESCs this one dominates (search.cc, R5); this one's rests on
  // min_hover_throttle, which a heavier ESC may meet, and does not. Only with a capacity range:
  // without one the run above (max_endurance) or below (min_energy) checks the mission's own
  // thrust-to-weight.
  if (screens && capacity_free && HoverOrWeightRefuses(true, out)) return true;
  if (bounds && m_.objective.type == ObjectiveType::kMaxEndurance) {
    const double ub = EnduranceUpperBound(-cutoff_score, 0.0, 0.0, screen_run.feasible ? &screen_run : nullptr);
    if (-ub >= cutoff_score) {
      MissionResult r;
      r.bounded_out = true;
      r.score = -ub;
      *out = std::move(r);
      return true;
    }
  }
  if (std::isfinite(cutoff_score) && m_.objective.type == ObjectiveType::kMinEnergy &&
      std::all_of(groups_.begin(), groups_.end(), [&](const GroupDrive& g) {
        return g.drive.esc().c0 == 0.0 && (!capacity_free || g.drive.esc().rsupply_ohm == 0.0);
      })) {
    // min_energy: MinEnergyLowerBoundJ over the free cruise airspeeds. With a capacity range the
    // run is at the smallest capacity: a larger pack only adds mass, so every segment's thrust,
    // speed, torque and so its PDC (no supply resistance: the terminal power does not depend on
    // the pack's voltage) rise with it (M3 of search.cc), and the wing-borne thrust W/(L/D) +
    // added drag too: the same sum bounds the energy at every capacity of the range.
    ContinuousVars v0;
    v0.airspeed_m_s.assign(m_.segments.size(), 0.0);
    if (m_.battery.capacity_ah) v0.capacity_ah = m_.battery.capacity_ah->lo;
    bool airspeed_free = false;
    for (const Segment& s : m_.segments) airspeed_free |= s.type == SegmentType::kCruise && s.airspeed_m_s.free();
    const bool nothing_free = !airspeed_free && !capacity_free;
    const MissionResult r0 = Run(v0, 0.0, nothing_free);
    if (nothing_free && !r0.feasible) {  // nothing free: this is the answer
      *out = std::move(r0);
      out->violations_everywhere = true;
      return true;
    }
    if (capacity_free && BreaksBeforeFreeAirspeeds(r0)) {
      *out = std::move(r0);
      out->violations_everywhere = true;
      return true;
    }
    if (r0.segments.size() == m_.segments.size()) {
      double e_lb_wh = MinEnergyLowerBoundJ(r0, v0) / 3600.0;
      bool over_range = false;
      if (capacity_free) {
        // R15 (needed_capacity.h): a feasible point's pack holds at least this energy above the
        // reserve, so its capacity is at least e_lb over the integral of OCV over [reserve, 1]
        // (per Ah; PackAt scales the charge only), and the sum above at that capacity bounds it
        // too (M3). A run that stops before the last segment proves nothing: the bound stays.
        // No feasible pack is heavier than min_thrust_to_weight's ceiling either
        // (HoverOrWeightRefuses): the range's top is the largest capacity below it.
        const Range& range = *m_.battery.capacity_ah;
        const double m_t = ThrustToWeightMassCeilingKg();
        const double c_top = fixed_mass_kg_ + BatteryMassKg(range.hi) > m_t
                                 ? LightestCapacityAtLeastKg(m_t, range.lo, range.hi)
                                 : range.hi;
        const double ocv_integral_v = OcvIntegralUpperBound(BatteryPack(PackAt(range.lo)), m_.battery.reserve_soc);
        e_lb_wh = RaisedByNeededCapacity(range.lo, c_top, ocv_integral_v, e_lb_wh, cutoff_score, &over_range,
                                         [&](double capacity_ah) {
                                           ContinuousVars vc = v0;
                                           vc.capacity_ah = capacity_ah;
                                           const MissionResult rc = Run(vc, 0.0);
                                           // Broken here, broken at every larger capacity: nothing is feasible.
                                           if (BreaksBeforeFreeAirspeeds(rc)) return kInf;
                                           if (rc.segments.size() != m_.segments.size()) return -kInf;
                                           return MinEnergyLowerBoundJ(rc, vc) / 3600.0;
                                         });
      }
      if (over_range) {  // no pack of the range holds even the bound: infeasible at every capacity
        MissionResult r;
        r.bounded_out = true;
        r.score = kInf;
        *out = std::move(r);
        return true;
      }
      if (e_lb_wh >= cutoff_score) {
        MissionResult r;
        r.bounded_out = true;
        r.score = e_lb_wh;
        *out = std::move(r);
        return true;
      }
      if (nothing_free) {
        // Nothing to optimise: r0 (feasible, so the screening never stopped it) is the very
        // simulation SolveContinuous would run again (WithEndurance = Run for min_energy).
        MissionResult r = r0;
        if (explain) {
          Summarize(&r);
          AddWarnings(&r);
        }
        *out = std::move(r);
        return true;
      }
    }
  }
  return false;
}

}  // namespace dynosize
