// R7 and R6 as floors of the vehicle's mass (mass_floors.h; docs/search.md#mass-floors).
#include "optimization/mass_floors.h"

#include <algorithm>
#include <array>
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

// R6 on one cell of vehicle masses [M_a, M_b] and airspeeds [V_a, V_b] (one airspeed when the
// segment's is fixed). The evaluator's figure of merit is P_ideal(T, v)/P(omega), the
// propeller's power as given at the speed omega that gives the segment's thrust T in its axial
// inflow v (mission_eval.cc, PropellerPoint; model/physics.h); a wing-borne cruise's inflow is
// its airspeed and its thrust rises with the mass (M3) and the airspeed (flight.h). On the cell
// T is in [T(M_a, V_a), T(M_b, V_b)]. At any inflow V of the cell the speed is at or below that
// of T_b = T(M_b, V_b) (M1) and the power at most the power there when it rises with speed
// (checked at kFomSamples speeds at V_a and V_b); that power is at most the one at V_b (M4,
// checked between V_a and V_b), itself at most P(omega_b, V_b), omega_b a speed whose thrust is
// at least T_b. P_ideal rises with T and v: the figure of merit is at least
// P_ideal(T_a, V_a)/P(omega_b, V_b). *proven: that is above the limit, so the cell holds no
// feasible point. *worth_refining: not proven, but P_ideal(T_b, V_b) over the least power seen
// is above the limit: smaller cells may be proven where this one is not. Static-only data are
// read at J = 0 in any inflow and held to the static bound (v = 0), as PropellerPoint does.
struct FomCells {
  const Mission& m;
  const Segment& sg;
  const PropEntry& p;
  const PropModel& model;
  double limit;
  bool static_only;

  struct Point {
    double thrust_n, v_m_s;  // the load and the inflow the data are read at
  };
  Point At(double kg, double airspeed_m_s) const {
    const RotorLoad l = SegmentRotorLoad(m, sg, kg, airspeed_m_s);
    return {l.thrust_per_rotor_n, static_only ? 0.0 : l.axial_airspeed_m_s};
  }
  // At inflow v: a speed whose thrust is at least t_hi (*omega_hi) and the power at the kFomSamples
  // speeds from one at or below that of t_lo up to it; false when the thrust cannot be reached or
  // the power does not rise on them. *p_lo, *p_hi: the first and last samples' power.
  bool RisingPower(double t_lo, double t_hi, double v, double* p_lo, double* p_hi) const {
    constexpr int kFomSamples = 8, kSteps = 50;
    if (!(model.Evaluate(kRotorCeilingRadS, m.rho_kg_m3, v).thrust_n >= t_hi)) return false;
    double lo = 0.0, hi = kRotorCeilingRadS;  // thrust(hi) >= t_hi kept through the bisection (M1)
    for (int it = 0; it < kSteps; ++it) {
      const double mid = 0.5 * (lo + hi);
      (model.Evaluate(mid, m.rho_kg_m3, v).thrust_n >= t_hi ? hi : lo) = mid;
    }
    const double w_lo = SpeedFromBelow(model, m.rho_kg_m3, t_lo, v, 0.0, hi, kSteps);
    double p_prev = -kInf, power_w = 0.0;
    for (int k = 0; k <= kFomSamples; ++k) {
      power_w = model.Evaluate(w_lo + (hi - w_lo) * k / kFomSamples, m.rho_kg_m3, v).power_w;
      if (k == 0) *p_lo = power_w;
      if (!(power_w >= p_prev)) return false;
      p_prev = power_w;
    }
    *p_hi = power_w;
    return power_w > 0;
  }
  void Check(double kg_a, double kg_b, double va, double vb, bool* proven, bool* worth_refining) const {
    *proven = *worth_refining = false;
    const Point a = At(kg_a, va), b = At(kg_b, vb);
    double p_lo_b = 0, p_b = 0;
    if (!RisingPower(a.thrust_n, b.thrust_n, b.v_m_s, &p_lo_b, &p_b)) return;
    double p_lo = p_lo_b;
    if (vb > va && !static_only) {  // M1 at V_a, and M4: the power at T_b no higher at V_a
      const Point a_b = At(kg_b, va);
      double p_hi_a = 0;
      if (!RisingPower(a.thrust_n, a_b.thrust_n, a.v_m_s, &p_lo, &p_hi_a) || p_hi_a > p_b) return;
    }
    *proven = IdealRotorPowerW(a.thrust_n, p.diameter_m, m.rho_kg_m3, a.v_m_s) / p_b > limit;
    *worth_refining =
        !*proven && p_lo > 0 && IdealRotorPowerW(b.thrust_n, p.diameter_m, m.rho_kg_m3, b.v_m_s) / p_lo > limit;
  }
  // The highest mass x in [kg_a, kg_b] with [kg_a, x] x [va, vb] proven to hold no feasible point
  // (kg_a when none); a cell worth refining is halved up to `depth` times, in whichever of its
  // mass and airspeed is the wider relative to its value.
  double ProvenUpTo(double kg_a, double kg_b, double va, double vb, int depth) const {
    bool proven = false, refine = false;
    Check(kg_a, kg_b, va, vb, &proven, &refine);
    if (proven) return kg_b;
    if (!refine || depth == 0) return kg_a;
    if (vb > va && (vb - va) / va > kg_b / kg_a - 1.0) {
      const double vm = 0.5 * (va + vb);
      return std::min(ProvenUpTo(kg_a, kg_b, va, vm, depth - 1), ProvenUpTo(kg_a, kg_b, vm, vb, depth - 1));
    }
    const double mid = std::sqrt(kg_a * kg_b);
    const double x = ProvenUpTo(kg_a, mid, va, vb, depth - 1);
    return x < mid ? x : ProvenUpTo(mid, kg_b, va, vb, depth - 1);
  }
  // A screen, not a proof (no floor is always a valid answer): false when the figure of merit at
  // kScreenSpeeds speeds of the data at the range's airspeeds va and vb, where the thrust is at
  // least the lightest vehicle's there, is below the limit by kScreenMargin everywhere, so that
  // no cell would be proven; most propellers, whose scan would otherwise check cells per query.
  bool MayBreakLimit(double mass_min_kg, double va, double vb) const {
    constexpr int kScreenSpeeds = 48;
    constexpr double kScreenMargin = 0.95, kSpeedLoRadS = 50.0, kSpeedHiRadS = 1e4;
    for (const double airspeed : {va, vb}) {
      const Point lightest = At(mass_min_kg, airspeed);
      for (int k = 0; k < kScreenSpeeds; ++k) {
        const double w = kSpeedLoRadS * std::pow(kSpeedHiRadS / kSpeedLoRadS, k / double(kScreenSpeeds - 1));
        const PropEvaluation ev = model.Evaluate(w, m.rho_kg_m3, lightest.v_m_s);
        if (ev.thrust_n >= lightest.thrust_n && ev.power_w > 0 &&
            IdealRotorPowerW(ev.thrust_n, p.diameter_m, m.rho_kg_m3, lightest.v_m_s) / ev.power_w >
                kScreenMargin * limit) {
          return true;
        }
      }
    }
    return false;
  }
};

// R6's floor. At a fixed airspeed: cells of FomCells scanned up from mass_min_kg, kFomCellRatio
// wide (kFomCells of them, each halved up to kFomRefinements times where worth it); the floor is
// the lowest mass not proven to hold no feasible vehicle. A wing-borne cruise with a free
// airspeed: the range in kFomAirspeedCells cells, each scanned so (kFomCellsFree mass cells,
// kFomRefinementsFree halvings in mass or airspeed); a feasible point lies in one of them, so
// the floor is the least of theirs. A propeller whose figure of merit is above the limit at
// every mass (it can rise with the thrust) gets a floor above any vehicle the search builds.
double FigureOfMeritMassFloorKg(const Mission& m, const Segment& sg, const PropEntry& p, const PropModel& model,
                                bool monotone, double mass_min_kg) {
  constexpr int kFomCells = 64, kFomRefinements = 4;
  constexpr int kFomAirspeedCells = 8, kFomCellsFree = 24, kFomRefinementsFree = 6;
  constexpr double kFomCellRatio = 1.03;
  // A shaft segment has no figure of merit; a multirotor cruise's inflow changes with the mass
  // (flight.h).
  const bool free_airspeed = sg.type == SegmentType::kCruise && sg.airspeed_m_s.free();
  if (sg.type == SegmentType::kShaft || (sg.type == SegmentType::kCruise && !(sg.lift_to_drag > 0)) ||
      !(m.constraints.max_figure_of_merit > 0) || !monotone || !(mass_min_kg > 0)) {
    return 0.0;
  }
  const bool static_only = model.data_kind() != PropDataKind::kTables || p.j_tables.empty();
  const double lo = sg.airspeed_m_s.lo, hi = free_airspeed ? sg.airspeed_m_s.hi : lo;
  if (SegmentRotorLoad(m, sg, 1.0, lo).axial_airspeed_m_s < 0) return 0.0;  // a descent: PropellerPoint's inflow differs
  // The limit at the segment's largest inflow, at least that of each of its points (mission.h);
  // the inflow does not depend on the mass here (a climb's rate, a wing-borne cruise's airspeed).
  const double top_inflow_m_s = static_only ? 0.0 : SegmentRotorLoad(m, sg, 1.0, hi).axial_airspeed_m_s;
  const FomCells cells{m, sg, p, model, FigureOfMeritLimit(m.constraints, top_inflow_m_s), static_only};
  if (!cells.MayBreakLimit(mass_min_kg, lo, hi)) return 0.0;
  const int airspeed_cells = free_airspeed ? kFomAirspeedCells : 1;
  const int mass_cells = free_airspeed ? kFomCellsFree : kFomCells;
  const int depth = free_airspeed ? kFomRefinementsFree : kFomRefinements;
  // Each airspeed cell's scan goes up from mass_min_kg one mass cell at a time and stops at the
  // first cell not wholly proven (at x, the mass proven up to) or after mass_cells of them; the
  // floor is the least of their stops. A scan's stop is at or above where it stands, so a scan
  // standing at or above the least stop found so far cannot lower it. The scans advance
  // best-first (always the one standing lowest; the lower airspeed of a tie), which gives the
  // same stops and floor as scanning the cells in turn, with fewer checks: one airspeed cell
  // whose first mass cell holds a feasible point ends the search at mass_min_kg.
  std::array<double, kFomAirspeedCells> at{};
  std::array<int, kFomAirspeedCells> steps{};
  std::array<bool, kFomAirspeedCells> stopped{};
  at.fill(mass_min_kg);
  double floor_kg = kInf;
  for (;;) {
    int c = -1;
    for (int i = 0; i < airspeed_cells; ++i) {
      if (!stopped[i] && at[i] < floor_kg && (c < 0 || at[i] < at[c])) c = i;
    }
    if (c < 0) break;
    const double va = lo + (hi - lo) * c / airspeed_cells, vb = lo + (hi - lo) * (c + 1) / airspeed_cells;
    const double kg_b = at[c] * kFomCellRatio;
    const double x = cells.ProvenUpTo(at[c], kg_b, va, vb, depth);
    at[c] = x;
    if (x < kg_b || ++steps[c] == mass_cells) {
      stopped[c] = true;
      floor_kg = std::min(floor_kg, x);
    }
  }
  return floor_kg;
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
