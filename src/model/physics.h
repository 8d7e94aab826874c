// Physical validity of the model's parameters and points (docs/model.md section 10):
// the one place that decides whether an ESC, a motor, an operating point or a propeller point
// creates energy or beats momentum theory. The fit (identification), the catalog reader, the
// operating point (Drive::Flag) and the mission evaluator all ask these functions, so the rule
// exists once.
//
// ESC. With K = kv (3/(sqrt(2)*pi) for a BLDC, 1 brushed) and kp (sqrt(27/10) BLDC, 1 brushed),
// eqs (47), (51), (57), (59), (52) give
//     PESC = PDC - PAC = Irms * [ VDC*((C1 - K*kp)*TR_eff + C0) + kp*RESC*Irms ].
// The bracket is linear in TR_eff in [0, 1] and the RESC term is >= 0 (vanishing as Irms -> 0),
// so PESC >= 0 for every throttle and every current exactly when
//     RESC >= 0,   C0 >= 0   and   C1 + C0 >= K*kp                 (BLDC: K*kp = 1.1095, eq 56)
// The ideal ESC of eq (56) sits on the boundary (PESC = RESC losses only).
//
// Motor. eta_motor = Pmech/PAC = [KT/(kp*KE)] * [KE*omega/(Rm*I + KE*omega)] * (1 - Io/I)
// (eqs 41, 42), below 1 for Rm >= 0, Io >= 0 only if KT <= kp*KE; a larger KT means waveforms
// other than the paper's trapezoid/rectangle and needs AC measurements to justify it. The
// speed-dependent no-load current of section 9 must not turn negative (io1 >= 0), and KT droop
// only lowers KT, so it cannot break the rule.
//
// Propeller. Momentum theory (Leishman, Principles of Helicopter Aerodynamics, 2nd ed., eq 2.14
// and 3.25): hovering thrust T needs at least P_ideal = T^1.5/sqrt(2*rho*A), A = pi*D^2/4; in
// axial flow V, P_ideal = T*(V/2 + sqrt(V^2/4 + T/(2*rho*A))). FM = P_ideal/P <= 1.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "common/units.h"
#include "model/operating_point.h"
#include "model/params.h"

namespace dynosize {

// K*kp of the ESC rule above: (3/pi)*sqrt(27/20) for a BLDC (eq 56), 1 for a brushed motor.
inline double IdealIdcPerIrmsPerThrottle(MotorType type) {
  return type == MotorType::kBldc ? kIdealIdcPerIrmsPerThrottle : 1.0;
}
// kp of eq (41): the largest KT/KE that keeps eta_motor <= 1.
inline double MaxKtPerKe(MotorType type) {
  return type == MotorType::kBldc ? kPacPerVllIrms : 1.0;
}

// Relative slack for numbers that sit on a boundary up to rounding (the ideal ESC, KT set to
// sqrt(27/10)*KE): 1e-9 is far above double rounding of a few operations (1e-15) and far below
// any physical effect a catalog can state.
inline constexpr double kPhysicsRelTol = 1e-9;

// The smaller of C0 and C1 + C0 - K*kp: >= 0 exactly when the ESC cannot create energy.
inline double EscEnergyMargin(const EscParams& esc, MotorType type = MotorType::kBldc) {
  return std::fmin(esc.c0, esc.c1 + esc.c0 - IdealIdcPerIrmsPerThrottle(type));
}

// "" when the ESC constants cannot create energy at any throttle and current, else one sentence
// naming the broken inequality and the numbers ("c1 + c0 = 0.53 < 1.1095: ...").
std::string EscEnergyViolation(const EscParams& esc, MotorType type = MotorType::kBldc);

// "" when the motor cannot have eta_motor > 1 at any point, else one sentence (KT > kp*KE,
// negative Rm or Io, io1 < 0).
std::string MotorEnergyViolation(const MotorParams& motor);

// Neither the motor nor an ESC of these C1, C0 can create energy (section 10: KT <= kp*KE,
// Rm, Io, io1 >= 0, C0 >= 0, C1 + C0 >= K*kp), the exact inequalities without kPhysicsRelTol:
// then PDC >= PAC >= Pmech at every operating point, the premise of the search's power bounds.
inline bool DriveIsLossy(const MotorParams& m, double c1, double c0) {
  return m.kt_nm_per_a <= MaxKtPerKe(m.type) * m.ke_v_s_per_rad && m.rm_ohm >= 0 && m.io_a >= 0 &&
         m.io1_a_s_per_rad >= 0 && c0 >= 0 && c1 + c0 >= IdealIdcPerIrmsPerThrottle(m.type);
}

// Losses every operating point of a motor carries beyond the shaft power, for DriveIsLossy's
// motors without winding heating or KT droop (rth_k_per_w = kt_droop_per_a = 0):
//   PAC >= Q*omega + copper_w_per_nm2*Q^2 + no_load_torque_nm*omega,
// copper_w_per_nm2 = kp*Rm/KT^2 and no_load_torque_nm = KT*Io. Proof: PAC = kp*VLL*I (41)
// with VLL = Rm*I + KE*omega (47, 48), Q = KT*(I - Io - io1*omega) (42), so
// PAC - Q*omega = kp*Rm*I^2 + (kp*KE - KT)*omega*I + KT*(Io + io1*omega)*omega, each term >= 0
// (KT <= kp*KE, io1 >= 0), and I >= Q/KT. Both 0 (no floor) for any other motor.
struct MotorLossFloor {
  double copper_w_per_nm2 = 0.0;
  double no_load_torque_nm = 0.0;
};
inline MotorLossFloor LossFloorOf(const MotorParams& m) {
  const bool applies = m.kt_nm_per_a > 0 && m.kt_nm_per_a <= MaxKtPerKe(m.type) * m.ke_v_s_per_rad &&
                       m.rm_ohm >= 0 && m.io_a >= 0 && m.io1_a_s_per_rad >= 0 && m.rth_k_per_w == 0.0 &&
                       m.kt_droop_per_a == 0.0;
  if (!applies) return {};
  return {MaxKtPerKe(m.type) * m.rm_ohm / (m.kt_nm_per_a * m.kt_nm_per_a), m.kt_nm_per_a * m.io_a};
}

// True when a computed operating point creates energy: PESC < 0 or eta_motor > 1 (beyond
// kPhysicsRelTol of the powers involved). Cheap and branch-free: Drive::Flag and the batch of
// model/drive_batch.h call it for every point.
inline bool PowersCreateEnergy(double pdc_w, double pac_w, double pesc_w, double pmech_w) {
  const double tol_w = kPhysicsRelTol * (std::fabs(pdc_w) + std::fabs(pac_w)) + 1e-12;
  return (pesc_w < -tol_w) | ((pac_w > 0.0) & (pmech_w > pac_w + tol_w));
}
inline bool PointCreatesEnergy(const OperatingPoint& p) {
  return PowersCreateEnergy(p.pdc_w, p.pac_w, p.pesc_w, p.pmech_w);
}

// The limits every operating point is checked against, beyond those its solve sets (stalled,
// overrunning, thermal runaway): the throttle in [0, 1], max(|IDC|, |Irms|) against the motor's
// and the ESC's current ratings, PAC against the motor's power rating, VDC against the ESC's
// voltage rating, and no energy created (above). Limit bits of model/drive.h; branch-free, one
// rule for Drive::Flag and the batch (which asks for 64-bit lanes, the width of its doubles, so
// that the compiler vectorises the check).
template <typename Bits = std::uint32_t>
inline Bits RatingLimits(const MotorParams& m, const EscParams& e, double vdc_v, double throttle, double irms_a,
                         double idc_a, double pac_w, double pdc_w, double pesc_w, double pmech_w) {
  const double i_max = std::max(std::fabs(idc_a), std::fabs(irms_a));
  const Bits none = 0;
  return (throttle > 1.0 ? Bits{kLimitThrottleAboveOne} : none) |
         (throttle < 0.0 ? Bits{kLimitThrottleBelowZero} : none) |
         (i_max > m.max_current_a ? Bits{kLimitMotorCurrent} : none) |
         (i_max > e.max_current_a ? Bits{kLimitEscCurrent} : none) |
         (pac_w > m.max_power_w ? Bits{kLimitMotorPower} : none) |
         (vdc_v > e.vdc_max_v ? Bits{kLimitEscVoltage} : none) |
         (PowersCreateEnergy(pdc_w, pac_w, pesc_w, pmech_w) ? Bits{kLimitCreatesEnergy} : none);
}

// Momentum-theory minimum shaft power for thrust T [N] from a rotor disk of diameter D [m] in
// axial inflow V [m/s] (V = 0: hover) at density rho [kg/m^3].
inline double IdealRotorPowerW(double thrust_n, double diameter_m, double rho_kg_m3,
                               double axial_airspeed_m_s = 0.0) {
  if (!(thrust_n > 0.0)) return 0.0;
  const double area_m2 = kPi * diameter_m * diameter_m / 4.0;
  const double half_v = axial_airspeed_m_s / 2.0;
  return thrust_n * (half_v + std::sqrt(half_v * half_v + thrust_n / (2.0 * rho_kg_m3 * area_m2)));
}

// Figure of merit P_ideal/P (its axial-flow analogue when V > 0); 0 when P <= 0.
inline double FigureOfMerit(double thrust_n, double power_w, double diameter_m,
                            double rho_kg_m3, double axial_airspeed_m_s = 0.0) {
  if (!(power_w > 0.0)) return 0.0;
  return IdealRotorPowerW(thrust_n, diameter_m, rho_kg_m3, axial_airspeed_m_s) / power_w;
}

}  // namespace dynosize
