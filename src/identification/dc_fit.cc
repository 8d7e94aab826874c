#include "identification/dc_fit.h"

#include <cmath>
#include <limits>

#include "common/numbers.h"
#include "common/units.h"
#include "identification/fit_rows.h"
#include "model/circuit.h"

namespace dynosize::identification {

namespace {

// The duty of the chopper: the command, through the throttle offset (dead band) the fit found
// (section 9: d = (TR - deadband)/(1 - deadband), model/circuit.h; no knee: the DC model has none).
double Duty(const logs::SteadyTable& t, std::size_t i, double assumed_throttle, double deadband) {
  const double command = t.Has(logs::Column::kThrottle) ? t.Get(logs::Column::kThrottle)[i] : assumed_throttle;
  return circuit::EffectiveThrottle(command, 1.0, 1.0, deadband);
}

}  // namespace

DcFit FitDcMotor(const logs::SteadyTable& t, const std::vector<std::size_t>& rows, double assumed_throttle,
                 double kv_label_rpm_per_v, double deadband) {
  DcFit out;
  out.deadband = deadband;
  using logs::Column;
  if (!t.Has(Column::kIdcA) || !t.Has(Column::kVdcV) || !t.Has(Column::kOmegaRadS)) return out;
  std::vector<double> cur, omega, u;
  for (std::size_t i : rows) {
    const double d = Duty(t, i, assumed_throttle, deadband);
    const double w = t.Get(Column::kOmegaRadS)[i], idc = t.Get(Column::kIdcA)[i];
    if (!(d > 0.0) || !(w > 0.0) || !(idc > 0.0)) continue;
    cur.push_back(idc / d);
    omega.push_back(w);
    u.push_back(d * t.Get(Column::kVdcV)[i]);
  }
  if (cur.size() < 2) {
    out.why = "fewer than 2 rows with speed, current and throttle";
    return out;
  }
  if (kv_label_rpm_per_v > 0.0) {
    out.motor.kv_rpm_per_v = kv_label_rpm_per_v;
    out.motor.r_ohm = ResistanceWithKeHeld(cur, omega, u, out.motor.kt_nm_per_a());  // KE_dc = KT_dc
  } else {
    const CircuitStart lin = LinearCircuitStart(cur, omega, u);  // ke = 1/Kv in V*s/rad
    if (!(lin.ke_v_s_per_rad > 0.0)) {
      out.why = "the least-squares Kv is not positive";
      return out;
    }
    out.motor.kv_rpm_per_v = 1.0 / (lin.ke_v_s_per_rad * kRadPerSecPerRpm);
    out.motor.r_ohm = lin.r_total_ohm;
  }
  if (!(out.motor.r_ohm >= 0.0)) {
    out.why = "the least-squares R is negative";
    return out;
  }
  if (t.Has(Column::kTorqueNm)) {
    const double kt = out.motor.kt_nm_per_a();
    double s = 0.0;
    int n = 0;
    for (std::size_t i : rows) {
      const double d = Duty(t, i, assumed_throttle, deadband), idc = t.Get(Column::kIdcA)[i];
      if (!(d > 0.0) || !(idc > 0.0)) continue;
      s += idc / d - t.Get(Column::kTorqueNm)[i] / kt;
      ++n;
    }
    out.motor.io_a = n > 0 ? s / n : 0.0;
  }
  out.ok = true;
  return out;
}

DcRowPrediction PredictDcRow(const DcMotor& m, const logs::SteadyTable& t, std::size_t i, double assumed_throttle,
                             double deadband) {
  using logs::Column;
  DcRowPrediction p{kNaN, kNaN, kNaN};
  const double d = Duty(t, i, assumed_throttle, deadband), vdc = t.Get(Column::kVdcV)[i];
  if (!(d > 0.0) || !(vdc > 0.0)) return p;
  if (t.Has(Column::kTorqueNm)) {
    const DcPoint q = DcAtThrottleTorque(m, vdc, d, t.Get(Column::kTorqueNm)[i]);
    p.omega_at_torque_rad_s = q.omega_rad_s;
    p.idc_at_torque_a = q.idc_a;
  }
  const double idc = t.Get(Column::kIdcA)[i];
  if (idc > 0.0) {
    // The torque the measured current gives, Q = KT_dc*(IDC/d - Io): the same speed as U = n/Kv + R*I.
    const double q = m.kt_nm_per_a() * (idc / d - m.io_a);
    p.omega_from_idc_rad_s = DcAtThrottleTorque(m, vdc, d, q).omega_rad_s;
  }
  return p;
}

}  // namespace dynosize::identification
