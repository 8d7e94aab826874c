// Parametric rotors for eVTOL design (issue 52 item 4): a blade given by its radius, blade count,
// solidity, linear twist, taper and root cut-out, its pitch set by the collective angle at 0.75 R,
// run through the blade-element model (docs/model.md section 13) with the sections' polar at the
// rotor's own Reynolds numbers (about 1e6 at 1-2 m radius: eq B2's Reynolds scaling lowers the
// drag from the UIUC propellers' 5e4-1e5) and Mach numbers up to the tip limit (eq B1).
//
// Hover design (HoverDesign): for a thrust, the collective (searched over kCollectiveRange) and
// the speed that give it at the best figure of merit (eq B9) with the tip Mach at or below the
// limit. What limits the rotor is named:
//   tip Mach    the thrust needs a tip speed above the limit at every collective;
//   blade loading  CT/sigma (eq B10) above kMaxBladeLoading: the sections are near stall in
//               hover (J. G. Leishman, Principles of Helicopter Aerodynamics, 2nd ed., section
//               2.14: a mean lift coefficient 6*CT/sigma above about 0.8-0.9);
//   stall       part of the span past cl_max at the design point.
// No I/O.
#pragma once

#include <string>

#include "rotor/airfoil.h"
#include "rotor/bemt.h"
#include "rotor/blade.h"

namespace dynosize {

struct ParametricRotor {
  double radius_m = 1.0;
  int blades = 3;
  double solidity = 0.10;      // B * blade area / (pi*R^2)
  double twist_deg = -10.0;    // linear, tip minus root (negative: washout)
  double taper = 1.0;          // tip chord / root chord
  double root_cutout = 0.2;    // r/R where the blade starts
  double collective_deg = 10.0;  // pitch angle at 0.75 R
};

// "" when usable, else one line naming the parameter and its rule.
std::string CheckParametricRotor(const ParametricRotor& p);
// The blade (throws UsageError when CheckParametricRotor fails).
BladeGeometry ParametricBlade(const ParametricRotor& p);

inline constexpr double kMaxBladeLoading = 0.14;  // CT/sigma, see above
inline constexpr double kCollectiveMinDeg = 2.0, kCollectiveMaxDeg = 25.0;

struct HoverDesign {
  bool feasible = false;
  std::string limit;         // "" when none binds, else "tip Mach" ("tip Mach and stall"), "blade loading", "stall"
  std::string message;       // one sentence
  double collective_deg = 0.0;
  BemtPoint point;           // at the design speed
  double induced_velocity_m_s = 0.0;  // momentum theory's sqrt(T/(2*rho*A))
  double disk_loading_n_m2 = 0.0;
  double power_loading_n_w = 0.0;
};

// The best hover design of the rotor `p` (its collective_deg is the search's start only) for
// thrust_n at rho, the tip Mach held <= tip_mach_max.
HoverDesign DesignHover(const ParametricRotor& p, const AirfoilPolar& polar, double thrust_n, double rho_kg_m3,
                        double tip_mach_max);

// The speed at which `bemt` gives thrust_n in hover at rho, omega <= omega_max; false when even
// omega_max gives less (then *omega = omega_max).
bool HoverSpeedForThrust(const Bemt& bemt, double thrust_n, double rho_kg_m3, double omega_max, double* omega_rad_s);

}  // namespace dynosize
