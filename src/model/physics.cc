#include "model/physics.h"

#include <sstream>

namespace dynosize {

std::string EscEnergyViolation(const EscParams& esc, MotorType type) {
  std::ostringstream os;
  os.precision(5);
  const double ideal = IdealIdcPerIrmsPerThrottle(type);
  if (esc.resc_ohm < 0.0) {
    os << "resc_ohm = " << esc.resc_ohm << " < 0: a negative ESC resistance creates energy";
  } else if (esc.c0 < -kPhysicsRelTol) {
    os << "c0 = " << esc.c0 << " < 0: PESC < 0 at low throttle (model.md section 10 needs c0 >= 0)";
  } else if (esc.c1 + esc.c0 < ideal * (1.0 - kPhysicsRelTol)) {
    os << "c1 + c0 = " << esc.c1 + esc.c0 << " < " << ideal
       << ": PDC < PAC at full throttle (model.md section 10 needs c1 + c0 >= the ideal ESC's "
       << ideal << ", eq 56)";
  }
  return os.str();
}

std::string MotorEnergyViolation(const MotorParams& motor) {
  std::ostringstream os;
  os.precision(5);
  const double kp = MaxKtPerKe(motor.type);
  if (!(motor.ke_v_s_per_rad > 0.0) || !(motor.kt_nm_per_a > 0.0)) {
    os << "ke = " << motor.ke_v_s_per_rad << ", kt = " << motor.kt_nm_per_a << ": both must be > 0";
  } else if (motor.rm_ohm < 0.0) {
    os << "rm_ohm = " << motor.rm_ohm << " < 0: a negative winding resistance creates energy";
  } else if (motor.io_a < 0.0) {
    os << "io_a = " << motor.io_a << " < 0: a negative no-load current creates energy";
  } else if (motor.io1_a_s_per_rad < 0.0) {
    os << "io1_a_s_per_rad = " << motor.io1_a_s_per_rad
       << " < 0: the no-load current falls with speed and turns negative";
  } else if (motor.kt_nm_per_a > kp * motor.ke_v_s_per_rad * (1.0 + kPhysicsRelTol)) {
    os << "kt/ke = " << motor.kt_nm_per_a / motor.ke_v_s_per_rad << " > " << kp
       << ": eta_motor > 1 (model.md section 10 needs KT <= sqrt(27/10)*KE for a BLDC, KT <= KE "
          "brushed)";
  }
  return os.str();
}

}  // namespace dynosize
