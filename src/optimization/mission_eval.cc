#include "optimization/mission_eval.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/units.h"
#include "mission/flight.h"
#include "optimization/search.h"
#include "optimization/shaft.h"
#include "solvers/solver.h"

namespace dynosize {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kSubsteps = 8;           // per fixed segment (midpoint rule in SOC)
constexpr int kStretchSubsteps = 16;   // for the stretched max_endurance segment
// An active limit is named when its relative slack is below this.
constexpr double kActiveSlack = 0.10;

std::string Num(double x, int precision = 4) {
  std::ostringstream o;
  o.precision(precision);
  o << x;
  return o.str();
}

// Propeller speed for a required thrust: the root of T(omega) - T_req on [0, w_hi] by the
// Illinois variant of regula falsi (T(0) = 0 < T_req). Returns false when T(w_hi) < T_req.
bool PropSpeedForThrust(const PropModel& prop, double thrust_n, double rho, double airspeed,
                        double w_hi, double* omega, PropEvaluation* ev) {
  double a = 0.0, fa = -thrust_n;
  PropEvaluation eb = prop.Evaluate(w_hi, rho, airspeed);
  double b = w_hi, fb = eb.thrust_n - thrust_n;
  if (fb < 0) {
    *omega = w_hi;
    *ev = eb;
    return false;
  }
  int side = 0;
  for (int it = 0; it < 200; ++it) {
    const double c = (a * fb - b * fa) / (fb - fa);
    const PropEvaluation ec = prop.Evaluate(c, rho, airspeed);
    const double fc = ec.thrust_n - thrust_n;
    if (fc > 0) {
      b = c; fb = fc; eb = ec;
      if (side == 1) fa *= 0.5;
      side = 1;
    } else {
      a = c; fa = fc;
      if (side == -1) fb *= 0.5;
      side = -1;
      if (fc == 0) { b = c; eb = ec; break; }
    }
    if (b - a < 1e-12 * b) break;
  }
  *omega = b;
  *ev = eb;
  return true;
}

// Tracks slacks and violations of one simulation.
class Tracker {
 public:
  explicit Tracker(MissionResult* r) : r_(r) {}
  // value <= limit (or >= when `at_least`); relative slack (limit - value)/|limit|.
  // `name` and `unit` are literals: no string is built unless the check fails.
  void Check(const char* name, const std::string& segment, double value, double limit,
             const char* unit, bool at_least = false, SegmentResult* seg = nullptr) {
    if (!std::isfinite(limit)) return;
    double slack = (limit - value) / std::max(std::fabs(limit), 1e-12);
    if (at_least) slack = -slack;
    if (std::isnan(slack)) slack = -kInf;
    r_->min_slack = std::min(r_->min_slack, slack);
    if (seg && slack < seg->active_limit_slack) {
      seg->active_limit_slack = slack;
      seg->active_limit = name;
    }
    if (slack < 0) {
      for (Violation& v : r_->violations) {
        if (v.constraint == name) {
          const double rel_old = std::fabs(v.excess()) / std::max(std::fabs(v.limit), 1e-12);
          if (-slack > rel_old) v = Violation{name, segment, value, limit, unit, at_least};
          return;
        }
      }
      r_->violations.push_back(Violation{name, segment, value, limit, unit, at_least});
    }
  }

 private:
  MissionResult* r_;
};

}  // namespace

double AssumedPropMassKg(double diameter_m) {
  return 0.014 * std::pow(diameter_m / 0.254, 2.5);
}

MissionEvaluator::MissionEvaluator(const Mission& mission, const Combination& c,
                                   const PropModel* prop_model)
    : m_(mission),
      c_(c),
      drive_(ScenarioMotorParams(*c.motor, mission), ScenarioEscParams(*c.esc, mission.objective.ranking)),
      owned_prop_(prop_model ? nullptr : std::make_unique<PropModel>(*c.prop)),
      prop_(prop_model ? *prop_model : *owned_prop_) {
  const BatteryEntry& b = *c.battery;
  if (c.cells < 1 || c.cells % b.cells_series != 0) {
    throw UsageError("battery '" + b.id + "' has " + std::to_string(b.cells_series) +
                     " cells in series: --cells " + std::to_string(c.cells) +
                     " must be a positive multiple of it");
  }
  pack_base_ = PackFromEntry(b, c.cells / b.cells_series, 1);
  base_capacity_ah_ = pack_base_.cell_capacity_ah * pack_base_.n_parallel;
  for (const auto& k : pack_base_.assumed) assumed_.push_back("battery " + b.id + ": " + k);
  if (!b.mass_kg) throw DataError("battery '" + b.id + "' has no mass_kg: the mission needs it");
  const int n = m_.vehicle.rotors;
  double motor_mass = 0;
  if (c.motor->mass_kg) {
    motor_mass = *c.motor->mass_kg;
  } else {
    throw DataError("motor '" + c.motor->id + "' has no mass_kg: the mission needs it");
  }
  double esc_mass = 0;
  if (c.esc->mass_kg) {
    esc_mass = *c.esc->mass_kg;
  } else {
    // An ESC without a mass: 1 g per A of rating + 5 g (hobby ESCs: 30 A ~ 25-35 g), assumed.
    const double rating = std::isfinite(c.esc->params.max_current_a) ? c.esc->params.max_current_a : 30.0;
    esc_mass = 0.005 + 0.001 * rating;
    assumed_.push_back("ESC " + c.esc->id + ": mass_kg");
  }
  double prop_mass = 0;
  if (c.prop->mass_kg) {
    prop_mass = *c.prop->mass_kg;
  } else {
    prop_mass = AssumedPropMassKg(c.prop->diameter_m);
    assumed_.push_back("propeller " + c.prop->id + ": mass_kg");
  }
  for (const auto& k : c.motor->assumed_keys) assumed_.push_back("motor " + c.motor->id + ": " + k);
  for (const auto& k : c.esc->assumed_keys) assumed_.push_back("ESC " + c.esc->id + ": " + k);
  for (const auto& k : c.prop->assumed_keys) assumed_.push_back("propeller " + c.prop->id + ": " + k);
  fixed_mass_kg_ = m_.vehicle.mass_kg + n * (motor_mass + esc_mass + prop_mass);
  prop_adj_ = PropAdjustmentFor(*c.prop, m_.objective.ranking);
  folding_refused_ = FoldingPropRefused(*c.prop, m_);
  ScenarioMotorParams(*c.motor, m_, &rating_estimated_, &motor_excluded_);
  if (rating_estimated_) {
    assumed_.push_back("motor " + c.motor->id +
                       (std::isfinite(c.motor->params.max_power_w) ? ": max_current_a (from mass and Kv)"
                                                                   : ": max_power_w, max_current_a (from mass and Kv)"));
  }
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

MissionResult MissionEvaluator::Run(const ContinuousVars& vars, double stretch_s, bool screen) const {
  MissionResult r;
  r.min_slack = kInf;
  r.segments.reserve(m_.segments.size());
  Tracker track(&r);
  const MissionConstraints& k = m_.constraints;
  const BatteryPack pack(PackAt(vars.capacity_ah));
  r.capacity_ah = pack.capacity_ah();
  r.total_mass_kg = fixed_mass_kg_ + pack.mass_kg();
  r.propulsion_mass_kg = r.total_mass_kg - m_.vehicle.mass_kg;
  DischargeOptions dopt;
  if (m_.battery.cutoff_cell_v) dopt.cutoff_cell_v = *m_.battery.cutoff_cell_v;
  const double cutoff_v = pack.cutoff_v(dopt);
  const double v_full = pack.OcvV(1.0);
  const double q_c = AhToCoulomb(pack.capacity_ah());
  const double current_factor = 1.0 - k.current_margin;
  const MotorParams& mp = drive_.motor();  // the scenario's (credibility.h)
  const EscParams& ep = drive_.esc();
  track.Check("esc_voltage", "", v_full, ep.vdc_max_v, "V");
  if (folding_refused_) track.Check("prop_folding", "", 1.0, 0.0, "");   // credibility.h
  if (motor_excluded_) track.Check("motor_unrated", "", 1.0, 0.0, "");
  track.Check("motor_voltage", "", v_full, MotorMaxVoltageV(*c_.motor), "V");
  if (m_.vehicle.max_prop_diameter_m) {
    track.Check("prop_diameter", "", c_.prop->diameter_m, *m_.vehicle.max_prop_diameter_m, "m");
  }
  const double w_motor_max = std::max(drive_.NoLoadSpeed(v_full, 1.0), 1.0);

  double soc = 1.0;
  double time_s = 0, energy_j = 0;
  for (std::size_t si = 0; si < m_.segments.size(); ++si) {
    const Segment& s = m_.segments[si];
    SegmentResult seg;
    seg.name = s.name;
    seg.type = s.type;
    seg.active_limit_slack = kInf;
    seg.airspeed_m_s = s.type == SegmentType::kCruise
                           ? (si < vars.airspeed_m_s.size() && vars.airspeed_m_s[si] > 0
                                  ? vars.airspeed_m_s[si]
                                  : s.airspeed_m_s.lo)
                           : 0.0;
    const bool stretched = m_.objective.type == ObjectiveType::kMaxEndurance &&
                           static_cast<int>(si) == m_.objective.segment_index;
    seg.duration_s = stretched ? stretch_s : SegmentDurationS(s, seg.airspeed_m_s);
    const RotorLoad load = SegmentRotorLoad(m_, s, r.total_mass_kg, seg.airspeed_m_s);
    seg.rotors = s.type == SegmentType::kShaft ? m_.vehicle.rotors : load.rotors;
    seg.thrust_per_rotor_n = s.type == SegmentType::kShaft ? 0.0 : load.thrust_per_rotor_n;
    seg.tilt_deg = load.tilt_rad * 180.0 / kPi;
    double omega = 0, torque = 0;
    if (s.type == SegmentType::kShaft) {
      ShaftRequest q;
      q.vdc_v = v_full;
      q.power_w = s.shaft_power_w;
      q.torque_nm = s.shaft_torque_nm;
      q.omega_rad_s = s.shaft_omega_rad_s;
      q.max_throttle = std::min(k.max_throttle, k.allow_esc_saturation ? 1.0 : ep.tr_sat);
      const double lim = std::min(mp.max_current_a, ep.max_current_a) * current_factor;
      q.max_current_a = std::isfinite(lim) ? lim : 1e300;
      const ShaftSolution sol = SolveShaftSpeed(drive_, q, "ipopt");
      omega = sol.omega_rad_s;
      torque = sol.point.torque_nm;
      seg.shaft_solver = sol.algorithm + ": " + sol.message;
    } else {
      PropEvaluation ev;
      const double w_hi = 4.0 * w_motor_max;
      if (!PropSpeedForThrust(prop_, load.thrust_per_rotor_n, m_.rho_kg_m3,
                              load.axial_airspeed_m_s, w_hi, &omega, &ev)) {
        // Even four times the motor's no-load speed does not give the thrust.
        const PropEvaluation at_nl = prop_.Evaluate(w_motor_max, m_.rho_kg_m3, load.axial_airspeed_m_s);
        track.Check("thrust", s.name, load.thrust_per_rotor_n, at_nl.thrust_n, "N", false, &seg);
        r.feasible = false;
        r.segments.push_back(seg);
        r.score = kInf;
        return r;
      }
      torque = ev.torque_nm;
      if (!ev.InData()) seg.prop_note = ev.Message();
      // Static-only data (DriveCalc power laws, static coefficients) say nothing about the
      // thrust lost to inflow; held at J = 0 they grossly over-state a propeller in fast axial
      // flow. Up to the mission's max_static_advance_ratio (default 0.2) the static values
      // are accepted as an approximation (and noted); beyond it the point fails.
      if (ev.no_forward_flight_data) {
        track.Check("prop_no_forward_flight_data", s.name, ev.j, k.max_static_advance_ratio, "", false, &seg);
      }
      // Momentum theory bounds a rotor's shaft power from below: an actuator disk of area A in
      // axial flow V needs P_ideal = T*(V/2 + sqrt((V/2)^2 + T/(2*rho*A))) (Leishman,
      // Principles of Helicopter Aerodynamics, 2nd ed., eqs 2.14 and 2.91; figure of merit
      // <= 1). Propeller data below it are not physical (some DriveCalc power laws are), and
      // would fly on impossible efficiency. The ratio P_ideal/P is the figure of merit (static) or
      // its axial-flow analogue; above the mission's max_figure_of_merit (default 0.8: small
      // propellers measure 0.5-0.75, Brandt & Selig 2011) the point fails
      // "prop_figure_of_merit".
      {
        const double area = 0.25 * kPi * c_.prop->diameter_m * c_.prop->diameter_m;
        // Static-only data evaluated in axial flow (flagged in prop_note) are held to the
        // static bound: they cannot see the climb power, which the note says.
        const double v_ax = ev.no_forward_flight_data ? 0.0 : 0.5 * load.axial_airspeed_m_s;
        const double t = load.thrust_per_rotor_n;
        const double p_ideal = t * (v_ax + std::sqrt(v_ax * v_ax + t / (2.0 * m_.rho_kg_m3 * area)));
        track.Check("prop_figure_of_merit", s.name, p_ideal / ev.power_w, k.max_figure_of_merit, "", false, &seg);
      }
      // The scenario's propeller power (credibility.h: the credible value by default).
      AdjustPropEvaluation(prop_adj_, c_.prop->diameter_m, &ev);
      torque = ev.torque_nm;
      if (c_.prop->max_rpm) {
        track.Check("prop_max_rpm", s.name, RadPerSecToRpm(omega), *c_.prop->max_rpm, "rpm", false, &seg);
      }
      if (s.type == SegmentType::kHover && k.min_hover_throttle > 0) {
        // At the full-charge voltage without sag: the lowest throttle this hover can need, and
        // the same at every moment of the mission (so the stretch stays monotone).
        const OperatingPoint full = drive_.Inverse(v_full, torque, omega);
        track.Check("min_hover_throttle", s.name, full.throttle, k.min_hover_throttle, "", true, &seg);
      }
    }
    const int n_active = seg.rotors;
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
    auto point_at = [&](double soc_now, OperatingPoint* op, double* v, double* i_batt) {
      const double ocv = pack.OcvV(soc_now);
      const double r_pack = pack.ri_ohm();
      // Warm start from the previous instant's sag (the current changes little in a segment).
      double vv = last_sag_v > 0 && last_sag_v < 0.5 * ocv ? ocv - last_sag_v : ocv;
      for (int it = 0; it < 30; ++it) {
        *op = drive_.Inverse(vv, torque, omega);
        const double p_w = n_active * op->idc_a * vv + m_.vehicle.avionics_power_w;
        const double disc = ocv * ocv - 4.0 * r_pack * p_w;
        demanded_w = p_w;
        deliverable_w = ocv * ocv / (4.0 * r_pack);
        if (!(disc >= 0.0)) return false;
        const double next = 0.5 * (ocv + std::sqrt(disc));
        if (next == vv) break;
        const bool done = std::fabs(next - vv) < 1e-10 * ocv;
        vv = next;
        if (done) {
          *op = drive_.Inverse(vv, torque, omega);
          break;
        }
      }
      *i_batt = n_active * op->idc_a + m_.vehicle.avionics_power_w / vv;
      *v = vv;
      last_sag_v = ocv - vv;
      return true;
    };
    auto check_point = [&](const OperatingPoint& op, double v, double i_batt) {
      track.Check("max_throttle", s.name, op.throttle, k.max_throttle, "", false, &seg);
      if (!k.allow_esc_saturation) track.Check("esc_saturation", s.name, op.throttle, ep.tr_sat, "", false, &seg);
      const double i = std::max(op.idc_a, op.irms_a);
      track.Check("motor_current", s.name, i, mp.max_current_a * current_factor, "A", false, &seg);
      track.Check("esc_current", s.name, i, ep.max_current_a * current_factor, "A", false, &seg);
      if (k.enforce_motor_power) track.Check("motor_power", s.name, op.pac_w, mp.max_power_w, "W", false, &seg);
      track.Check("battery_current", s.name, i_batt, pack.max_current_a() * current_factor, "A", false, &seg);
      track.Check("battery_cutoff", s.name, v, cutoff_v, "V", true, &seg);
      // PESC < 0 or eta_motor > 1 (model/physics.h, Drive::Flag): never a feasible point.
      if (op.limits & kLimitCreatesEnergy) track.Check("creates_energy", s.name, 1.0, 0.0, "", false, &seg);
    };
    seg.soc_start = soc;
    OperatingPoint op;
    double v = 0, ib = 0;
    bool ok = point_at(soc, &op, &v, &ib);
    if (ok) check_point(op, v, ib);
    seg.battery_current_start_a = ib;
    seg.vdc_min_v = seg.vdc_max_v = v;
    seg.throttle_min = seg.throttle_max = op.throttle;
    seg.idc_min_a = seg.idc_max_a = op.idc_a;
    const int steps = stretched ? kStretchSubsteps : kSubsteps;
    const double dt = seg.duration_s / steps;
    double e_seg = 0, e_mech = 0;
    for (int j = 0; ok && j < steps && dt > 0; ++j) {
      // Midpoint rule: predict SOC at mid-step with the start current, draw the mid current.
      OperatingPoint opm;
      double vm = 0, im = 0;
      ok = point_at(soc - 0.5 * ib * dt / q_c, &opm, &vm, &im);
      if (!ok) break;
      soc -= im * dt / q_c;
      e_seg += vm * im * dt;
      e_mech += n_active * opm.pmech_w * dt;
      ok = point_at(soc, &op, &v, &ib);
      if (!ok) break;
      check_point(op, v, ib);
      seg.vdc_min_v = std::min(seg.vdc_min_v, v);
      seg.vdc_max_v = std::max(seg.vdc_max_v, v);
      seg.throttle_min = std::min(seg.throttle_min, op.throttle);
      seg.throttle_max = std::max(seg.throttle_max, op.throttle);
      seg.idc_min_a = std::min(seg.idc_min_a, op.idc_a);
      seg.idc_max_a = std::max(seg.idc_max_a, op.idc_a);
    }
    if (!ok) {
      // The pack cannot deliver this power.
      track.Check("battery_power", s.name, demanded_w, deliverable_w, "W", false, &seg);
      r.segments.push_back(seg);
      r.feasible = false;
      r.score = kInf;
      return r;
    }
    seg.point = op;
    seg.battery_current_a = ib;
    seg.soc_end = soc;
    seg.energy_j = e_seg;
    seg.eta_average = e_seg > 0 ? e_mech / (e_seg - m_.vehicle.avionics_power_w * seg.duration_s) : op.eta_system;
    if (dt <= 0) seg.eta_average = op.eta_system;
    if (seg.active_limit_slack > kActiveSlack) seg.active_limit.clear();
    time_s += seg.duration_s;
    energy_j += e_seg;
    r.segments.push_back(seg);
    if (screen && !r.violations.empty()) {
      r.feasible = false;
      r.score = kInf;
      return r;
    }
  }
  r.final_soc = soc;
  track.Check("reserve_soc", "", soc, m_.battery.reserve_soc, "", true);
  r.endurance_s = time_s;
  r.energy_wh = energy_j / 3600.0;
  r.feasible = r.min_slack >= 0;
  switch (m_.objective.type) {
    case ObjectiveType::kMaxEndurance:
      r.objective = time_s;
      r.objective_unit = "s";
      r.score = -time_s;
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
  return r;
}

double MissionEvaluator::StretchStartCurrent(const MissionResult& r) const {
  return r.segments[m_.objective.segment_index].battery_current_start_a;
}

MissionResult MissionEvaluator::WithEndurance(ContinuousVars vars) const {
  if (m_.objective.type != ObjectiveType::kMaxEndurance) return Run(vars, 0.0);
  // The longest stretch that keeps every constraint: min_slack(T) falls with T (SOC and
  // voltage only fall), so bracket its zero and close in by Illinois regula falsi.
  MissionResult lo_r = Run(vars, 0.0);
  if (lo_r.min_slack < 0 || lo_r.segments.size() < m_.segments.size()) return lo_r;
  double lo = 0.0, f_lo = lo_r.min_slack;
  // First guess: the charge left above the reserve at the stretched segment's start current.
  // The stretched segment draws at least its start current (the voltage only falls, the power
  // does not), so the charge above the reserve lasts at most this long: an infeasible end.
  const SegmentResult& sr = lo_r.segments[m_.objective.segment_index];
  const double q_c = AhToCoulomb(lo_r.capacity_ah);
  const double i_start = std::max(StretchStartCurrent(lo_r), 1e-9);
  double hi = std::max(1.0, q_c * std::max(lo_r.final_soc - m_.battery.reserve_soc, 1e-4) / i_start * 1.0001);
  (void)sr;
  MissionResult hi_r = Run(vars, hi);
  for (int i = 0; i < 40 && hi_r.min_slack >= 0; ++i) {
    lo = hi; f_lo = hi_r.min_slack; lo_r = hi_r;
    hi *= 2;
    hi_r = Run(vars, hi);
  }
  double f_hi = hi_r.min_slack;
  if (!std::isfinite(f_hi)) f_hi = -1.0;
  int side = 0;
  for (int it = 0; it < 60 && hi - lo > 1e-6 * hi; ++it) {
    double t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    MissionResult tr = Run(vars, t);
    const double ft = std::isfinite(tr.min_slack) ? tr.min_slack : -1.0;
    if (ft >= 0) {
      lo = t; f_lo = ft; lo_r = std::move(tr);
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = t; f_hi = ft;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return lo_r;
}

namespace {

// Constraints that cannot recover with a larger capacity: the ESC voltage and the frame do not
// depend on it, and the thrust, propeller speed and PAC = sqrt(27/10)*(Rm*I + KE*omega)*I
// (eqs 41, 42, 47, 48) depend only on the shaft's speed and torque, which rise with the mass
// (search.cc, M3). Violated at one capacity, they are violated at every larger one. Throttle
// and IDC are not in the list: a larger pack also sags less, which lowers both.
bool RisesWithMass(const std::string& constraint) {
  static const char* const kNames[] = {"esc_voltage", "prop_diameter", "thrust", "motor_power", "prop_max_rpm",
                                       "prop_folding", "motor_unrated", "motor_voltage"};
  for (const char* name : kNames) {
    if (constraint == name) return true;
  }
  return false;
}

}  // namespace

double MissionEvaluator::EnduranceUpperBound(double target_s) const {
  // max_endurance with the stretched segment at a fixed airspeed (hover, or cruise with one
  // airspeed): over capacities C in a piece [C_a, C_b] of the range,
  //   t_total(C) <= t_fixed_max + Q(C_b)*integral of OCV over [reserve, 1] / P_stretch(C_a)
  // because more capacity means more mass and so no less power in every segment (M3 of
  // search.cc), and the terminal energy is at most the OCV-weighted charge above the reserve
  // (the power P_stretch does not fall as the voltage sags: exact for C0 = 0, eq 59).
  // P_stretch(C_a) is the terminal power at the start of the stretch, from one Run.
  // When the ESC has C0 = 0 and no supply resistance, every segment's terminal power
  // N*PDC + P_avionics = N*C1*U*Irms/kv + P_avionics (eqs 48, 57, 59) does not depend on the
  // voltage, so the other segments' energy at C_a, E_other(C_a), is a lower bound of theirs at
  // any larger capacity (M3), and the stretch gets only what is left of the budget:
  //   t_total(C) <= t_fixed_max + (Q(C_b)*integral of OCV - E_other(C_a)) / P_stretch(C_a).
  // The OCV curve per SOC does not depend on the capacity (PackAt scales charge, mass,
  // resistance and rating only), so the integral is computed once.
  // The range starts in kBoundPieces pieces; while the largest piece bound is at least
  // `target_s`, that piece is halved (one more Run), up to kMaxBoundRuns Runs: the bound only
  // tightens as far as it takes to prove "cannot reach target_s".
  constexpr int kBoundPieces = 6;
  constexpr int kMaxBoundRuns = 24;
  const Segment& st = m_.segments[m_.objective.segment_index];
  if (st.type == SegmentType::kCruise && st.airspeed_m_s.free()) return kInf;
  const double t_fixed_max = LongestFixedDurationS(m_);
  const bool free_c = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  const double c_lo = m_.battery.capacity_ah ? m_.battery.capacity_ah->lo : base_capacity_ah_;
  const double c_hi = m_.battery.capacity_ah ? m_.battery.capacity_ah->hi : base_capacity_ah_;
  const double ocv_integral_v = OcvIntegralUpperBound(BatteryPack(PackAt(c_lo)), m_.battery.reserve_soc);
  const bool energy_fixed = drive_.esc().c0 == 0.0 && drive_.esc().rsupply_ohm == 0.0;
  int runs = 0;
  double infeasible_from = kInf;  // every capacity from here up breaks a RisesWithMass constraint
  struct Piece { double ca, cb, p_ca, e_other_ca; };
  // The piece [c, cb] (P_stretch and E_other at c; P = 0 when no bound can be given there);
  // sets infeasible_from.
  auto piece_at = [&](double c, double cb) {
    Piece pc{c, cb, 0.0, 0.0};
    ContinuousVars v;
    v.capacity_ah = c;
    v.airspeed_m_s.assign(m_.segments.size(), 0.0);
    for (std::size_t k = 0; k < m_.segments.size(); ++k) v.airspeed_m_s[k] = m_.segments[k].airspeed_m_s.lo;
    ++runs;
    const MissionResult r = Run(v, 0.0);
    for (const Violation& x : r.violations) {
      if (RisesWithMass(x.constraint)) infeasible_from = std::min(infeasible_from, c);
    }
    if (r.segments.size() <= static_cast<std::size_t>(m_.objective.segment_index)) return pc;
    const SegmentResult& s = r.segments[m_.objective.segment_index];
    const double p = s.battery_current_start_a * s.vdc_max_v;
    pc.p_ca = p > 0 ? p : 0.0;
    if (energy_fixed && r.segments.size() == m_.segments.size()) {
      for (const SegmentResult& x : r.segments) pc.e_other_ca += x.energy_j;  // the stretch: 0 s
    }
    return pc;
  };
  auto bound_of = [&](const Piece& pc) {
    if (pc.ca >= infeasible_from) return -kInf;
    if (!(pc.p_ca > 0)) return kInf;
    return t_fixed_max + std::max(0.0, ocv_integral_v * AhToCoulomb(pc.cb) - pc.e_other_ca) / pc.p_ca;
  };
  std::vector<Piece> pieces;
  const int n0 = free_c ? kBoundPieces : 1;
  for (int i = 0; i < n0; ++i) {
    const double ca = c_lo + (c_hi - c_lo) * i / n0;
    const double cb = c_lo + (c_hi - c_lo) * (i + 1) / n0;
    pieces.push_back(piece_at(ca, cb));
  }
  while (true) {
    std::size_t worst = 0;
    for (std::size_t i = 1; i < pieces.size(); ++i) {
      if (bound_of(pieces[i]) > bound_of(pieces[worst])) worst = i;
    }
    const double ub = bound_of(pieces[worst]);
    if (!free_c || ub < target_s || runs >= kMaxBoundRuns || !std::isfinite(ub)) return ub;
    const Piece pc = pieces[worst];
    const double mid = 0.5 * (pc.ca + pc.cb);
    pieces[worst].cb = mid;
    pieces.push_back(piece_at(mid, pc.cb));
  }
}

MissionResult MissionEvaluator::Solve(double cutoff_score, bool explain) const {
  const bool capacity_free = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  if (std::isfinite(cutoff_score) && m_.objective.type == ObjectiveType::kMaxEndurance) {
    // One simulation decides most candidates of a search: infeasible before any stretch.
    // With a capacity range it is run at the smallest capacity (the lightest vehicle), and
    // decides only through constraints that no larger capacity can cure (RisesWithMass).
    ContinuousVars v0;
    v0.airspeed_m_s.assign(m_.segments.size(), 0.0);
    if (m_.battery.capacity_ah) v0.capacity_ah = m_.battery.capacity_ah->lo;
    bool airspeed_free = false;
    for (const Segment& s : m_.segments) airspeed_free |= s.type == SegmentType::kCruise && s.airspeed_m_s.free();
    if (!airspeed_free) {
      MissionResult r0 = Run(v0, 0.0, true);
      if (!r0.feasible) {
        if (!capacity_free) return r0;
        for (const Violation& v : r0.violations) {
          if (RisesWithMass(v.constraint)) return r0;
        }
      }
    }
    const double ub = EnduranceUpperBound(-cutoff_score);
    if (-ub >= cutoff_score) {
      MissionResult r;
      r.bounded_out = true;
      r.score = -ub;
      return r;
    }
  }
  if (std::isfinite(cutoff_score) && m_.objective.type == ObjectiveType::kMinEnergy &&
      !capacity_free && drive_.esc().c0 == 0.0) {
    // min_energy with free cruise airspeeds: every other segment's energy does not depend on
    // them (terminal power N*PDC + P_avionics, and PDC = C1*U*I/kv does not depend on the
    // voltage when C0 = 0, eqs 57, 59), and a wing-borne cruise needs at least the propulsive
    // work T*d = W/(L/D)*d (electrical >= shaft >= thrust power) plus the avionics.
    ContinuousVars v0;
    v0.airspeed_m_s.assign(m_.segments.size(), 0.0);
    if (m_.battery.capacity_ah) v0.capacity_ah = m_.battery.capacity_ah->lo;
    bool airspeed_free = false;
    for (const Segment& s : m_.segments) airspeed_free |= s.type == SegmentType::kCruise && s.airspeed_m_s.free();
    const MissionResult r0 = Run(v0, 0.0, !airspeed_free);
    if (!airspeed_free && !r0.feasible) return r0;  // nothing free: this is the answer
    if (r0.segments.size() == m_.segments.size()) {
      double e_lb = 0;
      for (std::size_t i = 0; i < m_.segments.size(); ++i) {
        const Segment& s = m_.segments[i];
        if (s.type == SegmentType::kCruise && s.airspeed_m_s.free()) {
          const double d = s.distance_m ? *s.distance_m : *s.duration_s * s.airspeed_m_s.lo;
          const double t_min = s.distance_m ? d / s.airspeed_m_s.hi : *s.duration_s;
          const double thrust = s.lift_to_drag > 0 ? r0.total_mass_kg * kStandardGravity / s.lift_to_drag : 0.0;
          e_lb += thrust * d + m_.vehicle.avionics_power_w * t_min;
        } else {
          e_lb += r0.segments[i].energy_j;
        }
      }
      if (e_lb / 3600.0 >= cutoff_score) {
        MissionResult r;
        r.bounded_out = true;
        r.score = e_lb / 3600.0;
        return r;
      }
    }
  }
  // Free variables, each scaled to [0, 1].
  struct Var { int segment; double lo, hi; };  // segment -1: capacity
  std::vector<Var> free;
  if (m_.battery.capacity_ah && m_.battery.capacity_ah->free()) {
    free.push_back({-1, m_.battery.capacity_ah->lo, m_.battery.capacity_ah->hi});
  }
  for (std::size_t i = 0; i < m_.segments.size(); ++i) {
    const Segment& s = m_.segments[i];
    if (s.type == SegmentType::kCruise && s.airspeed_m_s.free()) {
      free.push_back({static_cast<int>(i), s.airspeed_m_s.lo, s.airspeed_m_s.hi});
    }
  }
  auto vars_at = [&](const double* x) {
    ContinuousVars v;
    v.airspeed_m_s.assign(m_.segments.size(), 0.0);
    if (m_.battery.capacity_ah) v.capacity_ah = m_.battery.capacity_ah->lo;
    for (std::size_t i = 0; i < free.size(); ++i) {
      const double val = free[i].lo + std::clamp(x[i], 0.0, 1.0) * (free[i].hi - free[i].lo);
      if (free[i].segment < 0) v.capacity_ah = val;
      else v.airspeed_m_s[free[i].segment] = val;
    }
    return v;
  };
  if (free.empty()) {
    MissionResult r = WithEndurance(vars_at(nullptr));
    if (explain) AddWarnings(&r);
    return r;
  }

  // A coarse grid (5 levels per variable, at most 125 points) picks the start; COBYLA
  // (derivative-free: the objective passes through tabulated propeller data) polishes it.
  const int n = static_cast<int>(free.size());
  const int levels = 5;
  int total = 1;
  for (int i = 0; i < n && i < 3; ++i) total *= levels;
  Eigen::VectorXd best_x = Eigen::VectorXd::Constant(n, 0.5);
  double best_score = kInf, best_slack = -kInf;
  std::vector<double> x(n, 0.5);
  for (int g = 0; g < total; ++g) {
    int code = g;
    for (int i = 0; i < n; ++i) {
      x[i] = i < 3 ? (code % levels) / double(levels - 1) : 0.5;
      code /= levels;
    }
    const MissionResult r = WithEndurance(vars_at(x.data()));
    const bool better = r.feasible ? r.score < best_score
                                   : (best_score == kInf && r.min_slack > best_slack);
    if (better) {
      best_score = r.feasible ? r.score : kInf;
      best_slack = r.min_slack;
      best_x = Eigen::Map<Eigen::VectorXd>(x.data(), n);
    }
  }
  Problem p;
  p.name = "combination continuous variables";
  p.num_variables = n;
  p.initial_point = best_x;
  p.lower_bounds = Eigen::VectorXd::Zero(n);
  p.upper_bounds = Eigen::VectorXd::Ones(n);
  for (const Var& v : free) {
    p.variable_names.push_back(v.segment < 0 ? "capacity_ah" : m_.segments[v.segment].name + ".airspeed_m_s");
  }
  // Scale of the objective: the grid's best score (so that the solver sees O(1) values).
  const double scale = std::isfinite(best_score) && best_score != 0 ? std::fabs(best_score) : 1.0;
  // NLopt asks for the objective and the constraint at the same x one after the other: one
  // simulation serves both.
  Eigen::VectorXd memo_x;
  double memo_score = 0, memo_slack = 0;
  auto at = [&](const Eigen::VectorXd& xv) {
    if (memo_x.size() != xv.size() || memo_x != xv) {
      const MissionResult r = WithEndurance(vars_at(xv.data()));
      memo_x = xv;
      memo_score = std::isfinite(r.score) ? r.score / scale : 1e3;
      memo_slack = std::isfinite(r.min_slack) ? r.min_slack : -1.0;
    }
  };
  p.objective = [&](const Eigen::VectorXd& xv, Eigen::VectorXd*) {
    at(xv);
    return memo_score;
  };
  p.num_inequality_constraints = 1;
  p.inequality_names = {"-min constraint slack"};
  p.inequality_constraints = [&](const Eigen::VectorXd& xv, Eigen::VectorXd* g, Eigen::MatrixXd*) {
    at(xv);
    (*g)[0] = -memo_slack;
  };
  SolverOptions o;
  o.algorithm = "nlopt_cobyla";
  o.relative_tolerance = 1e-6;
  o.max_evaluations = 80;
  o.max_solver_time_in_seconds = 10.0;
  const SolverResult sr = dynosize::Solve(p, o);
  Eigen::VectorXd xs = best_x;
  if (sr.x.size() == n && sr.x.allFinite()) xs = sr.x;
  MissionResult r = WithEndurance(vars_at(xs.data()));
  const MissionResult grid = WithEndurance(vars_at(best_x.data()));
  if (!(r.feasible && r.score <= grid.score) && grid.feasible) r = grid;  // never worse than the grid
  if (!explain) return r;
  std::ostringstream msg;
  msg << sr.BriefReport();
  for (int i = 0; i < n; ++i) msg << (i ? ", " : "; ") << p.variable_names[i] << " = "
                                  << Num(free[i].lo + std::clamp(xs[i], 0.0, 1.0) * (free[i].hi - free[i].lo), 6);
  r.solver = msg.str();
  AddWarnings(&r);
  return r;
}

MissionResult MissionEvaluator::Simulate(const ContinuousVars& vars) const {
  MissionResult r = WithEndurance(vars);
  AddWarnings(&r);
  return r;
}

void MissionEvaluator::AddWarnings(MissionResult* r) const {
  r->assumed = assumed_;
  const MissionConstraints& k = m_.constraints;
  const MotorParams& mp = drive_.motor();
  const EscParams& ep = drive_.esc();
  for (const Violation& v : r->violations) {
    if (v.constraint == "max_throttle") {
      r->warnings.push_back("segment '" + v.segment + "': throttle " + Num(100 * v.value, 3) +
                            " % above the " + Num(100 * v.limit, 3) +
                            " % limit (no control authority left)");
    }
  }
  for (const SegmentResult& s : r->segments) {
    const OperatingPoint& p = s.point;
    const double i = std::max(p.idc_a, p.irms_a);
    auto near = [&](const char* what, double rating) {
      if (std::isfinite(rating) && i > 0.8 * rating && i <= rating) {
        r->warnings.push_back("segment '" + s.name + "': current " + Num(i, 3) + " A is " +
                              Num(100 * i / rating, 3) + " % of the " + what + " rating " +
                              Num(rating, 3) + " A");
      }
    };
    near("motor", mp.max_current_a);
    near("ESC", ep.max_current_a);
    if (s.throttle_max > ep.tr_sat) {
      r->warnings.push_back("segment '" + s.name + "': ESC in saturation (throttle up to " +
                            Num(100 * s.throttle_max, 3) + " % > knee " + Num(100 * ep.tr_sat, 3) +
                            " %): the speed per throttle step falls");
    }
    if (s.type != SegmentType::kShaft && p.throttle > 0 && p.throttle <= 1) {
      // On the segment's throttle line the efficiency peaks at MaxEfficiencySpeed (eq 14
      // analogue); running well above that speed means a light load for this motor.
      const double w_opt = drive_.MaxEfficiencySpeed(p.vdc_v, p.throttle);
      const OperatingPoint best = drive_.AtSpeed(p.vdc_v, p.throttle, w_opt);
      if (p.omega_rad_s > w_opt && p.eta_system < best.eta_system - 0.10) {
        r->warnings.push_back("segment '" + s.name + "': motor running below the current of "
                              "optimal efficiency (" + Num(p.irms_a, 3) + " A vs " +
                              Num(best.irms_a, 3) + " A, system efficiency " +
                              Num(100 * p.eta_system, 3) + " % vs " + Num(100 * best.eta_system, 3) +
                              " %): a smaller motor would do");
      }
    }
    if (p.throttle > 0 && p.throttle < 0.2) {
      r->warnings.push_back("segment '" + s.name + "': throttle only " + Num(100 * p.throttle, 3) +
                            " %: coarse speed control; a lower-Kv motor or fewer cells would "
                            "use more of the range");
    }
    if (!s.prop_note.empty()) {
      r->warnings.push_back("segment '" + s.name + "': propeller data held at an edge: " + s.prop_note);
    }
  }
  (void)k;
  if (!std::isfinite(mp.max_current_a) && !std::isfinite(mp.max_power_w)) {
    r->warnings.push_back("motor " + c_.motor->id + " has no current or power rating in the "
                          "catalog: its load could not be checked (the search may favour it)");
  }
  if (rating_estimated_) {
    r->warnings.push_back("motor " + c_.motor->id + " has no current or power rating in its source: "
                          "ratings " + Num(mp.max_power_w, 3) + " W, " + Num(mp.max_current_a, 3) +
                          " A estimated from its mass and Kv (laws of hobby outrunners, catalog/conventions.h, "
                          "assumed)");
  }
  for (const EntryBase* e : {static_cast<const EntryBase*>(c_.motor), static_cast<const EntryBase*>(c_.esc),
                             static_cast<const EntryBase*>(c_.prop), static_cast<const EntryBase*>(c_.battery)}) {
    if (!e->exclude_reason.empty()) {
      r->warnings.push_back(e->id + " is excluded from searches by the catalog: " + e->exclude_reason);
    }
  }
  if (motor_excluded_) {
    r->warnings.push_back("motor " + c_.motor->id + " has no current or power rating: excluded "
                          "(constraints.unrated_motors = \"exclude\")");
  }
  if (folding_refused_) {
    r->warnings.push_back("propeller " + c_.prop->id + " is a folding propeller: not used for multirotor "
                          "lift (constraints.allow_folding_props_for_lift)");
  }
  if (!std::isfinite(ep.max_current_a)) {
    r->warnings.push_back("ESC " + c_.esc->id + " has no current rating: its current was not checked");
  }
  if (!r->assumed.empty()) {
    std::string a;
    for (const auto& x : r->assumed) a += (a.empty() ? "" : "; ") + x;
    r->warnings.push_back("results rest on assumed values (" + a + ")");
  }
}

}  // namespace dynosize
