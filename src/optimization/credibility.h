// Trust in the data behind a result: the source tier of each catalog entry, the figure-of-merit
// envelope of measured propellers, the data scenarios a mission can be flown on, and the
// objective range of a result (its type here; optimization/objective_range.h fills it, above the
// evaluator, because it flies the mission again under the other scenarios).
//
// The trust rules themselves live in the catalog, one implementation each: the source tier of
// an entry (EntryBase::tier, catalog/conventions.h; ValueTier for one value), the figure-of-merit
// envelope of measured propellers by size class (catalog/prop_credibility.h, FmEnvelopeFor),
// the folding flag (PropEntry::folding), the ratings of motors without one (EstimatedMotorPowerW
// and EstimatedMotorCurrentA, catalog/conventions.h) and exclusion (EntryBase::exclude_reason).
// This file says what the sizing does with them.
//
// Data scenarios (mission.h, DataScenario), what each changes. Thrust is never changed; the
// propeller's shaft power (torque) at the thrust is, pointwise, in static evaluations (hover,
// and static-only data anywhere: forward-flight tables are used as given):
//     P' = max(f * P, P_ideal(T) / FM_cap)          P_ideal = T^1.5 / sqrt(2*rho*A)
// (momentum theory, docs/model.md section 10), i.e. FM' = min(FM / f, FM_cap). Below the lowest
// speed of a propeller's data the model's Reynolds correction (catalog/prop_reynolds.h, median
// exponents) is in P already; the pessimistic and optimistic scenarios widen it with the
// distance from the data (PropAdjustment::reynolds_fm_exp: the p90 and p10 of the law's FM
// exponent), every tier. f and FM_cap per tier and scenario:
//                        credible (ranking)      pessimistic             optimistic
//   measured             as measured             f = 1.05                f = 0.95 (FM <= 1)
//   manufacturer         f = 1/0.880, cap p90    f = 1/0.740             f = 1/0.911, cap p90
//   computed             (f on the raw data: see below)
//   manufacturer stated, cap class p50           cap class p10           cap class p90
//   user contributed,
//   assumed
// "Class" is the propeller's diameter class of the catalog's envelope (FmEnvelopeFor): p10/p50/
// p90 of the median static figure of merit of UIUC's measured propellers of that class (docs/model.md
// section 10: 239 props, median 0.555). Manufacturer-computed data (APC PER3 blade-element
// tables, and APC's computed coefficients in FAST-UAV) are scaled by the ratio measured/computed
// FM of the same product: the 9 APC products UIUC measured (SF and E families) give 0.740 /
// 0.880 / 0.911 (min, median, max; kComputedFmRatio), computed on the manufacturer's raw data.
// A propeller whose data are worse than the cap keeps its data (P' >= P): no scenario makes a
// propeller better than its own data, except the optimistic bands of the measured and computed
// tiers.
//
// Catalog derating (prop_credibility.h): at import, a non-measured propeller above its class
// maximum FM already has its power multiplied by power_derate_factor d >= 1. The scenarios do
// not derate twice: the cap is an absolute FM (max() with data that are already lower changes
// nothing), and the computed tier's ratio applies to the manufacturer's raw data P/d, so the
// factor on the stored data is f' = max(1, f/d) (P' = max(f*P_raw, P_stored, P_ideal/FM_cap)).
//
// Motor and ESC parameters in the pessimistic/optimistic scenarios move within their data's
// spread: a motor's Rm and Io that the in-system law gave (catalog/in_system.h) to one motor's
// p10/p90 scatter about that law, measured on stand data; other values within a band per value
// tier (TierValueBand, the tier of rm_ohm, io_a, resc_ohm, c0 by ValueTier; MotorSpreadParams):
// up/down by a relative band; an ESC whose C0 is assumed (the ideal prior, esc_prior.h) gets
// C0 = kAssumedEscC0Pessimistic in the pessimistic case, and an assumed RESC is multiplied/
// divided by exp(resistance_log_sd) of the prior. The credible scenario (the default ranking)
// leaves motors and ESCs at their catalog values.
//
// Motors without a source rating: the importers give a motor with neither a current nor a
// power rating max_power_w = EstimatedMotorPowerW(mass) marked "assumed" (catalog/conventions.h:
// 10.81*m[g]^0.878 W), or "exclude" when it has no mass. The mission (constraints.unrated_motors)
// either uses that estimate ("estimate", the default; a hand-written entry with no rating and
// a mass gets the same estimate here), together with the current law of conventions.h
// (EstimatedMotorCurrentA from mass and Kv: a power rating alone lets a small high-Kv motor run
// at 8 % throttle and 42 A rms), or leaves such motors out ("exclude").
//
// Entries with an exclude_reason are skipped by the search (catalog_exclude); evaluate warns.
//
// Folding propellers (PropEntry::folding, set by the importers from the Folder column or the
// name): never used for multirotor lift (a hover, climb or wingless cruise segment) unless the
// mission's constraints.allow_folding_props_for_lift is true.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "model/drive.h"
#include "prop/prop_model.h"

namespace dynosize {

// Measured over computed static FM (MedianStaticFigureOfMerit, prop_credibility.h) of the same
// APC products: UIUC apcsf/apce against the raw APC PER3 SF/E tables of the bundled catalog
// (stored power / power_derate_factor); recomputed in tests/optimization/credibility_test.cc.
struct FmRatio {
  double min, median, max;
  int pairs;
};
inline constexpr FmRatio kComputedFmRatio{0.7396, 0.8802, 0.9114, 9};

// Relative band of measured propeller power (pessimistic: +5 %, optimistic: -5 %): the
// agreement between UIUC's and other facilities' static CP of the same propeller model that
// Brandt & Selig (AIAA 2011-1255) report is a few percent; 5 % is an allowance, not a fit.
inline constexpr double kMeasuredPowerBand = 0.05;
// Switching-loss term of an ESC whose C1, C0 are the assumed ideal, in the pessimistic
// scenario: C0 = 0.03 (at 40 % throttle eta_ESC ~ 0.444/0.474 = 94 %; Brown's thesis saw ESC
// efficiencies as low as 65 %, docs/model.md section 1): an allowance, not a fit.
inline constexpr double kAssumedEscC0Pessimistic = 0.03;

// How a propeller's static evaluations are adjusted in one scenario.
struct PropAdjustment {
  double power_factor = 1.0;                                   // f
  double fm_cap = std::numeric_limits<double>::infinity();     // FM_cap
  // Below the data's lowest speed (PropEvaluation::reynolds_ratio r < 1) the model applies the
  // Reynolds law's median exponents (catalog/prop_reynolds.h); a scenario moves the figure of
  // merit's exponent e to its p90 (pessimistic) or max(p10, 0) (optimistic): power at the same
  // thrust x r^-(e_s - e_applied), in static and forward-flight evaluations alike.
  double reynolds_fm_exp = 0.0;  // e_s - e_applied
  bool identity() const { return power_factor == 1.0 && !(fm_cap < 1e300) && reynolds_fm_exp == 0.0; }
};
PropAdjustment PropAdjustmentFor(const PropEntry& prop, DataScenario scenario);

// Applies the adjustment to a static evaluation (ev->airspeed_m_s == 0 or static-only data
// held at J = 0): power and torque rise to the scenario's value, thrust unchanged. Evaluations
// from forward-flight tables get the Reynolds band only (reynolds_fm_exp).
void AdjustPropEvaluation(const PropAdjustment& adj, double diameter_m, PropEvaluation* ev);

// True when the mission has a segment in which the rotors lift the vehicle (hover, climb, or
// cruise without a wing).
bool MissionUsesRotorLift(const Mission& mission);
// True when the mission refuses the propeller: a folding one for rotor lift.
bool FoldingPropRefused(const PropEntry& prop, const Mission& mission);

// The motor's voltage rating from its recommended LiPo cell count (catalog key cells_max, as
// the DriveCalc importer derives an ESC's vdc_max_v): 4.2 V per fully charged cell; +inf when
// the entry has none. A pack whose full-charge voltage exceeds it fails "motor_voltage".
double MotorMaxVoltageV(const MotorEntry& motor);

// The motor parameters a mission flies: the catalog's, with max_power_w = EstimatedMotorPowerW
// (catalog/conventions.h) when the entry has neither rating and a mass, max_current_a =
// EstimatedMotorCurrentA when no source states a rating (the power one estimated here or by the
// importer), and moved within their
// bands in the pessimistic/optimistic scenarios. *rating_estimated (optional) says whether the
// power rating is an estimate from the mass (here or by the importer, source.values "assumed");
// *excluded (optional) whether the mission leaves the motor out (unrated_motors = "exclude").
// A geared motor (catalog keys gear_ratio, gear_efficiency) is returned as seen at the
// propeller shaft (model/gear.h, MotorAtPropellerShaft): every drive the evaluator and the
// search build from it turns the propeller at the propeller's own speed and counts the gear
// loss, and every bound proven for a direct-drive motor holds for it (gear.h).
MotorParams ScenarioMotorParams(const MotorEntry& motor, const Mission& mission,
                                bool* rating_estimated = nullptr, bool* excluded = nullptr);
EscParams ScenarioEscParams(const EscEntry& esc, DataScenario scenario);
// The most current any point may draw through the ESC in a mission: its peak rating where a peak
// duration is stated, else its continuous one (ApplyPeakRatings; the search's R1-R5 lists).
inline double EscReachCurrentA(const EscEntry& esc) {
  EscParams p = esc.params;
  ApplyPeakRatings(&p);
  return p.max_current_a;
}

// The tier of each part of a result and the objective under the other scenarios.
struct PartTier {
  std::string part;  // "motor", "ESC", "propeller", "battery"
  std::string id;
  DataTier tier = DataTier::kAssumed;
  std::string why;   // "source.tier" (stated in the file) or "source.values" (inferred)
};

// Filled by AddObjectiveRange (optimization/objective_range.h).
struct ObjectiveRange {
  bool computed = false;
  // The objective under the pessimistic and the optimistic data, ordered (low <= credible <=
  // high, in objective_unit). Each end is flown with the mission's limits relaxed to physics
  // (throttle <= 100 %, no current or power ratings, no hover-throttle floor, saturation
  // allowed, no thrust-to-weight or winding-temperature limit; the pack's power, cut-off and
  // reserve still hold), so that it is a number even when those data break a rating;
  // `*_breaks` lists what that end breaks under the mission's own limits ("" when nothing). An end
  // that cannot fly at all has no value (low_flies/high_flies false; held at the credible value
  // only so that the numbers stay ordered) and `complete` is false.
  double low = 0.0, high = 0.0;
  bool low_flies = true, high_flies = true;
  std::string low_breaks, high_breaks;
  bool complete = true;
  double as_given = 0.0;  // the objective on the catalog's data as given (no adjustment)
  bool as_given_feasible = true;
  std::string as_given_breaks;  // what the data as given break ("" when feasible)
  std::string basis;      // one line: what the range spans
  std::vector<PartTier> tiers;
  std::string motor_rating;  // "catalog", "... estimated from the mass (assumed)", ...
};

}  // namespace dynosize
