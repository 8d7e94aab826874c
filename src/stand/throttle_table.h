// The manufacturer-style table of a motor + ESC + propeller at one supply voltage (`dynosize
// simulate --prop P --vdc V` without a load): per throttle step, the operating point where the
// drive's torque (eq 49) meets the propeller's (SolveDriveWithProp), with thrust, DC current,
// speed, DC power, grams of thrust per DC watt and the system efficiency Pmech/PDC (eq 13).
#pragma once

#include <string>
#include <vector>

#include "model/drive.h"
#include "prop/prop_drive.h"
#include "prop/prop_model.h"

namespace dynosize {

struct ThrottleTableRow {
  double throttle = 0.0;
  PropDrivePoint point;
  double thrust_n = 0.0;
  double g_per_w = 0.0;  // thrust in gram-force per DC watt (0 when PDC <= 0)
  double figure_of_merit = 0.0;  // T^1.5/(P_shaft*sqrt(2*rho*A)), model/physics.h
};

// Thrust in gram-force per watt of DC power: the datasheets' "efficiency (g/W)".
double GramsPerWatt(double thrust_n, double pdc_w);

// Throttle 10, 20, ..., 100 % (steps of 1/steps), static (no airspeed).
std::vector<ThrottleTableRow> PropThrottleTable(const Drive& drive, const PropModel& prop, double vdc_v,
                                                double rho_kg_m3, int steps = 10);

}  // namespace dynosize
