#include "optimization/prop_bounds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "mission/flight.h"
#include "model/physics.h"

namespace dynosize {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Whether the scenario's adjustment keeps a propeller's power at or above the data's
// (credibility.cc AdjustPropEvaluation: a Reynolds exponent below 0 or a power factor below 1
// lowers it). The evaluator's prop_figure_of_merit judges the data as given, so only then
// does P >= P_ideal/max_figure_of_merit hold for the scenario's power too.
bool ScenarioKeepsPower(const PropAdjustment& adj) { return adj.reynolds_fm_exp >= 0.0 && adj.power_factor >= 1.0; }

}  // namespace

bool PropSpeedFromBelow(const PropModel& model, double rho, double thrust_n, double v_m_s, int steps, double* omega) {
  if (!(model.Evaluate(kPropSpeedCeilingRadS, rho, v_m_s).thrust_n >= thrust_n)) return false;
  *omega = BisectSpeedFromBelow(model, rho, thrust_n, v_m_s, 0.0, kPropSpeedCeilingRadS, steps);
  return true;
}

double BisectSpeedFromBelow(const PropModel& model, double rho, double thrust_n, double v_m_s, double lo, double hi,
                            int steps) {
  for (int i = 0; i < steps; ++i) {
    const double mid = 0.5 * (lo + hi);
    (model.Evaluate(mid, rho, v_m_s).thrust_n <= thrust_n ? lo : hi) = mid;
  }
  return lo;
}

namespace {

constexpr int kCells = 32;

// The samples V_k of the range and, from below at (T_k, V_k), the rotors' shaft power and
// (with a drive) PDC; a kind whose samples do not rise with k is switched off (M4).
struct CruiseSamples {
  std::array<double, kCells + 1> v{}, thrust{}, shaft_w{}, drive_w{};
  int rotors = 0;
  bool shaft_ok = false, drive_ok = false;
};

CruiseSamples SampleCruise(const Mission& m, const Segment& sg, const CruisePropBound& p,
                           const CruiseDriveBound* drive, double mass_kg) {
  CruiseSamples c;
  c.drive_ok = drive != nullptr && drive->drive != nullptr;
  c.shaft_ok = p.lossy && p.with_prop_data;
  const double lo = sg.airspeed_m_s.lo, hi = sg.airspeed_m_s.hi;
  for (int k = 0; k <= kCells; ++k) {
    c.v[k] = lo + (hi - lo) * k / kCells;
    const RotorLoad ld = SegmentRotorLoad(m, sg, mass_kg, c.v[k]);
    c.rotors = ld.rotors;
    c.thrust[k] = ld.thrust_per_rotor_n;
    if (!c.drive_ok && !c.shaft_ok) continue;
    double w = 0;
    PropEvaluation ev;
    if (PropSpeedFromBelow(*p.model, m.rho_kg_m3, c.thrust[k], ld.axial_airspeed_m_s, 40, &w)) {
      ev = p.model->Evaluate(w, m.rho_kg_m3, ld.axial_airspeed_m_s);
      AdjustPropEvaluation(p.adjustment, p.prop->diameter_m, &ev);  // the scenario's torque, as the evaluator's
    }
    if (!(ev.torque_nm > 0)) {
      c.shaft_ok = c.drive_ok = false;
      continue;
    }
    c.shaft_w[k] = ld.rotors * ev.torque_nm * w;
    if (c.drive_ok) {
      const Drive& d = *drive->drive;
      const double pdc = std::min(d.Inverse(drive->v_full_v, ev.torque_nm, w).pdc_w,
                                  d.Inverse(drive->v_cut_v, ev.torque_nm, w).pdc_w);
      c.drive_w[k] = ld.rotors * std::max(0.0, pdc);
    }
    if (k > 0 && c.shaft_w[k] < c.shaft_w[k - 1]) c.shaft_ok = false;  // M4 not seen on the samples
    if (k > 0 && c.drive_w[k] < c.drive_w[k - 1]) c.drive_ok = false;
  }
  return c;
}

}  // namespace

// The rules (docs/search.md#m1 to #m4 and R4's momentum bound), on a cell [V_k, V_k+1] of the range:
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
// - the drive (with `drive`): at V_k its PDC at that point, the smaller at the full-charge and
//   cut-off voltage (linear in VDC, eq 59), rising by M4 and M2 (checked the same way);
// - by distance d the energy is P(V)*d/V >= (P_k + P_av)*d/V_k+1; by duration t it is
//   P(V)*t >= (P_k + P_av)*t, with P_k the largest of the power bounds (momentum theory read
//   at V_k+1 by distance, at V_k by duration).
double FreeCruiseRotorPowerLowerBoundW(const Mission& m, const Segment& sg, const CruisePropBound& p,
                                       const CruiseDriveBound* drive, double mass_kg) {
  if (!(sg.lift_to_drag > 0) || p.prop == nullptr || p.model == nullptr) return 0.0;
  const double hi = sg.airspeed_m_s.hi;
  const bool by_distance = sg.distance_m.has_value();
  const bool axial_data = p.model->data_kind() == PropDataKind::kTables && !p.prop->j_tables.empty();
  const bool momentum = p.lossy && ScenarioKeepsPower(p.adjustment) && m.constraints.max_figure_of_merit > 0;
  const double p_av = m.vehicle.avionics_power_w;
  const CruiseSamples c = SampleCruise(m, sg, p, drive, mass_kg);
  double best = kInf;
  for (int k = 0; k < kCells; ++k) {
    const double v_read = by_distance ? c.v[k + 1] : c.v[k];
    const double v_in = axial_data ? v_read : 0.0;  // a wing-borne cruise's inflow is its airspeed (flight.h)
    double p_k = momentum ? c.rotors * IdealRotorPowerW(c.thrust[k], p.prop->diameter_m, m.rho_kg_m3, v_in) /
                                m.constraints.max_figure_of_merit
                          : 0.0;
    if (c.shaft_ok) p_k = std::max(p_k, c.shaft_w[k]);
    if (c.drive_ok) p_k = std::max(p_k, c.drive_w[k]);
    best = std::min(best, by_distance ? (p_k + p_av) * hi / c.v[k + 1] : p_k + p_av);
  }
  return std::isfinite(best) ? std::max(0.0, best - p_av) : 0.0;
}

}  // namespace dynosize
