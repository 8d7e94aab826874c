// The shaft speed at which a catalog propeller gives a required static thrust (for
// `simulate --prop P --thrust-n F`): T(omega) = CT*rho*n^2*D^4 (src/prop/prop_model.h, UIUC
// definitions) rises with speed, so the speed is bracketed by doubling from the data's lowest
// rpm and found by bisection.
#pragma once

#include "prop/prop_model.h"

namespace dynosize {

struct PropSpeedForThrust {
  bool found = false;       // false: the thrust needs more than kMaxRequestRpm, or T(omega) is not
                            // increasing where the bisection looked
  double omega_rad_s = 0.0;
  PropEvaluation prop;      // at omega_rad_s (carries the out-of-data flags)
};

// thrust_n > 0 and finite, rho_kg_m3 > 0 (else UsageError). Relative tolerance 1e-10 in speed.
PropSpeedForThrust SpeedForThrust(const PropModel& prop, double thrust_n, double rho_kg_m3,
                                  double airspeed_m_s = 0.0);

}  // namespace dynosize
