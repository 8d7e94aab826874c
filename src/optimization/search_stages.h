// The stages of the catalog search (one file each), each a function with its own test
// (tests/optimization/search_stages_test.cc):
//   1. BatteryOptions    (battery_options.cc) the (battery entry, cells in series) choices with
//                        their voltage, capacity and mass range and energy budget;
//   2. BuildEscTable     (esc_table.cc) ESC classes (same C1, C0, tr_sat, sat_slope) and, per
//                        battery option, the ESCs that pass R1 (voltage rating), lightest first;
//   3. BuildPropGrids    (prop_grids.cc) per propeller the static thrust, torque and figure of
//                        merit on a speed grid at the mission's density (R2, R6), and with
//                        forward-flight tables the thrust and torque in each fixed axial inflow
//                        (R10);
//   4. BuildCandidates   (pair_candidates.cc; how a pair is bounded: pair_bounds.cc,
//                        segmentwise_bound.cc) every (motor, propeller, battery option) pair
//                        that survives R0, R2, R3, R6, R7, with a lower bound of its score (R4,
//                        R11, R13); the search itself uses CandidateStream (candidate_stream.cc),
//                        which bounds a pair only when it may be drawn;
//   5. BranchAndBound    (branch_and_bound.cc) the pairs best bound first (CandidateStream),
//                        per ESC class R9 (hover throttle from above, per ESC), R10 (segment by
//                        segment) and the virtual ESC (R5), each remaining combination scored
//                        exactly by MissionEvaluator::Solve.
// Stages 0-3 into a SearchContext: search_context.cc; the fixed groups' power bounds (G1):
// fixed_group_bounds.cc. The entry (search.h, SearchCatalog) dispatches to SearchOneGroup or,
// with several free groups, to the joint search (joint_search.h); no stage includes it.
// The rules and their proofs: docs/search.md (anchors #m1, #r0 ... #g3). Internal to
// src/optimization (and its tests).
#pragma once

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "battery/battery.h"
#include "catalog/catalog.h"
#include "mission/mission.h"
#include "optimization/credibility.h"
#include "optimization/mass_floors.h"
#include "optimization/mission_eval.h"
#include "optimization/prop_bounds.h"
#include "optimization/search_options.h"
#include "optimization/search_result.h"
#include "prop/prop_model.h"

namespace dynosize::search_internal {

struct BatteryOption {
  const BatteryEntry* entry = nullptr;
  int cells = 0;
  double v_full = 0, v_cut = 0;  // full-charge OCV and cut-off of the pack, V
  double capacity_lo_ah = 0, capacity_hi_ah = 0, mass_lo_kg = 0, mass_hi_kg = 0;
  double max_current_hi_a = 0;
  double ocv_integral_v = 0;  // OcvIntegralUpperBound over [reserve, 1]
  BatteryChemistry chemistry = BatteryChemistry::kLiPo;
  double ri_at_hi_ohm = 0;  // the pack's resistance at capacity_hi_ah (the least, PackAt)
  double OcvV(double soc) const { return cells * CellOcvV(chemistry, soc); }  // as BatteryPack::OcvV
};

// Throws UsageError when no cell count in the mission's range fits any entry, DataError when an
// entry has no mass.
std::vector<BatteryOption> BatteryOptions(const Mission& m, const Catalog& cat);

struct EscClass {
  double c1 = 0, c0 = 0, tr_sat = 0, sat_slope = 0;
  std::vector<int> members;  // indices into Catalog::escs()
};

struct EscTable {
  std::vector<EscClass> classes;
  // [option][class]: the ESCs rated for the option's full-charge voltage and running at its
  // cut-off (R1), sorted by (mass, resistance, -current rating).
  std::vector<std::vector<std::vector<int>>> per_option;
  // [option][class], from per_option's lists: their current ratings in ascending order, and
  // the running maximum of the rating along the list (R3's count and its lightest passing ESC
  // by binary search).
  std::vector<std::vector<std::vector<double>>> currents_ascending, running_max_current;
  std::vector<double> min_mass_kg, max_mass_kg;  // per option over its ESCs (inf / 0 if none)
  std::vector<long long> rated;                  // per option: its ESCs that pass R0 and R1
  long long voltage_pruned = 0;                  // (option, ESC) pairs removed by R1
  long long excluded_pruned = 0;                 // (option, ESC) pairs the catalog excludes (R0)
};
EscTable BuildEscTable(const Catalog& cat, const std::vector<BatteryOption>& options);

// R5 (esc_table.cc, docs/search.md#r5): a dominates b (no heavier, no more resistance, no lower
// current or voltage rating; the caller compares ESCs of one class), and whether an infeasible
// result of the search's solve with a lets the search skip the ESCs a dominates.
bool EscDominates(const EscEntry& a, const EscEntry& b);
bool RulesOutDominatedEscs(const MissionResult& infeasible);

// The drive of a class with no ESC resistance: a lower bound of every member's throttle,
// currents and power at a point (M2, docs/search.md#m2).
inline EscParams ZeroResistanceEsc(const EscClass& c) {
  EscParams e;
  e.c1 = c.c1;
  e.c0 = c.c0;
  e.tr_sat = c.tr_sat;
  e.sat_slope = c.sat_slope;
  e.resc_ohm = 0.0;
  return e;
}

// The highest throttle a feasible point may have: max_throttle (at most 1) and, when
// saturation is not allowed, the ESC's knee.
inline double ThrottleLimit(const MissionConstraints& k, double tr_sat) {
  const double t = std::min(k.max_throttle, 1.0);
  return k.allow_esc_saturation ? t : std::min(t, tr_sat);
}

// R3 at a point from below (the drive's operating point `hi` there at the pack's full-charge
// voltage): the throttle, Irms and PAC of every real choice are at least these (M2: zero or the
// real ESC resistance, the highest voltage the pack can have). The rule whatever else is chosen
// breaks (throttle, motor_current, motor_power, esc_current), or null.
const char* DriveRule(const MissionConstraints& k, const MotorParams& mp, const OperatingPoint& hi, double tr_max,
                      double esc_max_current_a);
// The same rule from Drive::InverseLight's numbers at (torque_nm, omega_rad_s) and vdc_v
// (Inverse's bit for bit; the PAC computed only when the rule reads it).
const char* DriveRule(const MissionConstraints& k, const MotorParams& mp, const Drive& drive, double vdc_v,
                      const Drive::InverseCurrents& hi, double torque_nm, double omega_rad_s, double tr_max,
                      double esc_max_current_a);

// R2, R12's top and R3 over a wing-borne cruise's free airspeed range
// (docs/search.md#g1-torque-floor, #g2-free-cruise): every feasible point of the range is at or
// above the samples' floor point and, when their speeds and torques rise, their first point;
// a speed there above the speed limit fails the limit's rule, and `drive` there at the
// full-charge voltage v_full_v is at or below every feasible point (M2: throttle, Irms and PAC
// rise with the torque and the speed). The rule broken (DriveRule), or null; *irms_lb (if
// given) raised to the point's Irms.
const char* FreeCruiseRangeRule(const MissionConstraints& k, const Drive& drive, const FreeCruiseSamples& s,
                                 double v_full_v, double tr_max, double esc_max_current_a, double* irms_lb = nullptr);

// Which sized propellers of the catalog (rotor/family.h IsSizedPropId) each group is offered
// (mission.h OfferedSizes: its own sized_props and prop_sizing, or the catalog's families within
// its frame): a group searches only its own, so that one group's sizes are not another's.
class SizedPropOffer {
 public:
  SizedPropOffer() = default;  // offers every propeller (a context before ResolveGroups)
  SizedPropOffer(const Mission& m, const Catalog& cat);
  // True for every propeller that is not sized, and for the sized ones offered to `group`.
  bool Offered(int group, std::size_t prop) const {
    return offered_.empty() || offered_[static_cast<std::size_t>(group)][prop] != 0;
  }

 private:
  std::vector<std::vector<char>> offered_;  // [group][prop]
};

// R0 for propeller `prop` (an index into the catalog's) of `group` whatever the motor: a sized
// propeller not offered to the group, the frame's largest diameter, the catalog's exclusion, a
// folding propeller for lift (credibility.h); null when none applies.
const char* PropFrameRule(const Mission& m, const SizedPropOffer& offer, int group, bool lifts, const Catalog& cat,
                          std::size_t prop);

inline constexpr int kGrid = 256;
inline constexpr double kGridMinRadS = 30.0, kGridMaxRadS = kPropSpeedCeilingRadS;

// The thrust and torque of a propeller with forward-flight tables on the speed grid in a fixed
// axial inflow (a climb's rate, a wing-borne cruise's airspeed: R10).
struct InflowGrid {
  double v_m_s = 0;
  bool monotone = true;  // thrust strictly rising on the grid (M1 checked)
  double thrust[kGrid], torque_suffix_min[kGrid];
};

struct PropGrid {
  bool monotone = true;  // static thrust strictly rising on the grid (M1 checked)
  double omega[kGrid], thrust[kGrid], torque_suffix_min[kGrid];
  double torque_prefix_max[kGrid];  // largest grid torque at or below each speed (R9)
  double fom[kGrid];  // static figure of merit (R6)
  // R6 in O(1): the first grid index >= i whose figure of merit is within 1.02 x the mission's
  // max_figure_of_merit (kGrid when none): every point of [i, j] breaks it iff fom_ok_next[i] > j.
  int fom_ok_next[kGrid];
  double mass_kg = 0;
  // R12: the static thrust at the window's bottom (window_factor x the valid range's low edge)
  // of the mission the grid was built for; 0 when that mission does not check it.
  double window_factor = 0, window_thrust_n = 0;
  PropAdjustment adjustment;  // the scenario's (credibility.h), as the grids' torque has it
  // Forward-flight tables only: one grid per fixed axial inflow of the mission's segments
  // (InflowsOf), in its order; empty for static-only data (read at J = 0 in any inflow).
  std::vector<InflowGrid> inflow;
};

// The mission's fixed positive axial inflows, ascending: climb rates > 0 and the airspeeds of
// wing-borne cruises at a fixed airspeed (every group's segments: the grids are shared by the
// joint search's sub-missions).
std::vector<double> InflowsOf(const Mission& m);
// Grids and PropModels per catalog propeller (index as Catalog::props()).
void BuildPropGrids(const Mission& m, const Catalog& cat, std::vector<PropGrid>* grids,
                    std::vector<std::unique_ptr<PropModel>>* models);

struct Candidate {
  double bound = 0;  // lower bound of the score (smaller is better)
  int motor = 0, prop = 0, option = 0;
  double irms_lb = 0;  // lower bound of the motor's Irms in the first hover segment
};

// What the stages before the branch and bound share.
// The motors' stage-4 set-up kept between the one-group searches of the joint search, one
// entry per distinct set of what the set-up reads (motor_setup_cache.h).
struct MotorSetupCache {
  struct Entry;
  std::vector<std::shared_ptr<const Entry>> entries;
};

struct SearchContext {
  const Mission* mission = nullptr;
  const Catalog* catalog = nullptr;
  // Which sized propellers each group is offered (R0); built with the context.
  SizedPropOffer prop_offer;
  // Propulsion groups: the search chooses the parts of free_group; the others are fixed by the
  // mission (fixed_parts by group index, the free one's entry null; empty without groups).
  int free_group = 0;
  std::vector<GroupParts> fixed_parts;
  // Set before ResolveGroups: parts that replace fixed groups' catalog ids (SearchOneGroup).
  const std::vector<GroupParts>* given_parts = nullptr;
  double fixed_groups_mass_kg = 0;  // rotors x (motor + ESC + propeller) of the fixed groups
  int free_rotors = 0;              // GroupRotors(mission, free_group)
  // [option][k][segment]: a lower bound of a fixed group's segment's terminal power (its
  // rotors' PDC at vehicle mass fixed_power_mass_kg[option][k] plus the avionics;
  // FixedGroupPowerBounds), W; the masses rise from the lightest the vehicle can be. Empty
  // without groups.
  std::vector<std::vector<std::vector<double>>> fixed_power_lb_w;
  std::vector<std::vector<double>> fixed_power_mass_kg;
  // [option]: the fixed groups' R7 and R6 mass floor (mass_floors.h; FixedGroupPowerBounds): a
  // feasible combination's vehicle weighs at least fixed_mass_floor[o].kg (0: no floor, +inf:
  // no mass passes), else it breaks fixed_mass_floor[o].rule. Empty without groups.
  std::vector<MassFloor> fixed_mass_floor;
  // [option]: the fixed groups' mass ceiling (FixedGroupPowerBounds; docs/search.md#g1-torque-floor):
  // a vehicle of fixed_mass_ceiling[o].kg or more breaks fixed_mass_ceiling[o].rule (+inf with a
  // null rule: none). Empty without groups.
  std::vector<MassFloor> fixed_mass_ceiling;
  // PropModels of the fixed groups' propellers (by group index; null for the free group),
  // built once and shared by every evaluation.
  std::vector<std::unique_ptr<PropModel>> fixed_models;
  std::vector<const PropModel*> fixed_model_ptrs;
  std::vector<BatteryOption> options;
  EscTable escs;
  std::vector<PropGrid> grids;
  std::vector<std::unique_ptr<PropModel>> models;
  // Optional (SearchOneGroup with a PropGridCache): stage 4's motors set up once per key.
  MotorSetupCache* motor_setups = nullptr;
  // Optional (SearchOneGroup's pair_mask): the stream bounds only the pairs it marks.
  const std::vector<char>* pair_mask = nullptr;
};

// The vehicle's mass with a pack of pack_kg and each of the free group's rotors carrying a
// motor, propeller and ESC of these masses (the fixed groups' parts: fixed_groups_mass_kg).
inline double VehicleMassKg(const SearchContext& ctx, double pack_kg, double motor_kg, double prop_kg, double esc_kg) {
  return ctx.mission->vehicle.mass_kg + pack_kg + ctx.fixed_groups_mass_kg +
         ctx.free_rotors * (motor_kg + prop_kg + esc_kg);
}


// R4's energy budget for a stretched segment: the score bound -(t_fixed_max + what the budget
// leaves after the other segments, at the stretch's least power); -kInf without a power bound.
double BudgetScore(double t_fixed_max_s, double e_max_j, double e_other_j, double p_stretch_w);

struct CandidateList {
  std::vector<Candidate> candidates;  // unordered
  std::map<std::string, long long> pruned_by;
  long long skipped_without_mass = 0;
};
// Sets the group fields of ctx (ctx->mission and ->catalog set). DataError (the JSON path) when
// a fixed part is not in the catalog or when every group is fixed; std::logic_error when more
// than one is free (SearchCatalog gives those to the joint search, joint_search.h).
void ResolveGroups(SearchContext* ctx);

// Stages 0-3 into *ctx: mission and catalog, ResolveGroups, BatteryOptions, BuildEscTable and
// BuildPropGrids (the search then adds the fixed groups' power bounds and stages 4-5).
void PrepareStages(const Mission& m, const Catalog& cat, SearchContext* ctx);

// A wing-borne cruise of a group with a free airspeed: a power P_lb (W, avionics not
// included) with (P_lb + P_av) * SegmentDurationS(sg, hi) <= the segment's energy at every
// airspeed of its range, for the group's parts flying at vehicle mass >= mass_kg (prop_bounds.h
// FreeCruiseRotorPowerLowerBoundW; 0 when no bound applies). Without `drive` only momentum
// theory, for which the ESC's C1, C0 are read (its class); with it, also that drive's PDC
// (a class's zero-resistance drive bounds each of its ESCs, M2).
double FreeCruisePowerLowerBoundW(const Mission& m, const Segment& sg, const GroupParts& parts,
                                  const PropModel& model, double mass_kg, const CruiseDriveBound* drive = nullptr);

// R10 (segmentwise_bound.cc, docs/search.md#r10): a lower bound of the score of (motor, prop, option) with any ESC of class
// esc_class weighing at least esc_mass_kg, segment by segment (-kInf when none applies), or
// kInf with *rule naming the constraint that every such combination breaks. With a capacity
// range the pieces are refined while the bound is below `threshold` (kInf: as far as allowed).
double SegmentwiseBound(const SearchContext& ctx, int motor, int prop, int option, int esc_class, double esc_mass_kg,
                        double threshold, const char** rule, bool stop_when_unprovable = true);

// R9 (pair_bounds.cc, docs/search.md#r9): true when the hover throttle of (motor, prop, option) with this ESC is below
// the mission's min_hover_throttle at every mass and capacity, so the ESC fails that limit for
// the pair whatever else is chosen (false when the rule does not apply).
bool FailsHoverThrottleBound(const SearchContext& ctx, int motor, int prop, int option, const EscEntry& esc);

// R10's charge bound (docs/search.md#r10), and G2's voltage left before a segment
// (docs/search.md#g2-voltage): the charge a segment must draw, P_lb * t_min / v_full, is taken
// at this fraction of its value, against the evaluator's midpoint rule.
inline constexpr double kChargeAllowance = 1.0 - 1e-3;

// Fills ctx->fixed_power_lb_w, ctx->fixed_mass_floor and ctx->fixed_mass_ceiling (after stages
// 1-3 and ResolveGroups).
inline constexpr int kFixedPowerMasses = 64;
inline constexpr double kFixedPowerMassStep = 1.02;
void FixedGroupPowerBounds(SearchContext* ctx);
// The table's bound for segment si at a vehicle of at least mass_kg (option's grid point at or
// below it).
double FixedPowerLowerBoundW(const SearchContext& ctx, std::size_t option, std::size_t si, double mass_kg);

// Stage 4 on `threads` threads (motors interleaved; the list does not depend on timing once
// ordered by the branch and bound's total order).
CandidateList BuildCandidates(const SearchContext& ctx, int threads);

// R11 (pair_candidates.cc, docs/search.md#r11): the key of (prop, option) at the mass and loss floor of `motor` (whose
// drives must not be able to create energy): a lower bound of the score of every combination
// of that motor with them (-kInf when none applies).
double PropellerKeyBound(const SearchContext& ctx, int prop, int option, int motor);

// The branch and bound's total order of candidates: best bound first, then option, motor and
// propeller (a strict total order, so the sequence is unique).
bool CandidateBefore(const Candidate& a, const Candidate& b);

// Propeller grids and models kept between the one-group searches of the joint search (they
// depend on the mission's air, ranking and figure-of-merit limit only, which its sub-missions
// share), and the motors' stage-4 set-up (by what it reads, motor_setup_cache.h).
struct PropGridCache {
  bool built = false;
  std::vector<PropGrid> grids;
  std::vector<std::unique_ptr<PropModel>> models;
  MotorSetupCache motor_setups;
};
// Stages 0-5 for a mission with exactly one free group: its exact top N among the results
// scoring below `cutoff` (kInf: all). The results' objective ranges are not computed
// (AddObjectiveRange: the caller's). cache (optional): the grids, built on first use.
// given_parts (optional, by group index): parts used in place of a fixed group's catalog ids
// where the entry's motor is set (the joint search's virtual ESC; they must outlive the call).
// pair_mask (optional, motor * props + propeller): the free group's pairs that may score below
// the cutoff (0: none of its combinations does; the joint search's inner filter,
// docs/search.md#g2-inner-filter); the others are counted under objective_bound unbounded.
SearchResult SearchOneGroup(const Mission& m, const Catalog& cat, const SearchOptions& opt, double cutoff,
                            PropGridCache* cache, const std::vector<GroupParts>* given_parts = nullptr,
                            const std::vector<char>* pair_mask = nullptr);

// Stage 4 on demand: the candidate pairs of BuildCandidates in CandidateBefore order, each
// bounded only when it may be drawn next. Per motor, the pairs are bounded in the order of
// R11's keys (docs/search.md#r11: a bound that holds for every motor of the motor's mass class), in
// batches (the first, of first_batch pairs per motor, on `threads` threads when the stream is
// built; each later one twice the last, up to kMaxBatch); a pair whose key is not below the
// caller's cutoff is never bounded. Tests use small first batches to exercise later ones.
// cutoff: the first batches bound only pairs whose key is below it (a caller that asks Next
// with cutoffs at or below it, as the joint search's inner searches do, sees the same
// sequence: a pair whose key is not below the cutoff is never drawn).
// The batch sizes: the measurements that chose them are in docs/search.md#constants.
inline constexpr std::size_t kFirstBatch = 32, kMaxBatch = 512;
class CandidateStream {
 public:
  CandidateStream(const SearchContext& ctx, int threads, std::size_t first_batch = kFirstBatch,
                  double cutoff = std::numeric_limits<double>::infinity());
  ~CandidateStream();
  CandidateStream(const CandidateStream&) = delete;
  CandidateStream& operator=(const CandidateStream&) = delete;
  // The next candidate, or false when none is left. Pairs with a bound >= cutoff may be left
  // out (a caller that stops at the first bound >= cutoff, with a cutoff that never rises, sees
  // the same sequence up to there): the returned candidate is the true next one when its bound
  // is below the cutoff, else some candidate with a bound >= cutoff.
  bool Next(double cutoff, Candidate* c);
  long long batches() const;        // batches bounded after the first ones
  long long pairs_bounded() const;  // pairs that stage 4's rules and R4 were applied to
  // The combinations (pairs times their option's rated ESCs) neither drawn nor removed by a
  // stage 4 rule so far: when the caller stops, R4 (or R11) removed them.
  long long open_combinations() const;
  // An upper bound of the pairs still to be drawn below `cutoff` (progress): those waiting in
  // the motors' heaps and those not yet bounded whose R11 key is below it (a pair's bound is at
  // least its key).
  long long PairsLeftBelow(double cutoff) const;
  long long skipped_without_mass() const;
  // The combinations each stage 4 rule removed so far, added to *out.
  void MergePrunedInto(std::map<std::string, long long>* out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dynosize::search_internal
