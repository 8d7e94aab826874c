// R7 and R6 as floors of the vehicle's mass (docs/search.md#mass-floors): a segment
// flown on a given propeller can pass the evaluator's static-advance-ratio and figure-of-merit
// rules only at a vehicle at least this heavy. Shared by the joint search's outer group
// (JointBounds::MassFloorKg) and the one-group search's fixed groups (SearchContext's
// fixed_mass_floor_kg, FixedGroupPowerBounds).
#pragma once

#include "catalog/entries.h"
#include "mission/mission.h"
#include "prop/prop_model.h"

namespace dynosize::search_internal {

// What SegmentMassFloorKg found: the floor (kg; 0 when nothing is proven, +inf when no mass
// passes) and the rule that sets it (null with a floor of 0).
struct MassFloor {
  double kg = 0.0;
  const char* rule = nullptr;
};

// The lightest vehicle that may fly segment sg on propeller p (`model` its data, `monotone` its
// static grid's thrust rising with speed, M1) without breaking R7 (static-only data beyond
// max_static_advance_ratio: prop_no_forward_flight_data) or R6 (prop_figure_of_merit at a fixed
// axial inflow), scanning R6's mass cells up from mass_min_kg (the lightest vehicle the search
// allows). Every score bound read at a mass of at least the floor stays a bound (M3).
MassFloor SegmentMassFloorKg(const Mission& m, const Segment& sg, const PropEntry& p, const PropModel& model,
                             bool monotone, double mass_min_kg);

}  // namespace dynosize::search_internal
