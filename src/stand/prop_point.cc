#include "stand/prop_point.h"

#include <sstream>

#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"
#include "io/points_csv.h"
#include "model/physics.h"
#include "prop/prop_drive.h"
#include "stand/prop_speed.h"
#include "stand/throttle_table.h"

namespace dynosize {

namespace {

}  // namespace

std::string CheckPropPointRequest(const PropPointRequest& r) {
  const int given = (r.throttle ? 1 : 0) + (r.rpm ? 1 : 0) + (r.thrust_n ? 1 : 0);
  if (given != 1) {
    return "with a propeller give exactly one of throttle (forward), rpm or thrust_n (the "
           "throttle solved); the propeller's torque law is the load";
  }
  if (!(r.vdc_v > 0.0 && r.vdc_v <= kMaxRequestVdcV)) {
    return "vdc_v = " + SignificantText(r.vdc_v) + ": must be > 0 V and <= " + SignificantText(kMaxRequestVdcV) + " V";
  }
  if (r.throttle && !(*r.throttle >= 0.0 && *r.throttle <= 1.0)) {
    return "throttle = " + SignificantText(*r.throttle) + ": must be between 0 and 1 (a fraction, not percent)";
  }
  if (r.rpm && !(*r.rpm >= 0.0 && *r.rpm <= kMaxRequestRpm)) {
    return "rpm = " + SignificantText(*r.rpm) + ": must be >= 0 and <= " + SignificantText(kMaxRequestRpm);
  }
  if (r.thrust_n && !(*r.thrust_n > 0.0 && *r.thrust_n <= kMaxRequestThrustN)) {
    return "thrust_n = " + SignificantText(*r.thrust_n) +
           ": must be > 0 N and <= " + SignificantText(kMaxRequestThrustN) + " N";
  }
  if (!(r.rho_kg_m3 > 0.0 && r.rho_kg_m3 <= 100.0)) {
    return "air density " + SignificantText(r.rho_kg_m3) + " kg/m^3: must be > 0 and <= 100";
  }
  return "";
}

PropPoint SolvePropPoint(const Drive& drive, const PropModel& prop, const PropPointRequest& r) {
  if (const std::string rule = CheckPropPointRequest(r); !rule.empty()) throw UsageError(rule);
  PropPoint out;
  if (r.throttle) {
    const PropDrivePoint pd = SolveDriveWithProp(drive, prop, r.vdc_v, *r.throttle, r.rho_kg_m3);
    out.drive = pd.drive;
    out.prop = pd.prop;
    out.converged = pd.converged;
    out.note = pd.message;
  } else {
    double omega = 0.0;
    if (r.rpm) {
      omega = RpmToRadPerSec(*r.rpm);
      out.prop = prop.Evaluate(omega, r.rho_kg_m3);
    } else {
      const PropSpeedForThrust s = SpeedForThrust(prop, *r.thrust_n, r.rho_kg_m3);
      if (!s.found) {
        throw UsageError("thrust " + SignificantText(*r.thrust_n) + " N: propeller '" + prop.entry().id +
                         "' does not reach it below " + SignificantText(kMaxRequestRpm) +
                         " rpm within its data (thrust " + SignificantText(s.prop.thrust_n) + " N at " +
                         SignificantText(s.prop.rpm) + " rpm)");
      }
      omega = s.omega_rad_s;
      out.prop = s.prop;
    }
    out.drive = drive.Inverse(r.vdc_v, out.prop.torque_nm, omega);
    if (!out.prop.InData()) out.note = out.prop.Message();
  }
  out.thrust_n = out.prop.thrust_n;
  out.g_per_w = GramsPerWatt(out.thrust_n, out.drive.pdc_w);
  out.figure_of_merit = FigureOfMerit(out.thrust_n, out.prop.power_w, prop.diameter_m(), r.rho_kg_m3);
  return out;
}

}  // namespace dynosize
