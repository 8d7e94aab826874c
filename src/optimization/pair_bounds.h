// How a candidate (motor, propeller, battery option) pair is bounded (stage 4 of the catalog
// search, search_stages.h): the mission's facts, the pair's rotor loads, R4's score bound
// (pair_bounds.cc), R10's segment-by-segment bound (segmentwise_bound.cc) and the rules that
// refuse a pair or an ESC (R2, R6, R7, R9, R12). The rules: docs/search.md.
// Internal to src/optimization (and its tests).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "mission/flight.h"
#include "mission/mission.h"
#include "model/drive.h"
#include "optimization/needed_capacity.h"
#include "optimization/search_stages.h"

namespace dynosize::search_internal {

// What stage 4 derives once per mission.
struct MissionFacts {
  std::vector<int> hover;  // hover segment indices (R2-R4)
  double t_fixed_max = 0;  // the fixed segments' longest total duration (R4)
  bool stretch_is_hover = false;
  int free_group = 0;
  // The free group lifts the vehicle (LiftGroup, 0 when none): the evaluator's prop_folding,
  // motor_unrated and motor_voltage checks apply to it (credibility.h).
  bool free_lifts = false;
  // Stage 4 only (StageFourFacts): the R0 rules that remove propellers whatever the motor,
  // the propellers they let through, and R7's largest axial airspeed over the free group's
  // climbs and wing-borne cruises.
  std::vector<std::pair<const char*, long long>> prop_frame_counts;  // R0 rule -> propellers it removes
  std::vector<int> frame_ok_props;  // the propellers R0 lets through, index order
  double r7_axial_m_s = 0;
  // R13's pieces all assembled at their own mass (none passed over while it cannot be the
  // least): the same bounds, for the tests that check so.
  bool every_capacity_piece = false;
  // R13's least piece refined while the pair's bound is below a finite cutoff (PairCandidate;
  // StageFourFacts sets it): off, the bound is R13's over the fixed pieces, as the tests of the
  // passed-over pieces compare it.
  bool refine_capacity_pieces = false;
  // LoadTwins of the mission.
  std::vector<std::size_t> load_twin;
  // Stage 4 only (StageFourFacts): CapacityPieceEdges per battery option, computed once.
  std::vector<std::vector<double>> capacity_edges;
  // The same with kKeyCapacityPieces pieces, for R11's keys (PropOnlyBound).
  std::vector<std::vector<double>> key_capacity_edges;
};

// Groups (G1): the rules below speak of the free group's segments only; a segment of a fixed
// group draws at least P_avionics (its drive's power is >= 0), and every group's mass is in
// mass_lb and mass_ub, so each bound stays a bound.
MissionFacts FactsOf(const Mission& m, int free_group);

// FactsOf with what stage 4 reads per propeller (R0) and per pair (R7) worked out once.
MissionFacts StageFourFacts(const SearchContext& ctx);

// Per segment, the first segment (itself or an earlier one) whose rotor load is the same function
// of the vehicle mass (SegmentRotorLoad reads the same fields: type, group, climb rate, airspeed
// range, lift-to-drag and its reference, active rotors): such segments share one load, the same
// numbers (an out-and-back mission's two cruises).
std::vector<std::size_t> LoadTwins(const Mission& m);

// One of the other segments' terms of R4's max_endurance energy (ScoreLowerBoundTerms) at one
// vehicle mass, kept so that a heavier vehicle's can be bounded from below without its own
// assembly (R13, OtherEnergyAtLeastJ).
struct SegmentEnergyFloor {
  int rotors = 0;         // > 0: the power bound is rotors*pdc_lb + P_avionics
  double constant_w = 0;  // else this (P_avionics, or a fixed group's G1 bound)
  double t_min_s = 0;     // the segment's shortest duration
  double momentum_j = -std::numeric_limits<double>::infinity();  // momentum theory's energy (-inf: none)
};

// The rotor loads of one pair's lightest mass (SegmentRotorLoad), computed once per pair
// instead of once per ESC class: per segment at its lowest and highest airspeed (the same
// numbers, so the bounds do not change).
class PairLoads {
 public:
  explicit PairLoads(const Mission& m)
      : m_(m), lo_(m.segments.size()), hi_(m.segments.size()), twin_(LoadTwins(m)) {}
  void Reset(double mass_kg) {
    mass_kg_ = mass_kg;
    for (auto& x : lo_) x.first = false;
    for (auto& x : hi_) x.first = false;
    for (auto& x : energy_) x.first = false;
    for (auto& x : momentum_) x.first = false;
    for (auto& x : terms_) x.known = false;
  }
  // A segment's power bound as ScoreLowerBound's p_lb_of needs it: scales (rotors x the
  // hover bound's per-rotor PDC + the avionics) or a constant; set by f(&term) once per pair.
  struct PowerTerm {
    bool known = false, scales = false;
    int rotors = 0;
    double constant = 0;
  };
  template <typename F>
  const PowerTerm& Term(std::size_t si, const F& f) {
    if (terms_.size() != lo_.size()) terms_.assign(lo_.size(), PowerTerm{});
    PowerTerm& x = terms_[si];
    if (!x.known) {
      x = PowerTerm{};
      f(&x);
      x.known = true;
    }
    return x;
  }
  // A per-segment number that depends only on the pair (its mass and propeller), computed by
  // f() once per pair (ScoreLowerBound's momentum energy), not once per ESC class.
  template <typename F>
  double PerSegment(std::size_t si, const F& f) {
    if (energy_.size() != lo_.size()) energy_.assign(lo_.size(), {false, 0.0});
    std::pair<bool, double>& x = energy_[si];
    if (!x.first) x = {true, f()};
    return x.second;
  }
  // A number that depends only on the pair and the segment's load (LoadTwins), computed by f()
  // once per pair and load (ScoreLowerBound's momentum power).
  template <typename F>
  double PerLoad(std::size_t si, const F& f) {
    if (momentum_.size() != lo_.size()) momentum_.assign(lo_.size(), {false, 0.0});
    std::pair<bool, double>& x = momentum_[twin_[si]];
    if (!x.first) x = {true, f()};
    return x.second;
  }
  // The segment's load at airspeed v_m_s, which must be the same value per (segment, high) for
  // one mass (the callers pass airspeed_m_s.lo or .hi, or 0).
  double mass_kg() const { return mass_kg_; }
  // R13's pieces passed over without their own assembly (PairCandidate, PropOnlyBound).
  long long pieces_skipped = 0;
  // R13's least piece refined below the cutoff (PairCandidate): assemblies and splits made.
  long long pieces_refined = 0;
  // Scratch for the first piece's SegmentEnergyFloor per kind of drive ([DriveIsLossy]).
  std::vector<SegmentEnergyFloor> floors[2];
  const RotorLoad& At(std::size_t si, bool high, double v_m_s) {
    si = twin_[si];
    std::pair<bool, RotorLoad>& x = (high ? hi_ : lo_)[si];
    if (!x.first) x = {true, SegmentRotorLoad(m_, m_.segments[si], mass_kg_, v_m_s)};
    return x.second;
  }

 private:
  const Mission& m_;
  double mass_kg_ = 0;
  std::vector<std::pair<bool, RotorLoad>> lo_, hi_;
  std::vector<std::size_t> twin_;
  std::vector<std::pair<bool, double>> energy_, momentum_;
  std::vector<PowerTerm> terms_;
};

// Momentum theory's bound of a propeller segment's terminal power, W, when no stage can create
// energy: N*P_ideal(T, V)/max_figure_of_merit + P_avionics (the evaluator's
// prop_figure_of_merit; V the axial inflow with forward-flight tables, else 0, as
// PropellerPoint judges it; P_ideal rises with the thrust).
double MomentumPowerW(const Mission& m, const RotorLoad& ld, double diameter_m, bool axial_data);

// R4: a lower bound of the score of a (motor, propeller, option) pair with an ESC class whose
// drive is lossy or not (DriveIsLossy: only then momentum theory bounds the power drawn),
// given the hover bound's per-rotor electrical power pdc_lb at the lightest mass (R11: a floor
// of it that holds for a class of motors). loads: PairLoads at that mass.
// capacity_top_ah > 0: the energy budget of max_endurance is taken at that capacity instead of
// the option's largest (R13: a piece of the capacity range whose packs are at most that large,
// with loads and pdc_lb at the piece's lightest vehicle).
double ScoreLowerBound(const SearchContext& ctx, const MissionFacts& f, bool lossy, const PropEntry& prop,
                       const PropModel& model, std::size_t option, PairLoads* loads, double pdc_lb,
                       double capacity_top_ah = 0.0);

// ScoreLowerBound before its budget: with a max_endurance budget (budgeted), BudgetScore's other
// terms at the mass of `loads` (the fixed segments' longest time, the other segments' energy
// and the stretch's power bound), so that one assembly serves every budget; else the bound.
// stretch_only: the other segments' energy is not assembled (e_other_j 0; R13's pieces put a
// lighter piece's in its place, PairCandidate).
struct ScoreBoundTerms {
  bool budgeted = false;
  double bound = -std::numeric_limits<double>::infinity();  // when not budgeted
  double t_fixed_s = 0, e_other_j = 0, p_stretch_w = 0, ocv_integral_v = 0;
  // The stretch's power bound scales with the hover bound's per-rotor PDC (R4): p_stretch_w is
  // at least stretch_rotors*pdc_lb + P_avionics (0: a constant, no such term).
  int stretch_rotors = 0;
  // A lower bound of the stretch power of a heavier vehicle of the same pair (R13): this
  // one's (every term rises with the mass, M1-M3) and the drive's term at pdc_lb_w, a lower
  // bound of the heavier vehicle's hover PDC.
  double StretchPowerAtLeastW(double pdc_lb_w, double avionics_w) const;
  // The bound with the budget of a pack of budget_ah (ScoreLowerBound's capacity_top_ah).
  double At(double budget_ah) const;
};
// floors (optional): when the other segments' energy is assembled, its terms, in segment order.
ScoreBoundTerms ScoreLowerBoundTerms(const SearchContext& ctx, const MissionFacts& f, bool lossy, const PropEntry& prop,
                                     const PropModel& model, std::size_t option, PairLoads* loads, double pdc_lb,
                                     bool stretch_only = false, std::vector<SegmentEnergyFloor>* floors = nullptr);

// R13: the other segments' energy (ScoreBoundTerms::e_other_j) of a vehicle at least as heavy as
// the one `floors` was assembled at, whose hover bound's per-rotor PDC is at least pdc_lb_w: each
// term at least the lighter vehicle's (its thrust, momentum bound and fixed groups' bounds rise
// with the mass, M1-M3) with that PDC; the same operations in the same order, so it is at most
// the heavier vehicle's assembled number.
double OtherEnergyAtLeastJ(const std::vector<SegmentEnergyFloor>& floors, double pdc_lb_w, double avionics_w);

// R13 (docs/search.md#r13): R4's max_endurance budget over the option's capacity range in
// `pieces` pieces [C_j, C_j+1] (geometric; kCapacityPieces for the pairs): on a piece every pack
// holds at most C_j+1's charge and the vehicle weighs at least its mass with C_j's pack, so R4's
// bound at that mass with C_j+1's budget bounds the piece; the pair's bound is the least over
// the pieces. The pieces' capacities, ascending (pieces + 1 of them from capacity_lo_ah to
// capacity_hi_ah; empty when the option has no range or the objective no budget).
inline constexpr int kCapacityPieces = 12;
// R11's keys take finer pieces (docs/search.md#constants): a key bounds every pair of its motor
// class, and a tighter key leaves fewer pairs to bound (the pairs' own bound is refined below
// the cutoff instead, RefineLeastPiece).
inline constexpr int kKeyCapacityPieces = 20;
std::vector<double> CapacityPieceEdges(const SearchContext& ctx, const MissionFacts& f, std::size_t option,
                                       int pieces = kCapacityPieces);
// CapacityPieceEdges as StageFourFacts keeps them (keys: R11's, kKeyCapacityPieces); computed
// into *scratch when f has none.
const std::vector<double>& PieceEdges(const SearchContext& ctx, const MissionFacts& f, std::size_t option,
                                      std::vector<double>* scratch, bool keys = false);
// The option's pack mass at capacity_ah of its range, shrunk by 1e-9 against rounding (a lower
// bound of the pack's true mass there: the mass is proportional to the capacity, PackAt).
double PackMassLowerBoundKg(const BatteryOption& bo, double capacity_ah);

// Rule R15 (docs/search.md#r15, needed_capacity.h) for a battery option: min_energy over its
// capacity range [C_lo, C_hi], with R4's budget ocv_integral_v. bound_at(C) is the pair's bound
// at the vehicle with C's pack (PackMassLowerBoundKg; kInf when R3 refuses every class there).
// *over_range: no pack of the range holds the energy (reserve_soc). The bound as it is for
// another objective or without a range.
template <typename BoundAt>
double RaisedByNeededCapacity(const Mission& m, const BatteryOption& bo, double bound, double cutoff,
                              bool* over_range, BoundAt&& bound_at) {
  *over_range = false;
  if (m.objective.type != ObjectiveType::kMinEnergy) return bound;
  return dynosize::RaisedByNeededCapacity(bo.capacity_lo_ah, bo.capacity_hi_ah, bo.ocv_integral_v, bound, cutoff,
                                          over_range, std::forward<BoundAt>(bound_at));
}

// R12 as a mass floor: a feasible combination hovers at least at the window's bottom w_min, so
// (M1) each rotor's hover thrust is at least T(w_min), and the vehicle's mass at least the mass
// whose hover thrust per rotor that is (proportional to the mass, flight.h), shrunk by 1e-9
// against rounding. 0 when the rule does not apply. Every bound computed at a mass of at least
// this stays a bound of every feasible score (M3).
double WindowMassFloorKg(const SearchContext& ctx, const MissionFacts& f, int prop);

// The fixed groups' R7 and R6 mass floor for option o (SearchContext::fixed_mass_floor), kg (0
// without one): every bound computed at a mass of at least this stays a bound of every feasible
// score (M3).
double FixedMassFloorKg(const SearchContext& ctx, std::size_t o);
// The same floor as a rule: the one a combination of option o whose free group carries motors,
// propellers and ESCs of these masses breaks whatever its pack (the option's heaviest still
// leaves the vehicle below the floor), or null.
const char* FixedMassFloorRule(const SearchContext& ctx, std::size_t o, double motor_kg, double prop_kg, double esc_kg);
// The fixed groups' mass ceiling (SearchContext::fixed_mass_ceiling) as a rule: the one a
// combination of option o with these masses breaks whatever its pack (the option's lightest
// still leaves the vehicle at or above the ceiling), or null.
const char* FixedMassCeilingRule(const SearchContext& ctx, std::size_t o, double motor_kg, double prop_kg,
                                 double esc_kg);

// R12 (the window's bottom): true when the first hover's speed at the vehicle mass mass_ub_kg (an
// upper bound of the true mass) is below the propeller's data window, so that it is below it at
// every mass up to mass_ub_kg (M1, M3).
bool HoverSpeedBelowWindowAtMass(const SearchContext& ctx, const MissionFacts& f, int prop, double mass_ub_kg);

// R10 over the option's capacity range in pieces (one without a range): the least bound over
// the pieces that may be feasible; kInf with *rule (the first refusal's) when none is. While
// the least piece bound is below `threshold`, that piece is tightened: first its speeds are
// bisected within their grid cells (kRefineSteps), then it is halved (each half's bound is
// valid on its own), up to kMaxSplits steps and down to 1/1024 of the range: the bound
// tightens only as far as it takes to prove "cannot beat the threshold". With
// stop_when_unprovable, the tightening also stops as soon as a piece's bound at its lowest
// capacity alone is below the threshold, which proves that no splitting would get there: the
// answer is then below the threshold as it would have been, with less work (the tests compare
// the two).
double SegmentwiseBoundPieces(const SearchContext& ctx, const MissionFacts& f, const MotorParams& mp,
                              const Drive& ideal, double t_max, int motor, int prop, int option, double esc_mass_kg,
                              double threshold, const char** rule, bool stop_when_unprovable = true);

// The hover bound's speed and torque from below (R2): the last grid point whose thrust is at
// most the first hover segment's per-rotor thrust at the mass of `loads` (0, 0 without a
// hover segment, a monotone grid or such a point). Returns the grid index (0 when none).
int HoverGridPointFromBelow(const MissionFacts& f, const PropGrid& g, PairLoads* loads, double* omega_lb, double* q_lb);
// The same point when its raw grid index (-1: no grid thrust at or below the load's) is known to
// lie in [*lo, hi]: at a vehicle at least as heavy as the one whose raw index is *lo and no
// heavier than the one whose raw index is hi (the load's thrust rises with the mass, M3, the
// grid's with the index, M1); found in that bracket. *lo is set to the point's raw index.
void HoverGridPointInBracket(const MissionFacts& f, const PropGrid& g, PairLoads* loads, int* lo, int hi,
                             double* omega_lb, double* q_lb);

// R2, R6, R7 for one (motor, propeller, option) pair whose propeller passed R0 (counted per
// motor, MotorSetUp): the rule that removes it, or null. Sets omega_lb, q_lb (R2) for the
// hover bound.
// w_nl: the largest no-load speed of the motor's zero-resistance drives at full throttle and
// the option's full-charge voltage (R7; the same for every propeller, computed once per option).
// lb_idx (optional): the raw grid index of (omega_lb, q_lb), -1 when none (HoverGridPointInBracket).
const char* PropRule(const SearchContext& ctx, const MissionFacts& f, double motor_kg, double w_nl, std::size_t pi,
                     std::size_t o, PairLoads* loads, double* omega_lb, double* q_lb, int* lb_idx = nullptr);

// R9 with the mission's facts and the motor's scenario parameters given (BranchAndBound calls it
// per ESC).
bool HoverThrottleBelowLimit(const SearchContext& ctx, const MissionFacts& f, const MotorParams& mp, int motor,
                             int prop, int option, const EscEntry& esc);

// R12 per ESC: the first hover below the propeller's data window at the heaviest the vehicle can
// be with this ESC (the option's largest pack).
bool HoverSpeedBelowWindow(const SearchContext& ctx, const MissionFacts& f, int motor, int prop, int option,
                           double esc_kg);

}  // namespace dynosize::search_internal
