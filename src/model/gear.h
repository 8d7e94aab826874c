// A gearbox between a motor and its propeller: the one place where the propeller's speed and
// torque meet the motor's. A model of this repository (docs/model.md section 12); docs/model.md has no
// gearbox. N = gear_ratio >= 1 (motor turns per propeller turn; 1 = direct drive), eta =
// gear_efficiency in (0, 1] (the share of the motor's shaft power that reaches the propeller):
//
//     omega_motor = N * omega_prop,     Q_motor = Q_prop / (N * eta)
//     P_gear = Q_motor*omega_motor - Q_prop*omega_prop = (1/eta - 1) * Q_prop*omega_prop >= 0
//
// Substituted into the motor's circuit (eqs 42, 48; the extensions of model/drive.h):
//     U   = R*I + KE*omega_motor           = R*I + (N*KE)*omega_prop
//     Q_p = N*eta*Q_motor                  = (N*eta*KT)*(I - Io - io1*N*omega_prop)
// so the motor and its gearbox are, at the propeller shaft, a direct-drive motor with
//     KE' = N*KE,  KT' = N*eta*KT,  io1' = N*io1
// and the same R, Io, winding heating, KT droop (KT(I) = KT'/(1 + droop*I)) and ratings (the
// same currents flow; a current rating and a power rating on PAC do not see the gearbox).
// KT'/KE' = eta*KT/KE <= KT/KE: the equivalent motor stays within docs/model.md section 10 whenever
// the motor does, so every rule and bound written for a direct-drive motor (the search's, the
// evaluator's) holds for it unchanged, with the gear loss inside its PAC - Pmech.
// The evaluator and the search fly MotorAtPropellerShaft(params, gear) (optimization/
// credibility.h ScenarioMotorParams); reports turn a propeller-shaft point back into the
// motor's with MotorShaftOf / MotorSidePoint.
#pragma once

#include "model/drive.h"

namespace dynosize {

struct Gear {
  double ratio = 1.0;       // motor turns per propeller turn, >= 1
  double efficiency = 1.0;  // (0, 1]
  bool geared() const { return ratio != 1.0 || efficiency != 1.0; }
};

// The motor + gearbox seen at the propeller shaft (the substitution above). Direct drive
// (ratio 1, efficiency 1) returns the parameters unchanged, bit for bit.
inline MotorParams MotorAtPropellerShaft(const MotorParams& motor, const Gear& gear) {
  if (!gear.geared()) return motor;
  MotorParams p = motor;
  p.ke_v_s_per_rad = gear.ratio * motor.ke_v_s_per_rad;
  p.kt_nm_per_a = gear.ratio * gear.efficiency * motor.kt_nm_per_a;
  p.io1_a_s_per_rad = gear.ratio * motor.io1_a_s_per_rad;
  return p;
}

// The motor's shaft for a propeller turning at omega_prop_rad_s against torque_prop_nm.
struct MotorShaft {
  double omega_rad_s = 0.0;
  double torque_nm = 0.0;
  double power_w = 0.0;      // Q_motor*omega_motor
  double gear_loss_w = 0.0;  // power_w - Q_prop*omega_prop, >= 0
};

inline MotorShaft MotorShaftOf(double omega_prop_rad_s, double torque_prop_nm, const Gear& gear) {
  MotorShaft s;
  s.omega_rad_s = gear.ratio * omega_prop_rad_s;
  s.torque_nm = torque_prop_nm / (gear.ratio * gear.efficiency);
  s.power_w = s.torque_nm * s.omega_rad_s;
  // (1/eta - 1)*Q_prop*omega_prop: exactly 0 for a lossless gear (the difference of the two
  // products is not, where the compiler fuses a multiply and an add).
  s.gear_loss_w = (1.0 / gear.efficiency - 1.0) * torque_prop_nm * omega_prop_rad_s;
  return s;
}

// An operating point solved at the propeller shaft (a Drive of MotorAtPropellerShaft) restated
// at the motor's shaft: speed, torque, Pmech and the efficiencies that use it (eta_motor =
// Pmech/PAC, eta_system = Pmech/PDC, eqs 13, 53). The electrical side is the same point.
inline OperatingPoint MotorSidePoint(const OperatingPoint& at_prop, const Gear& gear) {
  if (!gear.geared()) return at_prop;
  OperatingPoint p = at_prop;
  const MotorShaft s = MotorShaftOf(at_prop.omega_rad_s, at_prop.torque_nm, gear);
  p.omega_rad_s = s.omega_rad_s;
  p.rpm = gear.ratio * at_prop.rpm;
  p.torque_nm = s.torque_nm;
  p.pmech_w = s.power_w;
  p.eta_motor = p.pac_w > 0 ? p.pmech_w / p.pac_w : 0.0;
  p.eta_system = p.pdc_w > 0 ? p.pmech_w / p.pdc_w : 0.0;
  return p;
}

}  // namespace dynosize
