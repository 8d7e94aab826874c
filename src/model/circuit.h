// The first-order rms circuit of docs/model.md (eqs 41, 42, 47, 48, 57 and section 7's knee with
// section 9's dead band), written once for every scalar type: Drive evaluates it in doubles,
// and calibrate's fit evaluates the same functions in dual numbers (common/dual.h) for its
// exact Jacobians. Each function is one equation; the callers compose them. No I/O, no state.
//
// Arguments may mix doubles and a dual type (a measured column next to a fitted parameter):
// every function is a template over each argument and returns the type of its expression.
#pragma once

namespace dynosize::circuit {

// Section 9's dead band then section 7's knee: d = (TR - deadband)/(1 - deadband), held at 0
// below the dead band (only when there is one, so that the inverse model's throttle below zero
// stays visible without it), TR_eff = d up to tr_sat and tr_sat + sat_slope*(d - tr_sat) above.
template <typename Slope, typename Deadband>
auto EffectiveThrottle(double throttle, double tr_sat, const Slope& sat_slope, const Deadband& deadband) {
  using T = decltype(sat_slope * (throttle - deadband));
  T d = (throttle - deadband) / (1.0 - deadband);
  if ((deadband < 0.0 || deadband > 0.0) && d < 0.0) d = T(0.0);
  if (d <= tr_sat) return d;
  return T(tr_sat + sat_slope * (d - tr_sat));
}

// The inverse of EffectiveThrottle (sat_slope > 0): the command that gives TR_eff.
template <typename Tre>
auto ThrottleFromEffective(const Tre& throttle_effective, double tr_sat, double sat_slope, double deadband) {
  using T = decltype(throttle_effective * 1.0);
  const T d = throttle_effective <= tr_sat ? T(throttle_effective)
                                           : T(tr_sat + (throttle_effective - tr_sat) / sat_slope);
  return deadband != 0.0 ? T(deadband + d * (1.0 - deadband)) : d;
}

// (47)/(48): the voltage the ESC applies, U = kv*VDC*TR_eff (kv = 3/(sqrt(2)*pi) for a BLDC,
// 1 for a brushed motor: Drive::volt_factor).
template <typename Tre>
auto AppliedVoltage(double volt_factor, double vdc_v, const Tre& throttle_effective) {
  return volt_factor * vdc_v * throttle_effective;
}

// (42) solved for the current: I = Q/KT + Io.
template <typename Q, typename Kt, typename Io>
auto CurrentAtTorque(const Q& torque_nm, const Kt& kt, const Io& io) {
  return torque_nm / kt + io;
}

// (42): Q = KT*(I - Io).
template <typename Kt, typename I, typename Io>
auto ShaftTorque(const Kt& kt, const I& current_a, const Io& io) {
  return kt * (current_a - io);
}

// (48) solved for the speed: omega = (U - R*I)/KE, R = Rm + RESC.
template <typename U, typename R, typename I, typename Ke>
auto SpeedAtCurrent(const U& u_v, const R& r_total_ohm, const I& current_a, const Ke& ke) {
  return (u_v - r_total_ohm * current_a) / ke;
}

// (48) solved for the current: I = (U - KE*omega)/R.
template <typename U, typename Ke, typename W, typename R>
auto CurrentAtSpeed(const U& u_v, const Ke& ke, const W& omega_rad_s, const R& r_total_ohm) {
  return (u_v - ke * omega_rad_s) / r_total_ohm;
}

// (48): the voltage that holds the current I at the speed omega, U = R*I + KE*omega.
template <typename R, typename I, typename Ke, typename W>
auto VoltageAtPoint(const R& r_total_ohm, const I& current_a, const Ke& ke, const W& omega_rad_s) {
  return r_total_ohm * current_a + ke * omega_rad_s;
}

// (47): the motor's line voltage, VLL = U - RESC*I.
template <typename U, typename Resc, typename I>
auto LineVoltage(const U& u_v, const Resc& resc_ohm, const I& current_a) {
  return u_v - resc_ohm * current_a;
}

// (41), (51): PAC = kp*VLL*I (kp = sqrt(27/10) for a BLDC, 1 for a brushed motor).
template <typename V, typename I>
auto AcPower(double power_factor, const V& vll_v, const I& current_a) {
  return power_factor * vll_v * current_a;
}

// (57): IDC = (C1*TR_eff + C0)*I.
template <typename C1, typename Tre, typename C0, typename I>
auto DcCurrent(const C1& c1, const Tre& throttle_effective, const C0& c0, const I& current_a) {
  return (c1 * throttle_effective + c0) * current_a;
}

}  // namespace dynosize::circuit
