#include "optimization/search.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "battery/battery.h"
#include "common/error.h"
#include "common/units.h"
#include "mission/flight.h"
#include "model/physics.h"
#include "optimization/components.h"
#include "optimization/joint_search.h"
#include "optimization/objective_range.h"
#include "optimization/search_stages.h"
#include "optimization/top_results.h"

namespace dynosize {

// Pruning rules and why they are safe.
//
// Monotonicity assumed of the model (true of eqs 42-59 and of the propeller data checked here):
//  (M1) a rotor's static thrust and torque rise with its speed (checked per propeller on the
//       grid below; a propeller whose grid is not monotone gets no thrust-based pruning);
//  (M2) at a fixed operating point (torque, speed) the drive's throttle, Irms, PAC and IDC rise
//       with the load and do not depend on the ESC except through RESC >= 0, which only adds
//       to them (eq 48: U = (Rm + RESC)*I + KE*omega); the throttle falls with the voltage;
//  (M3) more mass means more thrust in every segment (flight.h), hence (M1, M2) more speed,
//       torque, current and power;
//  (M4) at a fixed thrust a propeller's power rises with its axial inflow (as the ideal power
//       does; checked on the samples where it is used, prop_bounds.cc).
// Bounds on one (motor, propeller, battery option) pair use the lightest the vehicle can be
// with them: the lightest ESC that can take the cell count and the smallest battery capacity.
//
// R0 (frame): a propeller larger than the vehicle's max_prop_diameter_m fails prop_diameter
//    whatever else is chosen; so does a folding propeller for lift (prop_folding), a motor
//    without a source rating when the mission excludes such motors (motor_unrated),
//    credibility.h, and an entry the catalog excludes ("exclude", catalog_exclude). The first
//    two, and motor_voltage (R1), only when the free group is the lift group (LiftGroup), as
//    the evaluator checks them.
// Data scenario (credibility.h): the evaluator flies the mission's ranking scenario (the
//    credible value by default); the grids below use the same adjusted propeller torque (it
//    only rises, pointwise, and keeps rising with speed: M1 holds) and the same motor ratings,
//    so every rule bounds the score that is ranked.
// R1 (ratings, ESC voltage): an ESC whose vdc_max_v is below the full-charge OCV of the cells
//    fails the esc_voltage constraint whatever else is chosen; so does a motor whose cells_max
//    (4.2 V per cell) is below it (motor_voltage).
// R2 (thrust / prop speed): in every hover segment each rotor gives at least T_lb, the thrust
//    at the lightest mass. By (M1) its speed is at least omega_lb, the largest grid speed whose
//    thrust is <= T_lb, and its torque at least the smallest grid torque at or above omega_lb.
//    A propeller with max_rpm below omega_lb fails prop_max_rpm.
// R3 (motor): with (omega_lb, Q_lb) and an ESC of zero resistance at the highest voltage the
//    pack can have (its full-charge OCV), Drive::Inverse gives lower bounds of the throttle,
//    Irms and PAC of every real choice (M2). If that throttle is above the mission's limit
//    (or the ESC's saturation knee when saturation is not allowed), or Irms above the motor's
//    margin-reduced rating, or PAC above its power rating, no ESC and no capacity can fix it.
//    An ESC whose margin-reduced rating is below that Irms lower bound is left out for the pair.
// R4 (objective bound, branch and bound): with the same bounds the power drawn in a hover
//    segment is at least N*PDC_lb + P_avionics, PDC_lb the smaller of the zero-resistance
//    drive's PDC at the full-charge and the cut-off voltage (PDC = C1*U*I/kv + C0*VDC*I is
//    linear in VDC, eqs 57, 59). So is the power of a climb or fixed-airspeed cruise segment
//    whose per-rotor thrust is at least the hover bound's, when the propeller has static-only
//    data (read at J = 0 in any inflow: the same speed-thrust curve). Every segment draws at
//    least P_avionics. min_energy: the energy is at least the sum over segments of that power
//    times their shortest duration (and of the momentum bound below). max_endurance with a
//    hover segment stretched: the terminal energy of the whole mission is at most
//    Q_max*integral of OCV(s) ds over [reserve, 1] (Q_max the largest capacity); the other
//    segments take at least their energy bounds, the stretch gets the rest at no less than its
//    power bound; the fixed segments add at most their longest durations. Pairs are evaluated best bound
//    first and the search stops when the next bound cannot beat the N-th best found (every
//    later pair has a worse bound). max_efficiency has no such bound (it is not pruned by R4).
//    A fixed-airspeed cruise stretched gets the same budget with its power bound from
//    momentum theory (N*P_ideal/max_figure_of_merit + P_avionics, ScoreLowerBound).
// R9 (hover throttle from above): min_hover_throttle is checked at every hover point at the
//    pack's full-charge OCV (mission_eval.cc, PropellerPoint). In the free group's first hover
//    segment each rotor gives at most T_ub, the thrust at the heaviest mass of the pair (the
//    option's largest pack and heaviest ESC); by (M1) its speed is at most omega_ub, the first
//    grid speed whose thrust reaches T_ub, and its torque at most the largest grid torque up to
//    there. With an ESC's own RESC, Drive::Inverse at (omega_ub, Q_ub) and the full-charge OCV
//    is an upper bound of its hover throttle (M2): below the limit, that ESC fails
//    min_hover_throttle for the pair whatever else is chosen. Checked per ESC in stage 5, before
//    the class's virtual ESC (a class whose ESCs all fail it is skipped without one).
// R10 (segment by segment, stage 5): before a class's virtual ESC is evaluated, the mission is
//    bounded segment by segment with the class's zero-resistance drive and the lightest rated
//    ESC's mass, over the capacity range in pieces [C_a, C_b] (the pack's mass at C_a; its
//    charge, resistance and energy budget at C_b: PackAt). A segment of the free group with a
//    fixed axial inflow (hover, a climb: its rate or 0 when descending; a cruise at a fixed
//    airspeed: wing-borne, or multirotor when the data are static-only, read at J = 0) has a
//    thrust per rotor of at least T_s, its own at the lightest mass (M3), so by (M1) on the
//    propeller's grid in that inflow (static, or one grid per climb rate and wing-borne
//    airspeed for forward-flight tables, built with the scenario's torque and checked to rise)
//    a speed and torque of at least the grid point at or below T_s. There:
//    - R3 at the full-charge OCV: throttle, Irms, PAC from below (M2);
//    - the terminal power is at least N*PDC_s + P_avionics (PDC_s the smaller at the
//      full-charge and cut-off voltage, eq 59), and, when no stage creates energy, momentum
//      theory's N*P_ideal/max_figure_of_merit + P_avionics (as R4; P_ideal rises with the
//      thrust, also in a tilted multirotor cruise: P_ideal = V*D/2 + sqrt((V*D)^2/4 +
//      T^3/(2*rho*A)) there); any other segment draws at least P_avionics, a fixed group's
//      segment its G1 bound;
//    - the charge: the terminal current is at least the terminal power over the full-charge
//      OCV (V <= OCV <= v_full), so each segment takes at least P_lb*t_min/v_full (0 s for the
//      max_endurance stretch) and the SOC at its end is at most 1 - (their sum)/Q(C_b)
//      (coulomb counting); below the reserve the mission breaks reserve_soc (the SOC only
//      falls). At the end of a segment with a grid point the terminal voltage is at most
//      OCV(that SOC) - (P_lb/v_full)*R(C_b), and the drive's throttle there from below (M2:
//      it falls with the voltage) must stay within R3's limit, which the evaluator checks at
//      every segment end. The evaluator counts charge by the midpoint rule: the charge bound
//      is taken at kChargeAllowance (1 - 1e-3) of its value against that rule's error;
//    - the score: R4's budget with each segment's own power bound.
//    A piece whose bound is still below the N-th best gets its speeds bisected within their
//    grid cells on the propeller model (the largest speed found whose thrust is at most T_s,
//    so still at or below the true one, M1; the torque there, capped by the grid's least
//    torque above the cell), then it is halved.
//    A piece that breaks a limit holds no feasible point; the class is skipped for the pair
//    when every piece does, or when the least bound over the others is not below the N-th
//    best (SegmentwiseBound; tests/optimization/search_stages_test.cc against the full solve).
// R11 (stage 4's order: a bound for a whole class of motors). A motor whose drives cannot
//    create energy with any ESC class (DriveIsLossy: PDC >= PAC) and that has no winding
//    heating or KT droop has PAC >= Q*omega + a*Q^2 + b*omega at every operating point, with
//    a = kp*Rm/KT^2 and b = KT*Io (model/physics.h, LossFloorOf: eqs 41, 42, 47, 48). The
//    motors are put in classes by mass (each from its lightest motor up to 1.1 times it); per
//    class and per (propeller, option) the key is R4's bound with N*PDC_lb replaced by
//    N*(Q_lb*omega_lb + a_c*Q_lb^2 + b_c*omega_lb) (times 1 - 1e-9 against rounding), where
//    (omega_lb, Q_lb) is R2's grid point at the class's lightest mass and a_c, b_c are the
//    least over the class's motors. For a motor of the class, every combination with that
//    propeller and option is at least as heavy, so its hover speed and torque are at least
//    (omega_lb, Q_lb) (M1, M3) and the floor rises with both: the key is below its score, as
//    R4's bound is, and the pair's bound is the larger of the two. Stage 4 bounds a motor's
//    pairs in the order of its class's keys, only as the branch and bound reaches them (a key
//    at or above the N-th best leaves the rest of the motor's pairs unbounded, counted under
//    objective_bound), so the pairs still come best bound first and the search is unchanged;
//    what it saves is bounding the pairs that could never be drawn. Motors it does not apply
//    to have all their pairs bounded as before. Tests: search_stages_test.cc (the key below
//    every feasible score of the small catalog; the stream draws the sorted BuildCandidates
//    list).
// R12 (the propeller's data window, mission.h: prop_below_data, prop_above_data): a hover speed
//    above the window at omega_lb (R2) or below it at the speed bound of the heaviest vehicle
//    (as R6) fails it whatever else is chosen (M1, M3); see the rule (PropRule). The window's
//    bottom is, like min_hover_throttle, a limit that more mass helps: the virtual ESC is
//    evaluated without it and an ESC that fails it does not rule out the ESCs it dominates (R5);
//    A feasible combination's mass is at least the mass whose hover thrust per rotor turns the
//    propeller at the window's bottom (M1, M3; WindowMassFloorKg): stage 4's pair bound and R10's
//    pieces are taken at no less. Per ESC and per R10 piece, a hover below the bottom at the
//    heaviest mass refuses it. MissionEvaluator::DataWindowRefuses decides both ends before a
//    solve (the search calls it before the virtual ESC, for the top only, and before each ESC).
// R8 (capacity pieces of R4, per pair and class): retired; R10's pieces bound a capacity range
//    segment by segment, which holds R8's terms and more.
// R5 (ESC dominance): within one pair, an ESC with the same C1, C0, tr_sat, sat_slope as an
//    ESC already evaluated but no lighter, no lower in resistance and no higher in current
//    rating scores no better (M2, M3) and is infeasible if the other is; so when the other is
//    infeasible or not in the top N, it is skipped. A virtual ESC of zero resistance, the
//    lightest mass and no current limit dominates all ESCs of a class: when it cannot enter
//    the top N the whole class is skipped for the pair. min_hover_throttle is the one
//    constraint that more resistance or mass helps: the virtual ESC is evaluated without it,
//    and an ESC that fails it does not rule out the ESCs it dominates. Only whether the
//    virtual ESC's score beats the threshold is used, so its solve stops at the first feasible
//    point that beats it (MissionEvaluator::Solve's decide: the optimum is no worse).
// R6 (propeller data credibility): see the comment at the rule; the hover point's figure of
//    merit must not exceed the mission's max_figure_of_merit.
// R7 (static-only propeller data in fast axial flow): see the comment at the rule.
// G1 (propulsion groups): the search chooses the parts of one group; the others are fixed
//    (several free groups: G2 below fixes all but one in turn).
//    Every group's mass is in mass_lb and mass_ub (the fixed groups' exactly), R0-R3, R6, R7
//    speak of the free group's segments only, and in R4 a fixed group's segment draws at least
//    its own drive's PDC at the lightest vehicle mass the option allows (its thrust rises with
//    the mass, M3; speed and torque from below by bisection on the thrust, M1; PDC at the
//    smaller of the full-charge and cut-off voltage, eq 59) plus P_avionics, tabulated on a
//    mass grid and read at or below each pair's own lightest mass; a wing-borne cruise with a
//    free airspeed draws, cell by cell over its airspeed range, at least the larger of momentum
//    theory's power and the group's own drive's (M4; prop_bounds.h, FreeCruisePowerLowerBoundW),
//    over the cell's shortest duration. The groups are
//    coupled only through the mass and the shared pack's energy, so each bound stays a bound.
//    Thrust-to-weight and winding temperature: more mass or ESC resistance only lowers the
//    first and raises the second, so R5 (the virtual ESC is evaluated without the
//    thrust-to-weight, a relaxation) and the capacity screening stay sound.
// G2 (several free groups; joint_search.h): each free group picks its own motor, ESC and
//    propeller. The search fixes one free group at a time: the outer group g (a free group that
//    does not lift the vehicle, so that the innermost search is the lift group's, where R2-R4
//    grip) and, per (motor, ESC, propeller) of g and battery option, the search with g fixed to
//    them and the battery to that option (recursively until one group is free: stages 0-5
//    above with G1), asked only for results below the N-th best so far (its cutoff: pruning
//    against a threshold at least the final N-th best is safe, and the merge of the lists is
//    the top N). An outer choice is searched only when a lower bound of every completion's
//    score is below that N-th best. The bound, per segment a terminal power that every
//    completion draws at least at every instant, assembled as in R4 (min_energy: the sum of
//    power x shortest duration; max_endurance: the energy budget of the largest pack; none for
//    max_efficiency or a stretched free-airspeed cruise):
//    - mass: every group at its lightest. A fixed group exactly; a free group h at the lightest
//      motor + propeller that survives R0, R1, R3, R7 in all of h's segments with some ESC
//      class (and, for the lift group, reaches min_thrust_to_weight at its no-load speed at full
//      throttle and the full-charge voltage: the full-throttle speed is below it, eqs 42, 48, and
//      the static thrust rises with speed, M1) at the lightest vehicle found so far (a feasible
//      choice survives them at its true,
//      heavier mass, so at any lighter one, M1-M3), plus the lightest ESC of the option; two
//      passes, each keeping it a lower bound. The outer group at its own motor + propeller +
//      (lightest or its own) ESC. R7 as a mass floor for the outer group: static-only data in
//      axial flow V pass only at J = V/(n*D) <= max_static_advance_ratio, i.e. at a speed with a
//      static thrust of at least T(n_min) (M1), which needs at least the mass whose segment
//      thrust is T(n_min) (M3); the bound is read at the larger mass.
//    - a segment of a fixed group: G1's bound with its own drive (speed and torque at or below
//      the evaluator's by bisection on the thrust at the segment's axial airspeed, the
//      scenario's torque, PDC the smaller at the full-charge and cut-off voltage, eq 59).
//    - a segment of the outer group: the same with the zero-resistance drive of the ESC class
//      (M2; per pair) or the real ESC (per triple), at the mass grid point at or below the
//      choice's lightest mass (G1's grid); and R3 (throttle, Irms, PAC, the ESC's current
//      rating), R7 (no-load speed) and the thrust-to-weight rule above at that point: a choice
//      that fails them is infeasible.
//    - a segment of another free group: the least of that bound over all its (motor, ESC class,
//      propeller) choices that survive R0, R1, R3, R7 (and the thrust-to-weight rule) at the
//      lightest vehicle (each is below the
//      choice's power at any heavier mass, M3), found without trying every choice: a
//      propeller's floor rotors*max(Q*omega, P_ideal/max(1, max_figure_of_merit)) bounds every
//      drive that cannot create energy (PDC >= Pmech, model.md section 10; the scenario's
//      propeller power is at least P_ideal in every scenario, credibility.h), so propellers
//      are tried in order of their floor until it reaches the least bound found; drives that
//      could create energy are tried on every propeller.
//    - coupled (two free groups, min_energy; for the pairs taken): the other free group's
//      choices that survive those rules at the vehicle with their own mass, lightest first,
//      give a frontier of (extra mass over its lightest, least energy of its segments); every
//      feasible choice has a frontier point no heavier and with no more energy, so the least
//      over the points of (the outer choice's energy at the vehicle with that extra mass, at
//      least the R7 floor) + (the point's energy) + (the other segments' bounds) is a bound too,
//      and the larger of the two bounds is used.
//    Each term is a lower bound of that segment's terminal power for every completion of the
//    outer choice, the groups being coupled only through the mass (a lower bound used) and the
//    shared pack's energy (R4's budget), so the assembled number bounds the score. Outer pairs
//    (motor, propeller, option) are taken best bound first and the loop stops at the first
//    bound not below the N-th best. R5 for the outer group: per pair and ESC class, the inner
//    search runs first with the class's virtual ESC (no resistance, the lightest mass of the
//    class's ESCs still in play, no current limit; two free groups, a ranking that flies the
//    catalog's ESC values) on the mission without min_hover_throttle; every real ESC of the
//    class scores no better with every completion and is infeasible where it is (M2, M3), so
//    when that search finds nothing below the N-th best the class is skipped. tests/optimization/joint_search_test.cc checks the bounds
//    against every feasible combination of a small catalog and the answer against exhaustive
//    evaluation. Counts: combinations is the product over the free groups of motors x ESCs x
//    propellers, times the battery options; an outer choice pruned counts all its completions.
//    Order: a pair's coupled bound is computed when its uncoupled one is the least in the queue
//    (the coupled one is at least the uncoupled one), and the per-ESC inner searches wait in the
//    same queue under their triple bound, so every pair and triple is taken best bound first
//    and the loop stops at the first bound not below the N-th best. Before any result exists,
//    a class's best-bound ESC is searched first (its inner search sets the N-th best that the
//    virtual ESC's search below uses as its cutoff). While no N-th best is known, an inner
//    search that has not finished after kFirstSearchBudget solves (real and virtual ESCs) is
//    dropped, its results unused, and taken again once an N-th best exists (its bound then
//    decides) or when nothing else is left (without the budget): the order changes, not what is
//    searched. Without it an outer choice that no completion makes feasible (a pusher whose
//    cruise fails prop_figure_of_merit at every mass) searched the whole inner group without a
//    cutoff, 18 s each.
//    R6 as a mass floor for the outer group (FigureOfMeritMassFloorKg): in a segment at a fixed
//    axial inflow v the evaluator's figure of merit is P_ideal(T, v)/P(omega), the propeller's
//    power as given at the speed that gives the segment's thrust T. On a mass cell [M_a, M_b]
//    the thrust is in [T(M_a), T(M_b)] (M3) and the speed at or below omega_b, a speed whose
//    thrust is at least T(M_b) (M1); where the power rises with speed over the cell's speeds
//    (checked at samples, as the grids are) it is at most P(omega_b), and P_ideal rises with T,
//    so the figure of merit is at least P_ideal(T(M_a), v)/P(omega_b). A cell where that is
//    above max_figure_of_merit holds no feasible mass; cells are scanned up from the lightest
//    vehicle and the floor is the bottom of the first one not proven so. The outer bounds are
//    read at no less than the floor (as R7's), so they stay bounds (M3).
// G3 (the class's real ESCs from one virtual search): the virtual ESC's inner search above asks
//    for every completion (the inner group's motor, ESC, propeller and the pack) below the N-th
//    best, up to kCompletionLimit of them (joint_search.cc). With the virtual ESC on the relaxed
//    mission every completion scores no better with a real ESC e of the class on the mission
//    (M2, M3, as in R5), so a completion missing from that list cannot beat the N-th best with e
//    either, when the list holds every completion below it: when fewer than the limit were
//    found, or when the N-th best is at or below the list's last score (the search's top list is
//    exact). Then (outer pair, e) is solved exactly with each listed completion, best virtual
//    score first, until that score reaches the N-th best, instead of a whole inner search per
//    ESC; otherwise e gets its inner search. A solve is MissionEvaluator::Solve on the mission
//    with the outer group and the pack fixed, as the inner search's own.
// Everything not pruned is evaluated exactly (MissionEvaluator::Solve): the answer is the
// true top N over the catalog under (M1)-(M3).

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kChargeAllowance = 1.0 - 1e-3;  // R10's charge bound

// Counts per pruning rule without building a string per pruned pair (rule names are literals).
class RuleCounts {
 public:
  void Add(const char* rule, long long n) {
    for (auto& [name, count] : counts_) {
      if (std::strcmp(name, rule) == 0) {
        count += n;
        return;
      }
    }
    counts_.emplace_back(rule, n);
  }
  void MergeInto(std::map<std::string, long long>* out) const {
    for (const auto& [name, count] : counts_) (*out)[name] += count;
  }
  void MergeInto(RuleCounts* out) const {
    for (const auto& [name, count] : counts_) out->Add(name, count);
  }

 private:
  std::vector<std::pair<const char*, long long>> counts_;
};

// A result that breaks min_hover_throttle or prop_below_data (possibly among others) says
// nothing about a dominated ESC, whose higher throttle, or mass and so speed, may meet it (R5).
bool FailsMinHoverThrottle(const MissionResult& r) {
  for (const Violation& v : r.violations) {
    if (v.constraint == "min_hover_throttle" || v.constraint == "prop_below_data") return true;
  }
  return false;
}

bool Dominates(const EscEntry& a, const EscEntry& b) {
  return EscMassKg(a) <= EscMassKg(b) && a.params.resc_ohm <= b.params.resc_ohm &&
         a.params.max_current_a >= b.params.max_current_a && a.params.vdc_max_v >= b.params.vdc_max_v;
}

}  // namespace

namespace search_internal {

std::vector<BatteryOption> BatteryOptions(const Mission& m, const Catalog& cat) {
  std::vector<BatteryOption> options;
  for (const std::string& id : m.battery.ids) {
    const BatteryEntry& b = cat.battery(id);
    if (!b.mass_kg) throw DataError("battery '" + id + "' has no mass_kg: the mission needs it");
    for (int s = m.battery.cells_min; s <= m.battery.cells_max; ++s) {
      if (s % b.cells_series != 0) continue;
      const BatteryPack pack(PackFromEntry(b, s / b.cells_series, 1));
      DischargeOptions d;
      if (m.battery.cutoff_cell_v) d.cutoff_cell_v = *m.battery.cutoff_cell_v;
      BatteryOption o{&b, s, pack.OcvV(1.0), pack.cutoff_v(d), pack.capacity_ah(), pack.capacity_ah(),
                      pack.mass_kg(), pack.mass_kg(), pack.max_current_a()};
      o.ocv_integral_v = OcvIntegralUpperBound(pack, m.battery.reserve_soc);
      o.chemistry = pack.params().chemistry;
      o.ri_at_hi_ohm = pack.ri_ohm();
      if (m.battery.capacity_ah) {
        const double k_lo = m.battery.capacity_ah->lo / pack.capacity_ah();
        const double k_hi = m.battery.capacity_ah->hi / pack.capacity_ah();
        o.capacity_lo_ah = m.battery.capacity_ah->lo;
        o.capacity_hi_ah = m.battery.capacity_ah->hi;
        o.mass_lo_kg = pack.mass_kg() * k_lo;
        o.mass_hi_kg = pack.mass_kg() * k_hi;
        o.max_current_hi_a = pack.max_current_a() * k_hi;
        o.ri_at_hi_ohm = pack.ri_ohm() / k_hi;
      }
      options.push_back(o);
    }
  }
  if (options.empty()) {
    throw UsageError("mission battery: no cell count in [" + std::to_string(m.battery.cells_min) + ", " +
                     std::to_string(m.battery.cells_max) + "] is a multiple of the entries' cells in series");
  }
  return options;
}

EscTable BuildEscTable(const Catalog& cat, const std::vector<BatteryOption>& options) {
  const auto& escs = cat.escs();
  EscTable t;
  for (std::size_t i = 0; i < escs.size(); ++i) {
    const EscParams& e = escs[i].params;
    auto it = std::find_if(t.classes.begin(), t.classes.end(), [&](const EscClass& c) {
      return c.c1 == e.c1 && c.c0 == e.c0 && c.tr_sat == e.tr_sat && c.sat_slope == e.sat_slope;
    });
    if (it == t.classes.end()) {
      t.classes.push_back({e.c1, e.c0, e.tr_sat, e.sat_slope, {}});
      it = t.classes.end() - 1;
    }
    it->members.push_back(static_cast<int>(i));
  }
  t.per_option.resize(options.size());
  t.currents_ascending.resize(options.size());
  t.running_max_current.resize(options.size());
  t.min_mass_kg.assign(options.size(), kInf);
  t.max_mass_kg.assign(options.size(), 0.0);
  for (std::size_t o = 0; o < options.size(); ++o) {
    long long n_ok = 0, n_excluded = 0;
    for (const EscClass& c : t.classes) {
      std::vector<int> ok;
      for (int i : c.members) {
        if (!escs[i].exclude_reason.empty()) {  // R0: the catalog excludes it
          ++n_excluded;
          continue;
        }
        if (escs[i].params.vdc_max_v >= options[o].v_full) {  // R1
          ok.push_back(i);
          t.min_mass_kg[o] = std::min(t.min_mass_kg[o], EscMassKg(escs[i]));
          t.max_mass_kg[o] = std::max(t.max_mass_kg[o], EscMassKg(escs[i]));
        }
      }
      std::sort(ok.begin(), ok.end(), [&](int a, int b) {
        const double ma = EscMassKg(escs[a]), mb = EscMassKg(escs[b]);
        if (ma != mb) return ma < mb;
        if (escs[a].params.resc_ohm != escs[b].params.resc_ohm) return escs[a].params.resc_ohm < escs[b].params.resc_ohm;
        return escs[a].params.max_current_a > escs[b].params.max_current_a;
      });
      n_ok += static_cast<long long>(ok.size());
      std::vector<double> ascending, running_max;
      for (int i : ok) {
        ascending.push_back(escs[i].params.max_current_a);
        running_max.push_back(std::max(running_max.empty() ? -kInf : running_max.back(), escs[i].params.max_current_a));
      }
      std::sort(ascending.begin(), ascending.end());
      t.currents_ascending[o].push_back(std::move(ascending));
      t.running_max_current[o].push_back(std::move(running_max));
      t.per_option[o].push_back(std::move(ok));
    }
    t.rated.push_back(n_ok);
    t.voltage_pruned += static_cast<long long>(escs.size()) - n_ok - n_excluded;
    t.excluded_pruned += n_excluded;
  }
  return t;
}

double BudgetScore(double t_fixed_max_s, double e_max_j, double e_other_j, double p_stretch_w) {
  return p_stretch_w > 0 ? -(t_fixed_max_s + std::max(0.0, e_max_j - e_other_j) / p_stretch_w) : -kInf;
}

const char* PropFrameRule(const Mission& m, int group, bool lifts, const PropEntry& prop) {
  const std::optional<double> d_max = GroupMaxPropDiameterM(m, group);
  if (d_max && prop.diameter_m > *d_max) return "prop_diameter";
  if (!prop.exclude_reason.empty()) return "catalog_exclude";
  if (lifts && FoldingPropRefused(prop, m)) return "prop_folding";
  return nullptr;
}

std::vector<double> InflowsOf(const Mission& m) {
  std::vector<double> v;
  for (const Segment& sg : m.segments) {
    if (sg.type == SegmentType::kClimb && sg.climb_rate_m_s > 0) v.push_back(sg.climb_rate_m_s);
    if (sg.type == SegmentType::kCruise && sg.lift_to_drag > 0 && !sg.airspeed_m_s.free()) v.push_back(sg.airspeed_m_s.lo);
  }
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

void BuildPropGrids(const Mission& m, const Catalog& cat, std::vector<PropGrid>* grids,
                    std::vector<std::unique_ptr<PropModel>>* models) {
  const auto& props = cat.props();
  const std::vector<double> inflows = InflowsOf(m);
  grids->assign(props.size(), PropGrid{});
  models->clear();
  models->resize(props.size());
  for (std::size_t p = 0; p < props.size(); ++p) {
    (*models)[p] = std::make_unique<PropModel>(props[p]);
    const PropModel& model = *(*models)[p];
    const PropAdjustment prop_adj = PropAdjustmentFor(props[p], m.objective.ranking);
    PropGrid& g = (*grids)[p];
    g.adjustment = prop_adj;
    g.mass_kg = PropMassKg(props[p]);
    if (m.constraints.prop_below_data_factor > 0) {
      g.window_factor = m.constraints.prop_below_data_factor;
      g.window_thrust_n =
          model.Evaluate(RpmToRadPerSec(g.window_factor * model.valid_range().rpm_lo), m.rho_kg_m3, 0.0).thrust_n;
    }
    double torque[kGrid];
    for (int i = 0; i < kGrid; ++i) {
      g.omega[i] = kGridMinRadS * std::pow(kGridMaxRadS / kGridMinRadS, i / double(kGrid - 1));
      PropEvaluation ev = model.Evaluate(g.omega[i], m.rho_kg_m3, 0.0);
      g.thrust[i] = ev.thrust_n;
      g.fom[i] = ev.power_w > 0 ? FigureOfMerit(ev.thrust_n, ev.power_w, props[p].diameter_m, m.rho_kg_m3) : kInf;
      // The FM limit (R6) judges the data; the load is the scenario's (credibility.h), as in
      // the evaluator. The adjustment only raises the torque, and keeps it rising with speed.
      AdjustPropEvaluation(prop_adj, props[p].diameter_m, &ev);
      torque[i] = ev.torque_nm;
      if (i > 0 && !(g.thrust[i] > g.thrust[i - 1])) g.monotone = false;
    }
    g.torque_suffix_min[kGrid - 1] = torque[kGrid - 1];
    for (int i = kGrid - 2; i >= 0; --i) g.torque_suffix_min[i] = std::min(torque[i], g.torque_suffix_min[i + 1]);
    g.torque_prefix_max[0] = torque[0];
    for (int i = 1; i < kGrid; ++i) g.torque_prefix_max[i] = std::max(torque[i], g.torque_prefix_max[i - 1]);
    if (model.data_kind() == PropDataKind::kTables && !props[p].j_tables.empty()) {
      for (const double v : inflows) {  // R10: as the evaluator reads them in that inflow
        InflowGrid ig;
        ig.v_m_s = v;
        double q[kGrid];
        for (int i = 0; i < kGrid; ++i) {
          PropEvaluation ev = model.Evaluate(g.omega[i], m.rho_kg_m3, v);
          ig.thrust[i] = ev.thrust_n;
          AdjustPropEvaluation(prop_adj, props[p].diameter_m, &ev);
          q[i] = ev.torque_nm;
          if (i > 0 && !(ig.thrust[i] > ig.thrust[i - 1])) ig.monotone = false;
        }
        ig.torque_suffix_min[kGrid - 1] = q[kGrid - 1];
        for (int i = kGrid - 2; i >= 0; --i) ig.torque_suffix_min[i] = std::min(q[i], ig.torque_suffix_min[i + 1]);
        g.inflow.push_back(ig);
      }
    }
    const double fom_limit = 1.02 * m.constraints.max_figure_of_merit;  // R6's allowance (PropRule)
    int next_ok = kGrid;
    for (int i = kGrid - 1; i >= 0; --i) {
      if (g.fom[i] <= fom_limit) next_ok = i;
      g.fom_ok_next[i] = next_ok;
    }
  }
}

namespace {

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
};

// Groups (G1): the rules below speak of the free group's segments only; a segment of a fixed
// group draws at least P_avionics (its drive's power is >= 0), and every group's mass is in
// mass_lb and mass_ub, so each bound stays a bound.
MissionFacts FactsOf(const Mission& m, int free_group) {
  MissionFacts f;
  for (std::size_t i = 0; i < m.segments.size(); ++i) {
    if (m.segments[i].type == SegmentType::kHover && m.segments[i].group == free_group) {
      f.hover.push_back(static_cast<int>(i));
    }
  }
  f.t_fixed_max = LongestFixedDurationS(m);
  f.stretch_is_hover = m.objective.type == ObjectiveType::kMaxEndurance &&
                       m.segments[m.objective.segment_index].type == SegmentType::kHover &&
                       m.segments[m.objective.segment_index].group == free_group;
  f.free_group = free_group;
  f.free_lifts = free_group == std::max(0, LiftGroup(m));
  return f;
}

// FactsOf with what stage 4 reads per propeller (R0) and per pair (R7) worked out once.
MissionFacts StageFourFacts(const SearchContext& ctx) {
  const Mission& m = *ctx.mission;
  MissionFacts f = FactsOf(m, ctx.free_group);
  const auto& props = ctx.catalog->props();
  for (std::size_t pi = 0; pi < props.size(); ++pi) {
    const char* rule = PropFrameRule(m, f.free_group, f.free_lifts, props[pi]);
    if (!rule) {
      f.frame_ok_props.push_back(static_cast<int>(pi));
      continue;
    }
    auto it = std::find_if(f.prop_frame_counts.begin(), f.prop_frame_counts.end(),
                           [&](const auto& x) { return std::strcmp(x.first, rule) == 0; });
    if (it == f.prop_frame_counts.end()) it = f.prop_frame_counts.insert(f.prop_frame_counts.end(), {rule, 0});
    ++it->second;
  }
  for (const Segment& sg : m.segments) {
    if (sg.group != f.free_group) continue;
    if (sg.type == SegmentType::kClimb && sg.climb_rate_m_s > 0) f.r7_axial_m_s = std::max(f.r7_axial_m_s, sg.climb_rate_m_s);
    if (sg.type == SegmentType::kCruise && sg.lift_to_drag > 0) f.r7_axial_m_s = std::max(f.r7_axial_m_s, sg.airspeed_m_s.lo);
  }
  return f;
}

// The rotor loads of one pair's lightest mass (SegmentRotorLoad), computed once per pair
// instead of once per ESC class: per segment at its lowest and highest airspeed (the same
// numbers, so the bounds do not change).
class PairLoads {
 public:
  explicit PairLoads(const Mission& m) : m_(m), lo_(m.segments.size()), hi_(m.segments.size()) {}
  void Reset(double mass_kg) {
    mass_kg_ = mass_kg;
    for (auto& x : lo_) x.first = false;
    for (auto& x : hi_) x.first = false;
    for (auto& x : energy_) x.first = false;
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
  // The segment's load at airspeed v_m_s, which must be the same value per (segment, high) for
  // one mass (the callers pass airspeed_m_s.lo or .hi, or 0).
  double mass_kg() const { return mass_kg_; }
  const RotorLoad& At(std::size_t si, bool high, double v_m_s) {
    std::pair<bool, RotorLoad>& x = (high ? hi_ : lo_)[si];
    if (!x.first) x = {true, SegmentRotorLoad(m_, m_.segments[si], mass_kg_, v_m_s)};
    return x.second;
  }

 private:
  const Mission& m_;
  double mass_kg_ = 0;
  std::vector<std::pair<bool, RotorLoad>> lo_, hi_;
  std::vector<std::pair<bool, double>> energy_;
  std::vector<PowerTerm> terms_;
};

// Momentum theory's bound of a propeller segment's terminal power, W, when no stage can create
// energy: N*P_ideal(T, V)/max_figure_of_merit + P_avionics (the evaluator's
// prop_figure_of_merit; V the axial inflow with forward-flight tables, else 0, as
// PropellerPoint judges it; P_ideal rises with the thrust).
double MomentumPowerW(const Mission& m, const RotorLoad& ld, double diameter_m, bool axial_data) {
  const double p_ideal =
      IdealRotorPowerW(ld.thrust_per_rotor_n, diameter_m, m.rho_kg_m3, axial_data ? ld.axial_airspeed_m_s : 0.0);
  return ld.rotors * p_ideal / m.constraints.max_figure_of_merit + m.vehicle.avionics_power_w;
}

// R4's terminal power bound of segment si at every instant, W, for a pair at the mass of
// `loads`, given the hover bound's per-rotor PDC pdc_lb. The terminal power of a segment is at
// least N*PDC_lb + P_avionics when each of its N rotors must give at least T_lb (hover[0]'s
// per-rotor thrust at the lightest mass, which defines omega_lb and Q_lb) from the same
// speed-thrust curve: hover segments, and climb or fixed-airspeed cruise segments of a
// propeller with static-only data (the evaluator reads them at J = 0 in any inflow, so speed
// and torque are at least omega_lb and Q_lb there too, M1, M2); *scales says so. Any other
// segment draws at least P_avionics. Everything but pdc_lb depends on the pair only: kept per
// pair (PairLoads::Term). Requires a hover segment (f.hover not empty).
double SegmentPowerLowerBoundW(const SearchContext& ctx, const MissionFacts& f, const PropEntry& prop,
                               const PropModel& model, std::size_t option, PairLoads* loads, std::size_t si,
                               double pdc_lb) {
  const Mission& m = *ctx.mission;
  const PairLoads::PowerTerm& t = loads->Term(si, [&](PairLoads::PowerTerm* x) {
    const Segment& sg = m.segments[si];
    x->constant = m.vehicle.avionics_power_w;
    if (sg.group != f.free_group) {  // G1: the fixed group's own bound at the lightest mass
      if (!ctx.fixed_power_lb_w.empty()) x->constant = FixedPowerLowerBoundW(ctx, option, si, loads->mass_kg());
      return;
    }
    const double t_lb = loads->At(static_cast<std::size_t>(f.hover[0]), false, 0.0).thrust_per_rotor_n;
    const bool static_only = model.data_kind() != PropDataKind::kTables || prop.j_tables.empty();
    const bool fixed_v = sg.type != SegmentType::kCruise || !sg.airspeed_m_s.free();
    if (sg.type == SegmentType::kHover ||
        (static_only && fixed_v && (sg.type == SegmentType::kClimb || sg.type == SegmentType::kCruise))) {
      const RotorLoad& ld = loads->At(si, false, sg.type == SegmentType::kCruise ? sg.airspeed_m_s.lo : 0.0);
      if (ld.thrust_per_rotor_n >= t_lb) {
        x->scales = true;
        x->rotors = ld.rotors;
      }
    }
  });
  return t.scales ? t.rotors * pdc_lb + m.vehicle.avionics_power_w : t.constant;
}

// R4: a lower bound of the score of a (motor, propeller, option) pair with an ESC class whose
// drive is lossy or not (DriveIsLossy: only then momentum theory bounds the power drawn),
// given the hover bound's per-rotor electrical power pdc_lb at the lightest mass (R11: a floor
// of it that holds for a class of motors). loads: PairLoads at that mass.
double ScoreLowerBound(const SearchContext& ctx, const MissionFacts& f, bool lossy, const PropEntry& prop,
                       const PropModel& model, std::size_t option, PairLoads* loads, double pdc_lb) {
  const BatteryOption& bo = ctx.options[option];
  const Mission& m = *ctx.mission;
  if (f.hover.empty()) return -kInf;
  auto p_lb_of = [&](std::size_t si) {
    return SegmentPowerLowerBoundW(ctx, f, prop, model, option, loads, si, pdc_lb);
  };
  // The shortest a segment can last (free airspeed: at its top speed).
  auto t_min_of = [&](const Segment& sg) { return SegmentDurationS(sg, sg.airspeed_m_s.hi); };
  if (m.objective.type == ObjectiveType::kMinEnergy) {
    // Per segment the larger of: the hover bound above, and momentum theory. A feasible point
    // has prop power >= P_ideal/max_figure_of_merit (the evaluator's prop_figure_of_merit
    // constraint; P_ideal of model/physics.h per rotor), and PDC >= Pmech when neither the
    // motor nor the ESC can create energy (model.md section 10: KT <= sqrt(27/10)*KE, C0 >= 0,
    // C1 + C0 >= 1.1095; then eta_motor, eta_esc <= 1; a point that breaks it is infeasible,
    // creates_energy). V is the axial inflow (0 for static-only data: P_ideal rises with V).
    // (The inequalities of model/physics.h without its rounding allowance: exact here.)
    const bool axial_data = !prop.j_tables.empty();
    double e = 0;
    for (std::size_t si = 0; si < m.segments.size(); ++si) {
      const Segment& sg = m.segments[si];
      double e_seg = p_lb_of(si) * t_min_of(sg);
      const bool fixed_v = sg.type != SegmentType::kCruise || !sg.airspeed_m_s.free() || sg.lift_to_drag > 0;
      if (lossy && sg.group == f.free_group && sg.type != SegmentType::kShaft && fixed_v &&
          (sg.type != SegmentType::kCruise || sg.lift_to_drag > 0)) {
        const double v = sg.type == SegmentType::kCruise ? sg.airspeed_m_s.hi : 0.0;
        e_seg = std::max(e_seg, MomentumPowerW(m, loads->At(si, true, v), prop.diameter_m, axial_data) *
                                    SegmentDurationS(sg, v));
      }
      e += e_seg;
    }
    return e / 3600.0;
  }
  // max_endurance: the other segments' energy, each at least its power bound times its
  // shortest duration and, for the free group's propeller segments at a fixed airspeed when no
  // stage can create energy, momentum theory's N*P_ideal(T, V)/max_figure_of_merit plus the
  // avionics over its duration (the evaluator's prop_figure_of_merit; V the axial inflow with
  // forward-flight tables, else 0, as PropellerPoint judges it; P_ideal rises with the mass).
  const bool table_data = model.data_kind() == PropDataKind::kTables && !prop.j_tables.empty();
  auto e_other_of = [&](std::size_t stretch) {
    double e_other = 0;
    for (std::size_t si = 0; si < m.segments.size(); ++si) {
      if (si == stretch) continue;
      const Segment& sg = m.segments[si];
      double e_seg = p_lb_of(si) * t_min_of(sg);
      if (lossy && sg.group == f.free_group && sg.type != SegmentType::kShaft &&
          !(sg.type == SegmentType::kCruise && sg.airspeed_m_s.free())) {
        e_seg = std::max(e_seg, loads->PerSegment(si, [&]() {
          const double v = sg.type == SegmentType::kCruise ? sg.airspeed_m_s.lo : 0.0;
          return MomentumPowerW(m, loads->At(si, false, v), prop.diameter_m, table_data) * SegmentDurationS(sg, v);
        }));
      }
      e_other += e_seg;
    }
    return e_other;
  };
  if (f.stretch_is_hover) {
    // Terminal energy = integral of V*I dt <= integral of OCV*I dt = Q*integral of OCV(s) ds
    // over [reserve, 1] (coulomb counting): the energy budget.
    const double e_other = e_other_of(static_cast<std::size_t>(m.objective.segment_index));
    const double p_stretch = p_lb_of(static_cast<std::size_t>(m.objective.segment_index));
    const double e_max = bo.ocv_integral_v * AhToCoulomb(bo.capacity_hi_ah);
    return BudgetScore(f.t_fixed_max, e_max, e_other, p_stretch);
  }
  const std::size_t ist = static_cast<std::size_t>(std::max(0, m.objective.segment_index));
  const Segment& st = m.segments[ist];
  if (m.objective.type == ObjectiveType::kMaxEndurance && st.group == f.free_group &&
      st.type == SegmentType::kCruise && !st.airspeed_m_s.free()) {
    // The same energy budget with a fixed-airspeed cruise stretched: its thrust is constant, so
    // at every instant its power is at least p_lb_of (static-only data, above) and, when no
    // stage can create energy, N*P_ideal(T, V)/max_figure_of_merit + P_avionics (the
    // evaluator's prop_figure_of_merit; V the axial inflow with forward-flight tables, else 0,
    // as PropellerPoint judges it), at the lightest mass (M3).
    double p_stretch = p_lb_of(ist);
    if (lossy) {
      p_stretch = std::max(p_stretch, MomentumPowerW(m, loads->At(ist, false, st.airspeed_m_s.lo), prop.diameter_m, table_data));
    }
    const double e_other = e_other_of(ist);
    const double e_max = bo.ocv_integral_v * AhToCoulomb(bo.capacity_hi_ah);
    return BudgetScore(f.t_fixed_max, e_max, e_other, p_stretch);
  }
  return -kInf;
}

// R10: the grid a segment of the free group is read on, with its thrust and torque from below
// (null when none applies: a shaft segment, a free airspeed, a multirotor cruise with
// forward-flight tables, whose inflow changes with the mass, or a non-monotone grid).
struct SegmentGrid {
  const double* thrust = nullptr;
  const double* torque_suffix_min = nullptr;
  double v_m_s = 0;  // the inflow the grid was built in
};
SegmentGrid GridOf(const PropGrid& g, bool axial_data, const Segment& sg, const RotorLoad& ld) {
  if (sg.type == SegmentType::kShaft || (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free())) return {};
  if (!axial_data || ld.axial_airspeed_m_s == 0.0) {
    if (axial_data && sg.type == SegmentType::kCruise && sg.lift_to_drag <= 0) return {};
    return g.monotone ? SegmentGrid{g.thrust, g.torque_suffix_min} : SegmentGrid{};
  }
  if (sg.type == SegmentType::kCruise && sg.lift_to_drag <= 0) return {};
  for (const InflowGrid& ig : g.inflow) {
    if (ig.v_m_s == ld.axial_airspeed_m_s) return ig.monotone ? SegmentGrid{ig.thrust, ig.torque_suffix_min, ig.v_m_s} : SegmentGrid{};
  }
  return {};
}

// R10's speed and torque from below for a thrust T on a segment's grid: the grid point at or
// below T (0 below the grid), and with refine_steps > 0 the speed bisected that many times
// within the grid cell on the propeller model itself (the largest speed found whose thrust is
// at most T: still at or below the root, M1), the torque there (the scenario's), capped by
// the grid's least torque above the cell. By (M1) the torque at any speed at or above the
// bisected one is at least its torque there.
void SpeedTorqueFromBelow(const PropGrid& g, const SegmentGrid& sgrid, const PropModel& model, double diameter_m,
                          double rho, double thrust_n, int refine_steps, double* omega, double* torque) {
  const double* it = std::upper_bound(sgrid.thrust, sgrid.thrust + kGrid, thrust_n);
  const int idx = static_cast<int>(it - sgrid.thrust) - 1;  // last grid thrust <= T
  *omega = 0;
  *torque = 0;
  if (idx < 0) return;
  *omega = g.omega[idx];
  *torque = sgrid.torque_suffix_min[idx];
  if (refine_steps <= 0 || idx + 1 >= kGrid) return;
  const double lo = BisectSpeedFromBelow(model, rho, thrust_n, sgrid.v_m_s, g.omega[idx], g.omega[idx + 1], refine_steps);
  if (lo == g.omega[idx]) return;
  PropEvaluation ev = model.Evaluate(lo, rho, sgrid.v_m_s);
  AdjustPropEvaluation(g.adjustment, diameter_m, &ev);
  *omega = lo;
  *torque = std::min(ev.torque_nm, sgrid.torque_suffix_min[idx + 1]);
}

// R12 as a mass floor: a feasible combination hovers at least at the window's bottom w_min, so
// (M1) each rotor's hover thrust is at least T(w_min), and the vehicle's mass at least the mass
// whose hover thrust per rotor that is (proportional to the mass, flight.h), shrunk by 1e-9
// against rounding. 0 when the rule does not apply. Every bound computed at a mass of at least
// this stays a bound of every feasible score (M3).
double WindowMassFloorKg(const SearchContext& ctx, const MissionFacts& f, int prop) {
  const Mission& m = *ctx.mission;
  const PropGrid& g = ctx.grids[static_cast<std::size_t>(prop)];
  if (!(m.constraints.prop_below_data_factor > 0) || f.hover.empty() || !g.monotone) return 0.0;
  const PropModel& model = *ctx.models[static_cast<std::size_t>(prop)];
  const double factor = m.constraints.prop_below_data_factor;
  const double t_min = g.window_factor == factor
                           ? g.window_thrust_n  // computed once (BuildPropGrids)
                           : model.Evaluate(RpmToRadPerSec(factor * model.valid_range().rpm_lo), m.rho_kg_m3, 0.0).thrust_n;
  const double per_kg = SegmentRotorLoad(m, m.segments[static_cast<std::size_t>(f.hover[0])], 1.0, 0.0).thrust_per_rotor_n;
  return per_kg > 0 ? (1.0 - 1e-9) * t_min / per_kg : 0.0;
}

// R12 (the window's bottom): true when the first hover's speed at the vehicle mass mass_ub_kg (an
// upper bound of the true mass) is below the propeller's data window, so that it is below it at
// every mass up to mass_ub_kg (M1, M3).
bool HoverSpeedBelowWindowAtMass(const SearchContext& ctx, const MissionFacts& f, int prop, double mass_ub_kg) {
  const Mission& m = *ctx.mission;
  const PropGrid& g = ctx.grids[static_cast<std::size_t>(prop)];
  if (!(m.constraints.prop_below_data_factor > 0) || f.hover.empty() || !g.monotone) return false;
  const RotorLoad load = SegmentRotorLoad(m, m.segments[static_cast<std::size_t>(f.hover[0])], mass_ub_kg, 0.0);
  const double* it = std::lower_bound(g.thrust, g.thrust + kGrid, load.thrust_per_rotor_n);
  if (it == g.thrust + kGrid) return false;  // beyond the grid: no bound
  const PropModel& model = *ctx.models[static_cast<std::size_t>(prop)];
  const double w_min = RpmToRadPerSec(m.constraints.prop_below_data_factor * model.valid_range().rpm_lo);
  // The first grid speed whose thrust reaches T_ub is at or above the hover speed (M1).
  const std::ptrdiff_t i = it - g.thrust;
  double hi = g.omega[i];
  if (hi < w_min) return true;
  if (i == 0 || g.omega[i - 1] >= w_min) return false;  // the speed may be anywhere above w_min
  // Bisection within the cell on the model (static, as the evaluator reads a hover; the
  // scenarios do not change thrust): hi stays a speed whose thrust reaches T_ub.
  double lo = g.omega[i - 1];
  for (int step = 0; step < 20 && hi >= w_min; ++step) {
    const double mid = 0.5 * (lo + hi);
    (model.Evaluate(mid, m.rho_kg_m3, 0.0).thrust_n >= load.thrust_per_rotor_n ? hi : lo) = mid;
  }
  return hi * (1.0 + 1e-9) < w_min;  // 1e-9: the evaluator's root is found to a tolerance
}

// R10 for one pair and ESC class with ESCs of at least esc_mass_kg and capacities in
// [cap_a_ah, cap_b_ah] (see the rule): a lower bound of the score (-kInf when none applies), or
// kInf with *rule set when no such combination can fly the pair.
double SegmentwiseBoundAt(const SearchContext& ctx, const MissionFacts& f, const MotorParams& mp, const Drive& ideal,
                          double t_max, int motor, int prop, int option, double esc_mass_kg, double cap_a_ah,
                          double cap_b_ah, int refine_steps, const char** rule) {
  const Mission& m = *ctx.mission;
  const MissionConstraints& k = m.constraints;
  *rule = nullptr;
  const BatteryOption& bo = ctx.options[static_cast<std::size_t>(option)];
  const PropEntry& pe = ctx.catalog->props()[static_cast<std::size_t>(prop)];
  const PropGrid& g = ctx.grids[static_cast<std::size_t>(prop)];
  const MotorEntry& mo = ctx.catalog->motors()[static_cast<std::size_t>(motor)];
  // The pack at C_a (its mass rises with the capacity: the increment shrunk by 1e-9 against rounding, so that it
  // stays a lower bound)
  // and the charge, resistance and energy budget of C_b (PackAt).
  const double span_ah = bo.capacity_hi_ah - bo.capacity_lo_ah;
  const double pack_kg = span_ah > 0 ? bo.mass_lo_kg + (1.0 - 1e-9) * (bo.mass_hi_kg - bo.mass_lo_kg) *
                                                           (cap_a_ah - bo.capacity_lo_ah) / span_ah
                                     : bo.mass_lo_kg;
  const double mass_lb =
      std::max(VehicleMassKg(ctx, pack_kg, *mo.mass_kg, g.mass_kg, esc_mass_kg), WindowMassFloorKg(ctx, f, prop));
  // R12 (the window's bottom) over the piece: at its heaviest (the pack at C_b, grown by 1e-9
  // against rounding, and the option's heaviest ESC) the first hover is below the window.
  if (span_ah > 0 && ctx.mission->constraints.prop_below_data_factor > 0) {
    const double pack_ub_kg =
        (1.0 + 1e-9) * (bo.mass_lo_kg + (bo.mass_hi_kg - bo.mass_lo_kg) * (cap_b_ah - bo.capacity_lo_ah) / span_ah);
    const double mass_ub = VehicleMassKg(ctx, pack_ub_kg, *mo.mass_kg, g.mass_kg, ctx.escs.max_mass_kg[option]);
    if (HoverSpeedBelowWindowAtMass(ctx, f, prop, mass_ub)) {
      *rule = "prop_below_data";
      return kInf;
    }
  }
  const double ri_ohm = bo.ri_at_hi_ohm * bo.capacity_hi_ah / cap_b_ah;
  const bool lossy = DriveIsLossy(mp, ideal.esc().c1, ideal.esc().c0);
  const bool axial_data = ctx.models[static_cast<std::size_t>(prop)]->data_kind() == PropDataKind::kTables &&
                          !pe.j_tables.empty();
  const double margin = 1.0 - k.current_margin;
  const double q_c = AhToCoulomb(cap_b_ah);
  const int stretch = m.objective.type == ObjectiveType::kMaxEndurance ? m.objective.segment_index : -1;
  const double p_av = m.vehicle.avionics_power_w;
  double charge_c = 0, e_other = 0, p_stretch = 0;
  for (std::size_t si = 0; si < m.segments.size(); ++si) {
    const Segment& sg = m.segments[si];
    double p_w = p_av;
    bool point = false;
    double w = 0, q = 0;
    if (sg.group != f.free_group) {
      if (!ctx.fixed_power_lb_w.empty()) p_w = FixedPowerLowerBoundW(ctx, static_cast<std::size_t>(option), si, mass_lb);
    } else if (sg.type != SegmentType::kShaft && !(sg.type == SegmentType::kCruise && sg.airspeed_m_s.free())) {
      const RotorLoad ld = SegmentRotorLoad(m, sg, mass_lb, sg.type == SegmentType::kCruise ? sg.airspeed_m_s.lo : 0.0);
      if (const SegmentGrid sgrid = GridOf(g, axial_data, sg, ld); sgrid.thrust) {
        SpeedTorqueFromBelow(g, sgrid, *ctx.models[static_cast<std::size_t>(prop)], pe.diameter_m, m.rho_kg_m3,
                             ld.thrust_per_rotor_n, refine_steps, &w, &q);
        point = true;
        // R12 (the window's top): the segment's speed is at least w.
        if (k.prop_above_data_factor > 0 &&
            RadPerSecToRpm(w) > k.prop_above_data_factor * ctx.models[static_cast<std::size_t>(prop)]->valid_range().rpm_hi) {
          *rule = "prop_above_data";
          return kInf;
        }
        const Drive::InverseCurrents hi = ideal.InverseLight(bo.v_full, q, w);
        if (hi.throttle > t_max) { *rule = "throttle"; return kInf; }
        if (hi.irms_a > mp.max_current_a * margin) { *rule = "motor_current"; return kInf; }
        if (k.enforce_motor_power && ideal.InverseAcPower(bo.v_full, hi, q, w) > mp.max_power_w) {
          *rule = "motor_power";
          return kInf;
        }
        const double pdc = std::max(0.0, std::min(bo.v_full * hi.idc_a, bo.v_cut * ideal.InverseLight(bo.v_cut, q, w).idc_a));
        p_w = ld.rotors * pdc + p_av;
      }
      if (lossy) p_w = std::max(p_w, MomentumPowerW(m, ld, pe.diameter_m, axial_data));  // as R4
    }
    const double t_min = static_cast<int>(si) == stretch ? 0.0 : SegmentDurationS(sg, sg.airspeed_m_s.hi);
    charge_c += kChargeAllowance * p_w * t_min / bo.v_full;
    const double soc = 1.0 - charge_c / q_c;
    if (soc < m.battery.reserve_soc) { *rule = "reserve_soc"; return kInf; }
    if (point) {
      const double v_ub = bo.OcvV(soc) - p_w / bo.v_full * ri_ohm;
      if (!(v_ub > 0) || ideal.InverseLight(v_ub, q, w).throttle > t_max) { *rule = "throttle"; return kInf; }
    }
    if (static_cast<int>(si) == stretch) {
      p_stretch = p_w;
    } else {
      e_other += p_w * t_min;
    }
  }
  if (m.objective.type == ObjectiveType::kMinEnergy) return e_other / 3600.0;
  if (stretch < 0) return -kInf;
  const Segment& st = m.segments[static_cast<std::size_t>(stretch)];
  if (st.type == SegmentType::kShaft || (st.type == SegmentType::kCruise && st.airspeed_m_s.free())) return -kInf;
  const double e_max = bo.ocv_integral_v * AhToCoulomb(cap_b_ah);
  return BudgetScore(f.t_fixed_max, e_max, e_other, p_stretch);
}

// R10 over the option's capacity range in pieces (one without a range): the least bound over
// the pieces that may be feasible; kInf with *rule (the first refusal's) when none is. While
// the least piece bound is below `threshold`, that piece is tightened: first its speeds are
// bisected within their grid cells (kRefineSteps), then it is halved (each half's bound is
// valid on its own), up to kMaxSplits steps and down to 1/1024 of the range: the bound
// tightens only as far as it takes to prove "cannot beat the threshold".
double SegmentwiseBoundPieces(const SearchContext& ctx, const MissionFacts& f, const MotorParams& mp,
                              const Drive& ideal, double t_max, int motor, int prop, int option, double esc_mass_kg,
                              double threshold, const char** rule) {
  constexpr int kPieces = 2, kMaxSplits = 24, kRefineSteps = 6;
  const BatteryOption& bo = ctx.options[static_cast<std::size_t>(option)];
  const double lo = bo.capacity_lo_ah, hi = bo.capacity_hi_ah;
  const bool range = hi > lo;
  const char* first_rule = nullptr;
  struct Piece {
    double a, b, bound;
    bool refined;
  };
  auto piece = [&](double a, double b, bool refined) {
    const char* r = nullptr;
    const double x = SegmentwiseBoundAt(ctx, f, mp, ideal, t_max, motor, prop, option, esc_mass_kg, a, b,
                                        refined ? kRefineSteps : 0, &r);
    if (r && !first_rule) first_rule = r;
    return Piece{a, b, r ? kInf : x, refined};
  };
  std::vector<Piece> pieces;
  const int n = range ? kPieces : 1;
  for (int j = 0; j < n; ++j) {
    pieces.push_back(range ? piece(lo + (hi - lo) * j / n, lo + (hi - lo) * (j + 1) / n, false) : piece(lo, hi, false));
  }
  for (int step = 0; step < kMaxSplits; ++step) {
    auto least = std::min_element(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) { return x.bound < y.bound; });
    if (!(least->bound < threshold)) break;
    const Piece whole = *least;
    if (!whole.refined) {
      *least = piece(whole.a, whole.b, true);
      continue;
    }
    if (!range || whole.b - whole.a < (hi - lo) / 1024) break;
    const double mid = 0.5 * (whole.a + whole.b);
    *least = piece(whole.a, mid, true);
    pieces.push_back(piece(mid, whole.b, true));
  }
  double best = kInf;
  for (const Piece& x : pieces) best = std::min(best, x.bound);
  *rule = best == kInf ? first_rule : nullptr;
  return best;
}

// The hover bound's speed and torque from below (R2): the last grid point whose thrust is at
// most the first hover segment's per-rotor thrust at the mass of `loads` (0, 0 without a
// hover segment, a monotone grid or such a point). Returns the grid index (0 when none).
int HoverGridPointFromBelow(const MissionFacts& f, const PropGrid& g, PairLoads* loads, double* omega_lb, double* q_lb) {
  *omega_lb = 0;
  *q_lb = 0;
  if (f.hover.empty() || !g.monotone) return 0;
  const RotorLoad& load = loads->At(static_cast<std::size_t>(f.hover[0]), false, 0.0);
  const double* it = std::upper_bound(g.thrust, g.thrust + kGrid, load.thrust_per_rotor_n);
  const int idx = static_cast<int>(it - g.thrust) - 1;  // last grid thrust <= T_lb
  if (idx < 0) return 0;
  *omega_lb = g.omega[idx];
  *q_lb = g.torque_suffix_min[idx];
  return idx;
}

// R2, R6, R7 for one (motor, propeller, option) pair whose propeller passed R0 (counted per
// motor, MotorSetUp): the rule that removes it, or null. Sets omega_lb, q_lb (R2) for the
// hover bound.
// w_nl: the largest no-load speed of the motor's zero-resistance drives at full throttle and
// the option's full-charge voltage (R7; the same for every propeller, computed once per option).
const char* PropRule(const SearchContext& ctx, const MissionFacts& f, double motor_kg, double w_nl, std::size_t pi,
                     std::size_t o, PairLoads* loads, double* omega_lb, double* q_lb) {
  const Mission& m = *ctx.mission;
  const MissionConstraints& k = m.constraints;
  const PropEntry& prop = ctx.catalog->props()[pi];
  const PropGrid& g = ctx.grids[pi];
  const BatteryOption& bo = ctx.options[o];
  const int lb_idx = HoverGridPointFromBelow(f, g, loads, omega_lb, q_lb);  // grid index of omega_lb
  if (!f.hover.empty() && g.monotone) {
    // R6: the hover speed lies between omega_lb and the first grid speed whose thrust reaches
    // T_ub (the heaviest the vehicle can be); if the data break momentum theory (figure of
    // merit > the mission's limit) on that whole bracket, every hover point fails
    // prop_figure_of_merit (mission_eval.cc). The 2 % allowance covers the variation between
    // grid points. T_ub >= T_lb (M3) puts hi_idx at or above lb_idx, so when the point at
    // lb_idx keeps the limit the rule cannot fire and T_ub is not needed.
    if (g.fom_ok_next[lb_idx] != lb_idx) {
      const double mass_ub = VehicleMassKg(ctx, bo.mass_hi_kg, motor_kg, g.mass_kg, ctx.escs.max_mass_kg[o]);
      const RotorLoad load_ub = SegmentRotorLoad(m, m.segments[f.hover[0]], mass_ub, 0.0);
      const double* it_ub = std::lower_bound(g.thrust, g.thrust + kGrid, load_ub.thrust_per_rotor_n);
      const int hi_idx = std::min(static_cast<int>(it_ub - g.thrust), kGrid - 1);
      // Every grid point of [lb_idx, hi_idx] above 1.02 x the limit (fom_ok_next, BuildPropGrids).
      if (it_ub != g.thrust + kGrid && (lb_idx > hi_idx || g.fom_ok_next[lb_idx] > hi_idx)) return "prop_figure_of_merit";
    }
  }
  if (ctx.models[pi]->data_kind() != PropDataKind::kTables || prop.j_tables.empty()) {
    // R7: static-only data. The shaft cannot turn faster than the motor's no-load speed at full
    // throttle and the full-charge voltage with no ESC resistance, so the advance ratio in a
    // segment with axial airspeed >= V_ax is at least V_ax/(n_max*D); above the mission's
    // max_static_advance_ratio the segment fails prop_no_forward_flight_data whatever else is
    // chosen. (The largest V_ax over the segments, StageFourFacts.)
    const double n_max = w_nl / (2.0 * kPi);
    if (n_max > 0 && f.r7_axial_m_s / (n_max * prop.diameter_m) > k.max_static_advance_ratio) {
      return "prop_no_forward_flight_data";
    }
  }
  if (prop.max_rpm && RadPerSecToRpm(*omega_lb) > *prop.max_rpm) return "prop_max_rpm";  // R2
  // R12 (the propeller's data window, mission.h): every hover speed is at least omega_lb (R2);
  // above the window's top there, every hover point fails prop_above_data. And at most the first
  // grid speed whose thrust reaches T_ub (the heaviest the vehicle can be, as R6): below the
  // window's bottom there, every hover point fails prop_below_data (M1, M3).
  const PropValidRange& data = ctx.models[pi]->valid_range();
  if (k.prop_above_data_factor > 0 && RadPerSecToRpm(*omega_lb) > k.prop_above_data_factor * data.rpm_hi) {
    return "prop_above_data";
  }
  if (k.prop_below_data_factor > 0 && !f.hover.empty() && g.monotone) {
    const double mass_ub = VehicleMassKg(ctx, bo.mass_hi_kg, motor_kg, g.mass_kg, ctx.escs.max_mass_kg[o]);
    const RotorLoad load_ub = SegmentRotorLoad(m, m.segments[f.hover[0]], mass_ub, 0.0);
    const double* it_ub = std::lower_bound(g.thrust, g.thrust + kGrid, load_ub.thrust_per_rotor_n);
    if (it_ub != g.thrust + kGrid &&
        RadPerSecToRpm(g.omega[it_ub - g.thrust]) < k.prop_below_data_factor * data.rpm_lo) {
      return "prop_below_data";
    }
  }
  return nullptr;
}

// A motor's combinations with the ESCs that pass R0 and R1 (what a motor-level rule removes).
long long CombinationsPerMotor(const SearchContext& ctx) {
  long long n = 0;
  for (const long long r : ctx.escs.rated) n += r;
  return n * static_cast<long long>(ctx.catalog->props().size());
}

// What stage 4 reads for each of one motor's pairs, worked out once per motor (MotorSetUp).
struct MotorSetup {
  int motor = 0;
  double mass_kg = 0;
  MotorParams mp;           // the scenario's (credibility.h)
  std::vector<Drive> ideal;  // per ESC class, with no ESC resistance (R3, R4, R7)
  // Per option: R7's largest no-load speed of those drives at full throttle and the option's
  // full-charge voltage; NaN when R1 refuses the option for the motor (motor_voltage).
  std::vector<double> w_nl;
  bool lossy = true;  // every class's drive is lossy (DriveIsLossy): R11 applies
  MotorLossFloor loss;  // R11's loss floor (model/physics.h)
};

// Sets up motor mi (not skipped by SkipMotor) and counts the motor-level rules: the whole
// motor (motor_unrated), an option (motor_voltage, R1), a propeller (R0, StageFourFacts) for
// every option the motor can take. False when the motor is refused whole.
bool MotorSetUp(const SearchContext& ctx, const MissionFacts& f, std::size_t mi, MotorSetup* s, RuleCounts* pruned) {
  const Mission& m = *ctx.mission;
  const MotorEntry& mo = ctx.catalog->motors()[mi];
  // credibility.h: the scenario's ratings (estimated from the mass when no source states them),
  // as the evaluator flies them; an unrated motor the mission excludes is refused (R0).
  bool unrated_excluded = false;
  s->motor = static_cast<int>(mi);
  s->mass_kg = *mo.mass_kg;
  s->mp = ScenarioMotorParams(mo, m, nullptr, &unrated_excluded);
  if (f.free_lifts && unrated_excluded) {
    pruned->Add("motor_unrated", CombinationsPerMotor(ctx));
    return false;
  }
  const double motor_max_v = f.free_lifts ? MotorMaxVoltageV(mo) : kInf;
  s->ideal.clear();
  s->lossy = true;
  for (const EscClass& c : ctx.escs.classes) {
    s->ideal.emplace_back(s->mp, ZeroResistanceEsc(c));
    s->lossy = s->lossy && DriveIsLossy(s->mp, c.c1, c.c0);
  }
  s->loss = s->lossy ? LossFloorOf(s->mp) : MotorLossFloor{};
  const long long n_props = static_cast<long long>(ctx.catalog->props().size());
  s->w_nl.assign(ctx.options.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t o = 0; o < ctx.options.size(); ++o) {
    const BatteryOption& bo = ctx.options[o];
    const long long per_pair = ctx.escs.rated[o];
    if (bo.v_full > motor_max_v) {  // R1 for the motor's cells_max (credibility.h)
      pruned->Add("motor_voltage", per_pair * n_props);
      continue;
    }
    double w = 0;
    for (const Drive& d : s->ideal) w = std::max(w, d.NoLoadSpeed(bo.v_full, 1.0));
    s->w_nl[o] = w;
    for (const auto& [rule, props] : f.prop_frame_counts) pruned->Add(rule, per_pair * props);  // R0
  }
  return true;
}

// Stage 4 for one pair of a set-up motor whose option R1 lets through and whose propeller
// passed R0: false with its rule counted (its option's ESCs), or true with *c (R4's bound).
bool PairCandidate(const SearchContext& ctx, const MissionFacts& f, const MotorSetup& s, std::size_t pi, std::size_t o,
                   PairLoads* loads, Candidate* c, RuleCounts* pruned) {
  const MissionConstraints& k = ctx.mission->constraints;
  const double margin = 1.0 - k.current_margin;
  const BatteryOption& bo = ctx.options[o];
  const MotorParams& mp = s.mp;
  const long long per_pair = ctx.escs.rated[o];
  const double mass_lb = std::max(VehicleMassKg(ctx, bo.mass_lo_kg, s.mass_kg, ctx.grids[pi].mass_kg, ctx.escs.min_mass_kg[o]),
                                  WindowMassFloorKg(ctx, f, static_cast<int>(pi)));  // R12's floor
  double omega_lb = 0, q_lb = 0;
  loads->Reset(mass_lb);
  if (const char* rule = PropRule(ctx, f, s.mass_kg, s.w_nl[o], pi, o, loads, &omega_lb, &q_lb)) {
    pruned->Add(rule, per_pair);
    return false;
  }
  // R3 and R4 over the ESC classes: the pair survives if any class can. R4's bound is
  // nondecreasing in pdc_lb for a given DriveIsLossy (every term is, and so is each correctly
  // rounded operation): the least over the classes is the bound at the least pdc_lb of each
  // kind (ScoreLowerBound reads the class only through DriveIsLossy).
  bool any = false;
  double irms_lb = kInf;
  double pdc_min[2] = {kInf, kInf};  // [DriveIsLossy]
  bool has[2] = {false, false};
  const char* why = "throttle";
  const std::vector<EscClass>& classes = ctx.escs.classes;
  for (std::size_t ci = 0; ci < classes.size(); ++ci) {
    if (ctx.escs.per_option[o][ci].empty()) continue;
    const Drive& d = s.ideal[ci];
    const Drive::InverseCurrents hi_v = d.InverseLight(bo.v_full, q_lb, omega_lb);
    const double t_max = ThrottleLimit(k, classes[ci].tr_sat);
    if (hi_v.throttle > t_max) { why = "throttle"; continue; }
    if (hi_v.irms_a > mp.max_current_a * margin) { why = "motor_current"; continue; }
    if (k.enforce_motor_power && d.InverseAcPower(bo.v_full, hi_v, q_lb, omega_lb) > mp.max_power_w) {
      why = "motor_power";
      continue;
    }
    const double pdc_lo_v = bo.v_cut * d.InverseLight(bo.v_cut, q_lb, omega_lb).idc_a;  // (59), as Inverse
    const double pdc_lb = std::max(0.0, std::min(bo.v_full * hi_v.idc_a, pdc_lo_v));  // (59), as Inverse
    const int lossy = DriveIsLossy(mp, classes[ci].c1, classes[ci].c0) ? 1 : 0;
    if (!has[lossy] || pdc_lb < pdc_min[lossy]) {
      has[lossy] = true;
      pdc_min[lossy] = pdc_lb;
    }
    any = true;
    irms_lb = std::min(irms_lb, hi_v.irms_a);
  }
  if (!any) {
    pruned->Add(why, per_pair);
    return false;
  }
  const PropEntry& prop = ctx.catalog->props()[pi];
  double bound = kInf;
  for (int lossy = 0; lossy < 2; ++lossy) {
    if (!has[lossy]) continue;
    bound = std::min(bound, ScoreLowerBound(ctx, f, lossy == 1, prop, *ctx.models[pi], o, loads, pdc_min[lossy]));
  }
  if (std::isnan(bound)) bound = -kInf;  // no bound (the order needs a number)
  *c = Candidate{bound, s.motor, static_cast<int>(pi), static_cast<int>(o), irms_lb};
  return true;
}

// R9 with the mission's facts and the motor's scenario parameters given (BranchAndBound calls it
// per ESC).
bool HoverThrottleBelowLimit(const SearchContext& ctx, const MissionFacts& f, const MotorParams& mp, int motor,
                             int prop, int option, const EscEntry& esc) {
  const Mission& m = *ctx.mission;
  const PropGrid& g = ctx.grids[static_cast<std::size_t>(prop)];
  if (!(m.constraints.min_hover_throttle > 0) || f.hover.empty() || !g.monotone) return false;
  const BatteryOption& bo = ctx.options[static_cast<std::size_t>(option)];
  const MotorEntry& mo = ctx.catalog->motors()[static_cast<std::size_t>(motor)];
  // The heaviest the vehicle can be with this ESC: the option's largest pack.
  const double mass_ub = VehicleMassKg(ctx, bo.mass_hi_kg, *mo.mass_kg, g.mass_kg, EscMassKg(esc));
  const RotorLoad load = SegmentRotorLoad(m, m.segments[static_cast<std::size_t>(f.hover[0])], mass_ub, 0.0);
  const double* it = std::lower_bound(g.thrust, g.thrust + kGrid, load.thrust_per_rotor_n);
  if (it == g.thrust + kGrid) return false;  // beyond the grid: no bound
  const std::size_t i = static_cast<std::size_t>(it - g.thrust);
  return Drive(mp, esc.params).InverseLight(bo.v_full, g.torque_prefix_max[i], g.omega[i]).throttle <
         m.constraints.min_hover_throttle;
}

// R12 per ESC: the first hover below the propeller's data window at the heaviest the vehicle can
// be with this ESC (the option's largest pack).
bool HoverSpeedBelowWindow(const SearchContext& ctx, const MissionFacts& f, int motor, int prop, int option,
                           double esc_kg) {
  const BatteryOption& bo = ctx.options[static_cast<std::size_t>(option)];
  const MotorEntry& mo = ctx.catalog->motors()[static_cast<std::size_t>(motor)];
  const double mass_ub = VehicleMassKg(ctx, bo.mass_hi_kg, *mo.mass_kg, ctx.grids[static_cast<std::size_t>(prop)].mass_kg, esc_kg);
  return HoverSpeedBelowWindowAtMass(ctx, f, prop, mass_ub);
}

}  // namespace

double SegmentwiseBound(const SearchContext& ctx, int motor, int prop, int option, int esc_class, double esc_mass_kg,
                        double threshold, const char** rule) {
  const Mission& m = *ctx.mission;
  const MotorParams mp = ScenarioMotorParams(ctx.catalog->motors()[static_cast<std::size_t>(motor)], m, nullptr, nullptr);
  const EscClass& cls = ctx.escs.classes[static_cast<std::size_t>(esc_class)];
  const EscParams ideal = ZeroResistanceEsc(cls);
  const MissionFacts f = FactsOf(m, ctx.free_group);
  const double t_max = ThrottleLimit(m.constraints, cls.tr_sat);
  return SegmentwiseBoundPieces(ctx, f, mp, Drive(mp, ideal), t_max, motor, prop, option, esc_mass_kg, threshold, rule);
}

bool FailsHoverThrottleBound(const SearchContext& ctx, int motor, int prop, int option, const EscEntry& esc) {
  const Mission& m = *ctx.mission;
  const MotorParams mp = ScenarioMotorParams(ctx.catalog->motors()[static_cast<std::size_t>(motor)], m, nullptr, nullptr);
  return HoverThrottleBelowLimit(ctx, FactsOf(m, ctx.free_group), mp, motor, prop, option, esc);
}

void ResolveGroups(SearchContext* ctx) {
  const Mission& m = *ctx->mission;
  ctx->free_group = 0;
  ctx->fixed_parts.clear();
  ctx->fixed_groups_mass_kg = 0;
  if (!m.groups.empty()) {
    std::vector<int> free;
    for (int g = 0; g < GroupCount(m); ++g) {
      // given_parts: the joint search's virtual ESC (G2, as R5's) in place of the catalog entry.
      const bool given = ctx->given_parts && g < static_cast<int>(ctx->given_parts->size()) &&
                         (*ctx->given_parts)[static_cast<std::size_t>(g)].motor;
      ctx->fixed_parts.push_back(given ? (*ctx->given_parts)[static_cast<std::size_t>(g)]
                                       : FixedGroupParts(m, *ctx->catalog, g));
      if (!m.groups[g].fixed()) {
        free.push_back(g);
        continue;
      }
      const GroupParts& p = ctx->fixed_parts.back();
      if (!p.motor->mass_kg) throw DataError("motor '" + p.motor->id + "' has no mass_kg: the mission needs it");
      ctx->fixed_groups_mass_kg += m.groups[g].rotors * (*p.motor->mass_kg + EscMassKg(*p.esc) + PropMassKg(*p.prop));
    }
    if (free.empty()) {
      throw DataError(m.file + ": $.propulsion: every group has its motor, esc and prop: optimize has nothing to "
                      "choose; leave a group's parts out, or use evaluate");
    }
    if (free.size() > 1) {  // SearchCatalog gives such missions to the joint search (G2) instead
      throw std::logic_error("ResolveGroups: the one-group stages need exactly one free group, not " +
                             std::to_string(free.size()));
    }
    ctx->free_group = free.front();
    ctx->fixed_models.resize(m.groups.size());
    ctx->fixed_model_ptrs.assign(m.groups.size(), nullptr);
    for (int g = 0; g < GroupCount(m); ++g) {
      if (g == ctx->free_group) continue;
      ctx->fixed_models[g] = std::make_unique<PropModel>(*ctx->fixed_parts[g].prop);
      ctx->fixed_model_ptrs[g] = ctx->fixed_models[g].get();
    }
  }
  ctx->free_rotors = GroupRotors(m, ctx->free_group);
}

void PrepareStages(const Mission& m, const Catalog& cat, SearchContext* ctx) {
  ctx->mission = &m;
  ctx->catalog = &cat;
  ResolveGroups(ctx);
  ctx->options = BatteryOptions(m, cat);                  // stage 1
  ctx->escs = BuildEscTable(cat, ctx->options);           // stage 2 (R1)
  BuildPropGrids(m, cat, &ctx->grids, &ctx->models);      // stage 3
}

// G1 for a group's wing-borne cruise with a free airspeed: cell by cell over the airspeed
// range (prop_bounds.h), momentum theory (the ESC's C1, C0 are read for DriveIsLossy) and,
// with `drive`, that drive's PDC from below.
double FreeCruisePowerLowerBoundW(const Mission& m, const Segment& sg, const GroupParts& parts,
                                  const PropModel& model, double mass_kg, const CruiseDriveBound* drive) {
  const MotorParams mp = ScenarioMotorParams(*parts.motor, m);
  const EscParams ep = ScenarioEscParams(*parts.esc, m.objective.ranking);
  const CruisePropBound p{parts.prop, &model, PropAdjustmentFor(*parts.prop, m.objective.ranking),
                          DriveIsLossy(mp, ep.c1, ep.c0)};
  return FreeCruiseRotorPowerLowerBoundW(m, sg, p, drive, mass_kg);
}

void FixedGroupPowerBounds(SearchContext* ctx) {
  const Mission& m = *ctx->mission;
  ctx->fixed_power_lb_w.clear();
  ctx->fixed_power_mass_kg.clear();
  if (m.groups.empty()) return;
  // The lightest the vehicle can be with any choice of the free group (M3: every segment's
  // thrust, and so its speed, torque and power, rises with the mass). The bounds are tabulated
  // on a geometric mass grid from there (kFixedPowerMasses points, 2 % apart): a pair reads the
  // grid point at or below its own lightest mass, a bound for it by the same monotonicity.
  double motor_min = kInf, prop_min = kInf;
  for (const MotorEntry& mo : ctx->catalog->motors()) {
    if (mo.mass_kg) motor_min = std::min(motor_min, *mo.mass_kg);
  }
  for (const PropGrid& g : ctx->grids) prop_min = std::min(prop_min, g.mass_kg);
  for (std::size_t o = 0; o < ctx->options.size(); ++o) {
    const BatteryOption& bo = ctx->options[o];
    const double esc_min = std::isfinite(ctx->escs.min_mass_kg[o]) ? ctx->escs.min_mass_kg[o] : 0.0;
    const double mass_min = m.vehicle.mass_kg + bo.mass_lo_kg + ctx->fixed_groups_mass_kg +
                            ctx->free_rotors * (std::isfinite(motor_min) ? motor_min : 0.0) +
                            ctx->free_rotors * ((std::isfinite(prop_min) ? prop_min : 0.0) + esc_min);
    std::vector<double> masses(kFixedPowerMasses);
    std::vector<std::vector<double>> table;
    for (int k = 0; k < kFixedPowerMasses; ++k) {
      const double mass = k == 0 ? mass_min : mass_min * std::pow(kFixedPowerMassStep, k);
      masses[static_cast<std::size_t>(k)] = mass;
      std::vector<double> p_lb(m.segments.size(), m.vehicle.avionics_power_w);
      for (std::size_t si = 0; si < m.segments.size(); ++si) {
        const Segment& sg = m.segments[si];
        if (sg.group == ctx->free_group || sg.type == SegmentType::kShaft) continue;
        const GroupParts& parts = ctx->fixed_parts[sg.group];
        const PropModel& prop = *ctx->fixed_models[sg.group];
        if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free()) {
          // G1 with the group's own drive and data.
          const Drive d(ScenarioMotorParams(*parts.motor, m), ScenarioEscParams(*parts.esc, m.objective.ranking));
          const CruiseDriveBound db{&d, bo.v_full, bo.v_cut};
          p_lb[si] += FreeCruisePowerLowerBoundW(m, sg, parts, prop, mass, &db);
          continue;
        }
        const RotorLoad ld = SegmentRotorLoad(m, sg, mass, sg.airspeed_m_s.lo);
        // A speed at or below the evaluator's root; the torque there is at most the true one.
        double lo = 0.0;
        if (!PropSpeedFromBelow(prop, m.rho_kg_m3, ld.thrust_per_rotor_n, ld.axial_airspeed_m_s, 60, &lo)) continue;
        const double q = prop.Evaluate(lo, m.rho_kg_m3, ld.axial_airspeed_m_s).torque_nm;
        if (!(q > 0)) continue;
        const Drive d(ScenarioMotorParams(*parts.motor, m), ScenarioEscParams(*parts.esc, m.objective.ranking));
        const double pdc = std::min(d.Inverse(bo.v_full, q, lo).pdc_w, d.Inverse(bo.v_cut, q, lo).pdc_w);
        p_lb[si] += ld.rotors * std::max(0.0, pdc);
      }
      // Monotone in the mass by M3; the running maximum keeps the table so under rounding too
      // (each entry is still the bound at a mass at or below its own).
      if (!table.empty()) {
        for (std::size_t si = 0; si < p_lb.size(); ++si) p_lb[si] = std::max(p_lb[si], table.back()[si]);
      }
      table.push_back(std::move(p_lb));
    }
    ctx->fixed_power_lb_w.push_back(std::move(table));
    ctx->fixed_power_mass_kg.push_back(std::move(masses));
  }
}

double FixedPowerLowerBoundW(const SearchContext& ctx, std::size_t option, std::size_t si, double mass_kg) {
  const std::vector<double>& masses = ctx.fixed_power_mass_kg[option];
  // The last grid mass at or below mass_kg (the first when mass_kg is below the grid).
  const auto it = std::upper_bound(masses.begin(), masses.end(), mass_kg);
  const std::size_t k = it == masses.begin() ? 0 : static_cast<std::size_t>(it - masses.begin()) - 1;
  return ctx.fixed_power_lb_w[option][k][si];
}

namespace {

// R0 (the catalog excludes the motor: catalog.h, "exclude") and a motor without a mass, counted for
// all of the motor's pairs; true when the motor is skipped.
bool SkipMotor(const MotorEntry& m, long long per_motor, RuleCounts* pruned, long long* skipped) {
  if (!m.exclude_reason.empty()) {
    pruned->Add("catalog_exclude", per_motor);
    return true;
  }
  if (!m.mass_kg) {
    ++*skipped;
    pruned->Add("motor_without_mass", per_motor);
    return true;
  }
  return false;
}

// fn(thread, i) for i in [0, n), i interleaved over `threads` threads (each i on one thread).
template <typename F>
void ForEachOnThreads(std::size_t n, int threads, const F& fn) {
  threads = std::max(1, threads);
  auto work = [&](int tid) {
    for (std::size_t i = static_cast<std::size_t>(tid); i < n; i += static_cast<std::size_t>(threads)) fn(tid, i);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& th : pool) th.join();
}

// R11 (stage 4's order; see the rule at the top of the file). The factor keeps the key a bound
// under rounding (the floor and the evaluator's powers are each within a few ulps).
constexpr double kKeyRoundingAllowance = 1.0 - 1e-9;
// The classes: a class runs from its lightest motor up to this factor times that mass
// (exclusive); its key uses that mass and its members' least loss floors. Measured on the
// 1.5 kg quadcopter (4.55 M (motor, propeller, option) pairs; pairs bounded, search time):
// shaft power only (no loss floor), ratio 1.1: 355 k, 0.19 s; with the loss floor, ratio 1.05:
// 121 k, 0.175 s; 1.1: 146 k, 0.162 s; 1.25: 188 k, 0.163 s; classes split further by the
// copper-loss coefficient (ratio 4 within a class): 76 k, 0.19 s (the classes' keys cost more
// than the pairs they save).
constexpr double kMotorClassMassRatio = 1.1;

struct PropKey {
  double bound = 0;  // R11: a lower bound of the score of every pair of the class's motors
  int prop = 0, option = 0;
};

// R11's key of (pi, o) for lossy motors of at least motor_kg whose loss floors are at least
// `loss`'s.
double PropOnlyBound(const SearchContext& ctx, const MissionFacts& f, std::size_t pi, std::size_t o, double motor_kg,
                     const MotorLossFloor& loss, PairLoads* loads) {
  const BatteryOption& bo = ctx.options[o];
  const PropGrid& g = ctx.grids[pi];
  loads->Reset(VehicleMassKg(ctx, bo.mass_lo_kg, motor_kg, g.mass_kg, ctx.escs.min_mass_kg[o]));
  double omega_lb = 0, q_lb = 0;
  HoverGridPointFromBelow(f, g, loads, &omega_lb, &q_lb);
  const double pac_floor_w =
      omega_lb * q_lb + loss.copper_w_per_nm2 * q_lb * q_lb + loss.no_load_torque_nm * omega_lb;  // physics.h
  const double b = ScoreLowerBound(ctx, f, true, ctx.catalog->props()[pi], *ctx.models[pi], o, loads,
                                   kKeyRoundingAllowance * pac_floor_w);
  return std::isnan(b) ? -kInf : b;
}

// R11's class of motors: its lightest mass and its members' least loss floors.
struct MotorClass {
  double mass_kg = 0;
  MotorLossFloor loss;
};

// Every (propeller R0 lets through, option) with R11's key for the motors of class c, sorted
// by (key, option, propeller); with lossy false (motors R11 does not apply to) every key is
// -inf, in option then propeller order.
std::vector<PropKey> ClassKeys(const SearchContext& ctx, const MissionFacts& f, const MotorClass& c, bool lossy) {
  PairLoads loads(*ctx.mission);
  std::vector<PropKey> keys;
  keys.reserve(f.frame_ok_props.size() * ctx.options.size());
  for (std::size_t o = 0; o < ctx.options.size(); ++o) {
    for (const int pi : f.frame_ok_props) {
      const double b = lossy ? PropOnlyBound(ctx, f, static_cast<std::size_t>(pi), o, c.mass_kg, c.loss, &loads) : -kInf;
      keys.push_back(PropKey{b, pi, static_cast<int>(o)});
    }
  }
  if (lossy) {
    std::sort(keys.begin(), keys.end(), [](const PropKey& a, const PropKey& b) {
      if (a.bound != b.bound) return a.bound < b.bound;
      return a.option != b.option ? a.option < b.option : a.prop < b.prop;
    });
  }
  return keys;
}

// R11's classes of the set-up motors (null: skipped or refused): per motor its class, the last
// class (lightest mass 0, no loss floor) for the motors R11 does not apply to (a drive that
// may create energy); and the classes.
std::vector<int> MotorClasses(const std::vector<const MotorSetup*>& setups, std::vector<MotorClass>* classes) {
  std::vector<std::size_t> lossy;
  for (std::size_t i = 0; i < setups.size(); ++i) {
    if (setups[i] && setups[i]->lossy) lossy.push_back(i);
  }
  std::stable_sort(lossy.begin(), lossy.end(),
                   [&](std::size_t a, std::size_t b) { return setups[a]->mass_kg < setups[b]->mass_kg; });
  std::vector<int> cls(setups.size(), -1);
  classes->clear();
  for (const std::size_t i : lossy) {
    const MotorSetup& s = *setups[i];
    if (classes->empty() || s.mass_kg >= kMotorClassMassRatio * classes->back().mass_kg) {
      classes->push_back(MotorClass{s.mass_kg, s.loss});
    }
    MotorLossFloor& floor = classes->back().loss;
    floor.copper_w_per_nm2 = std::min(floor.copper_w_per_nm2, s.loss.copper_w_per_nm2);
    floor.no_load_torque_nm = std::min(floor.no_load_torque_nm, s.loss.no_load_torque_nm);
    cls[i] = static_cast<int>(classes->size()) - 1;
  }
  classes->push_back(MotorClass{});  // the class without R11
  for (std::size_t i = 0; i < setups.size(); ++i) {
    if (setups[i] && !setups[i]->lossy) cls[i] = static_cast<int>(classes->size()) - 1;
  }
  return cls;
}

// The motors of a search set up on `threads` threads (null where skipped or refused; the
// counts of SkipMotor and MotorSetUp in *pruned, *skipped).
std::vector<std::unique_ptr<MotorSetup>> SetUpMotors(const SearchContext& ctx, const MissionFacts& f, int threads,
                                                     RuleCounts* pruned, long long* skipped) {
  const auto& motors = ctx.catalog->motors();
  const long long per_motor = CombinationsPerMotor(ctx);
  std::vector<std::unique_ptr<MotorSetup>> out(motors.size());
  std::vector<RuleCounts> thread_pruned(static_cast<std::size_t>(std::max(1, threads)));
  std::vector<long long> thread_skipped(thread_pruned.size(), 0);
  ForEachOnThreads(motors.size(), threads, [&](int tid, std::size_t mi) {
    if (SkipMotor(motors[mi], per_motor, &thread_pruned[tid], &thread_skipped[tid])) return;
    auto s = std::make_unique<MotorSetup>();
    if (MotorSetUp(ctx, f, mi, s.get(), &thread_pruned[tid])) out[mi] = std::move(s);
  });
  for (std::size_t t = 0; t < thread_pruned.size(); ++t) {
    thread_pruned[t].MergeInto(pruned);
    *skipped += thread_skipped[t];
  }
  return out;
}

std::vector<const MotorSetup*> Pointers(const std::vector<std::unique_ptr<MotorSetup>>& setups) {
  std::vector<const MotorSetup*> p;
  for (const auto& s : setups) p.push_back(s.get());
  return p;
}

}  // namespace

CandidateList BuildCandidates(const SearchContext& ctx, int threads) {
  const MissionFacts f = StageFourFacts(ctx);
  RuleCounts pruned;
  CandidateList out;
  const std::vector<std::unique_ptr<MotorSetup>> setups = SetUpMotors(ctx, f, threads, &pruned, &out.skipped_without_mass);
  std::vector<MotorClass> classes;
  const std::vector<int> cls = MotorClasses(Pointers(setups), &classes);
  std::vector<std::vector<Candidate>> thread_cands(static_cast<std::size_t>(std::max(1, threads)));
  std::vector<RuleCounts> thread_pruned(thread_cands.size());
  ForEachOnThreads(setups.size(), threads, [&](int tid, std::size_t mi) {
    if (!setups[mi]) return;
    const MotorSetup& s = *setups[mi];
    PairLoads loads(*ctx.mission), key_loads(*ctx.mission);
    for (std::size_t o = 0; o < ctx.options.size(); ++o) {
      if (std::isnan(s.w_nl[o])) continue;  // R1 (MotorSetUp)
      for (const int pi : f.frame_ok_props) {
        Candidate c;
        if (!PairCandidate(ctx, f, s, static_cast<std::size_t>(pi), o, &loads, &c, &thread_pruned[tid])) continue;
        if (s.lossy) {  // R11
          const MotorClass& k = classes[static_cast<std::size_t>(cls[mi])];
          c.bound = std::max(c.bound, PropOnlyBound(ctx, f, static_cast<std::size_t>(pi), o, k.mass_kg, k.loss, &key_loads));
        }
        thread_cands[tid].push_back(c);
      }
    }
  });
  for (std::size_t t = 0; t < thread_cands.size(); ++t) {
    out.candidates.insert(out.candidates.end(), thread_cands[t].begin(), thread_cands[t].end());
    thread_pruned[t].MergeInto(&pruned);
  }
  pruned.MergeInto(&out.pruned_by);
  return out;
}

double PropellerKeyBound(const SearchContext& ctx, int prop, int option, int motor) {
  const MotorEntry& mo = ctx.catalog->motors()[static_cast<std::size_t>(motor)];
  PairLoads loads(*ctx.mission);
  return PropOnlyBound(ctx, StageFourFacts(ctx), static_cast<std::size_t>(prop), static_cast<std::size_t>(option),
                       *mo.mass_kg, LossFloorOf(ScenarioMotorParams(mo, *ctx.mission, nullptr, nullptr)), &loads);
}

bool CandidateBefore(const Candidate& a, const Candidate& b) {
  if (a.bound != b.bound) return a.bound < b.bound;
  if (a.option != b.option) return a.option < b.option;
  if (a.motor != b.motor) return a.motor < b.motor;
  return a.prop < b.prop;
}

// Stage 4 on demand (CandidateStream). Per set-up motor: its class's keys (R11) are walked in
// order and bounded in batches; the bounded pairs wait in a heap. A motor's head is its next
// bounded pair when that pair's bound is below the key of its next unbounded one, else that
// key (a "frontier", drawn first on ties: an unbounded pair may tie with it); the motors are
// in a heap by head. Drawing a frontier bounds the motor's next batch; drawing a pair returns
// it. A pair is returned only when its bound is below every frontier, and every unbounded
// pair's bound is at least its frontier (R11: the pair's bound is the larger of R4's and its
// key), so the pairs come in CandidateBefore order, as sorting BuildCandidates would give them.
struct CandidateStream::Impl {
  struct Motor {
    std::unique_ptr<MotorSetup> setup;
    const std::vector<PropKey>* keys = nullptr;  // its class's
    std::size_t walk = 0;                        // keys before it are bounded (or skipped)
    std::vector<Candidate> pending;              // a heap: the first in CandidateBefore order on top
    std::size_t batch = 0;                       // the next batch's size
    bool Live() const { return walk < keys->size() || !pending.empty(); }
    bool HeadIsPair() const {
      return !pending.empty() && (walk == keys->size() || pending.front().bound < (*keys)[walk].bound);
    }
    double HeadBound() const { return HeadIsPair() ? pending.front().bound : (*keys)[walk].bound; }
  };
  struct BatchCounts {
    RuleCounts pruned;
    long long bounded = 0;
  };

  explicit Impl(const SearchContext& c) : ctx(c), f(StageFourFacts(c)), loads(*c.mission) {}
  // a's head comes after b's.
  bool After(std::size_t a, std::size_t b) const {
    const Motor& x = motors[a];
    const Motor& y = motors[b];
    const double bx = x.HeadBound(), by = y.HeadBound();
    if (bx != by) return by < bx;
    const bool px = x.HeadIsPair(), py = y.HeadIsPair();
    if (px != py) return px;  // a frontier first
    if (!px) return y.setup->motor < x.setup->motor;
    return CandidateBefore(y.pending.front(), x.pending.front());
  }
  // Bounds up to n more of m's pairs whose key is below the cutoff (pairs at or above it are
  // never drawn: they stay open). Returns the combinations a rule removed.
  long long Expand(Motor* m, double cutoff, std::size_t n, PairLoads* pair_loads, BatchCounts* tally) const {
    const std::vector<PropKey>& keys = *m->keys;
    auto first = [](const Candidate& a, const Candidate& b) { return CandidateBefore(b, a); };
    long long removed = 0;
    for (std::size_t done = 0; m->walk < keys.size() && done < n;) {
      const PropKey& k = keys[m->walk];
      if (!(k.bound < cutoff)) {
        m->walk = keys.size();
        break;
      }
      ++m->walk;
      const std::size_t o = static_cast<std::size_t>(k.option);
      if (std::isnan(m->setup->w_nl[o])) continue;  // R1 (MotorSetUp counted it)
      ++done;
      ++tally->bounded;
      Candidate c;
      if (!PairCandidate(ctx, f, *m->setup, static_cast<std::size_t>(k.prop), o, pair_loads, &c, &tally->pruned)) {
        removed += ctx.escs.rated[o];
        continue;
      }
      c.bound = std::max(c.bound, k.bound);  // R11 (-inf when it does not apply)
      if (!(c.bound < cutoff)) continue;
      m->pending.push_back(c);
      std::push_heap(m->pending.begin(), m->pending.end(), first);
    }
    return removed;
  }

  const SearchContext& ctx;
  const MissionFacts f;
  std::vector<std::vector<PropKey>> classes;
  std::vector<Motor> motors;
  std::vector<std::size_t> heap;  // live motors; the first head on top
  PairLoads loads;
  BatchCounts counts;
  long long open = 0;  // combinations of the pairs neither drawn nor removed by a stage 4 rule
  long long skipped = 0, batches = 0;
};

CandidateStream::CandidateStream(const SearchContext& ctx, int threads, std::size_t first_batch)
    : impl_(std::make_unique<Impl>(ctx)) {
  Impl& s = *impl_;
  std::vector<std::unique_ptr<MotorSetup>> setups = SetUpMotors(ctx, s.f, threads, &s.counts.pruned, &s.skipped);
  std::vector<MotorClass> classes;
  const std::vector<int> cls = MotorClasses(Pointers(setups), &classes);
  s.classes.resize(classes.size());
  std::vector<char> used(classes.size(), 0);
  for (std::size_t mi = 0; mi < cls.size(); ++mi) {
    if (setups[mi]) used[static_cast<std::size_t>(cls[mi])] = 1;
  }
  ForEachOnThreads(s.classes.size(), threads, [&](int, std::size_t c) {
    const bool lossy = c + 1 < s.classes.size();  // the last class is the one without R11
    if (used[c]) s.classes[c] = ClassKeys(ctx, s.f, classes[c], lossy);
  });
  const long long per_option_props = static_cast<long long>(s.f.frame_ok_props.size());
  for (std::size_t mi = 0; mi < setups.size(); ++mi) {
    if (!setups[mi]) continue;
    Impl::Motor m;
    m.keys = &s.classes[static_cast<std::size_t>(cls[mi])];
    m.batch = std::max<std::size_t>(first_batch, 1);
    for (std::size_t o = 0; o < ctx.options.size(); ++o) {
      if (!std::isnan(setups[mi]->w_nl[o])) s.open += ctx.escs.rated[o] * per_option_props;
    }
    m.setup = std::move(setups[mi]);
    s.motors.push_back(std::move(m));
  }
  // Each motor's first batch, on the threads.
  std::vector<Impl::BatchCounts> thread_counts(static_cast<std::size_t>(std::max(1, threads)));
  std::vector<long long> thread_removed(thread_counts.size(), 0);
  ForEachOnThreads(s.motors.size(), threads, [&](int tid, std::size_t i) {
    PairLoads loads(*ctx.mission);
    thread_removed[tid] += s.Expand(&s.motors[i], kInf, s.motors[i].batch, &loads, &thread_counts[tid]);
    s.motors[i].batch = std::min(2 * s.motors[i].batch, kMaxBatch);
  });
  for (std::size_t t = 0; t < thread_counts.size(); ++t) {
    thread_counts[t].pruned.MergeInto(&s.counts.pruned);
    s.counts.bounded += thread_counts[t].bounded;
    s.open -= thread_removed[t];
  }
  for (std::size_t i = 0; i < s.motors.size(); ++i) {
    if (s.motors[i].Live()) s.heap.push_back(i);
  }
  std::make_heap(s.heap.begin(), s.heap.end(), [&s](std::size_t a, std::size_t b) { return s.After(a, b); });
}

CandidateStream::~CandidateStream() = default;

bool CandidateStream::Next(double cutoff, Candidate* c) {
  Impl& s = *impl_;
  auto after = [&s](std::size_t a, std::size_t b) { return s.After(a, b); };
  auto first = [](const Candidate& a, const Candidate& b) { return CandidateBefore(b, a); };
  while (!s.heap.empty()) {
    std::pop_heap(s.heap.begin(), s.heap.end(), after);
    const std::size_t i = s.heap.back();
    s.heap.pop_back();
    Impl::Motor& m = s.motors[i];
    const bool pair = m.HeadIsPair();
    if (pair) {
      std::pop_heap(m.pending.begin(), m.pending.end(), first);
      *c = m.pending.back();
      m.pending.pop_back();
      s.open -= s.ctx.escs.rated[static_cast<std::size_t>(c->option)];
    } else {
      s.open -= s.Expand(&m, cutoff, m.batch, &s.loads, &s.counts);
      m.batch = std::min(2 * m.batch, kMaxBatch);
      ++s.batches;
    }
    if (m.Live()) {
      s.heap.push_back(i);
      std::push_heap(s.heap.begin(), s.heap.end(), after);
    } else {
      std::vector<Candidate>().swap(m.pending);
    }
    if (pair) return true;
  }
  return false;
}

long long CandidateStream::batches() const { return impl_->batches; }
long long CandidateStream::pairs_bounded() const { return impl_->counts.bounded; }
long long CandidateStream::open_combinations() const { return impl_->open; }
long long CandidateStream::PairsLeftBelow(double cutoff) const {
  long long n = 0;
  for (const Impl::Motor& m : impl_->motors) {
    if (!m.Live()) continue;
    n += static_cast<long long>(m.pending.size());
    // The keys from `walk` on are in ascending order (ClassKeys; all -inf when R11 does not apply).
    const auto first = m.keys->begin() + static_cast<std::ptrdiff_t>(m.walk);
    n += std::partition_point(first, m.keys->end(), [cutoff](const PropKey& k) { return k.bound < cutoff; }) - first;
  }
  return n;
}
long long CandidateStream::skipped_without_mass() const { return impl_->skipped; }
void CandidateStream::MergePrunedInto(std::map<std::string, long long>* out) const { impl_->counts.pruned.MergeInto(out); }

}  // namespace search_internal

namespace {

using namespace search_internal;

// Stage 5: the candidate pairs best bound first, each pair's ESCs with R5, every combination
// not pruned scored exactly.
// Worker threads kept for a whole search: Start hands every thread the same job, Wait returns
// when all have finished it. A chunk of candidates lasts about a millisecond; starting and
// joining a thread per chunk cost 0.27 s over the first 10 k of the capacity-sized
// quadcopter's chunks.
class WorkerThreads {
 public:
  explicit WorkerThreads(int n) {
    for (int i = 0; i < n; ++i) threads_.emplace_back([this] { Loop(); });
  }
  ~WorkerThreads() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : threads_) t.join();
  }
  void Start(const std::function<void()>* job) {
    {
      std::lock_guard<std::mutex> lock(mu_);
      job_ = job;
      running_ = static_cast<int>(threads_.size());
      ++generation_;
    }
    start_.notify_all();
  }
  void Wait() {
    std::unique_lock<std::mutex> lock(mu_);
    done_.wait(lock, [this] { return running_ == 0; });
  }

 private:
  void Loop() {
    long seen = 0;
    while (true) {
      const std::function<void()>* job = nullptr;
      {
        std::unique_lock<std::mutex> lock(mu_);
        start_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        job = job_;
      }
      (*job)();
      std::lock_guard<std::mutex> lock(mu_);
      if (--running_ == 0) done_.notify_one();
    }
  }
  std::mutex mu_;
  std::condition_variable start_, done_;
  const std::function<void()>* job_ = nullptr;
  long generation_ = 0;
  int running_ = 0;
  bool stop_ = false;
  std::vector<std::thread> threads_;
};

class BranchAndBound {
 public:
  // cutoff: only results scoring below it are wanted (the joint search's N-th best, G2).
  BranchAndBound(const SearchContext& ctx, const SearchOptions& opt, CandidateStream* stream, SearchResult* out,
                 double cutoff = kInf)
      : ctx_(ctx),
        opt_(opt),
        stream_(*stream),
        open_at_start_(stream->open_combinations()),
        out_(out),
        relaxed_(*ctx.mission),
        cutoff_(cutoff),
        facts_(FactsOf(*ctx.mission, ctx.free_group)),
        board_(opt.top_n, opt.distinct_designs, cutoff) {
    // The virtual ESC (and so the class check) uses the mission without min_hover_throttle: a
    // real ESC's resistance and mass raise the throttle, so that lower limit is the one
    // constraint the virtual ESC may fail when a real one passes (R5). Relaxing it keeps the
    // check a bound. The thrust-to-weight is left out of it too (any relaxation keeps it a
    // bound): its full-throttle solve costs a third of a simulation, and the few real ESCs
    // that reach the evaluation check it.
    relaxed_.constraints.min_hover_throttle = 0.0;
    relaxed_.constraints.prop_below_data_factor = 0.0;  // a heavier real ESC turns the rotor faster
    relaxed_.constraints.min_thrust_to_weight = 0.0;
  }

  void Run();
  // Solves the top N again with explain (warnings, the solver's report, the designer's summary,
  // propeller notes): Process scores without them (text for results nobody reads), each with
  // the cutoff it had, so the numbers are the same.
  void Explain() const;
  long long virtual_evaluations() const { return virtual_evals_; }

 private:
  struct Outcome {
    std::vector<std::pair<Combination, MissionResult>> results;
    std::vector<double> cutoffs;  // per result, the cutoff its Solve had
    RuleCounts pruned;
    long long searched = 0, virtual_evals = 0;
  };

  // Candidates in CandidateBefore order (best bound first, a strict total order). The search
  // usually stops after a small fraction of them, so they are drawn on demand from the stream
  // (stage 4 bounds a pair only when it may come next), with the N-th best score as its
  // cutoff: the search stops at the first pair not below it (the threshold only falls), and a
  // pair that comes after it is never drawn.
  const Candidate* CandidateAt(std::size_t i) {  // the i-th best, or null
    Candidate c;
    while (base_ + ordered_.size() <= i && stream_.Next(NthBest(), &c)) ordered_.push_back(c);
    return i < base_ + ordered_.size() ? &ordered_[i - base_] : nullptr;
  }
  double NthBest() const { return board_.Threshold(); }
  void Insert(const Combination& c, MissionResult&& r, double cutoff);
  void Process(const Candidate& cand, TopScores top, Outcome* o) const;
  // Stops the search before the chunk at ci when a stop was requested and work is left.
  bool StopAt(std::size_t ci, double threshold);
  void ReportProgress(std::size_t ci);

  const SearchContext& ctx_;
  const SearchOptions& opt_;
  CandidateStream& stream_;
  long long open_at_start_ = 0;  // the stream's open combinations before the first draw (progress)
  std::vector<Candidate> ordered_;  // drawn candidates from index base_ on (earlier ones done)
  std::size_t base_ = 0;
  SearchResult* out_;
  Mission relaxed_;
  double cutoff_ = kInf;
  MissionFacts facts_;
  TopResults board_;  // the top N so far (top_results.h); out_->best at the end
  long long virtual_evals_ = 0;
};

void BranchAndBound::Insert(const Combination& c, MissionResult&& r, double cutoff) {
  if (!r.feasible) return;
  out_->evaluated_mass_objective.emplace_back(r.propulsion_mass_kg, r.objective);
  board_.Add(RankedCombination{c, std::move(r), {}}, cutoff);
}

void BranchAndBound::Explain() const {
  std::vector<double> cutoffs;
  out_->best = board_.Sorted(&cutoffs);
  out_->nth_best_score = board_.Threshold();
  for (std::size_t i = 0; i < out_->best.size(); ++i) {
    RankedCombination& b = out_->best[i];
    const PropModel* model = b.combination.prop == nullptr
                                 ? nullptr
                                 : ctx_.models[static_cast<std::size_t>(b.combination.prop - ctx_.catalog->props().data())].get();
    b.result = MissionEvaluator(*ctx_.mission, b.combination, model, &ctx_.fixed_model_ptrs).Solve(cutoffs[i]);
  }
}

// One candidate pair against the N best scores when its chunk started (`top`, updated with
// this pair's own results, so that the threshold tightens within the pair exactly as it would
// in a sequential search): virtual ESC per class first (R5), then the real ESCs, lightest first,
// skipping dominated ones. Pruning against a threshold at least the final N-th best is safe.
void BranchAndBound::Process(const Candidate& cand, TopScores top, Outcome* o) const {
  const Mission& m = *ctx_.mission;
  const auto& escs = ctx_.catalog->escs();
  const double margin = 1.0 - m.constraints.current_margin;
  auto threshold_now = [&]() { return top.Threshold(); };
  auto local_prune = [&](const char* rule, long long n) { o->pruned.Add(rule, n); };
  const BatteryOption& bo = ctx_.options[cand.option];
  const PropModel* model = ctx_.models[cand.prop].get();
  Combination c{&ctx_.catalog->motors()[cand.motor], nullptr, &ctx_.catalog->props()[cand.prop], bo.entry, bo.cells, {}};
  if (!ctx_.fixed_parts.empty()) {
    c.groups = ctx_.fixed_parts;
    c.groups[ctx_.free_group].motor = c.motor;
    c.groups[ctx_.free_group].prop = c.prop;
  }
  const MotorParams mp = ScenarioMotorParams(*c.motor, m, nullptr, nullptr);  // as MotorSetUp (R9)
  auto set_esc = [&](Combination* x, const EscEntry* e) {
    x->esc = e;
    if (!x->groups.empty()) x->groups[ctx_.free_group].esc = e;
  };
  std::vector<int> rated;  // per class, reused
  for (std::size_t cl = 0; cl < ctx_.escs.classes.size(); ++cl) {
    const std::vector<int>& list = ctx_.escs.per_option[cand.option][cl];
    if (list.empty()) continue;
    // R3: ESCs rated below the Irms lower bound. How many pass, and the lightest that does,
    // by binary search (EscTable's sorted currents and running maximum); the list of those
    // that pass is built only for the classes R10 lets through.
    auto below_r3 = [&](double current_a) { return current_a * margin < cand.irms_lb; };
    const std::vector<double>& ascending = ctx_.escs.currents_ascending[cand.option][cl];
    std::size_t n_rated = static_cast<std::size_t>(
        ascending.end() - std::partition_point(ascending.begin(), ascending.end(), below_r3));
    local_prune("esc_current", static_cast<long long>(list.size() - n_rated));
    if (n_rated == 0) continue;
    const std::vector<double>& running_max = ctx_.escs.running_max_current[cand.option][cl];
    const int lightest_rated =
        list[static_cast<std::size_t>(std::partition_point(running_max.begin(), running_max.end(), below_r3) -
                                      running_max.begin())];
    // R5's virtual ESC of the rated ESCs (only what the evaluator reads: no copy of the JSON).
    EscEntry virt;
    virt.id = "virtual";
    virt.params = escs[lightest_rated].params;
    virt.params.resc_ohm = 0.0;
    virt.params.max_current_a = kInf;
    virt.mass_kg = EscMassKg(escs[lightest_rated]);
    // R10: segment by segment, with the virtual ESC's drive and mass; true when it prunes the
    // class. First with every rated ESC (it refuses most classes, and R9 is then not needed),
    // again after R9 when R9 took the lightest away (a heavier virtual ESC: a tighter bound).
    auto segmentwise_prunes = [&]() {
      const char* rule = nullptr;
      const double t_max = ThrottleLimit(m.constraints, virt.params.tr_sat);
      const double threshold = threshold_now();
      const double b = SegmentwiseBoundPieces(ctx_, facts_, mp, Drive(mp, virt.params), t_max, cand.motor, cand.prop,
                                              cand.option, *virt.mass_kg, threshold, &rule);
      if (!rule && b < threshold) return false;
      local_prune(rule ? rule : "objective_bound", static_cast<long long>(n_rated));
      return true;
    };
    if (segmentwise_prunes()) continue;
    rated.clear();
    for (int e : list) {
      if (!below_r3(escs[e].params.max_current_a)) rated.push_back(e);
    }
    // R9, per ESC; skipped when the class's most favourable case (its lightest mass and least
    // resistance, which give the lowest throttle bound: M1-M3) is not below the limit.
    EscEntry least;
    least.params = escs[rated.front()].params;
    least.mass_kg = *virt.mass_kg;
    for (int e : rated) least.params.resc_ohm = std::min(least.params.resc_ohm, escs[e].params.resc_ohm);
    if (HoverThrottleBelowLimit(ctx_, facts_, mp, cand.motor, cand.prop, cand.option, least)) {
      const std::size_t before = rated.size();
      rated.erase(std::remove_if(rated.begin(), rated.end(), [&](int e) {
                    return HoverThrottleBelowLimit(ctx_, facts_, mp, cand.motor, cand.prop, cand.option, escs[e]);
                  }),
                  rated.end());
      local_prune("min_hover_throttle", static_cast<long long>(before - rated.size()));
      if (rated.empty()) continue;
      n_rated = rated.size();
      // The lists are sorted by mass (BuildEscTable) and `rated` keeps their order.
      if (const double kg = EscMassKg(escs[rated.front()]); kg != *virt.mass_kg) {
        virt.mass_kg = kg;
        if (segmentwise_prunes()) continue;
      }
    }
    // R12 per ESC (the window's bottom): the lightest ESCs fail it first (M3).
    if (HoverSpeedBelowWindow(ctx_, facts_, cand.motor, cand.prop, cand.option, *virt.mass_kg)) {
      const std::size_t before = rated.size();
      rated.erase(std::remove_if(rated.begin(), rated.end(), [&](int e) {
                    return HoverSpeedBelowWindow(ctx_, facts_, cand.motor, cand.prop, cand.option, EscMassKg(escs[e]));
                  }),
                  rated.end());
      local_prune("prop_below_data", static_cast<long long>(before - rated.size()));
      if (rated.empty()) continue;
      n_rated = rated.size();
      if (const double kg = EscMassKg(escs[rated.front()]); kg != *virt.mass_kg) {
        virt.mass_kg = kg;
        if (segmentwise_prunes()) continue;
      }
    }
    {
      Combination vc = c;
      set_esc(&vc, &virt);
      const double threshold = threshold_now();
      const MissionEvaluator virtual_eval(relaxed_, vc, model, &ctx_.fixed_model_ptrs);
      // R12: above the window at the lightest vehicle; every ESC of the class is heavier (M3).
      if (MissionResult w; virtual_eval.DataWindowRefuses(false, &w)) {
        local_prune("prop_above_data", static_cast<long long>(rated.size()));
        continue;
      }
      const MissionResult vr = virtual_eval.Solve(threshold, false, true, true);
      ++o->virtual_evals;
      if (vr.bounded_out || !vr.feasible || !(vr.score < threshold)) {
        local_prune(vr.bounded_out || vr.feasible ? "objective_bound" : "infeasible_bound",
                    static_cast<long long>(rated.size()));
        continue;
      }
    }
    std::vector<std::pair<int, bool>> done;  // ESC, "cannot enter the top N"
    for (int e : rated) {
      bool skip = false;
      for (const auto& d : done) {
        if (d.second && Dominates(escs[d.first], escs[e])) { skip = true; break; }
      }
      if (skip) {
        local_prune("esc_dominated", 1);
        continue;
      }
      set_esc(&c, &escs[e]);
      const double threshold = threshold_now();
      const MissionEvaluator eval(m, c, model, &ctx_.fixed_model_ptrs);
      if (MissionResult w; eval.DataWindowRefuses(true, &w)) {  // R12, before a solve
        const bool above = w.violations[0].constraint == "prop_above_data";
        local_prune(above ? "prop_above_data" : "prop_below_data", 1);
        done.emplace_back(e, !FailsMinHoverThrottle(w));  // below: a heavier ESC may meet it
        continue;
      }
      MissionResult r = eval.Solve(threshold, false, false, true);
      if (r.bounded_out) {
        local_prune("objective_bound", 1);
        done.emplace_back(e, true);
        continue;
      }
      ++o->searched;
      done.emplace_back(e, r.feasible ? !(r.score < threshold) : !FailsMinHoverThrottle(r));
      if (r.feasible) {
        top.Add(KeyOf(c, top.distinct_designs()), r.score);
        o->results.emplace_back(c, std::move(r));
        o->cutoffs.push_back(threshold);
      }
    }
  }
}

// Chunks of candidates evaluated on the worker threads against the threshold at the chunk's
// start, merged in candidate order: the answer and the counts do not depend on timing. Ipopt
// (the shaft segments' solver, MUMPS) is not thread-safe: missions with a free shaft speed run
// on one thread.
bool BranchAndBound::StopAt(std::size_t ci, double threshold) {
  const Candidate* next = CandidateAt(ci);
  if (!next || !(next->bound < threshold)) return false;  // nothing left: the search ends anyway
  // The candidates come best bound first: the next one's bound is below every later one's, and
  // every combination of a pair scores at least the pair's bound (R4, R11).
  out_->interrupted = true;
  out_->unsettled_bound_score = next->bound;
  out_->unsettled = stream_.open_combinations();
  for (std::size_t i = ci; i < base_ + ordered_.size(); ++i) {
    out_->unsettled += ctx_.escs.rated[static_cast<std::size_t>(ordered_[i - base_].option)];
  }
  return true;
}

// The share of the work done: the candidate pairs drawn against those drawn plus an upper bound
// of those still to draw below the N-th best (CandidateStream::PairsLeftBelow). It moves with
// the work (the bound gap does not: on the capacity-sized quadcopter the gap was 95 % closed
// after 3 s of 10, as the bounds crowd just below the threshold).
void BranchAndBound::ReportProgress(std::size_t ci) {
  if (!opt_.progress) return;
  SearchProgress p;
  const Candidate* next = CandidateAt(ci);
  const double threshold = NthBest();
  if (!next || !(next->bound < threshold)) {
    p.fraction = 1.0;
  } else {
    const double drawn = static_cast<double>(ci);
    const double left = static_cast<double>(base_ + ordered_.size() - ci + stream_.PairsLeftBelow(threshold));
    p.fraction = drawn / (drawn + left);
  }
  p.searched = out_->searched;
  for (const auto& [rule, n] : out_->pruned_by) p.pruned += n;
  p.has_best = !board_.empty();
  p.found = board_.size();
  p.best_objective = board_.best_objective();
  opt_.progress(p);
}

void BranchAndBound::Run() {
  const Mission& m = *ctx_.mission;
  const int workers = NeedsOneThread(m) ? 1 : std::max(1, opt_.threads);
  constexpr std::size_t kMaxChunk = 128;
  std::size_t chunk = 2;  // grows while the threshold settles
  WorkerThreads pool(workers - 1);
  std::size_t ci = 0;
  for (;;) {
    ReportProgress(ci);
    const double threshold = NthBest();
    const bool over_budget =
        opt_.evaluation_budget > 0 && out_->searched + virtual_evals_ >= opt_.evaluation_budget;
    if ((over_budget || StopRequested(opt_)) && StopAt(ci, threshold)) break;
    const TopScores top = board_.scores();
    std::size_t end = ci;
    while (end - ci < chunk && CandidateAt(end) && CandidateAt(end)->bound < threshold) ++end;
    // Distinct designs: a pair is one design, so its own results cannot tighten its threshold
    // (TopScores): while fewer than N designs are known every ESC of a chunk's pairs is scored,
    // so the chunks stay small until the threshold is finite (the capacity-sized quadcopter:
    // 28 s before its first threshold with growing chunks).
    chunk = opt_.distinct_designs && !std::isfinite(threshold) ? chunk : std::min(kMaxChunk, 2 * chunk);
    if (end == ci) {  // R4: every later candidate has a bound at least as bad
      // Those never drawn and those drawn for the next chunk (the stream draws ahead).
      long long undrawn = stream_.open_combinations();
      for (std::size_t i = ci; i < base_ + ordered_.size(); ++i) {
        undrawn += ctx_.escs.rated[static_cast<std::size_t>(ordered_[i - base_].option)];
      }
      out_->pruned_by["objective_bound"] += undrawn;
      break;
    }
    std::vector<Outcome> outs(end - ci);
    // The chunk's candidates, copied: while the other workers start on them, this thread draws
    // the next chunk's from the stream (bounding a motor's next batch is serial work), with the
    // threshold before this chunk's results (at least the final one: the stream only draws
    // more, and a drawn pair not processed is counted when the search stops), then joins them.
    const std::vector<Candidate> cands(ordered_.begin() + static_cast<std::ptrdiff_t>(ci - base_),
                                       ordered_.begin() + static_cast<std::ptrdiff_t>(end - base_));
    // Each worker takes the next unprocessed candidate (one exact evaluation can cost as much
    // as a thousand pruned pairs: a fixed split leaves a thread idle).
    std::atomic<std::size_t> next{0};
    auto run = [&]() {
      for (std::size_t i = next++; i < cands.size(); i = next++) Process(cands[i], top, &outs[i]);
    };
    const std::function<void()> job = run;
    pool.Start(&job);
    // On one thread too: the stream bounds a motor's next batch against the cutoff of the
    // moment it is drawn, and the pairs a rule removes are counted then, so the draws must
    // come at the same moments whatever the number of threads (the counts do not depend on it).
    CandidateAt(end + chunk - 1);
    run();
    pool.Wait();
    for (Outcome& o : outs) {
      o.pruned.MergeInto(&out_->pruned_by);
      out_->searched += o.searched;
      virtual_evals_ += o.virtual_evals;
      for (std::size_t j = 0; j < o.results.size(); ++j) Insert(o.results[j].first, std::move(o.results[j].second), o.cutoffs[j]);
    }
    ordered_.erase(ordered_.begin(), ordered_.begin() + static_cast<std::ptrdiff_t>(end - base_));
    base_ = end;
    ci = end;
  }
}

}  // namespace

SearchResult search_internal::SearchOneGroup(const Mission& m, const Catalog& cat, const SearchOptions& opt,
                                             double cutoff, PropGridCache* cache,
                                             const std::vector<GroupParts>* given_parts) {
  const auto t0 = std::chrono::steady_clock::now();
  if (opt.top_n < 1) throw UsageError("--top " + std::to_string(opt.top_n) + ": must be >= 1");
  SearchResult out;
  SearchContext ctx;
  ctx.given_parts = given_parts;
  if (cache) {  // stages 0-3 with the caller's propeller grids (they depend on the air and limits only)
    ctx.mission = &m;
    ctx.catalog = &cat;
    ResolveGroups(&ctx);
    ctx.options = BatteryOptions(m, cat);
    ctx.escs = BuildEscTable(cat, ctx.options);
    if (!cache->built) BuildPropGrids(m, cat, &cache->grids, &cache->models);
    cache->built = true;
    ctx.grids = std::move(cache->grids);
    ctx.models = std::move(cache->models);
  } else {
    PrepareStages(m, cat, &ctx);  // stages 0-3
  }
  FixedGroupPowerBounds(&ctx);
  out.combinations = static_cast<long long>(cat.motors().size()) * static_cast<long long>(cat.escs().size()) *
                     static_cast<long long>(cat.props().size()) * static_cast<long long>(ctx.options.size());
  out.pruned_by["esc_voltage"] += ctx.escs.voltage_pruned * static_cast<long long>(cat.motors().size() * cat.props().size());
  if (ctx.escs.excluded_pruned > 0) {
    out.pruned_by["catalog_exclude"] += ctx.escs.excluded_pruned * static_cast<long long>(cat.motors().size() * cat.props().size());
  }
  {
    CandidateStream stream(ctx, opt.threads);  // stage 4 (each motor's first batch)
    out.candidate_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    BranchAndBound bb(ctx, opt, &stream, &out, cutoff);  // stage 5 (and stage 4 on demand)
    bb.Run();
    bb.Explain();
    stream.MergePrunedInto(&out.pruned_by);
    out.skipped_without_mass = stream.skipped_without_mass();
    out.candidate_pairs = stream.pairs_bounded();
    out.candidate_batches = stream.batches();
    out.virtual_evaluations = bb.virtual_evaluations();
  }
  if (cache) {
    cache->grids = std::move(ctx.grids);
    cache->models = std::move(ctx.models);
  }
  out.pruned = out.combinations - out.searched - out.unsettled;
  if (opt.progress && !out.interrupted) {
    SearchProgress p;
    p.fraction = 1.0;
    p.searched = out.searched;
    p.pruned = out.pruned;
    p.has_best = !out.best.empty();
    p.found = static_cast<int>(out.best.size());
    p.best_objective = p.has_best ? out.best.front().result.objective : 0.0;
    opt.progress(p);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

namespace {

// One free group: stages 0-5 (R0-R11, G1); several: the joint search (G2, joint_search.h).
SearchResult SearchExactly(const Mission& m, const Catalog& cat, const SearchOptions& opt) {
  SearchResult out = FreeGroupCount(m) > 1 ? search_internal::JointSearch(m, cat, opt)
                                           : search_internal::SearchOneGroup(m, cat, opt, kInf, nullptr);
  for (RankedCombination& b : out.best) AddObjectiveRange(m, b.combination, &b.result);  // credibility.h
  return out;
}

}  // namespace

bool StopRequested(const SearchOptions& opt) {
  if (opt.stop && opt.stop->load(std::memory_order_relaxed)) return true;
  return opt.deadline != std::chrono::steady_clock::time_point::max() && std::chrono::steady_clock::now() >= opt.deadline;
}

bool NeedsOneThread(const Mission& mission) {
  for (const Segment& sg : mission.segments) {
    if (sg.type == SegmentType::kShaft && sg.shaft_omega_rad_s.free()) return true;
  }
  return false;
}

SearchResult SearchCatalog(const Mission& m, const Catalog& cat, const SearchOptions& opt) {
  SearchResult out = SearchExactly(m, cat, opt);
  // Stopped: what was found (nothing may mean "not yet"), not the relaxed search.
  if (out.interrupted || !out.best.empty() || !(m.constraints.min_thrust_to_weight > 0)) return out;
  // No combination reaches the thrust-to-weight (or nothing flies at all): the designer still
  // needs the candidates and how far each falls short. Search again without that limit and
  // return its best, each marked infeasible with the thrust-to-weight it reaches (computed by
  // Summarize at the mission's end, as the limit is checked).
  Mission relaxed = m;
  relaxed.constraints.min_thrust_to_weight = 0.0;
  SearchResult r = SearchExactly(relaxed, cat, opt);
  if (r.best.empty()) {
    out.interrupted = r.interrupted;  // the search without the limit did not finish
    return out;
  }
  for (RankedCombination& b : r.best) {
    MissionResult& x = b.result;
    x.feasible = false;
    x.violations.push_back(Violation{"min_thrust_to_weight", "", x.thrust_to_weight,
                                     m.constraints.min_thrust_to_weight, "", true});
  }
  r.relaxed_constraint = "min_thrust_to_weight";
  r.seconds += out.seconds;
  return r;
}

}  // namespace dynosize
