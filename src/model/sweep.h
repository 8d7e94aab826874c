// Characteristic points of a drive per throttle setting: the numbers behind the paper's
// torque-speed figures (Fig. 25) in a table. Pure computation on the closed-form model.
#pragma once

#include <vector>

#include "model/drive.h"

namespace dynosize {

struct ThrottleSummary {
  double throttle = 0.0;
  double throttle_effective = 0.0;
  double no_load_rpm = 0.0;          // eq (49) with Q = 0
  double stall_torque_nm = 0.0;      // eq (49) with omega = 0
  double max_power_rpm = 0.0;        // eq (12): half the no-load speed
  double max_power_w = 0.0;          // Pm at max_power_rpm (eq 50)
  double max_efficiency_rpm = 0.0;   // analogue of eq (14)
  double max_eta_system = 0.0;       // eta_system at max_efficiency_rpm
  OperatingPoint at_max_efficiency;  // the whole operating point there
};

ThrottleSummary SummarizeThrottle(const Drive& drive, double vdc_v, double throttle);

// Throttles 0.1, 0.2, ..., 1.0 (steps of 1/steps).
std::vector<ThrottleSummary> SummarizeThrottles(const Drive& drive, double vdc_v, int steps = 10);

// The largest current the drive may carry: the smaller of the motor's and the ESC's ratings,
// or the stall current at full throttle when neither is rated.
double CurrentLimit(const Drive& drive, double vdc_v);

}  // namespace dynosize
