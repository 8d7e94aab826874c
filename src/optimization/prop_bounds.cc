#include "optimization/prop_bounds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "common/units.h"
#include "mission/flight.h"
#include "model/physics.h"
#include "optimization/components.h"

namespace dynosize {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A floor's rounding allowance: a loss floor is a sum of products that the evaluator's PAC
// equals at best (R11's kKeyRoundingAllowance, pair_candidates.cc), and the evaluator's speed
// and torque may equal the floor point's (SetFloorPoint).
constexpr double kLossFloorRounding = 1.0 - 1e-9;

// Whether the scenario's adjustment keeps a propeller's power at or above the data's
// (credibility.cc AdjustPropEvaluation: a Reynolds exponent below 0 or a power factor below 1
// lowers it). The evaluator's prop_figure_of_merit judges the data as given, so only then
// does P >= P_ideal/max_figure_of_merit hold for the scenario's power too.
bool ScenarioKeepsPower(const PropAdjustment& adj) { return adj.reynolds_fm_exp >= 0.0 && adj.power_factor >= 1.0; }

}  // namespace

namespace {

// SpeedFromBelow's regula falsi (Illinois, secant steps in omega^2) on f = thrust - T over
// [lo, hi] with f(lo) <= 0 < f(hi) given: every step keeps lo at or below the root (M1), and
// a step that does not halve the bracket every second time is followed by a bisection. Stops
// when the bracket is kRelWidth of hi wide.
template <typename F>
double NarrowFromBelow(F&& f, double lo, double f_lo, double hi, double f_hi, int steps) {
  constexpr double kRelWidth = 1e-12;
  int side = 0;
  double width_before = hi - lo;
  for (int i = 0; i < steps && hi - lo > kRelWidth * hi; ++i) {
    const bool bisect = i % 2 == 1 && hi - lo > 0.5 * width_before;
    if (i % 2 == 1) width_before = hi - lo;
    // The secant in omega^2, where the thrust is close to linear (as PropSpeedForThrust's).
    double x = bisect ? 0.5 * (lo + hi) : std::sqrt((lo * lo * f_hi - hi * hi * f_lo) / (f_hi - f_lo));
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    if (!(x > lo && x < hi)) break;  // no representable point between them
    const double fx = f(x);
    if (fx <= 0) {
      lo = x;
      f_lo = fx;
      if (side < 0) f_hi *= 0.5;
      side = -1;
    } else {
      hi = x;
      f_hi = fx;
      if (side > 0) f_lo *= 0.5;
      side = 1;
    }
  }
  return lo;
}

}  // namespace

bool PropSpeedFromBelow(const PropModel& model, double rho, double thrust_n, double v_m_s, int steps, double* omega,
                        double start_rad_s) {
  auto f = [&](double w) { return model.Evaluate(w, rho, v_m_s).thrust_n - thrust_n; };
  const double f_top = f(kPropSpeedCeilingRadS);
  if (!(f_top >= 0)) return false;
  if (!(start_rad_s > 0 && start_rad_s < kPropSpeedCeilingRadS)) {
    *omega = SpeedFromBelow(model, rho, thrust_n, v_m_s, 0.0, kPropSpeedCeilingRadS, steps);
    return true;
  }
  // Bracket the root by steps from the start that grow as factors 1.05, 1.05^2, 1.05^4, ...
  // (a near guess costs one step, a far one a few), then narrow it (M1 throughout).
  constexpr double kFirstStep = 1.05;
  double lo = start_rad_s, f_lo = f(lo), hi = kPropSpeedCeilingRadS, f_hi = f_top;
  double step = kFirstStep;
  if (f_lo <= 0) {
    for (; lo * step < kPropSpeedCeilingRadS; step *= step) {
      const double x = lo * step, fx = f(x);
      if (fx > 0) {
        hi = x;
        f_hi = fx;
        break;
      }
      lo = x;
      f_lo = fx;
    }
    if (f_hi <= 0) {  // the ceiling itself gives T
      *omega = kPropSpeedCeilingRadS;
      return true;
    }
  } else {
    hi = lo;
    f_hi = f_lo;
    lo = 0.0;
    for (double x = hi / step; x > start_rad_s * 1e-3; step *= step, x = hi / step) {
      const double fx = f(x);
      if (fx <= 0) {
        lo = x;
        f_lo = fx;
        break;
      }
      hi = x;
      f_hi = fx;
    }
    if (!(lo > 0)) f_lo = f(0.0);
    if (f_lo > 0) {  // thrust above T at rest: no speed below the root is checked
      *omega = 0.0;
      return true;
    }
  }
  *omega = NarrowFromBelow(f, lo, f_lo, hi, f_hi, steps);
  return true;
}

double SpeedFromBelow(const PropModel& model, double rho, double thrust_n, double v_m_s, double lo, double hi,
                      int steps) {
  auto f = [&](double w) { return model.Evaluate(w, rho, v_m_s).thrust_n - thrust_n; };
  const double f_hi = f(hi);
  if (f_hi <= 0) return hi;  // the whole bracket gives at most T (M1)
  const double f_lo = f(lo);
  if (f_lo > 0) return lo;  // the caller's lo is above the root: nothing below it is checked
  return NarrowFromBelow(f, lo, f_lo, hi, f_hi, steps);
}

double SpeedFromBelowInCell(const PropModel& model, double rho, double thrust_n, double v_m_s, double lo, double t_lo_n,
                            double hi, double t_hi_n, int steps, PropEvaluation* at_lo) {
  // Every accepted step (thrust at most T) raises lo (NarrowFromBelow), so the last one accepted
  // is the speed returned.
  auto f = [&](double w) {
    const PropEvaluation ev = model.Evaluate(w, rho, v_m_s);
    const double fx = ev.thrust_n - thrust_n;
    if (fx <= 0) *at_lo = ev;
    return fx;
  };
  return NarrowFromBelow(f, lo, t_lo_n - thrust_n, hi, t_hi_n - thrust_n, steps);
}

namespace {

// FreeCruiseSamples' floor point and speed limit (docs/search.md#g1-torque-floor), for a
// feasible point of the range at a vehicle of at least the samples' mass:
// - its thrust is at least T_0 (the samples' first, at the lightest mass: M3) and at most
//   max_thrust_coefficient()*rho*n^2*D^4 (prop_model.h), so omega >= 2*pi*sqrt(T_0/(CT_max*rho*D^4));
// - it passes prop_max_rpm and prop_above_data, so omega <= the smaller of max_rpm and
//   prop_above_data_factor x the data's top;
// - it passes prop_figure_of_merit, so the data's power is at least P_ideal(T, V)/max_figure_of_merit
//   (V the airspeed with forward-flight tables, else 0, as the evaluator judges it), and the
//   scenario's power no less (ScenarioKeepsPower); P_ideal rises with T and V, so
//   Q = P/omega >= P_ideal(T_0, V_0)/(max_figure_of_merit * the speed limit).
void SetFloorPoint(const Mission& m, const CruisePropBound& p, FreeCruiseSamples* s) {
  const MissionConstraints& k = m.constraints;
  const double t0 = s->thrust[0], d = p.prop->diameter_m;
  if (!(t0 > 0)) return;
  if (const PropSpeedLimit lim = PropSpeedLimitOf(m, *p.prop); lim.rule) {
    s->omega_ub_rad_s = RpmToRadPerSec(lim.rpm);
    s->omega_ub_rule = lim.rule;
  }
  if (k.prop_above_data_factor > 0) {
    const double top = RpmToRadPerSec(k.prop_above_data_factor * p.model->valid_range().rpm_hi);
    if (top < s->omega_ub_rad_s) {
      s->omega_ub_rad_s = top;
      s->omega_ub_rule = "prop_above_data";
    }
  }
  const double ct_max = p.model->max_thrust_coefficient();
  // Both floors held kLossFloorRounding under their value: the evaluator's point may equal them.
  if (ct_max > 0) {
    s->omega_floor_rad_s = kLossFloorRounding * 2.0 * kPi * std::sqrt(t0 / (ct_max * m.rho_kg_m3 * d * d * d * d));
  }
  if (!(k.max_figure_of_merit > 0) || !ScenarioKeepsPower(p.adjustment) || !(s->omega_ub_rad_s < kInf)) return;
  const bool axial_data = p.model->data_kind() == PropDataKind::kTables && !p.prop->j_tables.empty();
  const double v0 = axial_data ? s->v[0] : 0.0;
  const double p_ideal = IdealRotorPowerW(t0, d, m.rho_kg_m3, v0);
  s->torque_floor_nm = kLossFloorRounding * p_ideal / FigureOfMeritLimit(k, v0) / s->omega_ub_rad_s;
}

}  // namespace

FreeCruiseSamples SampleFreeCruise(const Mission& m, const Segment& sg, const CruisePropBound& p, double mass_kg,
                                   bool with_points) {
  FreeCruiseSamples s;
  s.points = s.shaft_rises = s.point_rises = with_points;
  const double lo = sg.airspeed_m_s.lo, hi = sg.airspeed_m_s.hi;
  for (int k = 0; k <= kFreeCruiseCells; ++k) {
    s.v[k] = lo + (hi - lo) * k / kFreeCruiseCells;
    const RotorLoad ld = SegmentRotorLoad(m, sg, mass_kg, s.v[k]);
    s.rotors = ld.rotors;
    s.thrust[k] = ld.thrust_per_rotor_n;
    if (!s.points) continue;
    // A speed from below (M1); when even the ceiling gives less than T_k the rotor turns faster
    // than the ceiling, and its torque there is at least the ceiling's (M1).
    // The previous sample's speed starts the search (a guess: the bracket is checked).
    double w = kPropSpeedCeilingRadS;
    PropSpeedFromBelow(*p.model, m.rho_kg_m3, s.thrust[k], ld.axial_airspeed_m_s, 40, &w, k > 0 ? s.omega[k - 1] : 0.0);
    PropEvaluation ev = p.model->Evaluate(w, m.rho_kg_m3, ld.axial_airspeed_m_s);
    AdjustPropEvaluation(p.adjustment, p.prop->diameter_m, &ev);  // the scenario's torque, as the evaluator's
    if (!(ev.torque_nm > 0)) {
      s.points = s.shaft_rises = s.point_rises = false;
      continue;
    }
    s.omega[k] = w;
    s.torque[k] = ev.torque_nm;
    if (k > 0 && s.rotors * s.torque[k] * w < s.rotors * s.torque[k - 1] * s.omega[k - 1]) s.shaft_rises = false;
    if (k > 0 && (w < s.omega[k - 1] || s.torque[k] < s.torque[k - 1])) s.point_rises = false;
  }
  if (sg.lift_to_drag > 0 && p.prop != nullptr && p.model != nullptr) {
    const bool by_distance = sg.distance_m.has_value();
    const bool axial_data = p.model->data_kind() == PropDataKind::kTables && !p.prop->j_tables.empty();
    for (int k = 0; k < kFreeCruiseCells; ++k) {
      const double v_read = by_distance ? s.v[k + 1] : s.v[k];
      const double v_in = axial_data ? v_read : 0.0;  // a wing-borne cruise's inflow is its airspeed (flight.h)
      s.momentum_w[k] = s.rotors * IdealRotorPowerW(s.thrust[k], p.prop->diameter_m, m.rho_kg_m3, v_in) /
                        FigureOfMeritLimit(m.constraints, v_in);
    }
    SetFloorPoint(m, p, &s);
  }
  return s;
}

// The rules (docs/search.md#m1 to #m4, R4's momentum bound and G1's free cruise), on a cell
// [V_k, V_k+1] of the range:
// - the thrust W/(L/D) + 1/2*rho*V^2*Cd*A_add (flight.h) rises with V, so it is at least T_k,
//   its value at V_k (and rises with the mass, M3);
// - momentum theory: a feasible point's propeller power is at least P_ideal(T, V)/FM_max (the
//   evaluator's prop_figure_of_merit, V the axial inflow with forward-flight tables, else 0),
//   and PDC >= Pmech when no stage creates energy (docs/model.md section 10). P_ideal rises with T
//   and V, and P_ideal(T, V)/V falls with V at a fixed T;
// - the propeller's own data (with_prop_data, no stage creating energy): at V_k the shaft power
//   from below at T_k (speed from below, M1; the scenario's torque there, which only rises);
//   PDC >= Pmech. (M4) At a fixed thrust the power rises with the inflow, and with the thrust
//   at a fixed inflow: the samples are checked to rise, else this part is not used at all;
// - the motor's loss floor (with `loss`, no stage creating energy): PDC >= PAC >= Q*omega +
//   a*Q^2 + b*omega (model/physics.h, LossFloorOf), which rises with Q and omega; the speed and
//   torque at the cell's points are at least (omega_k, Q_k) as the drive's below (the samples'
//   speeds and torques are each checked to rise, else this part is not used);
// - the drive (with `drive`): at V_k its PDC at that point, the smaller at the full-charge and
//   cut-off voltage (linear in VDC, eq 59), rising by M4 and M2 (checked the same way);
// - by distance d the energy is P(V)*d/V >= (P_k + P_av)*d/V_k+1; by duration t it is
//   P(V)*t >= (P_k + P_av)*t, with P_k the largest of the power bounds (momentum theory read
//   at V_k+1 by distance, at V_k by duration).
double FreeCruiseRotorPowerFromSamples(const Mission& m, const Segment& sg, const CruisePropBound& p,
                                       const FreeCruiseSamples& s, const CruiseDriveBound* drive,
                                       const MotorLossFloor* loss) {
  if (!(sg.lift_to_drag > 0) || p.prop == nullptr || p.model == nullptr) return 0.0;
  const double hi = sg.airspeed_m_s.hi;
  const bool by_distance = sg.distance_m.has_value();
  const bool momentum = p.lossy && ScenarioKeepsPower(p.adjustment) && m.constraints.max_figure_of_merit > 0;
  const bool shaft = p.lossy && p.with_prop_data && s.points && s.shaft_rises;
  const bool floor = shaft && loss != nullptr && s.point_rises &&
                     (loss->copper_w_per_nm2 > 0 || loss->no_load_torque_nm > 0);
  std::array<double, kFreeCruiseCells + 1> drive_w{};
  bool drive_ok = drive != nullptr && drive->drive != nullptr && s.points;
  for (int k = 0; k <= kFreeCruiseCells && drive_ok; ++k) {
    const Drive& d = *drive->drive;
    const double pdc = std::min(d.InversePdcW(drive->v_full_v, s.torque[k], s.omega[k]),
                                d.InversePdcW(drive->v_cut_v, s.torque[k], s.omega[k]));
    drive_w[k] = s.rotors * std::max(0.0, pdc);
    if (k > 0 && drive_w[k] < drive_w[k - 1]) drive_ok = false;  // M4, M2 not seen on the samples
  }
  const double p_av = m.vehicle.avionics_power_w;
  double best = kInf;
  for (int k = 0; k < kFreeCruiseCells; ++k) {
    double p_k = momentum ? s.momentum_w[k] : 0.0;
    if (shaft) p_k = std::max(p_k, s.rotors * s.torque[k] * s.omega[k]);
    if (floor) {
      const double q = s.torque[k], w = s.omega[k];
      p_k = std::max(p_k, kLossFloorRounding * s.rotors *
                              (q * w + loss->copper_w_per_nm2 * q * q + loss->no_load_torque_nm * w));
    }
    if (drive_ok) p_k = std::max(p_k, drive_w[k]);
    best = std::min(best, by_distance ? (p_k + p_av) * hi / s.v[k + 1] : p_k + p_av);
  }
  return std::isfinite(best) ? std::max(0.0, best - p_av) : 0.0;
}

double FreeCruiseRotorPowerLowerBoundW(const Mission& m, const Segment& sg, const CruisePropBound& p,
                                       const CruiseDriveBound* drive, double mass_kg) {
  if (!(sg.lift_to_drag > 0) || p.prop == nullptr || p.model == nullptr) return 0.0;
  const bool with_points = (drive != nullptr && drive->drive != nullptr) || (p.lossy && p.with_prop_data);
  return FreeCruiseRotorPowerFromSamples(m, sg, p, SampleFreeCruise(m, sg, p, mass_kg, with_points), drive);
}

}  // namespace dynosize
