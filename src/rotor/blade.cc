#include "rotor/blade.h"

#include <algorithm>
#include <cmath>

#include "common/text_format.h"
#include "common/units.h"

namespace dynosize {

std::string CheckBladeGeometry(const BladeGeometry& g) {
  const std::string where = g.source.empty() ? g.name : g.source;
  if (!(g.radius_m > 0.0) || !std::isfinite(g.radius_m)) {
    return where + ": radius " + SignificantText(g.radius_m) + " m must be > 0";
  }
  if (g.blades < 1 || g.blades > 12) return where + ": blades " + std::to_string(g.blades) + " must be 1-12";
  if (g.stations.size() < 3) {
    return where + ": " + std::to_string(g.stations.size()) + " stations; the blade-element model needs >= 3";
  }
  double last = 0.0;
  for (size_t i = 0; i < g.stations.size(); ++i) {
    const BladeStation& s = g.stations[i];
    const std::string at = where + ": station " + std::to_string(i + 1) + " (r/R " + SignificantText(s.r_over_r) + ")";
    if (!std::isfinite(s.r_over_r) || !(s.r_over_r > last) || s.r_over_r > 1.0 + 1e-9) {
      return at + ": r/R must increase within (0, 1]";
    }
    if (!(s.chord_over_r > 0.0) || s.chord_over_r > 1.0) return at + ": c/R " + SignificantText(s.chord_over_r) + " must be in (0, 1]";
    if (!std::isfinite(s.beta_rad) || std::fabs(s.beta_rad) >= 0.5 * kPi) {
      return at + ": twist must be within +-90 degrees";
    }
    if (!(s.thickness_ratio >= 0.0) || s.thickness_ratio > 0.5) return at + ": thickness ratio must be in [0, 0.5]";
    last = s.r_over_r;
  }
  if (g.root_r_over_r < 0.0 || g.root_r_over_r >= g.stations.back().r_over_r) {
    return where + ": root r/R " + SignificantText(g.root_r_over_r) + " must be in [0, last station)";
  }
  return "";
}

BladeStation InterpolateStation(const BladeGeometry& g, double x) {
  const std::vector<BladeStation>& st = g.stations;
  if (x <= st.front().r_over_r) {
    BladeStation s = st.front();
    s.r_over_r = x;
    return s;
  }
  if (x >= st.back().r_over_r) {
    BladeStation s = st.back();
    s.r_over_r = x;
    return s;
  }
  const auto hi = std::upper_bound(st.begin(), st.end(), x,
                                   [](double v, const BladeStation& s) { return v < s.r_over_r; });
  const BladeStation& b = *hi;
  const BladeStation& a = *(hi - 1);
  const double t = (x - a.r_over_r) / (b.r_over_r - a.r_over_r);
  BladeStation s;
  s.r_over_r = x;
  s.chord_over_r = a.chord_over_r + t * (b.chord_over_r - a.chord_over_r);
  s.beta_rad = a.beta_rad + t * (b.beta_rad - a.beta_rad);
  s.thickness_ratio = a.thickness_ratio + t * (b.thickness_ratio - a.thickness_ratio);
  return s;
}

double Solidity(const BladeGeometry& g) {
  const double x0 = std::max(g.root_r_over_r, g.stations.front().r_over_r);
  const double x1 = g.stations.back().r_over_r;
  constexpr int kSteps = 64;
  double area = 0.0;  // integral of c/R d(r/R) by the midpoint rule
  for (int i = 0; i < kSteps; ++i) {
    const double x = x0 + (x1 - x0) * (i + 0.5) / kSteps;
    area += InterpolateStation(g, x).chord_over_r;
  }
  area *= (x1 - x0) / kSteps;
  return g.blades * area / kPi;
}

double GeometricPitchM(const BladeGeometry& g, double x) {
  return 2.0 * kPi * x * g.radius_m * std::tan(InterpolateStation(g, x).beta_rad);
}

}  // namespace dynosize
