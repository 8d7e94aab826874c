// The catalog search for a mission with several free propulsion groups (G2, docs/search.md#g2):
// each group picks its own motor, ESC and propeller; the battery and its cells are shared.
// An outer best-first loop over one group's (motor, ESC, propeller, battery option) choices,
// with a proven lower bound of every completion's score (rule G2, stated with R0-R11 and G1 in
// docs/search.md#g2), and for each outer choice that can still beat the N-th best the
// search with that group fixed and the N-th best as its cutoff (the one-group search of
// search_stages.h, or this search again when more than two groups are free). Internal to
// src/optimization (and its tests); SearchCatalog calls it.
#pragma once

#include <cstdint>
#include <deque>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "catalog/catalog.h"
#include "mission/flight.h"
#include "mission/mission.h"
#include "model/drive.h"
#include "optimization/prop_bounds.h"
#include "optimization/search_options.h"
#include "optimization/search_result.h"
#include "optimization/search_stages.h"

namespace dynosize {

// How many groups optimize chooses parts for: those without motor/esc/prop (1 for a mission
// without "propulsion": its one implicit group).
int FreeGroupCount(const Mission& m);

namespace search_internal {

// G2's order: while no N-th best is known, an inner search that has not finished after this many
// solves is put back (an outer choice that no completion makes feasible would otherwise search
// the whole inner group without a cutoff: 18 s each on the full catalog's quadplane).
inline constexpr long long kFirstSearchBudget = 5000;

// The exact top N (opt.top_n) among the combinations scoring below `cutoff`, over the joint
// choice of every free group's motor, ESC and propeller and the battery option. Needs
// FreeGroupCount(m) >= 2. The results' objective ranges are not computed (the caller's).
// first_search_budget: kFirstSearchBudget (the tests set another, to put inner searches back).
// dive: with two free groups and no cutoff, a good design first (docs/joint-search.md#dive)
// before every outer pair is bounded; the answer does not depend on it, only the order of the
// work (the tests turn it off to follow the loop's own order).
SearchResult JointSearch(const Mission& m, const Catalog& cat, const SearchOptions& opt,
                         double cutoff = std::numeric_limits<double>::infinity(), PropGridCache* cache = nullptr,
                         long long first_search_budget = kFirstSearchBudget, bool dive = true);

// The inner frontier's floors as JointBounds keeps them per level: 16-bit codes, a float's
// exponent (from 2^0 to 2^30 J) and the top 11 bits of its mantissa, truncated, so that each
// code's energy is at or below the floor it stands for (relative step 2^-11); code 0: no floor
// (-inf, and every floor below 1 J), kFloorCodeInf: +inf. Half a float's memory.
inline constexpr std::uint16_t kFloorCodeInf = 65535;
std::uint16_t CodeOfFloor(double e);
double FloorOfCode(std::uint16_t code);
// The least code whose energy is at least e: a floor below e has a code below it.
std::uint16_t LeastCodeAtOrAbove(double e);

// A rotor's speed and torque at or below those of any point that gives the segment's thrust
// (M1: bisection on the propeller's thrust at the segment's axial airspeed; the torque of the
// mission's data scenario, credibility.h). omega 0 when no bound applies.
struct RotorBound {
  double omega_rad_s = 0, torque_nm = 0;
  double thrust_n = 0, axial_airspeed_m_s = 0;  // the segment's per-rotor load
  int rotors = 0;
};
RotorBound RotorLowerBound(const Mission& m, const Segment& sg, const PropEntry& prop, const PropModel& model,
                           double mass_kg);

// G1/G2 for one segment: a lower bound of its terminal power (W, the avionics included) when
// flown by `drive` (its motor's scenario parameters mp) on `rb`'s propeller at vehicle mass >=
// the mass rb was computed at; and the rule that makes the segment infeasible whatever else
// is chosen (R3 at the bound point with the drive at the pack's full-charge voltage), or null.
struct SegmentBound {
  double power_w = 0;
  const char* infeasible = nullptr;
  double irms_lb_a = 0;  // the motor's Irms at the bound point (R3's ESC-current rule)
};
SegmentBound SegmentPowerBound(const Mission& m, std::size_t si, const GroupParts& parts, const MotorParams& mp,
                               const Drive& drive, double tr_max, double esc_max_current_a, const PropModel& model,
                               const BatteryOption& bo, double mass_kg, const RotorBound& rb);

// SegmentPowerBound's part for a free-airspeed cruise (R7 over the range, then momentum theory
// at mass_kg); with_power false: R7 only, power_w the avionics' alone.
SegmentBound FreeCruiseSegmentBound(const Mission& m, std::size_t si, const GroupParts& parts, const Drive& drive,
                                    const PropModel& model, const BatteryOption& bo, double mass_kg, bool with_power);

// R4's assembly from per-segment terminal power bounds (W, avionics included, by segment):
// min_energy the sum of power x shortest duration, max_endurance the energy budget of the
// largest pack; -inf when no bound applies (max_efficiency, a stretched free-airspeed cruise).
double ScoreFromSegmentPowers(const Mission& m, const std::vector<double>& p_lb_w, const BatteryOption& bo);

// G2's bounds for one mission: the outer group, and per battery option the lightest vehicle
// and the other groups' per-segment power bounds (fixed groups: their drives; other free
// groups: the least over their choices that survive R0, R1, R3).
class JointBounds {
 public:
  JointBounds(const Mission& m, const Catalog& cat, const PropGridCache& cache);
  int outer_group() const { return outer_; }
  const std::vector<BatteryOption>& options() const { return options_; }
  const EscTable& escs() const { return escs_; }
  // The lightest vehicle with option o (every free group at its lightest), kg.
  double mass_min_kg(std::size_t o) const { return mass_min_kg_[o]; }
  // The outer group's and (two free groups) the inner group's lightest with option o, kg.
  double outer_lightest_kg(std::size_t o) const { return outer_lightest_kg_[o]; }
  double inner_lightest_kg(std::size_t o) const { return o < inner_lightest_kg_.size() ? inner_lightest_kg_[o] : 0.0; }
  // The power bound of a segment the outer group does not fly (W; +inf: no choice of its
  // group survives R0, R1, R3 with option o).
  double other_power_w(std::size_t o, std::size_t si) const { return other_power_w_[o][si]; }
  // The energy every completion of an outer choice spends outside the inner group, from below
  // (the coupled stage's; docs/search.md#g2-inner-filter), J: the other groups' segments, and
  // the outer group's by vehicle mass. valid false when the coupled stage did not apply (the
  // bound ended before it, or no inner group).
  struct OuterEnergy {
    bool valid = false;
    double raw_kg = 0;  // the choice's lightest vehicle (the inner group at its lightest), kg
    double rest_j = 0;  // the segments of neither group
    // (vehicle kg, the outer segments' energy at every vehicle at least that heavy), kg rising
    // from the choice's lightest (R7's floor included): at floor and at G1's grid masses above.
    std::vector<std::pair<double, double>> outer_j_by_kg;
  };
  // Lower bounds of the score of every combination that flies the outer group on (motor,
  // prop) with option o: with any ESC of class esc_class (PairBound), or with ESC esc
  // (TripleBound). +inf and *why set when no such combination can be feasible. irms_lb: the
  // motor's Irms lower bound over the group's segments (R3's ESC-current rule). outer_energy
  // (optional): the choice's OuterEnergy (coupled only), for InnerPairsBelow.
  double PairBound(int motor, int prop, std::size_t o, int esc_class, const char** why, double* irms_lb,
                   OuterEnergy* outer_energy = nullptr);
  // G2's inner filter (docs/search.md#g2-inner-filter): with outer_energy from PairBound for an
  // outer choice with option o, marks in *allowed (motor * props + propeller, 1) the inner
  // group's (motor, propeller) pairs whose energy floor (InnerFrontier's, at a level at or below
  // the choice's) leaves its completions a score below cutoff; every other pair has none below
  // it. False (and *allowed untouched) when no floors apply.
  bool InnerPairsBelow(std::size_t o, const OuterEnergy& outer_energy, double cutoff, std::vector<char>* allowed) const;
  double TripleBound(int motor, int esc, int prop, std::size_t o, const char** why, OuterEnergy* outer_energy = nullptr);
  // With two free groups and min_energy: tighten PairBound and TripleBound by the coupled bound
  // (the inner group's frontier of mass and energy; docs/search.md#g2). Off by default (it costs
  // more per call): the search turns it on for the pairs it takes.
  void set_coupled(bool on) { coupled_ = on; }
  std::size_t frontier_size(std::size_t o) const { return o < frontier_.size() ? frontier_[o][0].size() : 0; }
  // The coupled bound's frontier of the inner group (two free groups, min_energy) for option o
  // and an outer choice outer_extra_kg heavier than the outer group's lightest: (the inner
  // group's extra mass over its lightest, the least energy of its segments, J, at the vehicle
  // with that mass and the outer group kFrontierLevelStep-levels heavier, at or below
  // outer_extra_kg). Every feasible inner choice of such a completion has a point no heavier
  // with no more energy (docs/search.md#g2-levels). Empty without an inner group.
  struct FrontierPoint {
    double extra_kg;  // the inner group's mass over its lightest
    double energy_j;  // the least energy of its segments with that mass, J
  };
  const std::vector<FrontierPoint>& Frontier(std::size_t o, double outer_extra_kg);
  // The outer group's extra mass of level k of option o's frontier, kg (k * the step * the
  // option's lightest vehicle).
  double FrontierLevelKg(std::size_t o, int k) const { return k * kFrontierLevelStep * mass_min_kg_[o]; }
  static constexpr int kFrontierLevels = 48;         // levels of the outer group's extra mass
  static constexpr double kFrontierLevelStep = 0.01;  // a level's step, of the lightest vehicle
  static constexpr int kFrontierLevelReuse = 3;       // Frontier: a computed level this far below serves
  static constexpr int kKeptFloorLevels = 8;          // levels whose floors are kept, besides level 0
  // R0 for the outer group's propeller and motor (the rule's name, or null).
  const char* PropRule(int prop) const;
  const char* MotorRule(int motor, std::size_t o) const;

 private:
  double OuterBound(const Drive& drive, const GroupParts& parts, double esc_max_a, double tr_max,
                    int prop, std::size_t o, double mass_kg, const char** why, double* irms_lb,
                    OuterEnergy* outer_energy = nullptr);
  const RotorBound& OuterRotor(int prop, std::size_t si, std::size_t o, double mass_kg);
  // SegmentPowerBound for the outer group's segment si where the caller takes the larger of its
  // power and known_w (W, a bound of its own): a free cruise's momentum bound at mass_kg (a
  // walk over 33 samples) is left out when CruiseMomentumAboveW shows it at or below known_w,
  // so the larger is the same.
  SegmentBound OuterSegmentBound(std::size_t si, const GroupParts& parts, const Drive& drive, double tr_max,
                                 double esc_max_a, int prop, std::size_t o, double mass_kg, double known_w);
  // A free cruise's momentum bound (FreeCruisePowerLowerBoundW with a drive that cannot create
  // energy, the larger case) at the first grid mass at or above mass_kg (G1's grid,
  // RotorCacheIndex), so at or above the bound at mass_kg (M3: the thrust rises with the mass);
  // +inf above the grid's top. Cached per grid mass.
  double CruiseMomentumAboveW(int prop, std::size_t si, std::size_t o, double mass_kg);
  // The caches' index of (prop, si, o) at the grid mass at or below mass_kg (G1's geometric grid
  // from the option's lightest vehicle), and that grid mass (kg).
  std::size_t RotorCacheIndex(int prop, std::size_t si, std::size_t o, double mass_kg, double* grid_kg) const;
  // A free cruise's samples (prop_bounds.h, with points) at the grid mass at or below mass_kg,
  // kept per (prop, si, o, grid mass): they do not depend on the motor or the ESC.
  const FreeCruiseSamples& OuterCruise(int prop, std::size_t si, std::size_t o, double mass_kg);
  // The outer group's free cruise si on `prop` flown by `drive` at a vehicle of at least mass_kg:
  // a bound of its terminal power (W, the avionics included) from OuterCruise's samples: momentum
  // theory, and for a drive that cannot create energy the propeller's shaft power raised by the
  // motor's loss floor (LossFloorOf); with the coupled stage also the drive's PDC.
  double OuterCruiseFloorW(const Drive& drive, int prop, std::size_t si, std::size_t o, double mass_kg);
  // R10's charge and voltage for the outer group (docs/search.md#g2-voltage): with scratch_
  // holding every segment's terminal power bound, the rule (throttle, reserve_soc) that the
  // outer group's segments on `prop` flown by `drive` break at a vehicle of at least mass_kg
  // with the voltage the charge drawn by then leaves, or null.
  const char* VoltageLeftRule(const Drive& drive, int prop, std::size_t o, double mass_kg, double tr_max);
  std::vector<FrontierPoint> InnerFrontier(std::size_t o, int level);
  double MinFreeGroupPower(int group, std::size_t si, std::size_t o, double mass_kg);
  double MassFloorKg(int prop, std::size_t si, std::size_t o, double mass_kg);
  // The lightest motor + propeller of a free group that survives R0, R1, R3, R7 in every one of
  // its segments with some ESC class at vehicle mass vehicle_kg (kInf: none), kg per rotor.
  double LightestSurvivorKg(int group, std::size_t o, double vehicle_kg);
  bool ReachesThrustToWeight(int group, const Drive& drive, int prop, double vehicle_kg, std::size_t o) const;
  bool Lifts(int group) const { return group == lift_group_; }
  bool PropAllowed(int group, const PropEntry& p) const;

  const Mission& m_;
  const Catalog& cat_;
  SizedPropOffer offer_;  // which sized propellers each group may take (R0)
  std::vector<const PropModel*> models_;
  int outer_ = 0, lift_group_ = 0;
  int lift_rotors_ = 0;  // LiftRotors(m_), read per pair by ReachesThrustToWeight
  int inner_ = -1;  // the other free group when there are two and the objective is min_energy
  bool coupled_ = false;
  std::vector<double> cruise_floor_w_;  // OuterBound's scratch: per segment, a free cruise's bound
  // OuterBound's scratch for the frontier points: per free cruise, the cache index last read
  // and its bound.
  std::vector<std::size_t> cruise_point_at_;
  std::vector<double> cruise_point_w_;
  // [option][level] (Frontier's levels, computed when first asked; level 0 by the constructor).
  std::vector<std::vector<std::vector<FrontierPoint>>> frontier_;
  std::vector<std::vector<char>> frontier_done_;
  // InnerFrontier's inner (motor, propeller) pairs, motor * props + propeller, by motor +
  // propeller mass ascending (built on its first call).
  std::vector<std::uint32_t> inner_by_mass_;
  std::vector<float> inner_pair_kg_;  // their motor + propeller masses, kg (G2's inner filter)
  // [option][level] (empty: not computed), by position in inner_by_mass_: a lower bound of the
  // pair's energy (J; +inf: it fails a rule with every ESC class) at every level at or above
  // this one (docs/search.md#g2-levels), found at this level or the computed one below it. Kept
  // as 16-bit codes, each code's energy at or below the floor (joint_frontier.cc, CodeOfFloor).
  std::vector<std::vector<std::vector<std::uint16_t>>> inner_floors_;
  // The highest computed level at or below `level` of option o's floors (null: none).
  const std::vector<std::uint16_t>* FloorsAtOrBelow(std::size_t o, int level) const;
  // Frontier's level of an outer choice outer_extra_kg above the outer group's lightest: the
  // highest at or below it.
  int LevelOf(std::size_t o, double outer_extra_kg) const;
  // The inner group's (motor, propeller) pair of motor + propeller mass pair_kg (inner_pair_kg_)
  // with option o's lightest ESC, over the group's lightest, kg.
  double InnerExtraKg(std::size_t o, double pair_kg) const {
    const double esc_min = std::isfinite(escs_.min_mass_kg[o]) ? escs_.min_mass_kg[o] : 0.0;
    return m_.groups[static_cast<std::size_t>(inner_)].rotors * (pair_kg + esc_min) - inner_lightest_kg_[o];
  }
  std::vector<double> inner_lightest_kg_;             // per option
  std::vector<BatteryOption> options_;
  EscTable escs_;
  std::vector<double> mass_min_kg_, outer_lightest_kg_;
  std::vector<double> grid_kg_;  // [o * kFixedPowerMasses + k]: mass_min_kg_[o] * kFixedPowerMassStep^k
  // The cache's static grids per propeller (M1's monotone flag, ReachesThrustToWeight's thrust).
  const std::vector<PropGrid>* grids_ = nullptr;
  std::vector<double> mass_floor_kg_;  // MassFloorKg's cache by RotorCacheIndex; < 0: not yet
  std::vector<std::vector<double>> other_power_w_;
  std::vector<std::size_t> outer_segments_;
  // OuterRotor's cache: [((o * segments + si) * props + prop) * kFixedPowerMasses + k].
  std::vector<RotorBound> rotor_cache_;
  std::vector<char> rotor_done_;
  // OuterCruise's cache: per rotor_cache_ index, the entry in cruise_samples_ (-1: not yet).
  std::vector<int> cruise_index_;
  // CruiseMomentumAboveW's cache by RotorCacheIndex (NaN: not yet; empty without a free cruise
  // in the outer group).
  std::vector<double> cruise_momentum_w_;
  std::deque<FreeCruiseSamples> cruise_samples_;
  std::vector<PropAdjustment> adjustments_;  // per propeller, the ranking scenario's
  std::vector<double> scratch_;
  // LightestSurvivorKg's lists: the usable motors (kg, motor) and per group its propellers (kg,
  // propeller), ascending.
  std::vector<std::pair<double, int>> motors_by_mass_;
  std::vector<std::vector<std::pair<double, int>>> props_by_mass_;
};

}  // namespace search_internal
}  // namespace dynosize
