// A mission: the vehicle without its propulsion, the air, the battery to use, the design
// constraints, the objective and the flight segments. Read from a JSON file (docs/missions.md) by a strict
// reader: unknown keys, wrong types, out-of-range values and inconsistent
// choices are DataError (exit 65) naming file, JSON path, value and rule.
//
// All values SI inside (kg, m, s, W, N*m, rad/s); rpm only at the JSON edge ("rpm" keys).
#pragma once

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/json_file.h"
#include "rotor/family.h"

namespace dynosize {

enum class SegmentType { kHover, kClimb, kCruise, kShaft };
const char* SegmentTypeName(SegmentType type);

// Whose lift-to-drag ratio a wing-borne cruise states (segment key "lift_to_drag_of"):
//  - kAircraft ("aircraft", the default): the whole aircraft in its cruise configuration, the
//    body included (the figure a designer quotes for the airframe); only the stopped rotors of
//    the idle groups (idle_drag_area_m2) are added.
//  - kWing ("wing"): the wing alone; the body's drag_area_m2 is added as well.
enum class LiftToDragOf { kAircraft, kWing };

// A closed interval; lo == hi for a fixed value.
struct Range {
  double lo = 0.0;
  double hi = 0.0;
  bool free() const { return hi > lo; }
};

struct Segment {
  std::string name;
  SegmentType type = SegmentType::kHover;
  // Exactly one of duration_s and distance_m is given in the file. For climb the distance is
  // the height change (|rate| * time), for cruise the ground distance (airspeed * time).
  std::optional<double> duration_s;
  std::optional<double> distance_m;
  double climb_rate_m_s = 0.0;  // climb: > 0 up, < 0 down (a descent)
  Range airspeed_m_s;           // cruise: fixed or free within bounds
  // cruise with a wing (lift + cruise): the wing carries the weight and the flow is axial;
  // 0 = no wing (a multirotor tilts into the wind). The thrust is W/(L/D) plus the drag the
  // ratio does not hold (mission/flight.h): the idle groups' idle_drag_area_m2 always, and the
  // body's drag_area_m2 when lift_to_drag_of is kWing.
  double lift_to_drag = 0.0;
  LiftToDragOf lift_to_drag_of = LiftToDragOf::kAircraft;
  int rotors_active = 0;  // rotors that thrust in this segment; 0 = all of its group's
  // The propulsion group that flies it (index into Mission::groups; 0 without groups).
  int group = 0;
  std::string group_name;  // as written ("" without groups)
  // shaft: per-motor shaft power or torque (one of them) and the speed range.
  std::optional<double> shaft_power_w;
  std::optional<double> shaft_torque_nm;
  Range shaft_omega_rad_s;
};

struct Vehicle {
  double mass_kg = 0.0;  // without motors, ESCs, propellers, battery
  int rotors = 4;
  bool coaxial = false;        // rotors in coaxial pairs (rotors must be even)
  double drag_area_m2 = 0.0;   // reference area of the body drag, m^2 (0: no drag)
  double drag_coefficient = 0.0;
  double avionics_power_w = 0.0;  // drawn from the battery throughout
  // The largest propeller the frame takes (arm length, rotor spacing); no limit when absent.
  std::optional<double> max_prop_diameter_m;
  // Without "propulsion" groups, the one searched group's sized propellers and propeller
  // sizing, as PropulsionGroup's below.
  std::vector<PropSize> sized_props;
  std::optional<std::vector<PropSizing>> prop_sizing;
};

// A propulsion group (mission key "propulsion"): rotors that share one motor, ESC and
// propeller type, e.g. the lift rotors and the pusher of a lift + cruise aircraft. The battery
// is shared; every group's mass counts in every segment.
struct PropulsionGroup {
  std::string name;
  int rotors = 1;
  std::optional<double> max_prop_diameter_m;  // the frame's largest propeller for this group
  // Body drag area added (x vehicle.drag_coefficient) while no segment flies on the group
  // (stopped lift rotors in cruise), m^2.
  double idle_drag_area_m2 = 0.0;
  std::string motor_id, esc_id, prop_id;  // all three given: the group is fixed; none: searched
  bool fixed() const { return !motor_id.empty(); }
  // Propellers from their size alone (rotor/family.h, importers/sized_prop.h): "sized_props"
  // offered to a searched group beside the catalog's, or a fixed group's "prop" given as
  // {"param": "DxP[xB]", "family": F} (then prop_id is its SizedPropId). The catalog a mission
  // runs on holds their entries (api/mission_catalog.h, CatalogForMission).
  std::vector<PropSize> sized_props;
  // "prop_sizing" (a searched group): families whose size the search chooses, each a diameter
  // range (and pitch ratio range and blade counts) laid on rotor/family.h's SizingGrid. Absent:
  // the catalog's prop_families within the group's max_prop_diameter_m (none without one);
  // an empty list: none. OfferedSizes gives the sizes.
  std::optional<std::vector<PropSizing>> prop_sizing;
};

struct MissionBattery {
  std::vector<std::string> ids;  // catalog battery entries (cells or packs) to choose from
  int cells_min = 1, cells_max = 1;  // cells in series (a multiple of the entry's cells_series)
  std::optional<Range> capacity_ah;  // size the capacity within this range (mass scales with it)
  double reserve_soc = 0.2;          // state of charge that must remain at the end
  std::optional<double> cutoff_cell_v;  // under-load cut-off per cell; default per chemistry
  // Catalog units in parallel (a Li-ion cell entry: the pack's capacity is cells_parallel x the
  // cell's); capacity_ah, when given, still sizes the capacity about it.
  int cells_parallel = 1;
  // The pack's mass over its units' mass (structure, BMS, wiring, cooling): 1 = the catalog
  // unit's mass as stated (a finished pack). Any other value needs mass_factor_source.
  double mass_factor = 1.0;
  std::string mass_factor_source;
};

// The largest pack voltage a mission may ask for, V, and so the most cells in series at the
// lithium cells' 4.2 V full charge (floor(1000/4.2) = 238): the 800 V class of eVTOL buses
// with room above it.
inline constexpr double kMaxPackVoltageV = 1000.0;
inline constexpr int kMaxCellsSeries = 238;

struct MissionConstraints {
  double max_throttle = 0.8;         // control authority: hover/climb throttle at most this
  // Speed-control resolution: in hover segments the throttle at the full-charge voltage (no
  // sag: the lowest the hover can need) at least this; 0 = no limit. The catalog ESCs' assumed
  // C1, C0 are the ideal ESC's (no low-throttle switching loss), which otherwise favours big
  // propellers on high-Kv motors at 10-15 % hover throttle.
  double min_hover_throttle = 0.0;
  double current_margin = 0.1;       // currents <= (1 - margin) * rating (motor, ESC, battery)
  bool allow_esc_saturation = false; // throttle above the ESC's tr_sat is allowed
  bool enforce_motor_power = true;   // PAC <= the motor's max_power_w when rated
  // Propeller data whose figure of merit P_ideal/P (momentum theory) exceeds this are not
  // credible: such points fail "prop_figure_of_merit" (optimization/mission_eval_flight.cc).
  // At rest, and static-only data in any inflow: max_figure_of_merit (0.8, the round-up of the
  // static envelope's 0.753). In axial inflow read from forward-flight data:
  // max_axial_figure_of_merit (0.95, the round-up of the 0.937 UIUC's measured sweeps reach;
  // docs/model.md section 11), never below the static one. FigureOfMeritLimit picks.
  double max_figure_of_merit = 0.8;
  double max_axial_figure_of_merit = 0.95;
  // Propeller tip Mach number in hover (pi*D*n over the speed of sound at the mission's air
  // temperature) at most this: "prop_tip_mach". 0.7: the largest measured propellers of the
  // catalog (KDE's 24.5-30.5 in sheets) reach 0.60-0.63, and thin propeller sections approach
  // their drag-divergence Mach number above it (docs/missions.md, "Propeller tip Mach"); 0 = not
  // checked.
  double max_tip_mach = 0.7;
  // Propellers with static data only may fly at advance ratios J = V/(n*D) up to this.
  double max_static_advance_ratio = 0.2;
  // Full-throttle static thrust of the lift rotors over the weight, at the lowest pack voltage
  // of the mission with the sag at that current (docs/missions.md: ArduPilot's mixer gives up
  // altitude for attitude below 2, ArduPilot PR #23512). Checked when the mission lifts the
  // vehicle on its rotors (a hover or climb segment); 0 = not checked.
  double min_thrust_to_weight = 2.0;
  // Steady winding temperature in every segment at most this, C (hobby motors' enamel wire of
  // thermal class 130, IEC 60085, less a 10 K hot-spot allowance); optimization/mission_eval.h.
  double max_winding_temp_c = 120.0;
  // Folding propellers (optimization/credibility.h) may lift a multirotor only when true.
  bool allow_folding_props_for_lift = false;
  // The propeller's speed window around its data (docs/ranking.md): in every
  // propeller segment the speed is at least prop_below_data_factor x the low edge of the
  // propeller's valid range and at most prop_above_data_factor x its high edge
  // (catalog/prop_credibility.h, ValidRange); beyond, the data do not rank a combination, which
  // fails "prop_below_data" / "prop_above_data" (the bottom is not checked in a descent: the
  // rotors unload for a landing). 0 = not checked. Below the data the model
  // corrects the coefficients for the Reynolds number (catalog/prop_reynolds.h), fitted and
  // checked on UIUC's tables down to 0.6x their lowest speed.
  double prop_below_data_factor = 0.6;
  double prop_above_data_factor = 1.5;
  // Motors without a current or power rating: a power rating estimated from the mass
  // (true, "estimate") or left out ("exclude"); optimization/credibility.h.
  bool estimate_unrated_motors = true;
};

// The figure-of-merit limit of a rotor point whose data are read at axial inflow
// judged_inflow_m_s (0 at rest, and for static-only data, which are held to the static bound):
// max_figure_of_merit at rest, the larger of it and max_axial_figure_of_merit in axial flow
// (docs/model.md section 11). It does not fall as the inflow rises, so the limit at a range's
// largest inflow is at least that of every point of the range.
inline double FigureOfMeritLimit(const MissionConstraints& k, double judged_inflow_m_s) {
  return judged_inflow_m_s > 0 ? std::max(k.max_figure_of_merit, k.max_axial_figure_of_merit) : k.max_figure_of_merit;
}

enum class ObjectiveType { kMaxEndurance, kMinEnergy, kMaxEfficiency };

// The data a combination is flown on (optimization/credibility.h): the credible value (the
// default ranking), the catalog's data as given, or the pessimistic/optimistic ends of the
// data-uncertainty model (objective_range). Files choose "credible" or "as_given".
enum class DataScenario { kCredible, kAsGiven, kPessimistic, kOptimistic };
const char* ObjectiveTypeName(ObjectiveType type);

struct Objective {
  ObjectiveType type = ObjectiveType::kMaxEndurance;
  // max_endurance: the segment whose duration is stretched until the battery reaches its
  // reserve (hover or cruise; default: the last hover segment). max_efficiency: the segment
  // whose energy-weighted system efficiency is maximised.
  std::string segment;
  int segment_index = -1;  // resolved by the reader
  // "ranking": what the search ranks and evaluate reports as the objective.
  DataScenario ranking = DataScenario::kCredible;
};

struct Mission {
  std::string file;  // where it was read from ("" when built in code)
  std::string name;
  Vehicle vehicle;
  double rho_kg_m3 = 1.225;
  double air_temperature_c = 15.0;  // ambient of the motors' thermal model (ISA sea level)
  MissionBattery battery;
  MissionConstraints constraints;
  Objective objective;
  std::vector<Segment> segments;
  // Empty without a "propulsion" key: one implicit group of vehicle.rotors rotors and
  // vehicle.max_prop_diameter_m. With it, vehicle.rotors is the sum of the groups' rotors.
  std::vector<PropulsionGroup> groups;
};

inline int GroupCount(const Mission& m) { return m.groups.empty() ? 1 : static_cast<int>(m.groups.size()); }
inline int GroupRotors(const Mission& m, int g) { return m.groups.empty() ? m.vehicle.rotors : m.groups[g].rotors; }
inline std::optional<double> GroupMaxPropDiameterM(const Mission& m, int g) {
  return m.groups.empty() ? m.vehicle.max_prop_diameter_m : m.groups[g].max_prop_diameter_m;
}
inline std::string GroupName(const Mission& m, int g) { return m.groups.empty() ? "" : m.groups[g].name; }
// The sizes offered to group g beside the catalog's propellers (PropulsionGroup::sized_props,
// or Vehicle's without groups); a fixed group's one is its own "prop".
inline const std::vector<PropSize>& GroupSizedProps(const Mission& m, int g) {
  return m.groups.empty() ? m.vehicle.sized_props : m.groups[g].sized_props;
}
inline const std::optional<std::vector<PropSizing>>& GroupPropSizing(const Mission& m, int g) {
  return m.groups.empty() ? m.vehicle.prop_sizing : m.groups[g].prop_sizing;
}
// The sized propellers searched group g is offered beside the catalog's (issue 52 item 5): its
// sized_props, then the grid (rotor/family.h SizingGrid) of each family of its prop_sizing or,
// without that key, of `catalog_families` (Catalog::prop_families) within its
// max_prop_diameter_m (none without one: a frame with no limit is not offered 4 m rotors by
// default). Each id once, in that order; a fixed group's is its sized "prop" (if any). The one rule for
// api::MissionCatalog (which builds their entries) and the search (which offers each group its own).
std::vector<PropSize> OfferedSizes(const Mission& m, const std::vector<PropSizing>& catalog_families, int g);

// Reads and checks a mission file: NoInputError when missing, DataError (one line: file, JSON
// path, value, rule) when anything is wrong.
Mission ReadMission(const std::string& path);
// Same for a parsed document; `name` is used in messages.
Mission ParseMission(const Json& doc, const std::string& name);

// The objective in the unit reports print it in (minutes, Wh, %), and that unit (" min", " Wh",
// " %").
double DisplayObjective(const Mission& mission, double objective);
const char* DisplayUnit(const Mission& mission);

}  // namespace dynosize
