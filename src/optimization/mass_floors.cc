// R7 and R6 as floors of the vehicle's mass (mass_floors.h; docs/search.md#g2).
#include "optimization/mass_floors.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/units.h"
#include "mission/flight.h"
#include "model/physics.h"
#include "optimization/prop_bounds.h"

namespace dynosize::search_internal {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMassCeilingKg = 1e5;     // R7's bisection range: beyond any vehicle
constexpr double kRotorCeilingRadS = 1e5;  // R6's speed range: ~1e6 rpm, beyond any motor
constexpr int kFreeCruiseFloorCells = 16;  // R7's floor over a free airspeed range

// R7's floor on one airspeed cell [v_a, v_b]: static-only data in axial flow V_ax pass the
// evaluator only at an advance ratio J = V_ax/(n*D) <= max_static_advance_ratio, so at a speed
// n >= V_ax/(J_max*D), where the static thrust (M1, the grid rising) is at least T(n); the
// segment's thrust rises with the vehicle's mass (M3), so a feasible vehicle weighs at least the
// mass whose thrust is T(n) (bisection, kept at or below it). kInf when no mass reaches the
// thrust, 0 when every mass does (or the inflow is 0).
double StaticAdvanceCellFloorKg(const Mission& m, const PropModel& model, double diameter_m, const Segment& sg,
                                double v_a, double v_b) {
  const double v_ax = SegmentRotorLoad(m, sg, 1.0, v_a).axial_airspeed_m_s;
  if (!(v_ax > 0)) return 0.0;
  const double omega_req = 2.0 * kPi * v_ax / (m.constraints.max_static_advance_ratio * diameter_m);
  const double t_req = model.Evaluate(omega_req, m.rho_kg_m3, 0.0).thrust_n;
  auto thrust_at = [&](double kg) { return SegmentRotorLoad(m, sg, kg, v_b).thrust_per_rotor_n; };
  double lo = 0.0, hi = kMassCeilingKg;
  if (!(thrust_at(hi) >= t_req)) return kInf;
  if (!(thrust_at(lo) < t_req)) return 0.0;
  for (int it = 0; it < 60; ++it) {  // keeps thrust(lo) < T(n)
    const double mid = 0.5 * (lo + hi);
    (thrust_at(mid) < t_req ? lo : hi) = mid;
  }
  return lo;
}

// R7 over the segment's airspeeds: a free (wing-borne) airspeed in cells [V_a, V_b] (the
// required speed and its static thrust rise with V, M1; the segment's thrust at a mass is
// largest at V_b, flight.h), the least over the cells; a fixed airspeed is one cell. 0 when the
// rule does not apply.
double StaticAdvanceMassFloorKg(const Mission& m, const Segment& sg, const PropEntry& p, const PropModel& model,
                                bool monotone) {
  const bool static_only = model.data_kind() != PropDataKind::kTables || p.j_tables.empty();
  const bool free_cruise = sg.type == SegmentType::kCruise && sg.airspeed_m_s.free();
  if (!static_only || !monotone || sg.type == SegmentType::kShaft || (free_cruise && !(sg.lift_to_drag > 0)) ||
      !(m.constraints.max_static_advance_ratio > 0)) {
    return 0.0;
  }
  const int cells = free_cruise ? kFreeCruiseFloorCells : 1;
  const double lo = sg.airspeed_m_s.lo, span = free_cruise ? sg.airspeed_m_s.hi - lo : 0.0;
  double floor_kg = kInf;
  for (int c = 0; c < cells && floor_kg > 0; ++c) {
    const double v_a = lo + span * c / cells, v_b = lo + span * (c + 1) / cells;
    floor_kg = std::min(floor_kg, StaticAdvanceCellFloorKg(m, model, p.diameter_m, sg, v_a, v_b));
  }
  return floor_kg;
}

// R6 on one mass cell [M_a, M_b] at a fixed axial inflow v (the evaluator's figure of merit is
// P_ideal(T, v)/P(omega), the propeller's power as given at the speed omega that gives the
// segment's thrust T; mission_eval.cc, PropellerPoint; model/physics.h). The thrust is in
// [T(M_a), T(M_b)] (M3), the speed at or below omega_b, a speed whose thrust is at least T(M_b)
// (M1), so the power is at most P(omega_b) when the power rises with speed on the cell's speeds
// (checked at kFomSamples speeds, else nothing is proven there), and P_ideal rises with T: the
// figure of merit is at least P_ideal(T(M_a), v)/P(omega_b). *proven: that is above the limit,
// so the cell holds no feasible mass. *worth_refining: not proven, but the figure of merit may
// be above the limit somewhere on the cell (P_ideal(T(M_b), v)/P(omega_a), omega_a a speed at or
// below the one of T(M_a), is above it): halves may be proven where the whole is not.
struct FomCells {
  const Mission& m;
  const Segment& sg;
  const PropEntry& p;
  const PropModel& model;
  double v_eval, v_fom, limit;

  void Check(double kg_a, double kg_b, bool* proven, bool* worth_refining) const {
    constexpr int kFomSamples = 8, kSteps = 50;
    *proven = *worth_refining = false;
    const double t_a = Load(kg_a).thrust_per_rotor_n, t_b = Load(kg_b).thrust_per_rotor_n;
    if (!(model.Evaluate(kRotorCeilingRadS, m.rho_kg_m3, v_eval).thrust_n >= t_b)) return;
    // omega_b: thrust(hi) >= t_b kept through the bisection (M1).
    double lo = 0.0, hi = kRotorCeilingRadS;
    for (int it = 0; it < kSteps; ++it) {
      const double mid = 0.5 * (lo + hi);
      (model.Evaluate(mid, m.rho_kg_m3, v_eval).thrust_n >= t_b ? hi : lo) = mid;
    }
    const double w_a = BisectSpeedFromBelow(model, m.rho_kg_m3, t_a, v_eval, 0.0, hi, kSteps);
    double p_prev = -kInf, p_a = 0.0, p_b = 0.0;
    bool rising = true;
    for (int k = 0; k <= kFomSamples && rising; ++k) {
      const double w = w_a + (hi - w_a) * k / kFomSamples;
      p_b = model.Evaluate(w, m.rho_kg_m3, v_eval).power_w;
      if (k == 0) p_a = p_b;
      rising = p_b >= p_prev;
      p_prev = p_b;
    }
    if (!rising || !(p_b > 0)) return;
    *proven = IdealRotorPowerW(t_a, p.diameter_m, m.rho_kg_m3, v_fom) / p_b > limit;
    *worth_refining = !*proven && p_a > 0 && IdealRotorPowerW(t_b, p.diameter_m, m.rho_kg_m3, v_fom) / p_a > limit;
  }
  // The highest mass x in [kg_a, kg_b] with [kg_a, x] proven to hold no feasible mass (kg_a when
  // none), halving a cell worth refining up to `depth` times.
  double ProvenUpTo(double kg_a, double kg_b, int depth) const {
    bool proven = false, refine = false;
    Check(kg_a, kg_b, &proven, &refine);
    if (proven) return kg_b;
    if (!refine || depth == 0) return kg_a;
    const double mid = std::sqrt(kg_a * kg_b);
    const double x = ProvenUpTo(kg_a, mid, depth - 1);
    return x < mid ? x : ProvenUpTo(mid, kg_b, depth - 1);
  }
  RotorLoad Load(double kg) const { return SegmentRotorLoad(m, sg, kg, sg.airspeed_m_s.lo); }
  // A screen, not a proof (no floor is always a valid answer): false when the figure of merit at
  // kScreenSpeeds speeds of the data whose thrust is at least the lightest vehicle's (thrust_min_n)
  // is below the limit by kScreenMargin everywhere, so that no cell would be proven; most
  // propellers, whose scan would otherwise check a cell per query.
  bool MayBreakLimit(double thrust_min_n) const {
    constexpr int kScreenSpeeds = 48;
    constexpr double kScreenMargin = 0.95, kSpeedLoRadS = 50.0, kSpeedHiRadS = 1e4;
    for (int k = 0; k < kScreenSpeeds; ++k) {
      const double w = kSpeedLoRadS * std::pow(kSpeedHiRadS / kSpeedLoRadS, k / double(kScreenSpeeds - 1));
      const PropEvaluation ev = model.Evaluate(w, m.rho_kg_m3, v_eval);
      if (ev.thrust_n >= thrust_min_n && ev.power_w > 0 &&
          IdealRotorPowerW(ev.thrust_n, p.diameter_m, m.rho_kg_m3, v_fom) / ev.power_w > kScreenMargin * limit) {
        return true;
      }
    }
    return false;
  }
};

// R6's floor: cells of FomCells scanned up from mass_min_kg, kFomCellRatio wide (kFomCells of
// them, each halved up to kFomRefinements times where worth it): the floor is the lowest mass not
// proven to hold no feasible vehicle. A propeller whose figure of merit is above the limit at
// every mass (it can rise with the thrust) gets a floor above any vehicle the search builds.
double FigureOfMeritMassFloorKg(const Mission& m, const Segment& sg, const PropEntry& p, const PropModel& model,
                                bool monotone, double mass_min_kg) {
  constexpr int kFomCells = 64, kFomRefinements = 4;
  constexpr double kFomCellRatio = 1.03;
  const double limit = m.constraints.max_figure_of_merit;
  // A fixed inflow: not a shaft segment, a free airspeed or a multirotor cruise (its inflow
  // changes with the mass, flight.h).
  const bool fixed_inflow = sg.type != SegmentType::kShaft &&
                            !(sg.type == SegmentType::kCruise && (sg.airspeed_m_s.free() || !(sg.lift_to_drag > 0)));
  if (!fixed_inflow || !(limit > 0) || !monotone || !(mass_min_kg > 0)) return 0.0;
  const bool static_only = model.data_kind() != PropDataKind::kTables || p.j_tables.empty();
  const double v = SegmentRotorLoad(m, sg, 1.0, sg.airspeed_m_s.lo).axial_airspeed_m_s;
  if (v < 0) return 0.0;  // a descent: PropellerPoint's inflow differs
  // PropellerPoint: static-only data are read at J = 0 in any inflow and held to the static bound.
  const FomCells cells{m, sg, p, model, static_only ? 0.0 : v, static_only ? 0.0 : v, limit};
  if (!cells.MayBreakLimit(cells.Load(mass_min_kg).thrust_per_rotor_n)) return 0.0;
  double kg = mass_min_kg;
  for (int cell = 0; cell < kFomCells; ++cell) {
    const double kg_b = kg * kFomCellRatio;
    const double x = cells.ProvenUpTo(kg, kg_b, kFomRefinements);
    if (x < kg_b) return x;
    kg = kg_b;
  }
  return kg;
}

}  // namespace

MassFloor SegmentMassFloorKg(const Mission& m, const Segment& sg, const PropEntry& p, const PropModel& model,
                             bool monotone, double mass_min_kg) {
  MassFloor out;
  const double r7 = StaticAdvanceMassFloorKg(m, sg, p, model, monotone);
  if (r7 > 0) out = {r7, "prop_no_forward_flight_data"};
  if (!(out.kg < kInf)) return out;
  const double r6 = FigureOfMeritMassFloorKg(m, sg, p, model, monotone, mass_min_kg);
  if (r6 > out.kg) out = {r6, "prop_figure_of_merit"};
  return out;
}

}  // namespace dynosize::search_internal
