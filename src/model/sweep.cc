#include "model/sweep.h"

#include <algorithm>
#include <cmath>

#include "common/units.h"

namespace dynosize {

ThrottleSummary SummarizeThrottle(const Drive& drive, double vdc_v, double throttle) {
  ThrottleSummary s;
  s.throttle = throttle;
  s.throttle_effective = drive.EffectiveThrottle(throttle);
  s.no_load_rpm = RadPerSecToRpm(drive.NoLoadSpeed(vdc_v, throttle));
  s.stall_torque_nm = drive.StallTorque(vdc_v, throttle);
  const double w_p = drive.MaxPowerSpeed(vdc_v, throttle);
  s.max_power_rpm = RadPerSecToRpm(w_p);
  s.max_power_w = drive.AtSpeed(vdc_v, throttle, w_p).pmech_w;
  const double w_e = drive.MaxEfficiencySpeed(vdc_v, throttle);
  s.at_max_efficiency = drive.AtSpeed(vdc_v, throttle, w_e);
  s.max_efficiency_rpm = RadPerSecToRpm(w_e);
  s.max_eta_system = s.at_max_efficiency.eta_system;
  return s;
}

std::vector<ThrottleSummary> SummarizeThrottles(const Drive& drive, double vdc_v, int steps) {
  std::vector<ThrottleSummary> rows;
  for (int k = 1; k <= steps; ++k) {
    rows.push_back(SummarizeThrottle(drive, vdc_v, static_cast<double>(k) / steps));
  }
  return rows;
}

double CurrentLimit(const Drive& drive, double vdc_v) {
  const double rated = std::min(drive.motor().max_current_a, drive.esc().max_current_a);
  if (std::isfinite(rated)) return rated;
  return drive.volt_factor() * vdc_v * drive.EffectiveThrottle(1.0) / drive.r_total_ohm();
}

}  // namespace dynosize
