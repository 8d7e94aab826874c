#include "model/dc_motor.h"

#include <algorithm>
#include <cmath>

#include "common/units.h"

namespace dynosize {

double DcMotor::kt_nm_per_a() const {
  // 60/(2*pi*Kv): one volt per (Kv rpm) of back-EMF, i.e. 1/(Kv in rad/s per volt).
  return 1.0 / (kv_rpm_per_v * kRadPerSecPerRpm);
}

namespace {

DcPoint Complete(const DcMotor& m, double vdc_v, double omega_rad_s, double torque_nm,
                 double duty) {
  DcPoint p;
  p.omega_rad_s = omega_rad_s;
  p.torque_nm = torque_nm;
  p.current_a = m.io_a + torque_nm / m.kt_nm_per_a();
  p.voltage_v = m.kt_nm_per_a() * omega_rad_s + m.r_ohm * p.current_a;
  p.duty = duty;
  p.idc_a = duty * p.current_a;
  p.pdc_w = vdc_v * p.idc_a;
  return p;
}

}  // namespace

DcPoint DcAtSpeedTorque(const DcMotor& m, double vdc_v, double omega_rad_s, double torque_nm) {
  DcPoint p = Complete(m, vdc_v, omega_rad_s, torque_nm, 0.0);
  p.duty = p.voltage_v / vdc_v;
  p.idc_a = p.duty * p.current_a;
  p.pdc_w = vdc_v * p.idc_a;
  return p;
}

DcPoint DcAtThrottleTorque(const DcMotor& m, double vdc_v, double throttle, double torque_nm) {
  const double i = m.io_a + torque_nm / m.kt_nm_per_a();
  const double omega = std::max(0.0, (throttle * vdc_v - m.r_ohm * i) / m.kt_nm_per_a());
  DcPoint p = Complete(m, vdc_v, omega, torque_nm, throttle);
  return p;
}

DcPoint DcAtThrottleLoad(const DcMotor& m, double vdc_v, double throttle,
                         const std::function<double(double)>& torque_of_omega_nm) {
  const double kt = m.kt_nm_per_a();
  const double u = throttle * vdc_v;
  // residual(omega) = U - KT*omega - R*(Io + Q(omega)/KT): strictly falling for Q non-decreasing.
  auto residual = [&](double w) { return u - kt * w - m.r_ohm * (m.io_a + torque_of_omega_nm(w) / kt); };
  double lo = 0.0, hi = std::max(0.0, u / kt);
  if (!(residual(lo) > 0.0)) return Complete(m, vdc_v, 0.0, torque_of_omega_nm(0.0), throttle);
  for (int k = 0; k < 200 && hi - lo > 1e-10 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) > 0.0 ? lo : hi) = mid;
  }
  const double w = 0.5 * (lo + hi);
  return Complete(m, vdc_v, w, torque_of_omega_nm(w), throttle);
}

}  // namespace dynosize
