// A rotor's blade geometry for the blade-element model (docs/model.md section 13): chord and
// twist along the radius, as UIUC's geometry tables (c/R, beta vs r/R) and APC's PE0 files
// (chord and twist per station) give them. No I/O: src/importers/blade_geometry.cc reads the files.
#pragma once

#include <string>
#include <vector>

namespace dynosize {

struct BladeStation {
  double r_over_r = 0.0;      // radial position over the tip radius, in (0, 1]
  double chord_over_r = 0.0;  // chord over the tip radius, > 0
  double beta_rad = 0.0;      // twist: the chord line's angle to the rotor plane
  // Thickness over chord where the source states it (APC PE0), else 0 (unknown).
  double thickness_ratio = 0.0;
};

struct BladeGeometry {
  std::string name;          // e.g. "apce 10.0x5.0" or "10x5E"
  double radius_m = 0.0;     // tip radius D/2
  int blades = 2;
  // Where the lifting blade starts, over R: the first station unless stated (the part inside
  // is hub and root fairing and carries no load in the model).
  double root_r_over_r = 0.0;
  std::vector<BladeStation> stations;  // by increasing r_over_r
  std::string source;                  // file and row, for messages
};

// A blade as a database files it: its family (e.g. UIUC's "apce") and nominal size.
struct FamilyBlade {
  BladeGeometry geometry;
  std::string family;
  double diameter_in = 0.0, pitch_in = 0.0;
};

// "" when the geometry is usable, else one line naming the station and the rule.
std::string CheckBladeGeometry(const BladeGeometry& g);

// Chord, twist and thickness at r_over_r by linear interpolation between stations, held at the
// first and last station outside them.
BladeStation InterpolateStation(const BladeGeometry& g, double r_over_r);

// Solidity sigma = B * (blade area) / (pi*R^2) over the lifting span: B/pi * integral of c/R d(r/R).
double Solidity(const BladeGeometry& g);

// Geometric pitch at r_over_r: 2*pi*r*tan(beta), m (the helix the chord line follows).
double GeometricPitchM(const BladeGeometry& g, double r_over_r);

}  // namespace dynosize
