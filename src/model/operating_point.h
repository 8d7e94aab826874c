// One operating point of a drive (docs/model.md eqs 41-59) and the limits it breaks: what
// model/drive.h computes and model/physics.h checks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace dynosize {

// Why an operating point is not feasible; bits of OperatingPoint::limits.
enum Limit : std::uint32_t {
  kLimitNone = 0,
  kLimitThrottleAboveOne = 1u << 0,  // the required throttle exceeds 100 %
  kLimitThrottleBelowZero = 1u << 1, // the required throttle is negative
  kLimitMotorCurrent = 1u << 2,      // max(IDC, Irms) above the motor's current rating
  kLimitEscCurrent = 1u << 3,        // max(IDC, Irms) above the ESC's current rating
  kLimitMotorPower = 1u << 4,        // PAC above the motor's power rating
  kLimitEscVoltage = 1u << 5,        // VDC above the ESC's voltage rating
  kLimitStalled = 1u << 6,           // the load torque exceeds the stall torque: omega = 0
  kLimitOverrunning = 1u << 7,       // omega above no-load speed: the load drives the motor
  kLimitThermalRunaway = 1u << 8,    // winding temperature rise without a steady state
  kLimitCreatesEnergy = 1u << 9,     // PESC < 0 or eta_motor > 1: parameters that break
                                     // docs/model.md section 10 (model/physics.h)
};

// Names of the set bits, in bit order ("throttle_above_one", "motor_current", ...).
std::vector<std::string> LimitNames(std::uint32_t limits);

struct OperatingPoint {
  double vdc_v = 0.0;
  double throttle = 0.0;
  double throttle_effective = 0.0;
  bool saturated = false;
  double omega_rad_s = 0.0;
  double rpm = 0.0;
  double torque_nm = 0.0;
  double irms_a = 0.0;     // BLDC: rms phase current; brushed: DC motor current
  double vll_rms_v = 0.0;  // BLDC: line-line rms voltage; brushed: terminal voltage
  double pac_w = 0.0;
  double idc_a = 0.0;
  double pdc_w = 0.0;
  double pesc_w = 0.0;
  double pmech_w = 0.0;
  double eta_motor = 0.0;
  double eta_esc = 0.0;
  double eta_system = 0.0;
  double winding_rise_k = 0.0;  // steady copper temperature rise (0 without rth_k_per_w)
  std::uint32_t limits = kLimitNone;
  bool feasible() const { return limits == kLimitNone; }
};

}  // namespace dynosize
