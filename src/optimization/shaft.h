// The shaft segment's continuous problem: a required shaft power (or torque) per motor with
// the speed free within bounds (a gearbox ratio or a variable-pitch rotor picks it), at a given
// supply voltage. The speed that maximises the system efficiency Pmech/PDC subject to the
// mission's throttle and current limits is found with Ipopt and exact derivatives (dual numbers
// of common/dual.h through solvers::AutoDiff*), then the point is recomputed with
// Drive::Inverse, which is what every report prints.
//
// Derivatives need the drive's equations on dual numbers, so ShaftPdc<T> below composes the
// inverse model of model/drive.h from model/circuit.h's generic equations:
//     I = Q/KT + Io                            (eq 42)
//     U = (Rm + RESC)*I + KE*omega             (eq 48), TR_eff = U/(kv*VDC)
//     TR = TR_eff below tr_sat, tr_sat + (TR_eff - tr_sat)/sat_slope above (section 7; then
//          the dead band of section 9)
//     PDC = VDC*(C1*TR_eff + C0)*I             (eqs 57, 59)
// tests/optimization/shaft_test.cc checks it against Drive::Inverse to 1e-12 on every motor/ESC
// pair it draws, so a model extension that changes Drive makes that test fail rather than
// letting the two drift apart silently; the reported numbers always come from Drive.
//
// With an ideal ESC (C0 = 0, no saturation) PDC = (C1/kv)*(R*I + KE*omega)*I, and at fixed
// power P = KT*(I - Io)*omega the optimum satisfies 2*R*I*(I - Io)^2 = KE*P*Io/KT (the
// fixed-power analogue of eq 14, derived the same way); the test compares with it.
#pragma once

#include <optional>
#include <string>

#include "mission/mission.h"
#include "model/circuit.h"
#include "model/drive.h"

namespace dynosize {

template <typename T>
struct ShaftEval {
  T current_a, throttle, idc_a, pdc_w;
};

template <typename T>
ShaftEval<T> ShaftPdc(const Drive& d, double vdc_v, const T& omega_rad_s, const T& torque_nm) {
  const MotorParams& m = d.motor();
  const EscParams& e = d.esc();
  ShaftEval<T> r;
  r.current_a = circuit::CurrentAtTorque(torque_nm, m.kt_nm_per_a, m.io_a);
  const T u = circuit::VoltageAtPoint(d.r_total_ohm(), r.current_a, m.ke_v_s_per_rad, omega_rad_s);
  const T tre = u / (d.volt_factor() * vdc_v);
  r.throttle = circuit::ThrottleFromEffective(tre, e.tr_sat, e.sat_slope, e.deadband);
  r.idc_a = circuit::DcCurrent(e.c1, tre, e.c0, r.current_a);
  r.pdc_w = vdc_v * r.idc_a;                                                          // (59)
  return r;
}

struct ShaftRequest {
  double vdc_v = 0.0;
  std::optional<double> power_w;   // per motor; exactly one of power_w, torque_nm
  std::optional<double> torque_nm;
  Range omega_rad_s;
  double max_throttle = 1.0;    // the throttle limit (the mission's, or tr_sat if lower)
  double max_current_a = 1e300; // limit on max(Irms, IDC)
};

struct ShaftSolution {
  double omega_rad_s = 0.0;
  OperatingPoint point;  // Drive::Inverse at the solution
  bool solved = false;   // the solver converged to a feasible point (or the speed is fixed)
  std::string algorithm;
  std::string message;   // the solver's brief report
};

// algorithm: any name of solvers/solver.h ("ipopt" by default, NLopt ones as a check).
ShaftSolution SolveShaftSpeed(const Drive& drive, const ShaftRequest& request,
                              const std::string& algorithm = "ipopt");

}  // namespace dynosize
