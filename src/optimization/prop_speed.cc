#include "optimization/prop_speed.h"

namespace dynosize {

bool PropSpeedForThrust(const PropModel& prop, double thrust_n, double rho, double airspeed,
                        double w_hi, double* omega, PropEvaluation* ev) {
  if (double w = 0; prop.StaticSpeedForThrust(thrust_n, rho, &w)) {
    const bool ok = w <= w_hi;
    *omega = ok ? w : w_hi;
    *ev = prop.Evaluate(*omega, rho, airspeed);
    return ok;
  }
  double a = 0.0, fa = -thrust_n;
  PropEvaluation eb = prop.Evaluate(w_hi, rho, airspeed);
  double b = w_hi, fb = eb.thrust_n - thrust_n;
  if (fb < 0) {
    *omega = w_hi;
    *ev = eb;
    return false;
  }
  int side = 0;
  for (int it = 0; it < 200; ++it) {
    const double c = (a * fb - b * fa) / (fb - fa);
    const PropEvaluation ec = prop.Evaluate(c, rho, airspeed);
    const double fc = ec.thrust_n - thrust_n;
    if (fc > 0) {
      b = c; fb = fc; eb = ec;
      if (side == 1) fa *= 0.5;
      side = 1;
    } else {
      a = c; fa = fc;
      if (side == -1) fb *= 0.5;
      side = -1;
      if (fc == 0) { b = c; eb = ec; break; }
    }
    if (b - a < 1e-12 * b) break;
  }
  *omega = b;
  *ev = eb;
  return true;
}

}  // namespace dynosize
