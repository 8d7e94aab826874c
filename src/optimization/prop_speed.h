// The propeller's speed for a required thrust: the evaluator's flight (each segment's shaft
// point), its early exits (the propeller data window, the hover throttle) and its summary (the
// designer's hover) all start from it.
#pragma once

#include "prop/prop_model.h"

namespace dynosize {

// Propeller speed for a required thrust: the root of T(omega) - T_req on [0, w_hi], in closed
// form for coefficients and power laws (PropModel::StaticSpeedForThrust: their thrust does not
// depend on the inflow), else by the Illinois variant of regula falsi in omega^2 (T(0) = 0 <
// T_req). Returns false when T(w_hi) < T_req.
// *omega and *ev: the root and the propeller there (w_hi and the propeller there when false).
bool PropSpeedForThrust(const PropModel& prop, double thrust_n, double rho, double airspeed,
                        double w_hi, double* omega, PropEvaluation* ev);

}  // namespace dynosize
