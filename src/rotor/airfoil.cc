#include "rotor/airfoil.h"

#include <cmath>

namespace dynosize {

std::string CheckAirfoil(const AirfoilPolar& p) {
  auto finite = [](double v) { return std::isfinite(v); };
  if (!finite(p.cl0) || !finite(p.cl_alpha_per_rad) || !finite(p.cl_max) || !finite(p.cl_min) ||
      !finite(p.cd0) || !finite(p.cd2) || !finite(p.cl_cd0) || !finite(p.re_ref) || !finite(p.re_exp)) {
    return "airfoil: every coefficient must be a finite number";
  }
  if (p.cl_alpha_per_rad <= 0.0) return "airfoil: cl_alpha_per_rad must be > 0";
  if (!(p.cl_min < p.cl0 && p.cl0 < p.cl_max)) return "airfoil: needs cl_min < cl0 < cl_max";
  if (p.cd0 < 0.0 || p.cd2 < 0.0) return "airfoil: cd0 and cd2 must be >= 0";
  if (p.re_ref <= 0.0) return "airfoil: re_ref must be > 0";
  if (p.re_exp > 0.0 || p.re_exp < -1.0) return "airfoil: re_exp must be in [-1, 0]";
  return "";
}

SectionCoefficients EvaluateSection(const AirfoilPolar& p, double alpha_rad, double re, double mach) {
  SectionCoefficients s;
  // (B1) Prandtl-Glauert, held above kMaxMach.
  double m = mach;
  if (m > kMaxMach) {
    m = kMaxMach;
    s.mach_held = true;
  }
  const double pg = 1.0 / std::sqrt(1.0 - m * m);
  const double cl_max = p.cl_max * pg;
  const double cl_min = p.cl_min * pg;
  double cl = (p.cl0 + p.cl_alpha_per_rad * alpha_rad) * pg;
  double stall_drag = 0.0;
  const double slope = p.cl_alpha_per_rad * pg;
  if (cl > cl_max) {
    const double alpha_stall = (cl_max - p.cl0 * pg) / slope;
    const double sn = std::sin(alpha_rad - alpha_stall);
    stall_drag = kStallDragRise * sn * sn;
    cl = cl_max;
    s.stalled = true;
  } else if (cl < cl_min) {
    const double alpha_stall = (cl_min - p.cl0 * pg) / slope;
    const double sn = std::sin(alpha_rad - alpha_stall);
    stall_drag = kStallDragRise * sn * sn;
    cl = cl_min;
    s.stalled = true;
  }
  // (B2) drag polar with its Reynolds-number scaling.
  const double dcl = cl - p.cl_cd0;
  const double re_factor = re > 0.0 ? std::pow(re / p.re_ref, p.re_exp) : 1.0;
  s.cl = cl;
  s.cd = (p.cd0 + p.cd2 * dcl * dcl) * re_factor + stall_drag;
  return s;
}

}  // namespace dynosize
