#include "prop/prop_drive.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace dynosize {

namespace {

// Bisection bound: halving [0, omega_NL] this often is below any rel_tolerance a double holds.
constexpr int kMaxBisections = 200;

// The speed where the drive's torque at speed (eq 49) meets the propeller's, by bisection on
// [0, omega_NL]; false when the ends do not bracket a sign change.
bool BracketSpeed(const Drive& drive, const PropModel& prop, double vdc_v, double throttle,
                  double rho_kg_m3, double airspeed_m_s, double rel_tolerance, double* omega_rad_s) {
  auto excess = [&](double w) {
    return drive.AtSpeed(vdc_v, throttle, w).torque_nm - prop.Evaluate(w, rho_kg_m3, airspeed_m_s).torque_nm;
  };
  double lo = 0.0, hi = drive.NoLoadSpeed(vdc_v, throttle);
  if (!(hi > 0.0) || !(excess(lo) > 0.0) || !(excess(hi) <= 0.0)) return false;
  for (int i = 0; i < kMaxBisections && hi - lo > rel_tolerance * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (excess(mid) > 0.0 ? lo : hi) = mid;
  }
  *omega_rad_s = 0.5 * (lo + hi);
  return true;
}

}  // namespace

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
  if (!r.converged) {
    double w = 0.0;
    if (BracketSpeed(drive, prop, vdc_v, throttle, rho_kg_m3, airspeed_m_s, options.rel_tolerance, &w)) {
      omega = w;
      r.drive = drive.AtSpeed(vdc_v, throttle, w);
      r.bracketed = true;
      r.converged = true;
      r.message.clear();
    } else if (r.message.empty()) {
      r.message = "no convergence in " + std::to_string(options.max_iterations) + " iterations";
    }
  }
  r.prop = prop.Evaluate(std::max(omega, 0.0), rho_kg_m3, airspeed_m_s);
  if (r.converged && !r.prop.InData()) r.message = r.prop.Message();
  return r;
}

}  // namespace dynosize
