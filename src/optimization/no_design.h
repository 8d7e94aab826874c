// When nothing flies, say why (issue 51 item 5): the requirements of a mission that no part, or
// no motor + propeller pair, of the catalog meets on its own, each with what the mission needs
// (a lower bound) and the best the catalog has (an upper bound), so that needed > best_available
// proves the requirement out of the catalog's reach. Each check is independent of the others and
// of the search; the search (search.h) runs them when it finds no combination, and the CLI, the
// sweep rows and the Python module print what it returns. No I/O.
//
// The vehicle is taken at its lightest: m_min = vehicle.mass_kg + the lightest pack of the
// mission's battery options + per rotor of every group the lightest motor (with a mass),
// propeller (that fits the frame) and ESC of the catalog (or the group's fixed parts); the
// thrust a rotor of the lift group (mission/flight.h, LiftGroup) gives in hover is at least
// T = m_min*g/N, N the most rotors any of its hover or climb segments thrusts with (LiftRotors).
// Propulsion groups other than the lift group are checked for the controller voltage only.
//
// The requirements (needed vs best_available, unit):
//   controller_voltage   the lowest full-charge OCV of the mission's packs vs the highest
//                        vdc_max_v of the ESCs (R1, docs/search.md#r1; rule esc_voltage), V.
//   controller_min_voltage  the lowest vdc_min_v of the ESCs vs the highest cut-off voltage of
//                        the packs, which every flight ends near (R1; rule esc_voltage, the
//                        evaluator's esc_min_voltage), V.
//   motor_voltage        the same OCV vs the highest voltage rating of the motors (cells_max x
//                        4.2 V; rule motor_voltage), V.
//   frame_prop_diameter  the smallest propeller of the catalog that is not excluded (nor folding
//                        for lift) vs the frame's max_prop_diameter_m (R0; rule prop_diameter), m.
//   hover_thrust_per_rotor  T vs the largest static thrust any motor + propeller pair can give
//                        at the hover-throttle limit (max_throttle, and the ESC's knee when
//                        saturation is not allowed) on the packs' highest full-charge OCV: per
//                        pair the first speed of the propeller's grid (monotone, M1) where a
//                        zero-resistance ESC of any class already needs more throttle, or the
//                        motor more current or power than rated (R3, docs/search.md#r3, M2),
//                        or the propeller turns above its max_rpm (R2) or its data window's top
//                        (R12); the thrust there bounds every feasible hover point, N (the
//                        largest grid thrust up to there: for the few propellers whose grid
//                        thrust does not rise with speed, M1, a bound on the grid's points only).
//   motor_power_per_rotor  the momentum-theory hover power of T on the largest propeller that
//                        fits, over the figure-of-merit limit: P = T^1.5/sqrt(2*rho*A)/FM_max
//                        (docs/model.md section 11; FM_max the mission's max_figure_of_merit,
//                        which the evaluator holds every point to), vs the most shaft power
//                        any motor gives within its ratings on the pack's highest voltage: the
//                        least of its power rating (PAC >= shaft power), (KT/KE)*U*(1 -
//                        current_margin)*I_max from its current rating and the highest ESC
//                        rating, and (KT/KE)*U^2/(4*Rm), the maximum-power point, with U =
//                        kv*VDC (docs/model.md eqs 12, 42, 48; rules motor_power,
//                        motor_current, esc_current), W.
//   propeller_diameter   the diameter whose hover power at FM_max the most powerful motor can
//                        give, D = sqrt(4/pi * T^3/(2*rho*(FM_max*P_max)^2)) (the same equation
//                        solved for the disk area A), vs the largest propeller that fits, m.
//   pack_energy          the energy of the segments the objective does not stretch: hover and
//                        climb at T per rotor (climb in axial inflow V: P_ideal =
//                        T*(V/2 + sqrt(V^2/4 + T/(2*rho*A))), FM_max the axial limit,
//                        docs/model.md section 11) with no drive loss, plus the avionics over
//                        every such segment at its shortest (cruise: at its highest airspeed;
//                        descents and cruise add no rotor power, as forward flight can need
//                        less than hover), vs the most any pack option holds above the reserve,
//                        Q_max * integral of OCV over [reserve, 1] (R4, docs/search.md#r4), J.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "optimization/unmet_requirement.h"

namespace dynosize {

// The requirements above that nothing in the catalog meets, in the order listed (empty when
// each is met by some part; the parts may still fail together). UsageError as SearchCatalog
// when no battery option fits.
std::vector<UnmetRequirement> UnmetRequirements(const Mission& mission, const Catalog& catalog);

// A value of `unit` for people: 4 significant digits (no exponent: whole units from 1000 up),
// energy in Wh ("368.4 N", "20904 W", "300.5 Wh").
std::string RequirementValueText(double value, const std::string& unit);

// One line: "hover_thrust_per_rotor: needs at least 368.4 N, the catalog's best gives at most
// 68.42 N (MOTOR, PROP): <description> [search rule throttle, ...]"; with the search's counts
// (SearchResult::pruned_by) the rules end it with what each pruned ("[the search's rules
// pruned: throttle 13662186, ...]"). Energy is printed in Wh.
std::string UnmetRequirementText(const UnmetRequirement& r,
                                 const std::map<std::string, long long>* pruned_by = nullptr);

}  // namespace dynosize
