// How a candidate pair is bounded (pair_bounds.h): R4's score bound and the pair rules R2, R6,
// R7, R9, R12 (docs/search.md).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "common/units.h"
#include "mission/flight.h"
#include "model/physics.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "optimization/pair_bounds.h"
#include "optimization/prop_bounds.h"

namespace dynosize::search_internal {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();


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
                               double pdc_lb, int* scaled_rotors = nullptr) {
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
  if (scaled_rotors) *scaled_rotors = t.scales ? t.rotors : 0;
  return t.scales ? t.rotors * pdc_lb + m.vehicle.avionics_power_w : t.constant;
}

}  // namespace

double BudgetScore(double t_fixed_max_s, double e_max_j, double e_other_j, double p_stretch_w) {
  return p_stretch_w > 0 ? -(t_fixed_max_s + std::max(0.0, e_max_j - e_other_j) / p_stretch_w) : -kInf;
}
// Groups (G1): the rules below speak of the free group's segments only; a segment of a fixed
// group draws at least P_avionics (its drive's power is >= 0), and every group's mass is in
// mass_lb and mass_ub, so each bound stays a bound.
std::vector<std::size_t> LoadTwins(const Mission& m) {
  const std::vector<Segment>& sgs = m.segments;
  std::vector<std::size_t> twin(sgs.size());
  for (std::size_t i = 0; i < sgs.size(); ++i) {
    const Segment& a = sgs[i];
    twin[i] = i;
    for (std::size_t j = 0; j < i; ++j) {
      const Segment& b = sgs[j];
      if (a.type == b.type && a.group == b.group && a.climb_rate_m_s == b.climb_rate_m_s &&
          a.airspeed_m_s.lo == b.airspeed_m_s.lo && a.airspeed_m_s.hi == b.airspeed_m_s.hi &&
          a.lift_to_drag == b.lift_to_drag && a.lift_to_drag_of == b.lift_to_drag_of &&
          a.rotors_active == b.rotors_active) {
        twin[i] = twin[j];
        break;
      }
    }
  }
  return twin;
}

MissionFacts FactsOf(const Mission& m, int free_group) {
  MissionFacts f;
  f.load_twin = LoadTwins(m);
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
    const char* rule = PropFrameRule(m, ctx.prop_offer, f.free_group, f.free_lifts, *ctx.catalog, pi);
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
  for (std::size_t o = 0; o < ctx.options.size(); ++o) f.capacity_edges.push_back(CapacityPieceEdges(ctx, f, o));
  for (std::size_t o = 0; o < ctx.options.size(); ++o) {
    f.key_capacity_edges.push_back(CapacityPieceEdges(ctx, f, o, kKeyCapacityPieces));
  }
  f.refine_capacity_pieces = true;
  return f;
}

// Momentum theory's bound of a propeller segment's terminal power, W, when no stage can create
// energy: N*P_ideal(T, V)/FM_limit(V) + P_avionics (the evaluator's prop_figure_of_merit; V the
// axial inflow with forward-flight tables, else 0, as PropellerPoint judges it; FM_limit of
// mission.h; P_ideal rises with the thrust).
double MomentumPowerW(const Mission& m, const RotorLoad& ld, double diameter_m, bool axial_data) {
  const double v = axial_data ? ld.axial_airspeed_m_s : 0.0;
  const double p_ideal = IdealRotorPowerW(ld.thrust_per_rotor_n, diameter_m, m.rho_kg_m3, v);
  return ld.rotors * p_ideal / FigureOfMeritLimit(m.constraints, v) + m.vehicle.avionics_power_w;
}
// Rule R4 (docs/search.md#r4): every segment draws at least its power bound for at least its
// shortest duration, so the score is at least the assembled bound; pairs best bound first,
// stopping at the first bound not below the N-th best.
// R4: a lower bound of the score of a (motor, propeller, option) pair with an ESC class whose
// drive is lossy or not (DriveIsLossy: only then momentum theory bounds the power drawn),
// given the hover bound's per-rotor electrical power pdc_lb at the lightest mass (R11: a floor
// of it that holds for a class of motors). loads: PairLoads at that mass.
ScoreBoundTerms ScoreLowerBoundTerms(const SearchContext& ctx, const MissionFacts& f, bool lossy, const PropEntry& prop,
                                     const PropModel& model, std::size_t option, PairLoads* loads, double pdc_lb,
                                     bool stretch_only, std::vector<SegmentEnergyFloor>* floors) {
  const BatteryOption& bo = ctx.options[option];
  const Mission& m = *ctx.mission;
  ScoreBoundTerms out;
  out.ocv_integral_v = bo.ocv_integral_v;
  out.t_fixed_s = f.t_fixed_max;
  if (f.hover.empty()) return out;
  auto p_lb_of = [&](std::size_t si) {
    return SegmentPowerLowerBoundW(ctx, f, prop, model, option, loads, si, pdc_lb);
  };
  // The shortest a segment can last (free airspeed: at its top speed).
  auto t_min_of = [&](const Segment& sg) { return SegmentDurationS(sg, sg.airspeed_m_s.hi); };
  if (m.objective.type == ObjectiveType::kMinEnergy) {
    // Per segment the larger of: the hover bound above, and momentum theory. A feasible point
    // has prop power >= P_ideal/max_figure_of_merit (the evaluator's prop_figure_of_merit
    // constraint; P_ideal of model/physics.h per rotor), and PDC >= Pmech when neither the
    // motor nor the ESC can create energy (docs/model.md section 10: KT <= sqrt(27/10)*KE, C0 >= 0,
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
    out.bound = e / 3600.0;
    return out;
  }
  // max_endurance: the other segments' energy, each at least its power bound times its
  // shortest duration and, for the free group's propeller segments at a fixed airspeed when no
  // stage can create energy, momentum theory's N*P_ideal(T, V)/max_figure_of_merit plus the
  // avionics over its duration (the evaluator's prop_figure_of_merit; V the axial inflow with
  // forward-flight tables, else 0, as PropellerPoint judges it; P_ideal rises with the mass).
  const bool table_data = model.data_kind() == PropDataKind::kTables && !prop.j_tables.empty();
  auto e_other_of = [&](std::size_t stretch) {
    double e_other = 0;
    if (floors) floors->clear();
    for (std::size_t si = 0; si < m.segments.size(); ++si) {
      if (si == stretch) continue;
      const Segment& sg = m.segments[si];
      SegmentEnergyFloor x;
      const double p_lb = SegmentPowerLowerBoundW(ctx, f, prop, model, option, loads, si, pdc_lb, &x.rotors);
      x.t_min_s = t_min_of(sg);
      double e_seg = p_lb * x.t_min_s;
      if (lossy && sg.group == f.free_group && sg.type != SegmentType::kShaft &&
          !(sg.type == SegmentType::kCruise && sg.airspeed_m_s.free())) {
        x.momentum_j = loads->PerSegment(si, [&]() {
          const double v = sg.type == SegmentType::kCruise ? sg.airspeed_m_s.lo : 0.0;
          const double p_w = loads->PerLoad(
              si, [&]() { return MomentumPowerW(m, loads->At(si, false, v), prop.diameter_m, table_data); });
          return p_w * SegmentDurationS(sg, v);
        });
        e_seg = std::max(e_seg, x.momentum_j);
      }
      e_other += e_seg;
      if (floors) {
        x.constant_w = p_lb;
        floors->push_back(x);
      }
    }
    return e_other;
  };
  if (f.stretch_is_hover) {
    // Terminal energy = integral of V*I dt <= integral of OCV*I dt = Q*integral of OCV(s) ds
    // over [reserve, 1] (coulomb counting): the energy budget.
    // The stretch holds the hover's thrust throughout, so when no stage can create energy its
    // power is also at least momentum theory's N*P_ideal(T)/max_figure_of_merit + P_avionics
    // (the evaluator's prop_figure_of_merit, as for the other segments; static: V = 0). The
    // one bound of a propeller whose grid is not monotone (no R2 point).
    const std::size_t ist = static_cast<std::size_t>(m.objective.segment_index);
    const double e_other = stretch_only ? 0.0 : e_other_of(ist);
    double p_stretch = SegmentPowerLowerBoundW(ctx, f, prop, model, option, loads, ist, pdc_lb, &out.stretch_rotors);
    if (lossy) p_stretch = std::max(p_stretch, MomentumPowerW(m, loads->At(ist, false, 0.0), prop.diameter_m, false));
    out.budgeted = true;
    out.e_other_j = e_other;
    out.p_stretch_w = p_stretch;
    return out;
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
    double p_stretch = SegmentPowerLowerBoundW(ctx, f, prop, model, option, loads, ist, pdc_lb, &out.stretch_rotors);
    if (lossy) {
      p_stretch = std::max(p_stretch, MomentumPowerW(m, loads->At(ist, false, st.airspeed_m_s.lo), prop.diameter_m, table_data));
    }
    out.budgeted = true;
    out.e_other_j = stretch_only ? 0.0 : e_other_of(ist);
    out.p_stretch_w = p_stretch;
  }
  return out;
}

double OtherEnergyAtLeastJ(const std::vector<SegmentEnergyFloor>& floors, double pdc_lb_w, double avionics_w) {
  double e = 0;
  for (const SegmentEnergyFloor& x : floors) {
    const double p_lb = x.rotors > 0 ? x.rotors * pdc_lb_w + avionics_w : x.constant_w;
    e += std::max(p_lb * x.t_min_s, x.momentum_j);
  }
  return e;
}

double ScoreBoundTerms::StretchPowerAtLeastW(double pdc_lb_w, double avionics_w) const {
  return stretch_rotors > 0 ? std::max(p_stretch_w, stretch_rotors * pdc_lb_w + avionics_w) : p_stretch_w;
}

double ScoreBoundTerms::At(double budget_ah) const {
  return budgeted ? BudgetScore(t_fixed_s, ocv_integral_v * AhToCoulomb(budget_ah), e_other_j, p_stretch_w) : bound;
}

double ScoreLowerBound(const SearchContext& ctx, const MissionFacts& f, bool lossy, const PropEntry& prop,
                       const PropModel& model, std::size_t option, PairLoads* loads, double pdc_lb,
                       double capacity_top_ah) {
  const double budget_ah = capacity_top_ah > 0 ? capacity_top_ah : ctx.options[option].capacity_hi_ah;
  return ScoreLowerBoundTerms(ctx, f, lossy, prop, model, option, loads, pdc_lb).At(budget_ah);
}

// Rule R13 (docs/search.md#r13): R4's budget piece by piece over a capacity range.
std::vector<double> CapacityPieceEdges(const SearchContext& ctx, const MissionFacts& f, std::size_t option,
                                       int pieces) {
  const BatteryOption& bo = ctx.options[option];
  const Mission& m = *ctx.mission;
  std::vector<double> edges;
  if (!(bo.capacity_hi_ah > bo.capacity_lo_ah) || !(bo.capacity_lo_ah > 0) ||
      m.objective.type != ObjectiveType::kMaxEndurance || f.hover.empty()) {
    return edges;
  }
  const double ratio = bo.capacity_hi_ah / bo.capacity_lo_ah;
  edges.push_back(bo.capacity_lo_ah);
  for (int j = 1; j < pieces; ++j) {
    edges.push_back(bo.capacity_lo_ah * std::pow(ratio, double(j) / pieces));
  }
  edges.push_back(bo.capacity_hi_ah);
  return edges;
}

const std::vector<double>& PieceEdges(const SearchContext& ctx, const MissionFacts& f, std::size_t option,
                                      std::vector<double>* scratch, bool keys) {
  const std::vector<std::vector<double>>& kept = keys ? f.key_capacity_edges : f.capacity_edges;
  if (option < kept.size()) return kept[option];
  *scratch = CapacityPieceEdges(ctx, f, option, keys ? kKeyCapacityPieces : kCapacityPieces);
  return *scratch;
}

double PackMassLowerBoundKg(const BatteryOption& bo, double capacity_ah) {
  const double span_ah = bo.capacity_hi_ah - bo.capacity_lo_ah;
  if (!(span_ah > 0) || capacity_ah <= bo.capacity_lo_ah) return bo.mass_lo_kg;
  return bo.mass_lo_kg + (1.0 - 1e-9) * (bo.mass_hi_kg - bo.mass_lo_kg) * (capacity_ah - bo.capacity_lo_ah) / span_ah;
}

// Rule R12 (docs/search.md#r12): a hover below the propeller's data window fails
// prop_below_data; more mass turns the rotor faster (M3).
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

double FixedMassFloorKg(const SearchContext& ctx, std::size_t o) {
  return o < ctx.fixed_mass_floor.size() ? ctx.fixed_mass_floor[o].kg : 0.0;
}

const char* FixedMassFloorRule(const SearchContext& ctx, std::size_t o, double motor_kg, double prop_kg, double esc_kg) {
  if (o >= ctx.fixed_mass_floor.size() || !ctx.fixed_mass_floor[o].rule) return nullptr;
  const double mass_ub_kg = VehicleMassKg(ctx, ctx.options[o].mass_hi_kg, motor_kg, prop_kg, esc_kg);
  return mass_ub_kg < ctx.fixed_mass_floor[o].kg ? ctx.fixed_mass_floor[o].rule : nullptr;
}

const char* FixedMassCeilingRule(const SearchContext& ctx, std::size_t o, double motor_kg, double prop_kg,
                                 double esc_kg) {
  if (o >= ctx.fixed_mass_ceiling.size() || !ctx.fixed_mass_ceiling[o].rule) return nullptr;
  const double mass_lb_kg = VehicleMassKg(ctx, ctx.options[o].mass_lo_kg, motor_kg, prop_kg, esc_kg);
  return mass_lb_kg >= ctx.fixed_mass_ceiling[o].kg ? ctx.fixed_mass_ceiling[o].rule : nullptr;
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

// The hover bound's speed and torque from below (R2): the last grid point whose thrust is at
// most the first hover segment's per-rotor thrust at the mass of `loads` (0, 0 without a
// hover segment, a monotone grid or such a point). Returns the grid index (0 when none).
void HoverGridPointInBracket(const MissionFacts& f, const PropGrid& g, PairLoads* loads, int* lo, int hi,
                             double* omega_lb, double* q_lb) {
  *omega_lb = 0;
  *q_lb = 0;
  if (f.hover.empty() || !g.monotone) {
    *lo = -1;
    return;
  }
  const RotorLoad& load = loads->At(static_cast<std::size_t>(f.hover[0]), false, 0.0);
  // Every grid thrust up to *lo is at or below the load's and every one after hi above it.
  const double* it = std::upper_bound(g.thrust + (*lo + 1), g.thrust + (hi + 1), load.thrust_per_rotor_n);
  *lo = static_cast<int>(it - g.thrust) - 1;
  if (*lo < 0) return;
  *omega_lb = g.omega[*lo];
  *q_lb = g.torque_suffix_min[*lo];
}

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

// Rules R2, R6, R7, R12 (docs/search.md#r2, #r6, #r7, #r12): the hover speed is at least the
// grid speed of the lightest vehicle's thrust (M1, M3); a propeller whose data break momentum
// theory, static-only data in fast axial flow, or a speed outside its rpm limit or data window
// there fails whatever ESC and pack are chosen.
// R2, R6, R7 for one (motor, propeller, option) pair whose propeller passed R0 (counted per
// motor, MotorSetUp): the rule that removes it, or null. Sets omega_lb, q_lb (R2) for the
// hover bound.
// w_nl: the largest no-load speed of the motor's zero-resistance drives at full throttle and
// the option's full-charge voltage (R7; the same for every propeller, computed once per option).
const char* PropRule(const SearchContext& ctx, const MissionFacts& f, double motor_kg, double w_nl, std::size_t pi,
                     std::size_t o, PairLoads* loads, double* omega_lb, double* q_lb, int* lb_idx) {
  const Mission& m = *ctx.mission;
  const MissionConstraints& k = m.constraints;
  const PropEntry& prop = ctx.catalog->props()[pi];
  const PropGrid& g = ctx.grids[pi];
  const BatteryOption& bo = ctx.options[o];
  int raw_idx = -1;
  HoverGridPointInBracket(f, g, loads, &raw_idx, kGrid - 1, omega_lb, q_lb);
  if (lb_idx) *lb_idx = raw_idx;
  const int lb_idx_0 = std::max(0, raw_idx);  // grid index of omega_lb (0 when none)
  if (!f.hover.empty() && g.monotone) {
    // R6: the hover speed lies between omega_lb and the first grid speed whose thrust reaches
    // T_ub (the heaviest the vehicle can be); if the data break momentum theory (figure of
    // merit > the mission's limit) on that whole bracket, every hover point fails
    // prop_figure_of_merit (mission_eval.cc). The 2 % allowance covers the variation between
    // grid points. T_ub >= T_lb (M3) puts hi_idx at or above lb_idx, so when the point at
    // lb_idx keeps the limit the rule cannot fire and T_ub is not needed.
    if (g.fom_ok_next[lb_idx_0] != lb_idx_0) {
      const double mass_ub = VehicleMassKg(ctx, bo.mass_hi_kg, motor_kg, g.mass_kg, ctx.escs.max_mass_kg[o]);
      const RotorLoad load_ub = SegmentRotorLoad(m, m.segments[f.hover[0]], mass_ub, 0.0);
      const double* it_ub = std::lower_bound(g.thrust, g.thrust + kGrid, load_ub.thrust_per_rotor_n);
      const int hi_idx = std::min(static_cast<int>(it_ub - g.thrust), kGrid - 1);
      // Every grid point of [lb_idx, hi_idx] above 1.02 x the limit (fom_ok_next, BuildPropGrids).
      if (it_ub != g.thrust + kGrid && (lb_idx_0 > hi_idx || g.fom_ok_next[lb_idx_0] > hi_idx)) return "prop_figure_of_merit";
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
  if (const PropSpeedLimit lim = PropSpeedLimitOf(m, prop); lim.rule && RadPerSecToRpm(*omega_lb) > lim.rpm) {
    return lim.rule;  // R2
  }
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

// Rule R9 (docs/search.md#r9): the hover throttle at the heaviest vehicle is an upper bound
// (M1-M3); below min_hover_throttle there, the ESC fails that limit for the pair.
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

bool FailsHoverThrottleBound(const SearchContext& ctx, int motor, int prop, int option, const EscEntry& esc) {
  const Mission& m = *ctx.mission;
  const MotorParams mp = ScenarioMotorParams(ctx.catalog->motors()[static_cast<std::size_t>(motor)], m, nullptr, nullptr);
  return HoverThrottleBelowLimit(ctx, FactsOf(m, ctx.free_group), mp, motor, prop, option, esc);
}

}  // namespace dynosize::search_internal
