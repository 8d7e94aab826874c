// The combined motor + ESC model of Brown & Chopra (docs/model.md), closed form.
//
// One "drive" is a motor and the controller that feeds it. Both motor types share the
// quasi-single-phase circuit
//
//     kv * VDC * TR_eff = (Rm + RESC) * I + KE * omega          (BLDC: eq 48; brushed: eq 15)
//     Q = KT * (I - Io)                                          (eq 42 / eq 2)
//
// with kv = 3/(sqrt(2)*pi) for a BLDC (eq 46, I is the rms phase current Irms and the voltage
// the line-line rms VLL,rms) and kv = 1 for a brushed motor (I and V are DC at the terminals).
// The remaining outputs follow:
//
//     VLL,rms = kv*VDC*TR_eff - RESC*I                           (47)
//     PAC     = kp * VLL,rms * I, kp = sqrt(27/10) BLDC, 1 brushed  (41, 51)
//     IDC     = (C1*TR_eff + C0) * I                             (57)
//     PDC     = VDC * IDC,  PESC = PDC - PAC                     (59, 52)
//     Pmech   = Q * omega                                        (50)
//     eta_motor = Pmech/PAC, eta_esc = PAC/PDC (53), eta_system = Pmech/PDC (13)
//
// ESC saturation (docs/model.md section 7): TR_eff = TR up to tr_sat, tr_sat + sat_slope*(TR -
// tr_sat) above it; TR_eff is used in both (47) and (57).
//
// Extensions of docs/model.md section 9, used by `diagnose`. Each defaults to 0, which reproduces
// the first-order model above exactly (same arithmetic, same results):
//  - throttle dead band (EscParams::deadband): the command is first mapped through the dead
//    band, d = max(0, (TR - deadband)/(1 - deadband)), and the saturation knee is then applied
//    to d: TR_eff = d (d <= tr_sat), tr_sat + sat_slope*(d - tr_sat) above. Order: dead band
//    first, knee second (the knee is where the ESC runs out of duty cycle, a property of the
//    duty the ESC is asked for, i.e. of the dead-band-corrected command). A negative dead band
//    is a throttle offset: TR_eff = (TR + o)/(1 + o), o = -deadband, voltage already at TR = 0
//    (the Strawson / T-Motor stand logs of docs/validation.md).
//  - speed-dependent no-load current (MotorParams::io1_a_s_per_rad): Io(omega) = io_a +
//    io1*omega (section 9, QPROP "motor type 2"); Q = KT*(I - Io(omega)). Closed form: it only
//    adds KT*io1 to the linear term of the speed equation.
//  - supply resistance (EscParams::rsupply_ohm): wires/connectors between the point where VDC
//    is measured and the ESC: the ESC sees VDC - rsupply*IDC. With IDC = g*I (57), g = C1*TR_eff
//    + C0, (48) becomes kv*VDC*TR_eff = (R + kv*rsupply*g*TR_eff)*I + KE*omega: still closed
//    form, with a throttle-dependent series resistance. PDC stays VDC*IDC at the measuring point.
//  - winding temperature rise (MotorParams::rth_k_per_w): steady copper temperature rise dT =
//    rth*P_cu above the temperature at which rm_ohm holds, P_cu = kp*Rm*I^2 (the resistive share
//    of PAC in (41)/(42)), and Rm = Rm0*(1 + alpha_cu*dT), alpha_cu = 0.00393 /K (copper). Solved
//    for Rm: Rm(I) = Rm0/(1 - alpha_cu*rth*kp*Rm0*I^2) (thermal runaway where the denominator
//    reaches 0: such points are flagged kLimitThermalRunaway).
//  - torque constant droop (MotorParams::kt_droop_per_a): magnetic saturation / armature reaction
//    lower the torque per ampere at high current, KT(I) = KT0/(1 + kt_droop*|I|). KE is left
//    unchanged: the back-EMF at a given speed is set by the magnet flux, which the droop
//    (a load-current effect) leaves at its no-load value in this first-order description.
// The last two make the circuit nonlinear in I; only when one of them is non-zero is the scalar
// equation in I solved by a bracketed root finder (Illinois regula falsi; the residual is
// monotone in I), so the base model keeps its closed forms and its speed.
//
// For a brushed motor fed by the paper's voltage regulator (eqs 15-18: the motor sees VDC*TR,
// the input power is VDC*I) use an ESC with C1 = 0, C0 = 1; an ideal PWM chopper is C1 = 1,
// C0 = 0.
//
// The model does no I/O and allocates nothing per point. Every function is closed form.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common/units.h"
#include "model/operating_point.h"
#include "model/params.h"

namespace dynosize {

// Temperature coefficient of the resistance of copper near 20 C (docs/model.md section 9), 1/K.
inline constexpr double kAlphaCopperPerK = 0.00393;

// A load torque law Q = a + b*omega + c*omega^2 (a propeller: c > 0; a hysteresis brake: b = c
// = 0; viscous friction: b > 0).
struct TorqueLaw {
  double a_nm = 0.0;
  double b_nm_s_per_rad = 0.0;
  double c_nm_s2_per_rad2 = 0.0;
};

class Drive {
 public:
  Drive(const MotorParams& motor, const EscParams& esc);

  const MotorParams& motor() const { return motor_; }
  const EscParams& esc() const { return esc_; }
  // Total series resistance Rm + RESC of eq (48).
  double r_total_ohm() const { return r_total_ohm_; }
  // kv of eq (46): 3/(sqrt(2)*pi) for a BLDC, 1 for a brushed motor.
  double volt_factor() const { return volt_factor_; }
  // kp of eq (41): sqrt(27/10) for a BLDC, 1 for a brushed motor.
  double power_factor() const { return power_factor_; }

  // True when a nonlinear extension (rth_k_per_w, kt_droop_per_a) is active.
  bool nonlinear() const { return nonlinear_; }
  // True when any extension of section 9 is non-zero (dead band, supply resistance, Io(omega),
  // heating, droop); false: the first-order equations 42-59 alone.
  bool extended() const { return extended_; }
  // Winding resistance at current I (winding temperature rise; rm_ohm without it). Infinite
  // past thermal runaway.
  double WindingResistance(double current_a) const;
  // Torque constant at current I (droop; kt_nm_per_a without it).
  double TorqueConstant(double current_a) const;

  // Section 7 with the dead band: d = max(0, (TR - deadband)/(1 - deadband)) (d = TR without a
  // dead band), TR_eff = d (d <= tr_sat), tr_sat + sat_slope*(d - tr_sat) above.
  double EffectiveThrottle(double throttle) const;
  // Inverse of EffectiveThrottle (sat_slope > 0).
  double ThrottleFromEffective(double throttle_effective) const;

  // Forward model: VDC and throttle given, the load sets the operating point.
  // Constant torque (a hysteresis brake, docs/model.md section 1).
  OperatingPoint AtTorque(double vdc_v, double throttle, double torque_nm) const;
  // Fixed speed (a speed-controlled dyno).
  OperatingPoint AtSpeed(double vdc_v, double throttle, double omega_rad_s) const;
  // Torque law Q = a + b*omega + c*omega^2 (a propeller): the positive root of a quadratic.
  OperatingPoint AtLoad(double vdc_v, double throttle, const TorqueLaw& load) const;

  // Inverse model: the throttle that holds (torque, speed) at VDC. Infeasible (flagged in
  // limits) above 100 % throttle or over a current limit; the numbers are still computed.
  OperatingPoint Inverse(double vdc_v, double torque_nm, double omega_rad_s) const;
  // Inverse's throttle, IDC and Irms only (eqs 42, 48, 57), the same numbers bit for bit,
  // without the powers, efficiencies and limits: for a caller that iterates on VDC (the pack's
  // sag in MissionEvaluator) and needs the whole point only where the iteration ends.
  struct InverseCurrents {
    double throttle = 0.0, idc_a = 0.0, irms_a = 0.0;
  };
  InverseCurrents InverseLight(double vdc_v, double torque_nm, double omega_rad_s) const;
  // Inverse's PDC = VDC*IDC (eq 59) from InverseLight, bit for bit (the bounds' drive floors).
  double InversePdcW(double vdc_v, double torque_nm, double omega_rad_s) const {
    return vdc_v * InverseLight(vdc_v, torque_nm, omega_rad_s).idc_a;
  }
  // Inverse's PAC (eq 47) from InverseLight's numbers at the same VDC, bit for bit.
  double InverseAcPower(double vdc_v, const InverseCurrents& c, double torque_nm, double omega_rad_s) const;

  // Derived points at a given VDC and throttle.
  // No-load speed omega_NL = (kv*VDC*TR_eff - Io*R)/KE (eq 49 with Q = 0).
  double NoLoadSpeed(double vdc_v, double throttle) const;
  // Stall torque KT*(kv*VDC*TR_eff/R - Io) (eq 49 with omega = 0).
  double StallTorque(double vdc_v, double throttle) const;
  // Maximum mechanical power speed omega_NL/2 (eq 12, eq 50).
  double MaxPowerSpeed(double vdc_v, double throttle) const;
  // Speed of maximum system efficiency Pmech/PDC at fixed throttle: the analogue of eq (14),
  // omega_opt = (U - sqrt(Io*R*U))/KE with U = kv*VDC*TR_eff and R = Rm + RESC. It holds
  // because PDC = VDC*(C1*TR_eff + C0)*I is proportional to I at fixed throttle, exactly as
  // the brushed motor's VDC*I in eq (13).
  double MaxEfficiencySpeed(double vdc_v, double throttle) const;
  // ESC timing figure (t_on + t_off)*f_sw of eq (62): (C1 - (3/pi)*sqrt(27/20))*TR_eff + C0.
  double EscTimingFigure(double throttle) const;

 private:
  // Series resistance of (48) at this effective throttle: Rm + RESC + kv*rsupply*g*TR_eff.
  double SeriesResistance(double throttle_effective) const;
  // Current that holds the circuit (48) at U - KE*omega = x with the temperature-dependent Rm.
  double CircuitCurrent(double x_v, double r_series_ohm) const;
  // Paths with an extension (the first-order paths stay short and inlinable).
  OperatingPoint AtLoadExtended(double vdc_v, double throttle, const TorqueLaw& load) const;
  OperatingPoint InverseExtended(double vdc_v, double torque_nm, double omega_rad_s) const;
  void CompleteExtended(double vdc_v, double throttle, double omega_rad_s, double current_a,
                        OperatingPoint* p, std::uint32_t* limits) const;
  // Sets the limit bits shared by every path.
  void Flag(OperatingPoint* p, std::uint32_t limits) const;
  // Nonlinear path of AtLoad (temperature rise or droop).
  OperatingPoint AtLoadNonlinear(double vdc_v, double throttle, const TorqueLaw& load) const;

  // Fills every output from (VDC, TR, omega, I); shared by all entry points.
  OperatingPoint Complete(double vdc_v, double throttle, double omega_rad_s, double current_a,
                          std::uint32_t limits) const;

  MotorParams motor_;
  EscParams esc_;
  double r_total_ohm_;
  double volt_factor_;
  double power_factor_;
  bool nonlinear_;
  bool extended_;  // any extension non-zero (else the first-order code paths run unchanged)
  double thermal_k_per_a2_;  // alpha_cu*rth*kp*Rm0: Rm(I) = Rm0/(1 - thermal_k*I^2)
};

}  // namespace dynosize
