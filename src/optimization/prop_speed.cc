#include "optimization/prop_speed.h"

#include <cmath>

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
  // Illinois steps in x = omega^2, in which the thrust is close to linear (T = CT*rho*n^2*D^4
  // with CT slowly varying): about 8 steps instead of 13 in omega itself. The bracket and the
  // stopping rule are omega's, as before.
  int side = 0;
  for (int it = 0; it < 200; ++it) {
    double c = std::sqrt((a * a * fb - b * b * fa) / (fb - fa));
    if (!(c > a && c < b)) c = 0.5 * (a + b);
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
