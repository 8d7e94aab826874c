// One combination (motor, ESC, propeller, battery cell, cells in series) flying one mission:
// its continuous problem.
//
// Per segment the rotors' thrust and axial airspeed follow from the weight (vehicle plus
// propulsion) and mission/flight.h; the propeller's speed is the root of T_prop(omega) =
// T_required (PropModel, thrust rising with speed), its torque is the load, and the drive's
// throttle and currents come from Drive::Inverse at the battery's terminal voltage. The battery
// (battery/battery.h: OCV(SOC) - I*R_pack) sags with the total current N*IDC + P_avionics/V,
// solved as a fixed point per instant; SOC follows by coulomb counting (a midpoint rule over
// sub-steps of each segment). Each segment reports ONE operating point, its end (the lowest
// voltage and the highest throttle of the segment: the worst case), reproducible by
// `dynosize simulate --vdc V --throttle TR --torque Q`, plus the range over the segment.
//
// Continuous variables: the battery capacity (when the mission gives a range: mass, capacity,
// resistance and current rating scale with it, the cell's specific values held), the airspeed
// of cruise segments with a range, the duration of the max_endurance segment (the longest
// that keeps every constraint: found by regula falsi on the smallest constraint slack, which
// falls monotonically with time) and the shaft speed (optimization/shaft.h, Ipopt).
// Capacity and airspeeds pass through tabulated propeller data (piecewise linear: not smooth),
// so they are solved by a derivative-free NLopt method (COBYLA, see SolveCombination).
#pragma once

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "battery/battery.h"
#include "catalog/catalog.h"
#include "mission/mission.h"
#include "model/drive.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "prop/prop_model.h"

namespace dynosize {

struct RotorLoad;  // mission/flight.h
namespace eval_internal {
class Tracker;  // slacks and violations of one Run (mission_eval_flight.cc)
}  // namespace eval_internal

// The parts of one propulsion group.
struct GroupParts {
  const MotorEntry* motor = nullptr;
  const EscEntry* esc = nullptr;
  const PropEntry* prop = nullptr;
};

// The parts a mission fixes for group g ("motor", "esc", "prop" of its "propulsion" entry), looked
// up in the catalog; all null for a searched group. DataError naming the JSON path and the id
// when one is not in the catalog.
GroupParts FixedGroupParts(const Mission& m, const Catalog& cat, int g);

// The fixed parts of one combination, built once.
struct Combination {
  const MotorEntry* motor = nullptr;
  const EscEntry* esc = nullptr;
  const PropEntry* prop = nullptr;
  const BatteryEntry* battery = nullptr;
  int cells = 0;  // cells in series
  // With propulsion groups (Mission::groups): every group's parts, by group index; motor, esc
  // and prop above are then those of the group the search chooses (for its bookkeeping).
  // Empty: motor, esc and prop fly every segment (the one implicit group).
  std::vector<GroupParts> groups;
  GroupParts Parts(int g) const { return groups.empty() ? GroupParts{motor, esc, prop} : groups[g]; }
};

// A constraint that fails: where, value, limit and by how much (value - limit, in its unit).
struct Violation {
  std::string constraint;  // "max_throttle", "motor_current", ...
  std::string segment;     // "" for mission-wide ones
  double value = 0.0;
  double limit = 0.0;
  std::string unit;
  bool at_least = false;  // the rule is value >= limit (cut-off voltage, reserve SOC)
  // By how much it fails, > 0, in the constraint's unit.
  double excess() const { return at_least ? limit - value : value - limit; }
};

struct SegmentResult {
  std::string name;
  int group = 0;  // the propulsion group that flies it (Mission::groups)
  SegmentType type = SegmentType::kHover;
  double duration_s = 0.0;
  double airspeed_m_s = 0.0;
  double thrust_per_rotor_n = 0.0;
  double tilt_deg = 0.0;
  int rotors = 0;
  OperatingPoint point;  // the segment's end: its worst case (lowest voltage)
  // Ranges over the segment (start to end).
  double vdc_min_v = 0, vdc_max_v = 0, throttle_min = 0, throttle_max = 0, idc_min_a = 0,
         idc_max_a = 0;
  double soc_start = 0, soc_end = 0;
  double battery_current_a = 0;  // at the end
  double battery_current_start_a = 0;
  double energy_j = 0;           // drawn from the battery in this segment
  double eta_average = 0;        // energy-weighted system efficiency (motor + ESC)
  std::string active_limit;      // the tightest constraint ("" if none is within 10 %)
  double active_limit_slack = 0; // its relative slack (negative: violated)
  const char* active_limit_id = nullptr;  // internal: the check's literal while the segment is flown
  // Steady winding temperature at the segment's hottest point (MissionEvaluator::WindingTempC).
  double winding_temp_c = 0;
  std::string prop_note;         // propeller data held at an edge, if any
  // The evaluation behind prop_note, kept as numbers while the solvers run (no text on the hot
  // path); Solve and Simulate write prop_note from it (FillPropNotes).
  bool prop_edge = false;
  PropEvaluation prop_edge_eval;
  std::string shaft_solver;      // shaft segments: the solver's brief report
};

// The numbers a designer compares with eCalc, for the mission's total mass on the lift rotors
// (MissionEvaluator::Summarize): at mid charge (SOC 0.5, a mid-pack voltage like eCalc's
// nominal one) with the sag at each current; endurances by coulomb counting of the charge
// above the reserve at that current.
struct DesignSummary {
  bool valid = false;               // false: the hover or the full-throttle point has no solution
  // false: at half charge the lift rotors cannot hold the weight (the hover needs more than full
  // throttle, or the full-throttle thrust is below the weight): the hover figures below are not
  // endurances then and reports leave them out.
  bool can_hover = true;
  double hover_throttle = 0.0;
  double hover_battery_current_a = 0.0;
  double hover_endurance_s = 0.0;   // hovering from full to the reserve
  double full_throttle_battery_current_a = 0.0;
  double full_throttle_endurance_s = 0.0;  // at full throttle from full to the reserve
  double reserve_hover_s = 0.0;     // hover time of the charge left at the mission's end
  double full_throttle_thrust_n = 0.0;     // all lift rotors, static, at mid charge
  bool full_throttle_current_limited = false;  // held at the current rating below full throttle
  // The steepest steady vertical climb at the full-throttle shaft power: momentum theory with
  // the body drag and the hover's figure of merit (Summarize); an estimate (the propeller's
  // thrust lapse in fast inflow is not modelled).
  double max_climb_rate_m_s = 0.0;
  double winding_temp_max_c = 0.0;  // hottest segment
};

// Two constraint names (the literals the checks pass) are the same constraint.
inline bool SameConstraint(const char* a, const char* b) {
  return a == b || (a && b && std::strcmp(a, b) == 0);
}

// The smallest slack per constraint over a run's stretch-dependent checks (a fixed array: no
// allocation on the hot path; the constraints are a few literals).
struct StretchSlacks {
  static constexpr int kMax = 24;
  std::array<const char*, kMax> name{};
  std::array<double, kMax> slack{};
  int n = 0;
  // By the literal's address (a name passed from two places may take two entries: Of and
  // Worst read them by name, so that costs nothing but a slot).
  void Add(const char* c, double s) {
    for (int i = 0; i < n; ++i) {
      if (name[i] == c) {
        slack[i] = std::min(slack[i], s);
        return;
      }
    }
    if (n < kMax) { name[n] = c; slack[n++] = s; }
  }
  // The slack of constraint c, or the smallest of all when c is null; +inf when not checked.
  double Of(const char* c) const {
    double out = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      if (!c || SameConstraint(name[i], c)) out = std::min(out, slack[i]);
    }
    return out;
  }
  // The constraint with the smallest slack (null when none was checked).
  const char* Worst() const {
    int k = -1;
    for (int i = 0; i < n; ++i) if (k < 0 || slack[i] < slack[k]) k = i;
    return k < 0 ? nullptr : name[k];
  }
};

// The objective (MissionResult::objective's unit) of a score (MissionResult::score: -objective for
// max_*, objective for min_energy); infinities pass through with their sign turned as the score's.
double ObjectiveOfScore(ObjectiveType type, double score);

struct MissionResult {
  bool feasible = false;
  // Solve(cutoff_score) proved that the score cannot beat the cutoff and stopped early; the
  // other fields are then incomplete.
  bool bounded_out = false;
  // Infeasible at every value of the free continuous variables through a violation listed (the
  // mission has none free, or an early exit proved one over the whole range: the others listed
  // may hold at the point reported only); false for the best infeasible point of a search over a
  // range. Only then may the search skip the ESCs a failing one dominates (docs/search.md#r5).
  bool violations_everywhere = false;
  double objective = 0.0;   // in objective_unit; larger is better for max_*, smaller for min_*
  std::string objective_unit;
  double score = 0.0;       // to minimise: -objective for max_*, objective for min_energy
  double endurance_s = 0.0; // total mission time
  double energy_wh = 0.0;   // drawn from the battery
  double propulsion_mass_kg = 0.0, total_mass_kg = 0.0, capacity_ah = 0.0;
  double final_soc = 0.0;
  std::vector<SegmentResult> segments;
  std::vector<Violation> violations;  // worst per constraint
  std::vector<std::string> warnings;
  std::vector<std::string> assumed;   // "motor x: mass_kg", ...
  std::string solver;                 // continuous solver's brief report ("" when none needed)
  // Full-throttle static thrust of the lift rotors over the weight at the lowest pack voltage of
  // the mission (its end) with the sag at that current, held at the current rating of the motor
  // and ESC (FullThrottleAt); 0 when not computed (screening runs of a mission that does not
  // check it).
  double thrust_to_weight = 0.0;
  int lift_rotors = 0;
  DesignSummary summary;              // filled by Solve/Simulate (not by screening runs)
  double min_slack = 0.0;             // smallest relative constraint slack (< 0: infeasible)
  // Per constraint, the smallest slack of the checks that depend on the max-endurance
  // stretch's duration (from its second point on): WithEndurance's root functions. Internal.
  StretchSlacks stretch_slacks;
  // The tiers of the parts and the objective under the data-uncertainty model
  // (optimization/credibility.h); filled by AddObjectiveRange (evaluate, optimize's top N).
  ObjectiveRange range;
};

struct ContinuousVars {
  double capacity_ah = 0.0;            // 0: the entry's capacity
  std::vector<double> airspeed_m_s;    // per segment (cruise), else unused
  double endurance_segment_s = 0.0;    // max_endurance: the stretched segment's duration
};

class MissionEvaluator {
 public:
  // Throws UsageError when the cell count is not a multiple of the battery entry's cells, or
  // DataError when a component lacks data the mission needs.
  // `prop_model` (optional) is a PropModel of combination.prop shared between evaluators (the
  // catalog search builds one per propeller); it must outlive the evaluator.
  // `group_prop_models` (optional, by group index, null entries allowed): PropModels of the
  // groups' propellers built once by the caller (the search, for the fixed groups).
  MissionEvaluator(const Mission& mission, const Combination& combination,
                   const PropModel* prop_model = nullptr,
                   const std::vector<const PropModel*>* group_prop_models = nullptr);

  // Simulates with fixed continuous variables (no optimisation).
  MissionResult Simulate(const ContinuousVars& vars) const;

  // Solves the continuous problem: the endurance segment's duration, the capacity and free
  // airspeeds (NLopt COBYLA through solvers/, checked from several starts), the shaft speeds
  // (Ipopt). This is what `evaluate` and `optimize` report.
  // With cutoff_score: stop early (bounded_out) once a bound proves score >= cutoff_score
  // (max_endurance only; see EnduranceUpperBound, mission_eval_early_exits.cc).
  // explain = false leaves out the warnings, the continuous solver's report, the designer's
  // summary and the propeller notes (text nobody reads for the search's evaluations: it
  // explains its top N again); the numbers are the same.
  // decide = true (with a finite cutoff; the search's virtual ESC, R5, which only asks whether
  // the score beats the cutoff): a search over a free capacity or cruise airspeed stops at the
  // first feasible point whose score beats cutoff_score and returns it, unexplained (feasible,
  // score < cutoff, not the optimum: the optimum is no worse, so the answer to that question
  // is the same); when no point beats it the result is the full solve's.
  // search = true (the branch and bound's evaluations, search.cc): only the result's score, its
  // feasibility and, when infeasible, whether it fails min_hover_throttle (R5's dominance) are
  // read, so the early exits that end in an infeasible result (EarlyExit: a constraint no value
  // of the continuous variables can meet) run even without a finite cutoff, as they do with one
  // (before the top N is full the search's threshold is infinite; the capacity-sized
  // quadcopter's search made 14 k such solves, each a whole 1-D search of infeasible points).
  // The propeller data window (constraints.prop_below_data_factor, prop_above_data_factor)
  // decided without a solve: true, with the infeasible result (one violation, no segments) in
  // *out, when a segment at a fixed inflow turns its propeller above the window at the lightest
  // vehicle the continuous variables allow, or (below_too) a hover turns it below the window at
  // the heaviest; the full solve then fails the same constraint. Solve runs it as an early
  // exit when it has a cutoff; the search before its solves (search.cc, R12).
  bool DataWindowRefuses(bool below_too, MissionResult* out) const;
  MissionResult Solve(double cutoff_score = std::numeric_limits<double>::infinity(),
                      bool explain = true, bool decide = false, bool search = false) const;
  // Writes each segment's prop_note from its prop_edge_eval (Solve with explain, and Simulate).
  static void FillPropNotes(MissionResult* r);

  // Steady winding temperature of the motor at an operating point, C: the winding heats by
  // its copper loss kp*R(T)*I^2 (eqs 41, 48 with R(T) = Rm*(1 + alpha_Cu*(T - 25 C)), alpha_Cu
  // = 0.00393/K, Rm stated at 25 C) plus the rest of the motor's loss PAC - Pmech (no-load
  // loss KT*Io*omega, eq 42) over a thermal resistance to the air: T = T_air + Rth*(P_cu(T) +
  // P_0), solved in closed form; a winding that cannot reach a steady state (alpha*Rth*P_cu >=
  // 1) gets kRunawayTempC. Rth is the catalog's rth_k_per_w or AssumedMotorRthKPerW (assumed).
  double WindingTempC(const OperatingPoint& p, int group = 0) const;
  double rth_k_per_w(int group = 0) const { return groups_[group].rth_k_per_w; }

  // The heaviest vehicle (kg) that can meet min_thrust_to_weight: the lift rotors' thrust at
  // full throttle from the full-charge OCV with no sag over g*min_thrust_to_weight (an upper
  // bound of the thrust at every state of charge, capacity and stretch; mission_eval_early_exits.cc proves it);
  // +inf when the mission does not check it or no bound can be given. Solve's search exits use it.
  double ThrustToWeightMassCeilingKg() const;

  double fixed_mass_kg() const { return fixed_mass_kg_; }  // everything but the battery
  double BatteryMassKg(double capacity_ah) const;
  double entry_capacity_ah() const { return base_capacity_ah_; }

 private:
  // --- mission_eval.cc: the battery at a capacity.
  BatteryPackParams PackAt(double capacity_ah) const;

  // --- mission_eval_flight.cc: Run and its stages, WithEndurance.
  // What Run carries from one segment to the next.
  struct RunState {
    BatteryPack pack;
    double cutoff_v = 0, v_full = 0, q_c = 0, current_factor = 1;
    double soc = 1.0, time_s = 0, energy_j = 0;
    bool in_stretch = false;  // past the first point of the max-endurance stretch (WithEndurance)
  };
  // A Run stopped before segment `next`: everything Run has at that point (the segments before
  // `next` do not depend on the stretch, so WithEndurance flies them once per set of variables).
  struct RunPrefix {
    MissionResult r;
    RunState st;
    std::size_t next = 0;
    bool finished = false;  // the run ended early (r is its final result)
  };
  // screen: stop at the end of the first segment that breaks a constraint (the result then
  // only says "infeasible"; used by Solve(cutoff) to discard search candidates quickly).
  MissionResult Run(const ContinuousVars& vars, double stretch_s, bool screen = false) const;
  RunPrefix RunUpTo(const ContinuousVars& vars, std::size_t end, bool screen) const;
  void RunSegments(const ContinuousVars& vars, double stretch_s, bool screen, std::size_t end, RunPrefix* p) const;
  MissionResult RunFrom(RunPrefix p, const ContinuousVars& vars, double stretch_s, bool screen) const;
  void CheckParts(const RunState& st, eval_internal::Tracker* track) const;
  bool SegmentShaftPoint(std::size_t si, const RunState& st, const RotorLoad& load, eval_internal::Tracker* track,
                         SegmentResult* seg, double* omega, double* torque) const;
  bool IntegrateSegment(std::size_t si, bool stretched, double omega, double torque, RunState* st,
                        eval_internal::Tracker* track, SegmentResult* seg) const;
  void FinishRun(const RunState& st, eval_internal::Tracker* track, MissionResult* out) const;
  double StretchStartCurrent(const MissionResult& r) const;
  // decide_cutoff (Solve's decide): return the first feasible run whose score is below it (the
  // longest feasible stretch, the answer otherwise, is no worse).
  MissionResult WithEndurance(ContinuousVars vars,
                              double decide_cutoff = -std::numeric_limits<double>::infinity()) const;

  // --- mission_eval_continuous.cc: the continuous variables.
  MissionResult SolveContinuous(double cutoff_score, bool explain, bool decide, bool search) const;
  // A free continuous variable of SolveContinuous: the capacity (segment -1) or a cruise's
  // airspeed, searched over [lo, hi] as x in [0, 1].
  struct FreeVar {
    int segment;
    double lo, hi;
  };
  std::vector<FreeVar> FreeVariables() const;
  ContinuousVars VarsAt(const std::vector<FreeVar>& free, const double* x) const;  // x: one per free var, or null
  MissionResult SolveOneFree(const std::vector<FreeVar>& free, double cutoff_score, bool explain, bool decide) const;
  MissionResult SolveManyFree(const std::vector<FreeVar>& free, double cutoff_score, bool explain, bool decide) const;

  // --- mission_eval_early_exits.cc: the search's early exits and bounds (and the public
  // DataWindowRefuses and ThrustToWeightMassCeilingKg).
  bool EarlyExit(double cutoff_score, bool explain, bool search, MissionResult* out) const;
  bool HoverOrWeightRefuses(bool with_weight, MissionResult* out) const;
  // A lower bound of a min_energy mission's energy, J, over the free cruise airspeeds, from a
  // Run at `vars` (C0 = 0, no supply resistance: EarlyExit's conditions).
  double MinEnergyLowerBoundJ(const MissionResult& r, const ContinuousVars& vars) const;
  // The lightest capacity of [c_lo, c_hi] whose vehicle weighs at least mass_kg (c_hi if none).
  double LightestCapacityAtLeastKg(double mass_kg, double c_lo, double c_hi) const;
  // r breaks a constraint no larger pack cures in a segment before the first free cruise.
  bool BreaksBeforeFreeAirspeeds(const MissionResult& r) const;
  // An upper bound of the total mission time over the capacity range (max_endurance), tightened
  // until it falls below target_s or a budget of simulations is spent.
  // [from_ah, to_ah] (to_ah > 0): only that part of the capacity range.
  // run_at_lo: Run(the variables at the range's lowest capacity and the segments' lowest
  // airspeeds, stretch 0), feasible and so flown in full, when the caller has it (the bound
  // flies that run first); null to fly it.
  double EnduranceUpperBound(double target_s, double from_ah = 0.0, double to_ah = 0.0,
                             const MissionResult* run_at_lo = nullptr) const;

  // --- mission_eval_summary.cc: the designer's summary and the warnings.
  // The assumed catalog values and the warnings a designer expects (hover throttle over the limit, currents near a rating,
  // ESC saturation, a motor running far below its efficient load, assumed parameters).
  void AddWarnings(MissionResult* r) const;
  // The lift rotors at full throttle at `soc`, the pack sagging at that current (plus the
  // avionics): per-rotor static thrust and shaft power, the battery current. Where full throttle
  // would draw more than the motor's or ESC's current rating (no margin), the point at that
  // rating instead: thrust a drive cannot hold is not thrust to count on. False when the motor
  // cannot turn the propeller.
  struct FullThrottle {
    double thrust_per_rotor_n = 0, pmech_w = 0, battery_current_a = 0, vdc_v = 0;
    bool current_limited = false;  // held at the motor's or ESC's current rating below full throttle
  };
  bool FullThrottleAt(const BatteryPack& pack, double soc, FullThrottle* f) const;
  // The same from a source of open-circuit voltage ocv_v behind r_pack_ohm.
  bool FullThrottleFrom(double ocv_v, double r_pack_ohm, FullThrottle* f) const;
  // Per lift rotor, a full-throttle thrust at or below FinishRun's at the end of every run that
  // ends at an SOC of at least soc (0: none known). Kept per SOC level (kThrustFloorLevels).
  double ThrustFloorN(double soc) const;
  // The hover of the whole vehicle (mass_kg) on the lift rotors at `soc` with sag.
  bool HoverAt(const BatteryPack& pack, double soc, double mass_kg, OperatingPoint* op,
               double* battery_current_a, double* shaft_w) const;
  void Summarize(MissionResult* r) const;

  // One propulsion group's drive, propeller model and thermal resistance.
  struct GroupDrive {
    GroupParts parts;
    Drive drive;
    std::unique_ptr<PropModel> owned_prop;
    const PropModel* prop = nullptr;
    double rth_k_per_w = 0;  // catalog or assumed (AssumedMotorRthKPerW)
    // The mission's data scenario (credibility.h): the propeller adjustment, a folding propeller
    // refused for lift, a motor without ratings estimated from its mass or excluded (the last
    // two checked on the lift group only).
    PropAdjustment prop_adj;
    bool folding_refused = false, rating_estimated = false, motor_excluded = false;
  };

  const Mission& m_;
  Combination c_;
  std::vector<GroupDrive> groups_;  // by group index (one without Mission::groups)
  int lift_group_ = 0;              // LiftGroup(mission), 0 when none
  BatteryPackParams pack_base_;
  double base_capacity_ah_ = 0;
  double fixed_mass_kg_ = 0;
  int lift_rotors_ = 0;    // LiftRotors(mission); thrust-to-weight and the summary use them
  std::vector<std::string> assumed_;
  // Set by each Solve to its `search`: the result's score and feasibility are all that is read,
  // so FinishRun may settle min_thrust_to_weight from a bound (ThrustFloorN).
  mutable bool search_only_ = false;
  // ThrustFloorN's floors by SOC level once computed (< 0: not yet), and the runs finished
  // (the floors are only read from the second on: a one-run evaluator would pay for both).
  static constexpr int kThrustFloorLevels = 10;
  mutable std::array<double, kThrustFloorLevels> thrust_floor_n_{-1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  mutable int runs_finished_ = 0;
  mutable double mass_ceiling_kg_ = -1.0;  // ThrustToWeightMassCeilingKg's value once computed (< 0: not yet)
};

}  // namespace dynosize
