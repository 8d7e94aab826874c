#include "stand/prop_speed.h"

#include <cmath>

#include "common/error.h"
#include "common/units.h"
#include "io/points_csv.h"

namespace dynosize {

PropSpeedForThrust SpeedForThrust(const PropModel& prop, double thrust_n, double rho_kg_m3,
                                  double airspeed_m_s) {
  if (!(std::isfinite(thrust_n) && thrust_n > 0.0)) {
    throw UsageError("thrust " + std::to_string(thrust_n) + " N: must be a finite number > 0");
  }
  PropSpeedForThrust r;
  const double w_cap = RpmToRadPerSec(kMaxRequestRpm);
  double lo = 0.0, hi = RpmToRadPerSec(1000.0);
  while (prop.Evaluate(hi, rho_kg_m3, airspeed_m_s).thrust_n < thrust_n) {
    lo = hi;
    hi *= 2.0;
    if (hi > w_cap) {
      r.prop = prop.Evaluate(w_cap, rho_kg_m3, airspeed_m_s);
      r.omega_rad_s = w_cap;
      return r;
    }
  }
  for (int k = 0; k < 200 && hi - lo > 1e-10 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (prop.Evaluate(mid, rho_kg_m3, airspeed_m_s).thrust_n < thrust_n ? lo : hi) = mid;
  }
  r.omega_rad_s = 0.5 * (lo + hi);
  r.prop = prop.Evaluate(r.omega_rad_s, rho_kg_m3, airspeed_m_s);
  // Held-edge coefficients can make T(omega) locally flat; say so rather than return a speed
  // whose thrust is off.
  r.found = std::fabs(r.prop.thrust_n - thrust_n) <= 1e-6 * thrust_n;
  return r;
}

}  // namespace dynosize
