// Propeller credibility: the valid range of a catalog propeller's data, its figure of merit
// over that range, and the envelope of measured propellers of its size class. The catalog
// reader refuses an entry that beats momentum theory (FM > 1) inside its range; the importers
// derate entries above the envelope; the optimizer reads the envelope (p10/p50/p90) for the
// spread of credible values.
//
// Figure of merit (model/physics.h, Leishman eq 2.14): FM = T^1.5/(P*sqrt(2*rho*A)). With the
// UIUC coefficients (T = CT*rho*n^2*D^4, P = CP*rho*n^3*D^5) it is FM = CT^1.5/(CP*sqrt(pi/2)),
// independent of rho and D; FigureOfMerit of physics.h is used on dimensional T and P so that
// the rule exists once.
//
// Valid range (PropValidRange): the rpm (and advance ratio J) over which the entry's data hold:
//   - tables (UIUC measured, APC PER3 computed): the rpm of the static table (or of the sweeps
//     when there is no static table) and the largest J of the sweeps;
//   - power laws (DriveCalc) and constant coefficients: the entry's rpm_min/rpm_max keys (the
//     importer writes them: the rpm of DriveCalc's own measurements with that propeller, else
//     an assumed tip-speed band capped by the stated MaxRPM); without keys the tip-speed band
//     kDefaultTipSpeedLo/HiMS, capped by max_rpm.
// Outside the range src/prop/prop_model holds the coefficients at the edge and flags it.
//
// Envelope (FmEnvelopeFor): by diameter class, the distribution over UIUC's measured propellers
// (static tests, volumes 1-3, 239 props) of each propeller's median FM over its measured rpm
// range (docs/model.md section 10: median 0.555, maximum 0.753 over all classes). Generated from
// catalog/uiuc_propdb.json; tests/catalog/prop_credibility_test.cc recomputes it.
#pragma once

#include <string>

#include "catalog/entries.h"
#include "fit/statistics.h"

namespace dynosize {

// Tip speeds bounding an assumed rpm range where the data do not state one: below 40 m/s a
// hobby propeller's Reynolds number (~2e4 at 75 % radius) is below the measured range of UIUC's
// static tests; 230 m/s (tip Mach 0.68) is above any hobby propeller's stated limit.
inline constexpr double kDefaultTipSpeedLoMS = 40.0;
inline constexpr double kDefaultTipSpeedHiMS = 230.0;

struct PropValidRange {
  double rpm_lo = 0.0;
  double rpm_hi = 0.0;
  double j_hi = 0.0;       // largest advance ratio with data (0: static data only)
  bool rpm_assumed = false;  // the range is the default tip-speed band, not data
};

PropValidRange ValidRange(const PropEntry& entry);

// Static figure of merit of the entry over its valid range (at the power laws' density; the
// coefficient form does not depend on density).
struct PropFmScan {
  double fm_min = 0.0;
  double fm_max = 0.0;
  double fm_median = 0.0;   // median over the scanned points
  double rpm_at_max = 0.0;
  // Largest axial-flow analogue of FM (ideal climb power over shaft power, physics.h) over the
  // forward-flight sweeps, 0 without sweeps; points with CT <= 0 or CP <= 0 are not scanned.
  double axial_fm_max = 0.0;
  double j_at_axial_max = 0.0;
};

PropFmScan ScanFigureOfMerit(const PropEntry& entry);

// "" when the entry cannot beat momentum theory inside its valid range, else one sentence
// ("static FM 1.07 at 2000 rpm > 1: beats momentum theory (docs/model.md section 10)").
std::string PropMomentumViolation(const PropEntry& entry);

// The median over the points of the static table of FM = CT^1.5/(CP*sqrt(pi/2)) (the number
// the envelope is built from); 0 without a static table.
double MedianStaticFigureOfMerit(const PropEntry& entry);

// The distribution of measured propellers' median FM in one diameter class.
struct FmEnvelopeClass {
  double d_lo_m = 0.0, d_hi_m = 0.0;  // [lo, hi)
  const char* label = "";
  int n_props = 0;
  double p10 = 0.0, p50 = 0.0, p90 = 0.0, max = 0.0;
};

// The class of a diameter (every positive diameter has one).
const FmEnvelopeClass& FmEnvelopeFor(double diameter_m);
// All classes, by increasing diameter.
const std::vector<FmEnvelopeClass>& FmEnvelope();
// The envelope computed from a set of measured propellers (what FmEnvelope() holds when given
// UIUC's entries); props without a static table are skipped.
std::vector<FmEnvelopeClass> ComputeFmEnvelope(const std::vector<const PropEntry*>& measured);

// The quantile of sorted values (fit/statistics.h; one implementation).
using fit::SortedQuantile;

// True when a name says the blades fold ("folding", "klapp", "CAM Carbon", Aeronaut "CAM"
// folders, UIUC family "ancf"): such propellers are for gliders, not multirotor lift.
bool NameSaysFolding(const std::string& name);

}  // namespace dynosize
