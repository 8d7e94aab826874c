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

// The rules (search.cc M1-M4 and R4's momentum bound), on a cell [V_k, V_k+1] of the range:
// - the thrust W/(L/D) + 1/2*rho*V^2*Cd*A_add (flight.h) rises with V, so it is at least T_k,
//   its value at V_k (and rises with the mass, M3);
// - momentum theory: a feasible point's propeller power is at least P_ideal(T, V)/FM_max (the
//   evaluator's prop_figure_of_merit, V the axial inflow with forward-flight tables, else 0),
//   and PDC >= Pmech when no stage creates energy (model.md section 10). P_ideal rises with T
//   and V, and P_ideal(T, V)/V falls with V at a fixed T;
// - the drive (with `drive`): at V_k the PDC from below at T_k (speed from below, M1; the
//   scenario's torque there; PDC the smaller at the full-charge and cut-off voltage, linear in
//   VDC by eq 59). (M4) At a fixed thrust the power rises with the inflow, and with the thrust
//   at a fixed inflow: the samples are checked to rise, else no drive bound is used at all;
// - by distance d the energy is P(V)*d/V >= (P_k + P_av)*d/V_k+1; by duration t it is
//   P(V)*t >= (P_k + P_av)*t, with P_k the larger of the two power bounds (momentum theory
//   read at V_k+1 by distance, at V_k by duration).
double FreeCruiseRotorPowerLowerBoundW(const Mission& m, const Segment& sg, const CruisePropBound& p,
                                       const CruiseDriveBound* drive, double mass_kg) {
  constexpr int kCells = 32;
  if (!(sg.lift_to_drag > 0) || p.prop == nullptr || p.model == nullptr) return 0.0;
  const double lo = sg.airspeed_m_s.lo, hi = sg.airspeed_m_s.hi;
  const bool by_distance = sg.distance_m.has_value();
  const bool axial_data = p.model->data_kind() == PropDataKind::kTables && !p.prop->j_tables.empty();
  const bool momentum = p.lossy && ScenarioKeepsPower(p.adjustment) && m.constraints.max_figure_of_merit > 0;
  const double p_av = m.vehicle.avionics_power_w;
  std::array<double, kCells + 1> v{}, thrust{}, drive_w{};
  int rotors = 0;
  bool drive_ok = drive != nullptr && drive->drive != nullptr;
  for (int k = 0; k <= kCells; ++k) {
    v[k] = lo + (hi - lo) * k / kCells;
    const RotorLoad ld = SegmentRotorLoad(m, sg, mass_kg, v[k]);
    rotors = ld.rotors;
    thrust[k] = ld.thrust_per_rotor_n;
    if (!drive_ok) continue;
    const double v_ax = ld.axial_airspeed_m_s;
    double w = 0;
    if (!PropSpeedFromBelow(*p.model, m.rho_kg_m3, thrust[k], v_ax, 40, &w)) {
      drive_ok = false;
      continue;
    }
    PropEvaluation ev = p.model->Evaluate(w, m.rho_kg_m3, v_ax);
    AdjustPropEvaluation(p.adjustment, p.prop->diameter_m, &ev);  // the scenario's torque, as the evaluator's
    if (!(ev.torque_nm > 0)) {
      drive_ok = false;
      continue;
    }
    const Drive& d = *drive->drive;
    const double pdc = std::min(d.Inverse(drive->v_full_v, ev.torque_nm, w).pdc_w,
                                d.Inverse(drive->v_cut_v, ev.torque_nm, w).pdc_w);
    drive_w[k] = ld.rotors * std::max(0.0, pdc);
    if (k > 0 && drive_w[k] < drive_w[k - 1]) drive_ok = false;  // M4 not seen on the samples
  }
  double best = kInf;
  for (int k = 0; k < kCells; ++k) {
    const double v_read = by_distance ? v[k + 1] : v[k];
    const double v_in = axial_data ? v_read : 0.0;  // a wing-borne cruise's inflow is its airspeed (flight.h)
    double p_k = momentum ? rotors * IdealRotorPowerW(thrust[k], p.prop->diameter_m, m.rho_kg_m3, v_in) /
                                m.constraints.max_figure_of_merit
                          : 0.0;
    if (drive_ok) p_k = std::max(p_k, drive_w[k]);
    best = std::min(best, by_distance ? (p_k + p_av) * hi / v[k + 1] : p_k + p_av);
  }
  return std::isfinite(best) ? std::max(0.0, best - p_av) : 0.0;
}

}  // namespace dynosize
