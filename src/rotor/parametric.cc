#include "rotor/parametric.h"

#include <cmath>

#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"

namespace dynosize {
namespace {

constexpr double kDeg = kPi / 180.0;
constexpr int kStations = 21;
constexpr int kCollectiveSteps = 24;  // grid over the collective range, then a golden refinement
constexpr int kGoldenSteps = 20;
constexpr double kThrustTolerance = 1e-6;  // relative, of the speed's root

}  // namespace

std::string CheckParametricRotor(const ParametricRotor& p) {
  if (!(p.radius_m > 0.0) || p.radius_m > 20.0) return "rotor radius " + SignificantText(p.radius_m) + " m must be in (0, 20]";
  if (p.blades < 2 || p.blades > 8) return "rotor blades " + std::to_string(p.blades) + " must be 2-8";
  if (!(p.solidity >= 0.02 && p.solidity <= 0.3)) return "rotor solidity " + SignificantText(p.solidity) + " must be 0.02-0.3";
  if (!(p.twist_deg >= -30.0 && p.twist_deg <= 10.0)) return "rotor twist " + SignificantText(p.twist_deg) + " deg must be -30..10";
  if (!(p.taper >= 0.2 && p.taper <= 2.0)) return "rotor taper " + SignificantText(p.taper) + " must be 0.2-2";
  if (!(p.root_cutout >= 0.05 && p.root_cutout <= 0.5)) return "rotor root cut-out " + SignificantText(p.root_cutout) + " must be 0.05-0.5";
  if (!(p.collective_deg >= -10.0 && p.collective_deg <= 40.0)) return "rotor collective must be -10..40 deg";
  return "";
}

BladeGeometry ParametricBlade(const ParametricRotor& p) {
  const std::string bad = CheckParametricRotor(p);
  if (!bad.empty()) throw UsageError(bad);
  BladeGeometry g;
  g.name = "parametric rotor";
  g.radius_m = p.radius_m;
  g.blades = p.blades;
  g.root_r_over_r = p.root_cutout;
  // Linear chord c(x) = c_root*(1 + (taper - 1)*(x - x0)/(1 - x0)); its area over the span sets
  // the solidity: sigma = B/pi * c_root/R * (1 - x0) * (1 + taper)/2.
  const double x0 = p.root_cutout;
  const double c_root = p.solidity * kPi / (p.blades * (1.0 - x0) * 0.5 * (1.0 + p.taper));
  for (int i = 0; i < kStations; ++i) {
    const double x = x0 + (1.0 - x0) * i / (kStations - 1.0);
    const double s = (x - x0) / (1.0 - x0);
    BladeStation st;
    st.r_over_r = x;
    st.chord_over_r = c_root * (1.0 + (p.taper - 1.0) * s);
    st.beta_rad = (p.collective_deg + p.twist_deg * (x - 0.75) / (1.0 - x0)) * kDeg;
    g.stations.push_back(st);
  }
  return g;
}

bool HoverSpeedForThrust(const Bemt& bemt, double thrust_n, double rho, double omega_max, double* omega) {
  // Thrust rises with the speed (about as its square): bisection on omega in (0, omega_max].
  const BemtPoint top = bemt.Evaluate(omega_max, 0.0, rho);
  if (top.thrust_n < thrust_n) {
    *omega = omega_max;
    return false;
  }
  double lo = 0.0, hi = omega_max;
  for (int it = 0; it < 80 && hi - lo > kThrustTolerance * omega_max; ++it) {
    const double mid = 0.5 * (lo + hi);
    (bemt.Evaluate(mid, 0.0, rho).thrust_n < thrust_n ? lo : hi) = mid;
  }
  *omega = hi;
  return true;
}

HoverDesign DesignHover(const ParametricRotor& p, const AirfoilPolar& polar, double thrust_n, double rho,
                        double tip_mach_max) {
  if (!(thrust_n > 0.0) || !std::isfinite(thrust_n)) throw UsageError("hover thrust must be > 0 N");
  if (!(rho > 0.0)) throw UsageError("air density must be > 0");
  if (!(tip_mach_max > 0.1 && tip_mach_max <= kMaxMach)) {
    throw UsageError("tip Mach limit " + SignificantText(tip_mach_max) + " must be in (0.1, " + SignificantText(kMaxMach) + "]");
  }
  const double omega_max = tip_mach_max * kIsaSeaLevelSpeedOfSoundMS / p.radius_m;
  // FM at a collective (0 when the thrust is out of reach); the best over a grid, then refined.
  auto fm_at = [&](double collective, HoverDesign* d) {
    ParametricRotor q = p;
    q.collective_deg = collective;
    const Bemt bemt(ParametricBlade(q), polar);
    double omega = 0.0;
    const bool reached = HoverSpeedForThrust(bemt, thrust_n, rho, omega_max, &omega);
    d->collective_deg = collective;
    d->point = bemt.Evaluate(omega, 0.0, rho);
    d->feasible = reached;
    return reached ? d->point.figure_of_merit : 0.0;
  };
  HoverDesign best, d, strongest;
  double best_fm = -1.0, best_c = kCollectiveMinDeg;
  const double step = (kCollectiveMaxDeg - kCollectiveMinDeg) / kCollectiveSteps;
  for (int i = 0; i <= kCollectiveSteps; ++i) {
    const double c = kCollectiveMinDeg + step * i;
    const double fm = fm_at(c, &d);
    if (!d.feasible && d.point.thrust_n > strongest.point.thrust_n) strongest = d;  // at the tip limit
    if (fm > best_fm) {
      best_fm = fm;
      best_c = c;
      best = d;
    }
  }
  double a = std::max(kCollectiveMinDeg, best_c - step), b = std::min(kCollectiveMaxDeg, best_c + step);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < kGoldenSteps; ++i) {
    const double c1 = b - g * (b - a), c2 = a + g * (b - a);
    HoverDesign d1, d2;
    const double f1 = fm_at(c1, &d1), f2 = fm_at(c2, &d2);
    if (f1 >= f2) b = c2; else a = c1;
    if (f1 > best_fm) { best_fm = f1; best = d1; }
    if (f2 > best_fm) { best_fm = f2; best = d2; }
  }
  const double area = kPi * p.radius_m * p.radius_m;
  best.induced_velocity_m_s = std::sqrt(thrust_n / (2.0 * rho * area));
  best.disk_loading_n_m2 = thrust_n / area;
  best.power_loading_n_w = best.point.power_w > 0.0 ? thrust_n / best.point.power_w : 0.0;
  if (!best.feasible) {
    // Nothing reaches the thrust: the strongest collective at the tip limit is what it can do.
    const HoverDesign at_limit = strongest;
    best = at_limit;
    best.induced_velocity_m_s = std::sqrt(thrust_n / (2.0 * rho * area));
    best.disk_loading_n_m2 = thrust_n / area;
    best.power_loading_n_w = best.point.power_w > 0.0 ? best.point.thrust_n / best.point.power_w : 0.0;
    best.limit = "tip Mach";
    best.message = "at most " + SignificantText(best.point.thrust_n, 4) + " N at tip Mach " + FixedText(tip_mach_max, 2) +
                   " (collective " + FixedText(best.collective_deg, 1) + " deg): a larger radius or solidity";
    // The strongest collective is usually deep in stall: say so (the blade limit, not the speed alone).
    if (best.point.ct_over_sigma > kMaxBladeLoading || best.point.stalled_span > 0.05) {
      best.limit = "tip Mach and stall";
      best.message += "; there CT/sigma is " + FixedText(best.point.ct_over_sigma, 3) + " and " +
                      PercentText(best.point.stalled_span, 0) + " of the span is past stall";
    }
  } else if (best.point.ct_over_sigma > kMaxBladeLoading) {
    best.limit = "blade loading";
    best.message = "CT/sigma " + FixedText(best.point.ct_over_sigma, 3) + " above " + FixedText(kMaxBladeLoading, 2) +
                   ": the blades are near stall; more solidity or tip speed";
  } else if (best.point.stalled_span > 0.05) {
    best.limit = "stall";
    best.message = PercentText(best.point.stalled_span, 0) + " of the span past stall at the design point";
  }
  return best;
}

}  // namespace dynosize
