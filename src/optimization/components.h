// The propulsion components' masses, the one place that decides them for the evaluator
// (mission_eval.cc) and the search's bounds (search.cc): the catalog's mass_kg, or an assumed
// law when the catalog has none (the result then lists the key as assumed).
//
//  - propeller: 14 g for a 10-inch hobby propeller (APC 10x4.5 MR: 14 g; datasheet), scaled as
//    D^2.5 (between area and volume scaling);
//  - ESC: 5 g + 1 g per A of continuous rating (hobby ESCs: 30 A ~ 25-35 g); 30 A when the
//    rating is missing too;
//  - motor: none is assumed: a motor without mass_kg cannot fly a mission (the evaluator
//    refuses it, the search leaves it out and counts it).
#pragma once

#include "battery/battery.h"
#include "catalog/catalog.h"
#include "mission/mission.h"

namespace dynosize {

struct ComponentMass {
  double kg = 0.0;
  bool assumed = false;  // from the law above, not from the catalog
};

double AssumedPropMassKg(double diameter_m);
double AssumedEscMassKg(double max_current_a);

// Thermal resistance winding-to-air of a hobby outrunner in its propeller's wash, K/W, when
// the catalog has none: 1.5 K/W at 100 g, scaled as mass^(-2/3) (the cooled surface grows as
// mass^(2/3)). The anchor: a 100 g motor at its rated power loses about 15 % of, say, 400 W
// (60 W), and hobby ratings sit near a 90 K rise; an ASSUMPTION to replace by a measured value
// (diagnose fits rth_k_per_w from a log with temperatures).
double AssumedMotorRthKPerW(double motor_mass_kg);

ComponentMass PropMass(const PropEntry& prop);
ComponentMass EscMass(const EscEntry& esc);
inline double PropMassKg(const PropEntry& prop) { return PropMass(prop).kg; }
inline double EscMassKg(const EscEntry& esc) { return EscMass(esc).kg; }

// A propeller's speed limit in a mission, rpm: its max_rpm ("prop_max_rpm") and the mission's
// tip Mach limit ("prop_tip_mach": rpm = 60*M*a/(pi*D), a = sqrt(1.4*287.05 J/(kg K) * T) at the
// mission's air temperature), the lower; +inf with rule null when neither applies. The one
// rule the evaluator and the search's bounds (R2) both read.
struct PropSpeedLimit {
  double rpm;
  const char* rule;
};
PropSpeedLimit PropSpeedLimitOf(const Mission& m, const PropEntry& prop);

// The mission's pack of `cells_series` cells in series from a catalog battery entry (a multiple
// of the entry's cells_series), with the mission's units in parallel and pack mass factor
// (mission.h MissionBattery): the one place the evaluator and the search build it.
BatteryPackParams MissionPackParams(const MissionBattery& battery, const BatteryEntry& entry,
                                    int cells_series);

}  // namespace dynosize
