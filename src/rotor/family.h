// Propeller families: a blade shape in non-dimensional form, so that a propeller given only by its
// diameter, pitch and blade count can be built and run through the blade-element model
// (docs/model.md section 13, eq B12):
//   (B12) c(r) = R * c/R_family(x),   beta(r) = atan(P * p_family(x) / (2*pi*x*R)),   x = r/R
// c/R_family is the mean chord over radius of the family's measured blades, p_family(x) their
// mean local geometric pitch 2*pi*x*R*tan(beta(x)) over the nominal pitch of their name, both on
// the stations x = 0.15, 0.20, ..., 1.00. The bundled families (rotor/family_data.cc) are printed
// from the data by `dynosize rotor families --shared ../shared/data` and checked against it in
// tests/rotor/family_test.cc. No I/O.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rotor/blade.h"

namespace dynosize {

inline constexpr int kFamilyStations = 18;
inline constexpr double kFamilyFirstStation = 0.15;
inline constexpr double kFamilyStationStep = 0.05;

struct RotorFamily {
  std::string id;           // "apc_e"
  std::string description;  // "APC thin electric (E)"
  std::string source;       // which data, how many blades
  int blades_averaged = 0;
  double d_min_in = 0.0, d_max_in = 0.0;    // the measured blades' diameters
  double pd_min = 0.0, pd_max = 0.0;        // and pitch ratios
  std::array<double, kFamilyStations> chord_over_r{};
  std::array<double, kFamilyStations> pitch_over_nominal{};
};

// The mean shape of `blades` (each with its nominal pitch in FamilyBlade::pitch_in), leaving out
// the blade named `leave_out` (""= none). Throws UsageError when no blade is left.
RotorFamily FamilyShape(const std::string& id, const std::string& description, const std::string& source,
                        const std::vector<FamilyBlade>& blades, const std::string& leave_out = "");

// Eq B12: the blade of a family at a size. Throws UsageError for a diameter, pitch or blade
// count out of range (D > 0, P > 0, P/D <= 2, 1-8 blades).
BladeGeometry SizedBlade(const RotorFamily& family, double diameter_m, double pitch_m, int blades);

// The bundled families (rotor/family_data.cc).
const std::vector<RotorFamily>& BundledFamilies();
// The parametric eVTOL rotor family "evtol_rotor" (not from measured blades: rotor/parametric.h's
// default rotor, three blades of constant chord at solidity 0.10, -10 degrees of linear twist,
// root cut-out 0.2, at 10 degrees collective), its shape normalized like the others: a size
// "DxPxB" scales its chord with D and its pitch with P.
const RotorFamily& EvtolRotorFamily();
// nullptr when no family (bundled or evtol_rotor) has that id.
const RotorFamily* FindFamily(const std::string& id);
// "apc_e, apc_sf, ...": every id FindFamily knows, for messages.
std::string KnownFamilyIds();
// The family a size alone picks: multirotor propellers (pitch ratio <= 0.5 from 12 in) take the
// multirotor shape, others APC's thin electric one (the commonest electric propeller).
std::string DefaultFamilyId(double diameter_m, double pitch_m);

// A propeller given by its size alone (issue 52): "DxP[xB]" in inches, its family ("" = the
// default of DefaultFamilyId).
struct PropSize {
  double diameter_m = 0.0;
  double pitch_m = 0.0;
  int blades = 2;
  std::string family;
};

// "DxP" or "DxPxB", inches ("40x13", "40x13x3"). Throws UsageError naming the text and the rule.
PropSize ParsePropParam(const std::string& text);
// The family the size uses: size.family, or DefaultFamilyId.
std::string FamilyIdOf(const PropSize& size);
// "40x13x2": the size as the ids and names print it (inches, 4 significant digits).
std::string SizeText(const PropSize& size);
// The catalog id of the sized propeller: "sized_<family>_<D>x<P>x<B>".
std::string SizedPropId(const PropSize& size);
// True for the ids SizedPropId makes (the entries api::MissionCatalog adds for a mission).
bool IsSizedPropId(const std::string& id);
// The family of a sized propeller's id (the longest family id after "sized_"); nullptr when the
// id is not a sized one.
const RotorFamily* FamilyOfSizedPropId(const std::string& id);
// True for a family not drawn from measured blades (evtol_rotor): it has no measured diameters.
bool IsParametricFamily(const RotorFamily& family);
// How far a size is from its family's data, for a result's line: "the family's measured blades
// span 12-18 in; this one is 3.6x the largest", or that the family is parametric.
std::string FamilyReachText(const RotorFamily& family, double diameter_m);

// A family offered to the search with its sizes free (issue 52 item 5): the catalog's
// "prop_families" (catalog/catalog.h) and a mission's "prop_sizing" (docs/missions.md). The
// search sizes the rotor on the grid SizingGrid lays over the ranges, every point an entry of
// its own searched exactly with the motor, ESC and pack (docs/missions.md, "Sizing the rotor").
struct PropSizing {
  std::string id;      // the catalog entry's id ("" for a mission's own)
  std::string family;  // a FindFamily id
  double diameter_min_m = 0.0, diameter_max_m = 0.0;
  double pitch_ratio_min = 0.0, pitch_ratio_max = 0.0;
  std::vector<int> blades;  // 1-8 each
  std::string source;       // why these ranges (the catalog's provenance)
};

// The grid's steps: 2 cm of diameter (finer than the inch propellers are sold in; issue 52's goal
// compares with the best of a 2 cm grid) and 0.05 of pitch ratio.
inline constexpr double kSizingDiameterStepM = 0.02;
inline constexpr double kSizingPitchRatioStep = 0.05;

// The sizes of the grid over `sizing`'s ranges with the diameter at most `max_diameter_m`:
// diameters from the range's low end by kSizingDiameterStepM, the range's high end (or
// max_diameter_m, the lower) always included; pitch ratios likewise by kSizingPitchRatioStep;
// every blade count. Empty when the frame takes none of the family's diameters. A range
// shorter than its step gives its two ends (one for a single value).
std::vector<PropSize> SizingGrid(const PropSizing& sizing, double max_diameter_m);
// Throws UsageError naming the rule when a sizing's family is unknown or a range is out of
// bounds (diameter 0 < min <= max <= 10 m, pitch ratio 0 < min <= max <= 2, blades 1-8).
void CheckPropSizing(const PropSizing& sizing);

}  // namespace dynosize
