#include "rotor/family.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"
#include "rotor/parametric.h"

namespace dynosize {
namespace {

double FamilyStation(int k) { return kFamilyFirstStation + kFamilyStationStep * k; }

}  // namespace

RotorFamily FamilyShape(const std::string& id, const std::string& description, const std::string& source,
                        const std::vector<FamilyBlade>& blades, const std::string& leave_out) {
  RotorFamily f;
  f.id = id;
  f.description = description;
  f.source = source;
  f.d_min_in = 1e300;
  f.pd_min = 1e300;
  for (const FamilyBlade& b : blades) {
    if (b.geometry.name == leave_out || !(b.pitch_in > 0.0)) continue;
    ++f.blades_averaged;
    f.d_min_in = std::min(f.d_min_in, b.diameter_in);
    f.d_max_in = std::max(f.d_max_in, b.diameter_in);
    f.pd_min = std::min(f.pd_min, b.pitch_in / b.diameter_in);
    f.pd_max = std::max(f.pd_max, b.pitch_in / b.diameter_in);
    const double pitch_m = InchToMeter(b.pitch_in);
    for (int k = 0; k < kFamilyStations; ++k) {
      const double x = FamilyStation(k);
      f.chord_over_r[k] += InterpolateStation(b.geometry, x).chord_over_r;
      f.pitch_over_nominal[k] += GeometricPitchM(b.geometry, x) / pitch_m;
    }
  }
  if (f.blades_averaged == 0) throw UsageError("family " + id + ": no blade to average");
  for (int k = 0; k < kFamilyStations; ++k) {
    f.chord_over_r[k] /= f.blades_averaged;
    f.pitch_over_nominal[k] /= f.blades_averaged;
  }
  return f;
}

BladeGeometry SizedBlade(const RotorFamily& f, double diameter_m, double pitch_m, int blades) {
  if (!(diameter_m > 0.0) || !std::isfinite(diameter_m)) {
    throw UsageError("propeller diameter " + SignificantText(diameter_m) + " m must be > 0");
  }
  if (!(pitch_m > 0.0) || !(pitch_m <= 2.0 * diameter_m)) {
    throw UsageError("propeller pitch " + SignificantText(pitch_m) + " m must be > 0 and at most 2 diameters");
  }
  if (blades < 1 || blades > 8) throw UsageError("propeller blades " + std::to_string(blades) + " must be 1-8");
  BladeGeometry g;
  g.radius_m = 0.5 * diameter_m;
  g.blades = blades;
  g.root_r_over_r = kFamilyFirstStation;
  g.source = "family " + f.id;
  for (int k = 0; k < kFamilyStations; ++k) {
    const double x = FamilyStation(k);
    BladeStation s;
    s.r_over_r = x;
    s.chord_over_r = f.chord_over_r[k];
    s.beta_rad = std::atan(pitch_m * f.pitch_over_nominal[k] / (2.0 * kPi * x * g.radius_m));
    g.stations.push_back(s);
  }
  return g;
}

const RotorFamily& EvtolRotorFamily() {
  static const RotorFamily kFamily = [] {
    const ParametricRotor p;  // the defaults named in family.h
    FamilyBlade b;
    b.geometry = ParametricBlade(p);
    b.diameter_in = 2.0 * p.radius_m / 0.0254;
    b.pitch_in = GeometricPitchM(b.geometry, 0.75) / 0.0254;  // the pitch at 0.75 R is the nominal one
    b.family = "evtol_rotor";
    return FamilyShape("evtol_rotor", "parametric eVTOL rotor (solidity 0.10 at 3 blades, -10 deg twist)",
                       "rotor/parametric.h default rotor, not a measured blade", {b});
  }();
  return kFamily;
}

const RotorFamily* FindFamily(const std::string& id) {
  for (const RotorFamily& f : BundledFamilies()) {
    if (f.id == id) return &f;
  }
  if (id == EvtolRotorFamily().id) return &EvtolRotorFamily();
  return nullptr;
}

std::string KnownFamilyIds() {
  std::string known;
  for (const RotorFamily& f : BundledFamilies()) known += (known.empty() ? "" : ", ") + f.id;
  return known + ", " + EvtolRotorFamily().id;
}

std::string DefaultFamilyId(double diameter_m, double pitch_m) {
  return diameter_m >= InchToMeter(12.0) && pitch_m <= 0.5 * diameter_m ? "multirotor" : "apc_e";
}

PropSize ParsePropParam(const std::string& text) {
  const std::string rule = "propeller size '" + text + "': must be DxP or DxPxB, inches, e.g. 40x13 or 40x13x3";
  std::vector<double> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size() && text[i] != 'x' && text[i] != 'X') continue;
    const std::string part = text.substr(start, i - start);
    char* end = nullptr;
    const double v = part.empty() ? std::nan("") : std::strtod(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(v) || !(v > 0.0)) throw UsageError(rule);
    parts.push_back(v);
    start = i + 1;
  }
  if (parts.size() < 2 || parts.size() > 3) throw UsageError(rule);
  if (parts[0] > 400.0) throw UsageError(rule + " (diameter above 400 in)");
  PropSize s;
  s.diameter_m = InchToMeter(parts[0]);
  s.pitch_m = InchToMeter(parts[1]);
  if (parts.size() == 3) {
    if (parts[2] != std::floor(parts[2]) || parts[2] > 8) throw UsageError(rule + " (blades 1-8)");
    s.blades = static_cast<int>(parts[2]);
  }
  return s;
}

std::string FamilyIdOf(const PropSize& size) {
  return size.family.empty() ? DefaultFamilyId(size.diameter_m, size.pitch_m) : size.family;
}

std::string SizeText(const PropSize& size) {
  return SignificantText(size.diameter_m / 0.0254, 4) + "x" + SignificantText(size.pitch_m / 0.0254, 4) + "x" +
         std::to_string(size.blades);
}

std::string SizedPropId(const PropSize& size) { return "sized_" + FamilyIdOf(size) + "_" + SizeText(size); }

bool IsSizedPropId(const std::string& id) { return id.rfind("sized_", 0) == 0; }

const RotorFamily* FamilyOfSizedPropId(const std::string& id) {
  if (!IsSizedPropId(id)) return nullptr;
  const RotorFamily* best = nullptr;
  auto consider = [&](const RotorFamily& f) {
    const std::string prefix = "sized_" + f.id + "_";
    if (id.rfind(prefix, 0) == 0 && (!best || f.id.size() > best->id.size())) best = &f;
  };
  for (const RotorFamily& f : BundledFamilies()) consider(f);
  consider(EvtolRotorFamily());
  return best;
}

bool IsParametricFamily(const RotorFamily& family) { return family.id == EvtolRotorFamily().id; }

std::string FamilyReachText(const RotorFamily& family, double diameter_m) {
  if (IsParametricFamily(family)) return "the family is parametric: no measured rotor of its class to check it on";
  const double d_in = diameter_m / 0.0254;
  std::string text = "the family's measured blades span " + SignificantText(family.d_min_in, 3) + "-" +
                     SignificantText(family.d_max_in, 3) + " in";
  if (d_in > family.d_max_in) return text + "; this one is " + FixedText(d_in / family.d_max_in, 1) + "x the largest";
  if (d_in < family.d_min_in) return text + "; this one is " + FixedText(family.d_min_in / d_in, 1) + "x below the smallest";
  return text + "; this one is inside them";
}

namespace {

// lo, lo + step, ... below hi, then hi (lo alone when hi == lo).
std::vector<double> GridOver(double lo, double hi, double step) {
  std::vector<double> v;
  const double tol = 1e-9 * step;
  for (int k = 0;; ++k) {
    const double x = lo + k * step;
    if (x >= hi - tol) break;
    v.push_back(x);
  }
  v.push_back(hi);
  return v;
}

}  // namespace

std::vector<PropSize> SizingGrid(const PropSizing& sizing, double max_diameter_m) {
  std::vector<PropSize> out;
  const double d_hi = std::min(sizing.diameter_max_m, max_diameter_m);
  if (!(d_hi >= sizing.diameter_min_m)) return out;
  const std::vector<double> diameters = GridOver(sizing.diameter_min_m, d_hi, kSizingDiameterStepM);
  const std::vector<double> ratios = GridOver(sizing.pitch_ratio_min, sizing.pitch_ratio_max, kSizingPitchRatioStep);
  for (const int b : sizing.blades) {
    for (const double d : diameters) {
      for (const double pd : ratios) out.push_back(PropSize{d, pd * d, b, sizing.family});
    }
  }
  return out;
}

void CheckPropSizing(const PropSizing& s) {
  if (FindFamily(s.family) == nullptr) {
    throw UsageError("family \"" + s.family + "\": not a bundled family (known: " + KnownFamilyIds() + ")");
  }
  if (!(s.diameter_min_m > 0.0 && s.diameter_min_m <= s.diameter_max_m && s.diameter_max_m <= 10.0)) {
    throw UsageError("diameter_m [" + SignificantText(s.diameter_min_m, 4) + ", " + SignificantText(s.diameter_max_m, 4) +
                     "]: must be a range with 0 < min <= max <= 10 m");
  }
  if (!(s.pitch_ratio_min > 0.0 && s.pitch_ratio_min <= s.pitch_ratio_max && s.pitch_ratio_max <= 2.0)) {
    throw UsageError("pitch_ratio [" + SignificantText(s.pitch_ratio_min, 4) + ", " + SignificantText(s.pitch_ratio_max, 4) +
                     "]: must be a range with 0 < min <= max <= 2");
  }
  if (s.blades.empty()) throw UsageError("blades: must list 1-8 blade counts");
  for (const int b : s.blades) {
    if (b < 1 || b > 8) throw UsageError("blades: " + std::to_string(b) + ": must be 1-8");
  }
}

}  // namespace dynosize
