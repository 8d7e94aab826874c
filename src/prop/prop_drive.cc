#include "prop/prop_drive.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace dynosize {

PropDrivePoint SolveDriveWithProp(const Drive& drive, const PropModel& prop, double vdc_v,
                                  double throttle, double rho_kg_m3, double airspeed_m_s,
                                  const PropDriveOptions& options) {
  if (options.max_iterations < 1 || !(options.rel_tolerance > 0)) {
    throw UsageError("PropDriveOptions: max_iterations must be >= 1 and rel_tolerance > 0");
  }
  PropDrivePoint r;
  // Start at half the no-load speed (the maximum-power speed, eq 12): a propeller load puts the
  // operating point between it and no-load.
  double omega = drive.MaxPowerSpeed(vdc_v, throttle);
  if (!(omega > 0)) {
    r.drive = drive.AtLoad(vdc_v, throttle, TorqueLaw{});
    r.prop = prop.Evaluate(0.0, rho_kg_m3, airspeed_m_s);
    r.converged = true;
    r.message = "no-load speed is zero at this voltage and throttle";
    return r;
  }
  for (r.iterations = 1; r.iterations <= options.max_iterations; ++r.iterations) {
    const LocalTorqueFit fit =
        prop.FitTorqueLaw(omega, rho_kg_m3, airspeed_m_s, options.fit_rel_step);
    r.drive = drive.AtLoad(vdc_v, throttle, fit.law);
    const double next = r.drive.omega_rad_s;
    if (!(next > 0)) {
      r.message = "the drive stalls under the propeller's torque law";
      break;
    }
    const bool done = std::abs(next - omega) < options.rel_tolerance * next;
    omega = next;
    if (done) {
      r.converged = true;
      break;
    }
  }
  if (!r.converged && r.message.empty()) {
    r.message = "no convergence in " + std::to_string(options.max_iterations) + " iterations";
  }
  r.prop = prop.Evaluate(std::max(omega, 0.0), rho_kg_m3, airspeed_m_s);
  if (r.converged && !r.prop.InData()) r.message = r.prop.Message();
  return r;
}

}  // namespace dynosize
