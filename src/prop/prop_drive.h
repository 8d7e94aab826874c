// A motor + ESC driving a catalog propeller: the operating point where the drive's torque
// (model/drive.h, eq 49) equals the propeller's torque at the same speed.
//
// The closed form Drive::AtLoad needs a quadratic load law. PropModel::FitTorqueLaw gives the
// quadratic through the exact propeller torque at 0.95, 1 and 1.05 times a speed omega_k; the
// operating point omega_{k+1} = AtLoad(fit at omega_k) is then a fixed-point iteration that
// converges in a few steps (the fit is exact at omega_k, so the error shrinks with the square of
// the step). Measured tables with kinks (binned medians, KDE's sheets) can throw the local fit
// off: when the iteration stalls or does not converge, the speed is bracketed instead, where
// the drive's torque at the speed (Drive::AtSpeed, eq 49: falling in omega) minus the
// propeller's changes sign on [0, omega_NL] (positive at rest when the drive can start, the
// propeller's torque >= 0 at no-load), by bisection to rel_tolerance. A result that does not
// converge either way is a status, not an exception.
#pragma once

#include <string>

#include "model/drive.h"
#include "prop/prop_model.h"

namespace dynosize {

struct PropDriveOptions {
  int max_iterations = 30;
  // Stop when |omega_{k+1} - omega_k| < rel_tolerance * omega_{k+1}.
  double rel_tolerance = 1e-10;
  double fit_rel_step = 0.05;  // PropModel::FitTorqueLaw's step
};

struct PropDrivePoint {
  OperatingPoint drive;  // the motor + ESC point (limits flagged as Drive::AtLoad does)
  PropEvaluation prop;   // thrust, torque and data flags at that speed
  int iterations = 0;      // of the fixed point
  bool bracketed = false;  // the fixed point failed and bisection found the speed
  bool converged = false;
  std::string message;  // why not converged, or the propeller's out-of-data message
};

// Throws UsageError for rho <= 0, airspeed < 0 or bad options; everything else is a status.
PropDrivePoint SolveDriveWithProp(const Drive& drive, const PropModel& prop, double vdc_v,
                                  double throttle, double rho_kg_m3, double airspeed_m_s = 0.0,
                                  const PropDriveOptions& options = {});

}  // namespace dynosize
