// The blade section of the blade-element model: a lift curve and a drag polar with Reynolds-number
// and Mach-number corrections (docs/model.md section 13, eqs B1-B3).
//
//   (B1)  cl = (cl0 + cl_alpha*alpha) / sqrt(1 - M^2)       (Prandtl-Glauert, M <= kMaxMach)
//         held at cl_max / cl_min beyond them (stall), where the drag rises by
//         kStallDragRise*sin^2(alpha - alpha_stall)            (flat-plate drag past stall)
//   (B2)  cd = (cd0 + cd2*(cl - cl_cd0)^2) * (Re/re_ref)^re_exp
//   (B3)  Re = rho*W*c/mu,   M = W/a
// alpha is the section's angle of attack from the chord line of the blade's twist beta (B5).
// No I/O, no allocation: Evaluate is called in the inner loop of the element solve.
#pragma once

#include <string>

namespace dynosize {

// Mach number beyond which the Prandtl-Glauert factor is held (it diverges at M = 1); the
// eVTOL rotors of issue 52 run at tip Mach <= 0.7, and a section above this is flagged.
inline constexpr double kMaxMach = 0.8;
// Drag added past stall: cd += kStallDragRise*sin^2(alpha - alpha_stall), so that a section
// at 90 degrees past stall reaches a flat plate's cd of about 2 (Hoerner, Fluid-Dynamic Drag,
// ch. 3: a flat plate normal to the flow, cd 1.98).
inline constexpr double kStallDragRise = 2.0;

struct AirfoilPolar {
  double cl0 = 0.5;                 // lift coefficient at alpha = 0 (camber)
  double cl_alpha_per_rad = 5.8;    // lift-curve slope at low Mach
  double cl_max = 1.2;              // positive stall
  double cl_min = -0.4;             // negative stall
  double cd0 = 0.028;               // least drag, at cl_cd0 and re_ref
  double cd2 = 0.05;                // drag rise with (cl - cl_cd0)^2
  double cl_cd0 = 0.5;              // lift coefficient of least drag
  double re_ref = 70000.0;          // Reynolds number of cd0
  double re_exp = -0.5;             // drag's Reynolds exponent (-0.5 laminar, -0.2 turbulent)
};

// "" when the polar is usable, else what is wrong ("cl_max 0.3 <= cl0 ...").
std::string CheckAirfoil(const AirfoilPolar& polar);

struct SectionCoefficients {
  double cl = 0.0;
  double cd = 0.0;
  bool stalled = false;  // held at cl_max or cl_min
  bool mach_held = false;  // M above kMaxMach: the compressibility factor held at its value there
};

// Eqs B1-B3 at angle of attack alpha (rad), Reynolds number re (> 0) and Mach number mach (>= 0).
SectionCoefficients EvaluateSection(const AirfoilPolar& polar, double alpha_rad, double re,
                                    double mach);

}  // namespace dynosize
