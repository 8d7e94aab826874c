#include "rotor/bemt.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"

namespace dynosize {
namespace {

// psi's tolerance: 1e-9 rad moves W by 1e-9*U, far below the sections' data.
constexpr double kPsiTolerance = 1e-9;
constexpr int kMaxRootIterations = 60;

struct ElementFlow {
  double ua, ut;     // freestream at the element: V and omega*r
  double r, x, c, beta, rho;
};

// Eqs B5-B8 at one psi; fills e and returns Gamma(B6) - Gamma(B7).
double Residual(const ElementFlow& f, double psi, const AirfoilPolar& polar, const BemtOptions& opt,
                int blades, double radius_m, BemtElement* e) {
  const double u = std::hypot(f.ua, f.ut);
  const double wa = 0.5 * (f.ua + u * std::sin(psi));
  const double wt = 0.5 * (f.ut + u * std::cos(psi));
  const double w = std::hypot(wa, wt);
  const double alpha = f.beta - std::atan2(wa, wt);
  const double re = f.rho * w * f.c / opt.viscosity_pa_s;
  const double mach = w / opt.speed_of_sound_m_s;
  const SectionCoefficients sec = EvaluateSection(polar, alpha, re, mach);
  const double gamma_blade = 0.5 * w * f.c * sec.cl;  // (B6)
  double tip_f = 1.0;
  double lw = 0.0;
  if (wt > 0.0) lw = f.x * wa / wt;
  if (opt.tip_loss && lw > 1e-12) {
    const double fexp = 0.5 * blades * (1.0 - f.x) / lw;
    tip_f = (2.0 / kPi) * std::acos(std::min(1.0, std::exp(-fexp)));
  }
  const double vt = f.ut - wt;
  const double k = 4.0 * lw * radius_m / (kPi * blades * f.r);
  const double gamma_wake = vt * (4.0 * kPi * f.r / blades) * tip_f * std::sqrt(1.0 + k * k);  // (B7)
  e->psi_rad = psi;
  e->wa_m_s = wa;
  e->wt_m_s = wt;
  e->va_m_s = wa - f.ua;
  e->vt_m_s = vt;
  e->alpha_rad = alpha;
  e->cl = sec.cl;
  e->cd = sec.cd;
  e->reynolds = re;
  e->mach = mach;
  e->tip_loss_f = tip_f;
  e->stalled = sec.stalled;
  e->mach_held = sec.mach_held;
  return gamma_blade - gamma_wake;
}

}  // namespace

Bemt::Bemt(const BladeGeometry& geometry, const AirfoilPolar& polar, const BemtOptions& options)
    : geometry_(geometry), polar_(polar), options_(options) {
  const std::string bad_geometry = CheckBladeGeometry(geometry);
  if (!bad_geometry.empty()) throw UsageError(bad_geometry);
  const std::string bad_polar = CheckAirfoil(polar);
  if (!bad_polar.empty()) throw UsageError(geometry.name + ": " + bad_polar);
  if (options.elements < 4 || options.elements > 400) {
    throw UsageError("blade elements " + std::to_string(options.elements) + " must be 4-400");
  }
  if (!(options.viscosity_pa_s > 0.0) || !(options.speed_of_sound_m_s > 0.0)) {
    throw UsageError("air viscosity and speed of sound must be > 0");
  }
  // Elements between the root and the tip, their edges at x0 + (1 - x0)*sin(pi/2 * s) for
  // uniform s: closer toward the tip, where the tip loss changes the load fastest.
  const double x0 = std::max(geometry.root_r_over_r, geometry.stations.front().r_over_r);
  const int n = options.elements;
  elements_.reserve(n);
  for (int i = 0; i < n; ++i) {
    const double xa = x0 + (1.0 - x0) * std::sin(0.5 * kPi * i / n);
    const double xb = x0 + (1.0 - x0) * std::sin(0.5 * kPi * (i + 1) / n);
    const double x = 0.5 * (xa + xb);
    const BladeStation s = InterpolateStation(geometry, x);
    elements_.push_back({x, x * geometry.radius_m, (xb - xa) * geometry.radius_m,
                         s.chord_over_r * geometry.radius_m, s.beta_rad});
  }
  solidity_ = Solidity(geometry);
}

void Bemt::set_polar(const AirfoilPolar& polar) {
  const std::string bad_polar = CheckAirfoil(polar);
  if (!bad_polar.empty()) throw UsageError(geometry_.name + ": " + bad_polar);
  polar_ = polar;
}

double Bemt::disk_area_m2() const { return kPi * geometry_.radius_m * geometry_.radius_m; }

BemtElement Bemt::SolveElement(int index, double omega_rad_s, double airspeed_m_s, double rho_kg_m3) const {
  const Layout& l = elements_.at(index);
  const ElementFlow f{airspeed_m_s, omega_rad_s * l.r_m, l.r_m, l.x, l.chord_m, l.beta_rad, rho_kg_m3};
  const int b = geometry_.blades;
  const double radius = geometry_.radius_m;
  BemtElement e;
  e.r_m = l.r_m;
  e.dr_m = l.dr_m;
  e.chord_m = l.chord_m;
  e.beta_rad = l.beta_rad;
  // The no-induction state psi0 (va = vt = 0, so Gamma(B7) = 0): the residual there has the
  // sign of the section's lift. Positive lift: the root lies toward more induction, up to
  // psi = pi/2 (vt = Ut/2); negative lift: toward less.
  const double psi0 = std::atan2(f.ua, f.ut);
  const double r0 = Residual(f, psi0, polar_, options_, b, radius, &e);
  if (r0 == 0.0) {
    e.solved = true;
  } else {
    double lo = psi0, flo = r0;
    // Negative lift (an inner element in strong inflow): at psi = -psi0 the axial velocity
    // through the disk is 0 (Gamma(B7) = 0 again) and the section sees alpha = beta, so the
    // root lies in (-psi0, psi0) when the section lifts at its twist angle; else further down.
    double hi = r0 > 0.0 ? 0.5 * kPi : -0.5 * kPi;
    double fhi = 0.0;
    if (r0 < 0.0 && psi0 > 0.0) {
      fhi = Residual(f, -psi0, polar_, options_, b, radius, &e);
      if (fhi > 0.0) hi = -psi0;
    }
    if (hi != -psi0) fhi = Residual(f, hi, polar_, options_, b, radius, &e);
    if ((flo > 0.0) == (fhi > 0.0)) {
      e.solved = false;  // no root in the bracket: keep the no-induction state
      Residual(f, psi0, polar_, options_, b, radius, &e);
    } else {
      // Illinois (modified regula falsi): keeps the bracket, converges superlinearly.
      int side = 0;
      double psi = lo;
      for (int it = 0; it < kMaxRootIterations; ++it) {
        psi = (lo * fhi - hi * flo) / (fhi - flo);
        const double fp = Residual(f, psi, polar_, options_, b, radius, &e);
        if (std::fabs(hi - lo) < kPsiTolerance || fp == 0.0) break;
        if ((fp > 0.0) == (fhi > 0.0)) {
          hi = psi;
          fhi = fp;
          if (side == -1) flo *= 0.5;
          side = -1;
        } else {
          lo = psi;
          flo = fp;
          if (side == 1) fhi *= 0.5;
          side = 1;
        }
      }
      e.solved = true;
    }
  }
  // (B8), all blades.
  const double w = std::hypot(e.wa_m_s, e.wt_m_s);
  const double q = 0.5 * rho_kg_m3 * b * w * l.chord_m * l.dr_m;
  e.dthrust_n = q * (e.cl * e.wt_m_s - e.cd * e.wa_m_s);
  e.dtorque_nm = q * (e.cl * e.wa_m_s + e.cd * e.wt_m_s) * l.r_m;
  return e;
}

BemtPoint Bemt::Evaluate(double omega_rad_s, double airspeed_m_s, double rho_kg_m3) const {
  if (!(omega_rad_s > 0.0) || !std::isfinite(omega_rad_s)) {
    throw UsageError("rotor speed " + SignificantText(omega_rad_s) + " rad/s must be > 0");
  }
  if (!(airspeed_m_s >= 0.0) || !std::isfinite(airspeed_m_s)) {
    throw UsageError("airspeed " + SignificantText(airspeed_m_s) + " m/s must be >= 0");
  }
  if (!(rho_kg_m3 > 0.0) || !std::isfinite(rho_kg_m3)) {
    throw UsageError("air density " + SignificantText(rho_kg_m3) + " kg/m^3 must be > 0");
  }
  BemtPoint p;
  p.omega_rad_s = omega_rad_s;
  p.airspeed_m_s = airspeed_m_s;
  p.rho_kg_m3 = rho_kg_m3;
  double span = 0.0, stalled = 0.0;
  double best_re_distance = 1e300;
  for (int i = 0; i < elements(); ++i) {
    const BemtElement e = SolveElement(i, omega_rad_s, airspeed_m_s, rho_kg_m3);
    p.thrust_n += e.dthrust_n;
    p.torque_nm += e.dtorque_nm;
    span += e.dr_m;
    if (e.stalled) stalled += e.dr_m;
    p.mach_held = p.mach_held || e.mach_held;
    if (!e.solved) ++p.unsolved_elements;
    const double d75 = std::fabs(elements_[i].x - 0.75);
    if (d75 < best_re_distance) {
      best_re_distance = d75;
      p.mean_reynolds = e.reynolds;
    }
  }
  const double radius = geometry_.radius_m;
  const double d = 2.0 * radius;
  const double n = omega_rad_s / (2.0 * kPi);
  const double area = disk_area_m2();
  p.power_w = p.torque_nm * omega_rad_s;
  p.ct = p.thrust_n / (rho_kg_m3 * n * n * d * d * d * d);
  p.cp = p.power_w / (rho_kg_m3 * n * n * n * d * d * d * d * d);
  p.j = airspeed_m_s / (n * d);
  p.stalled_span = span > 0.0 ? stalled / span : 0.0;
  const double tip_speed = omega_rad_s * radius;
  p.tip_mach = std::hypot(tip_speed, airspeed_m_s) / options_.speed_of_sound_m_s;
  p.ct_over_sigma = p.thrust_n / (rho_kg_m3 * area * tip_speed * tip_speed) / solidity_;
  if (p.thrust_n > 0.0 && p.power_w > 0.0) {
    const double vh2 = p.thrust_n / (2.0 * rho_kg_m3 * area);  // induced velocity squared (hover)
    const double v = airspeed_m_s;
    const double ideal = p.thrust_n * (0.5 * v + std::sqrt(0.25 * v * v + vh2));  // (B9)
    p.figure_of_merit = ideal / p.power_w;
    if (v > 0.0) p.efficiency = p.thrust_n * v / p.power_w;
  }
  return p;
}

BemtPoint Bemt::EvaluateAtAdvanceRatio(double omega_rad_s, double j, double rho_kg_m3) const {
  if (!(j >= 0.0) || !std::isfinite(j)) throw UsageError("advance ratio " + SignificantText(j) + " must be >= 0");
  const double n = omega_rad_s / (2.0 * kPi);
  return Evaluate(omega_rad_s, j * n * 2.0 * geometry_.radius_m, rho_kg_m3);
}

}  // namespace dynosize
