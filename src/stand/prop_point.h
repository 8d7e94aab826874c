// One operating point of a motor + ESC + catalog propeller (`dynosize simulate --prop P`, and
// batch rows that name `prop`), asked in one of three ways at a supply voltage:
//   throttle  forward: the drive's torque (eq 49) meets the propeller's torque law at the speed
//             it settles to (SolveDriveWithProp, src/prop/prop_drive.h);
//   rpm       the propeller's torque at that speed, the throttle solved (Drive::Inverse);
//   thrust_n  the speed where the propeller gives that static thrust (stand/prop_speed.h), then
//             as rpm.
// Results carry the thrust, grams-force per DC watt and the propeller's out-of-data flags.
#pragma once

#include <optional>
#include <string>

#include "model/drive.h"
#include "prop/prop_model.h"

namespace dynosize {

struct PropPointRequest {
  double vdc_v = 0.0;
  std::optional<double> throttle, rpm, thrust_n;  // exactly one
  double rho_kg_m3 = 1.225;
};

struct PropPoint {
  OperatingPoint drive;
  PropEvaluation prop;
  bool converged = true;  // throttle requests: the fixed-point iteration converged
  std::string note;       // why not converged, or the propeller's out-of-data message
  double thrust_n = 0.0;
  double g_per_w = 0.0;
  // Figure of merit T^1.5/(P*sqrt(2*rho*A)) at the shaft power (model/physics.h; static): above 1
  // the propeller data beat momentum theory (docs/model.md section 10).
  double figure_of_merit = 0.0;
};

// "" when the request gives exactly one of throttle, rpm, thrust_n (each in range), else the rule.
std::string CheckPropPointRequest(const PropPointRequest& r);

// Throws UsageError when CheckPropPointRequest fails or a thrust cannot be reached below
// kMaxRequestRpm.
PropPoint SolvePropPoint(const Drive& drive, const PropModel& prop, const PropPointRequest& r);

}  // namespace dynosize
