// Trust in the data behind a result (issue 13, item 4, and the sizing side of items 3 and 5):
// the source tier of each catalog entry, the figure-of-merit envelope of measured propellers,
// the data scenarios a mission can be flown on, and the objective range of a result.
//
// Source tier (best first): measured (stand or wind tunnel) > manufacturer computed (APC PER3)
// > manufacturer stated > user contributed (DriveCalc's data base and power laws) > assumed.
// Today the tier is inferred from source.dataset and source.values of the entry's performance
// keys (EntryTier); the worst label of those keys is the entry's tier. When the catalog gets a
// tier field of its own, EntryTier is the one function to switch.
//
// Data scenarios (mission.h, DataScenario), what each changes. Thrust is never changed; the
// propeller's shaft power (torque) at the thrust is, pointwise, in static evaluations (hover,
// and static-only data anywhere: forward-flight tables are used as given):
//     P' = max(f * P, P_ideal(T) / FM_cap)          P_ideal = T^1.5 / sqrt(2*rho*A)
// (momentum theory, model.md section 10), i.e. FM' = min(FM / f, FM_cap). f and FM_cap per
// tier and scenario:
//                        credible (ranking)      pessimistic             optimistic
//   measured             as measured             f = 1.05                f = 0.95 (FM <= 1)
//   manufacturer         f = 1/0.880, cap p90    f = 1/0.740             f = 1/0.911, cap p90
//   computed
//   manufacturer stated, cap class p50           cap class p10           cap class p90
//   user contributed,
//   assumed
// "Class" is the propeller's diameter class in PropFmClasses(): p10/p50/p90 of the median static
// figure of merit of UIUC's measured propellers of that class (model.md section 10: 239 props,
// median 0.555). Manufacturer-computed data (APC PER3 blade-element tables, and APC's computed
// coefficients in FAST-UAV) are scaled by the ratio measured/computed FM of the same product:
// the 9 APC products UIUC measured (SF and E families) give 0.740 / 0.880 / 0.911 (min, median,
// max; kComputedFmRatio). A propeller whose data are worse than the cap keeps its data
// (P' >= P): no scenario makes a propeller better than its own data, except the optimistic
// bands of the measured and computed tiers.
// Motor and ESC parameters in the pessimistic/optimistic scenarios move within a band per value
// label (ValueBand in credibility.cc): Rm and Io up/down by a relative band; an ESC whose C1, C0 are the
// assumed ideal (esc_prior.h) gets C0 = kAssumedEscC0Pessimistic in the pessimistic case, and
// an assumed RESC is multiplied/divided by exp(resistance_log_sd) of the prior.
// The credible scenario (the default ranking) leaves motors and ESCs at their catalog values.
//
// Motors without a current or power rating: by default ratings from the mass, the laws of
// hobby outrunners fitted (least squares in logs) to the FAST-UAV catalogues (204 motors with
// mass, Kv, I_max and V_nominal):
//     P_max [W] = 4319 * (m / 1 kg)^0.953                  (I_max*V_nominal; log sd 0.85)
//     I_max [A] = 0.5956 * (m / 1 kg)^1.2816 * Kv^0.9629   (Kv in rpm/V;      log sd 0.55)
// (a specific power of about 4.3 kW/kg; at a fixed design speed the voltage falls as 1/Kv, so
// the current rises about as m*Kv), marked assumed; or (mission constraints.unrated_motors =
// "exclude") the motor is left out.
//
// Folding propellers (the name says "folding", "klapp", "CAM" or "foldable"): never used for
// multirotor lift (a hover, climb or wingless cruise segment) unless the mission's
// constraints.allow_folding_props_for_lift is true.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "model/drive.h"
#include "prop/prop_model.h"

namespace dynosize {

struct Combination;
struct MissionResult;

enum class SourceTier { kMeasured, kManufacturerComputed, kManufacturerStated, kUserContributed, kAssumed };

// "measured", "manufacturer_computed", "manufacturer_stated", "user_contributed", "assumed".
const char* SourceTierName(SourceTier tier);

// The tier of one value label of source.values; `dataset` is the entry's source.dataset and
// catalog file name ("fitted" counts as measured unless either names a manufacturer's table,
// "manufacturer" or "mfr"; "datasheet" of DriveCalc's data base is user contributed);
// "derived" returns false (it inherits from the values it comes from).
bool LabelTier(const std::string& label, const std::string& dataset, SourceTier* tier);

// The entry's tier: the worst tier of its performance keys (motor: kv/ke, rm, io; ESC: resc,
// c1, c0; propeller: its tables, coefficients or power laws; battery: capacity, voltage, ri);
// `why` (optional) gets the key that sets it. Entries without labels fall back on the data set.
SourceTier EntryTier(const EntryBase& entry, ComponentKind kind, std::string* why = nullptr);

// The figure-of-merit envelope of one diameter class of measured propellers.
struct FmClass {
  double d_lo_m, d_hi_m;  // [lo, hi)
  double p10, p50, p90;   // of the per-propeller median static FM
  int n;                  // propellers in the class
  const char* label;
};

// The classes, from catalog/uiuc_propdb.json (UIUC Propeller Data Site vol 1-3, static tables;
// FM = CT^1.5/(CP*sqrt(pi/2)) per point, the median over each propeller's rpm points, then the
// percentiles over the class with linear interpolation). tests/optimization/credibility_test.cc
// recomputes them from the bundled catalog.
const std::vector<FmClass>& PropFmClasses();
const FmClass& PropFmClassOf(double diameter_m);

// The static figure of merit CT^1.5/(CP*sqrt(pi/2)) at each point of the static table, and its
// median; 0 when the entry has no static table.
double MedianStaticFigureOfMerit(const PropEntry& prop);
// The classes recomputed from the measured propellers (tier measured, with a static table) of
// `props`.
std::vector<FmClass> ComputePropFmClasses(const std::vector<PropEntry>& props);

// Measured over computed static FM of the same APC products (UIUC apcsf/apce against APC PER3
// SF/E tables of the bundled catalog; recomputed in tests/optimization/credibility_test.cc).
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
// efficiencies as low as 65 %, model.md section 1): an allowance, not a fit.
inline constexpr double kAssumedEscC0Pessimistic = 0.03;

// How a propeller's static evaluations are adjusted in one scenario.
struct PropAdjustment {
  double power_factor = 1.0;                                   // f
  double fm_cap = std::numeric_limits<double>::infinity();     // FM_cap
  bool identity() const { return power_factor == 1.0 && !(fm_cap < 1e300); }
};
PropAdjustment PropAdjustmentFor(const PropEntry& prop, DataScenario scenario);

// Applies the adjustment to a static evaluation (ev->airspeed_m_s == 0 or static-only data
// held at J = 0): power and torque rise to the scenario's value, thrust unchanged. Evaluations
// from forward-flight tables are left as they are.
void AdjustPropEvaluation(const PropAdjustment& adj, double diameter_m, PropEvaluation* ev);

bool IsFoldingProp(const PropEntry& prop);
// True when the mission has a segment in which the rotors lift the vehicle (hover, climb, or
// cruise without a wing).
bool MissionUsesRotorLift(const Mission& mission);
// True when the mission refuses the propeller: a folding one for rotor lift.
bool FoldingPropRefused(const PropEntry& prop, const Mission& mission);

// The motor's voltage rating from its recommended LiPo cell count (catalog key cells_max, as
// the DriveCalc importer derives an ESC's vdc_max_v): 4.2 V per fully charged cell; +inf when
// the entry has none. A pack whose full-charge voltage exceeds it fails "motor_voltage".
double MotorMaxVoltageV(const MotorEntry& motor);

// Motor ratings from its mass (and Kv, rpm/V) by the laws above: W and A.
double EstimatedMotorPowerW(double mass_kg);
double EstimatedMotorCurrentA(double mass_kg, double kv_rpm_per_v);
// The motor's Kv: the catalog's, else from KE (model.md section 8: Kv = 0.675/(KE*pi/30) for a
// BLDC, 1/(KE*pi/30) brushed), rpm/V.
double MotorKvRpmPerV(const MotorEntry& motor);

// The motor parameters a mission flies: the catalog's, with the estimated power rating when
// the motor has neither rating (and the mission estimates), and moved within their bands in
// the pessimistic/optimistic scenarios. *rating_estimated (optional) says whether the estimate
// was used; *excluded (optional) whether the mission excludes the motor (no rating, "exclude").
MotorParams ScenarioMotorParams(const MotorEntry& motor, const Mission& mission,
                                bool* rating_estimated = nullptr, bool* excluded = nullptr);
EscParams ScenarioEscParams(const EscEntry& esc, DataScenario scenario);

// The tier of each part of a result and the objective under the other scenarios.
struct PartTier {
  std::string part;  // "motor", "ESC", "propeller", "battery"
  std::string id;
  SourceTier tier = SourceTier::kAssumed;
  std::string why;   // the key that sets the tier
};

struct ObjectiveRange {
  bool computed = false;
  // The objective under the pessimistic and the optimistic data, ordered (low <= credible <=
  // high, in objective_unit). Each end is flown with the mission's limits relaxed to physics
  // (throttle <= 100 %, no current or power ratings, no hover-throttle floor, saturation
  // allowed; the pack's power, cut-off and reserve still hold), so that it is a number even
  // when those data break a rating; `*_breaks` lists what that end breaks under the mission's
  // own limits ("" when nothing). An end that cannot fly at all is held at the credible value
  // and `complete` is false.
  double low = 0.0, high = 0.0;
  std::string low_breaks, high_breaks;
  bool complete = true;
  double as_given = 0.0;  // the objective on the catalog's data as given (no adjustment)
  bool as_given_feasible = true;
  std::string as_given_breaks;  // what the data as given break ("" when feasible)
  std::string basis;      // one line: what the range spans
  std::vector<PartTier> tiers;
  std::string motor_rating;  // "catalog", "... estimated from the mass (assumed)", ...
};

// Fills result->range: the objective re-solved under the pessimistic, optimistic and as-given
// scenarios (three more MissionEvaluator::Solve runs; the search calls it for its top N only).
void AddObjectiveRange(const Mission& mission, const Combination& combination, MissionResult* result);

}  // namespace dynosize
