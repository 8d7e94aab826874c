// R10: a pair with an ESC class bounded segment by segment over its capacity range in pieces
// (docs/search.md#r10).
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
  // The cell's end thrusts are the grid's (prop_grids.cc: the same evaluation).
  PropEvaluation ev;
  const double lo = SpeedFromBelowInCell(model, rho, thrust_n, sgrid.v_m_s, g.omega[idx], sgrid.thrust[idx],
                                         g.omega[idx + 1], sgrid.thrust[idx + 1], refine_steps, &ev);
  if (lo == g.omega[idx]) return;
  AdjustPropEvaluation(g.adjustment, diameter_m, &ev);
  *omega = lo;
  *torque = std::min(ev.torque_nm, sgrid.torque_suffix_min[idx + 1]);
}

// Rule R10 (docs/search.md#r10): with the class's zero-resistance drive and the lightest
// mass, each segment's speed, torque, power, charge and terminal voltage are bounded from
// below (M1-M3); a piece that breaks a limit holds no feasible point.
// R10's terms of a piece that depend only on its lightest vehicle (the pack at C_a): per
// segment its power bound and, with a grid point, its speed and torque from below; and the
// first segment (in mission order) whose speed or drive limit refuses the piece at that mass.
// A piece [C_a, C_b] and its left half [C_a, (C_a + C_b)/2] share them.
struct PieceMass {
  struct Seg {
    double p_w = 0, w = 0, q = 0;
    bool point = false;
  };
  std::vector<Seg> segs;
  std::size_t refused_at = 0;  // segs.size() when no segment is refused
  const char* rule = nullptr;
};

// PieceMass for ESCs of at least esc_mass_kg and the pack at cap_a_ah.
PieceMass PieceMassAt(const SearchContext& ctx, const MissionFacts& f, const MotorParams& mp, const Drive& ideal,
                      double t_max, int motor, int prop, int option, double esc_mass_kg, double cap_a_ah,
                      int refine_steps) {
  const Mission& m = *ctx.mission;
  const MissionConstraints& k = m.constraints;
  const BatteryOption& bo = ctx.options[static_cast<std::size_t>(option)];
  const PropEntry& pe = ctx.catalog->props()[static_cast<std::size_t>(prop)];
  const PropGrid& g = ctx.grids[static_cast<std::size_t>(prop)];
  const MotorEntry& mo = ctx.catalog->motors()[static_cast<std::size_t>(motor)];
  // The pack at C_a (its mass rises with the capacity: the increment shrunk by 1e-9 against
  // rounding, so that it stays a lower bound).
  const double span_ah = bo.capacity_hi_ah - bo.capacity_lo_ah;
  const double pack_kg = span_ah > 0 ? bo.mass_lo_kg + (1.0 - 1e-9) * (bo.mass_hi_kg - bo.mass_lo_kg) *
                                                           (cap_a_ah - bo.capacity_lo_ah) / span_ah
                                     : bo.mass_lo_kg;
  const double mass_lb = std::max({VehicleMassKg(ctx, pack_kg, *mo.mass_kg, g.mass_kg, esc_mass_kg),
                                   WindowMassFloorKg(ctx, f, prop), FixedMassFloorKg(ctx, static_cast<std::size_t>(option))});
  const bool lossy = DriveIsLossy(mp, ideal.esc().c1, ideal.esc().c0);
  const bool axial_data = ctx.models[static_cast<std::size_t>(prop)]->data_kind() == PropDataKind::kTables &&
                          !pe.j_tables.empty();
  const double margin = 1.0 - k.current_margin;
  PieceMass out;
  out.segs.resize(m.segments.size());
  out.refused_at = m.segments.size();
  for (std::size_t si = 0; si < m.segments.size(); ++si) {
    const Segment& sg = m.segments[si];
    PieceMass::Seg& x = out.segs[si];
    x.p_w = m.vehicle.avionics_power_w;
    if (sg.group != f.free_group) {
      if (!ctx.fixed_power_lb_w.empty()) x.p_w = FixedPowerLowerBoundW(ctx, static_cast<std::size_t>(option), si, mass_lb);
      continue;
    }
    if (sg.type == SegmentType::kShaft || (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free())) continue;
    const std::size_t twin = si < f.load_twin.size() ? f.load_twin[si] : si;
    if (twin != si && out.refused_at == m.segments.size()) {
      // The same load as an earlier segment (LoadTwins): the same speed, torque, limits and power.
      x = out.segs[twin];
      continue;
    }
    const RotorLoad ld = SegmentRotorLoad(m, sg, mass_lb, sg.type == SegmentType::kCruise ? sg.airspeed_m_s.lo : 0.0);
    if (const SegmentGrid sgrid = GridOf(g, axial_data, sg, ld); sgrid.thrust) {
      SpeedTorqueFromBelow(g, sgrid, *ctx.models[static_cast<std::size_t>(prop)], pe.diameter_m, m.rho_kg_m3,
                           ld.thrust_per_rotor_n, refine_steps, &x.w, &x.q);
      x.point = true;
      auto refuse = [&](const char* rule) {
        out.refused_at = si;
        out.rule = rule;
        return out;
      };
      // R12 (the window's top): the segment's speed is at least w.
      if (k.prop_above_data_factor > 0 &&
          RadPerSecToRpm(x.w) > k.prop_above_data_factor * ctx.models[static_cast<std::size_t>(prop)]->valid_range().rpm_hi) {
        return refuse("prop_above_data");
      }
      const Drive::InverseCurrents hi = ideal.InverseLight(bo.v_full, x.q, x.w);
      if (hi.throttle > t_max) return refuse("throttle");
      if (hi.irms_a > mp.max_current_a * margin) return refuse("motor_current");
      if (k.enforce_motor_power && ideal.InverseAcPower(bo.v_full, hi, x.q, x.w) > mp.max_power_w) {
        return refuse("motor_power");
      }
      const double pdc = std::max(0.0, std::min(bo.v_full * hi.idc_a, bo.v_cut * ideal.InverseLight(bo.v_cut, x.q, x.w).idc_a));
      x.p_w = ld.rotors * pdc + m.vehicle.avionics_power_w;
    }
    if (lossy) x.p_w = std::max(x.p_w, MomentumPowerW(m, ld, pe.diameter_m, axial_data));  // as R4
  }
  return out;
}

// R10 for one pair and ESC class with ESCs of at least esc_mass_kg and capacities in
// [cap_a_ah, cap_b_ah] (see the rule), given the piece's PieceMass at cap_a_ah: a lower bound
// of the score (-kInf when none applies), or kInf with *rule set when no such combination can
// fly the pair.
double SegmentwiseBoundAt(const SearchContext& ctx, const MissionFacts& f, const Drive& ideal, double t_max,
                          int motor, int prop, int option, const PieceMass& at_a, double cap_b_ah, const char** rule) {
  const Mission& m = *ctx.mission;
  *rule = nullptr;
  const BatteryOption& bo = ctx.options[static_cast<std::size_t>(option)];
  const PropGrid& g = ctx.grids[static_cast<std::size_t>(prop)];
  const MotorEntry& mo = ctx.catalog->motors()[static_cast<std::size_t>(motor)];
  // The charge, resistance and energy budget of C_b (PackAt).
  const double span_ah = bo.capacity_hi_ah - bo.capacity_lo_ah;
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
  const double q_c = AhToCoulomb(cap_b_ah);
  const int stretch = m.objective.type == ObjectiveType::kMaxEndurance ? m.objective.segment_index : -1;
  double charge_c = 0, e_other = 0, p_stretch = 0;
  for (std::size_t si = 0; si < m.segments.size(); ++si) {
    if (si == at_a.refused_at) {  // the speed or drive limits at the lightest mass
      *rule = at_a.rule;
      return kInf;
    }
    const Segment& sg = m.segments[si];
    const PieceMass::Seg& x = at_a.segs[si];
    const double t_min = static_cast<int>(si) == stretch ? 0.0 : SegmentDurationS(sg, sg.airspeed_m_s.hi);
    charge_c += kChargeAllowance * x.p_w * t_min / bo.v_full;
    const double soc = 1.0 - charge_c / q_c;
    if (soc < m.battery.reserve_soc) { *rule = "reserve_soc"; return kInf; }
    if (x.point) {
      const double v_ub = bo.OcvV(soc) - x.p_w / bo.v_full * ri_ohm;
      if (!(v_ub > 0) || ideal.InverseLight(v_ub, x.q, x.w).throttle > t_max) { *rule = "throttle"; return kInf; }
    }
    if (static_cast<int>(si) == stretch) {
      p_stretch = x.p_w;
    } else {
      e_other += x.p_w * t_min;
    }
  }
  if (m.objective.type == ObjectiveType::kMinEnergy) return e_other / 3600.0;
  if (stretch < 0) return -kInf;
  const Segment& st = m.segments[static_cast<std::size_t>(stretch)];
  if (st.type == SegmentType::kShaft || (st.type == SegmentType::kCruise && st.airspeed_m_s.free())) return -kInf;
  const double e_max = bo.ocv_integral_v * AhToCoulomb(cap_b_ah);
  return BudgetScore(f.t_fixed_max, e_max, e_other, p_stretch);
}

}  // namespace

// R10 over the option's capacity range in pieces (one without a range): the least bound over
// the pieces that may be feasible; kInf with *rule (the first refusal's) when none is. While
// the least piece bound is below `threshold`, that piece is tightened: first its speeds are
// bisected within their grid cells (kRefineSteps), then it is halved (each half's bound is
// valid on its own), up to kMaxSplits steps and down to 1/1024 of the range: the bound
// tightens only as far as it takes to prove "cannot beat the threshold".
double SegmentwiseBoundPieces(const SearchContext& ctx, const MissionFacts& f, const MotorParams& mp,
                              const Drive& ideal, double t_max, int motor, int prop, int option, double esc_mass_kg,
                              double threshold, const char** rule, bool stop_when_unprovable) {
  // The first pieces: with max_endurance 4 (each piece's bound takes the budget of its top, and
  // 4 pieces prove more pairs before any split: docs/search.md#r10), else 2 (min_energy's bound
  // does not read the budget: the lowest piece is the least).
  constexpr int kMaxSplits = 24, kRefineSteps = 6;
  const int first_pieces = ctx.mission->objective.type == ObjectiveType::kMaxEndurance ? 4 : 2;
  const BatteryOption& bo = ctx.options[static_cast<std::size_t>(option)];
  const double lo = bo.capacity_lo_ah, hi = bo.capacity_hi_ah;
  const bool range = hi > lo;
  const char* first_rule = nullptr;
  struct Piece {
    double a, b, bound;
    bool refined;
    std::size_t mass;  // its PieceMass in `masses`
  };
  std::vector<PieceMass> masses;
  // A piece [a, b]; `mass` its PieceMass when known (a left half's is its whole's), else the size
  // of `masses`.
  auto piece = [&](double a, double b, bool refined, std::size_t mass) {
    if (mass == masses.size()) {
      masses.push_back(PieceMassAt(ctx, f, mp, ideal, t_max, motor, prop, option, esc_mass_kg, a,
                                   refined ? kRefineSteps : 0));
    }
    const char* r = nullptr;
    const double x = SegmentwiseBoundAt(ctx, f, ideal, t_max, motor, prop, option, masses[mass], b, &r);
    if (r && !first_rule) first_rule = r;
    return Piece{a, b, r ? kInf : x, refined, mass};
  };
  std::vector<Piece> pieces;
  const int n = range ? first_pieces : 1;
  for (int j = 0; j < n; ++j) {
    pieces.push_back(range ? piece(lo + (hi - lo) * j / n, lo + (hi - lo) * (j + 1) / n, false, masses.size())
                           : piece(lo, hi, false, masses.size()));
  }
  // Whether no splitting can lift the least bound to the threshold, read on a refined piece [a, b]
  // just given its own lightest vehicle: its bound at the one capacity a. Every later piece that
  // starts at a shares that vehicle (a left half keeps its whole's) with a budget of at least
  // a, and its bound is then no higher (SegmentwiseBoundAt falls as C_b rises: more charge and
  // energy, less resistance, a heavier vehicle for R12's bottom); one such piece is always left,
  // so the splitting would end below the threshold anyway.
  auto unprovable = [&](const Piece& x) {
    if (!stop_when_unprovable || !(x.bound < threshold)) return false;
    const char* r = nullptr;
    const double at_a = SegmentwiseBoundAt(ctx, f, ideal, t_max, motor, prop, option, masses[x.mass], x.a, &r);
    return !r && at_a < threshold;
  };
  for (int step = 0; step < kMaxSplits; ++step) {
    auto least = std::min_element(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) { return x.bound < y.bound; });
    if (!(least->bound < threshold)) break;
    const Piece whole = *least;
    if (!whole.refined) {
      *least = piece(whole.a, whole.b, true, masses.size());
      if (unprovable(*least)) break;
      continue;
    }
    if (!range || whole.b - whole.a < (hi - lo) / 1024) break;
    const double mid = 0.5 * (whole.a + whole.b);
    *least = piece(whole.a, mid, true, whole.mass);  // the same lightest vehicle
    pieces.push_back(piece(mid, whole.b, true, masses.size()));
    if (unprovable(pieces.back())) break;
  }
  double best = kInf;
  for (const Piece& x : pieces) best = std::min(best, x.bound);
  *rule = best == kInf ? first_rule : nullptr;
  return best;
}

double SegmentwiseBound(const SearchContext& ctx, int motor, int prop, int option, int esc_class, double esc_mass_kg,
                        double threshold, const char** rule, bool stop_when_unprovable) {
  const Mission& m = *ctx.mission;
  const MotorParams mp = ScenarioMotorParams(ctx.catalog->motors()[static_cast<std::size_t>(motor)], m, nullptr, nullptr);
  const EscClass& cls = ctx.escs.classes[static_cast<std::size_t>(esc_class)];
  const EscParams ideal = ZeroResistanceEsc(cls);
  const MissionFacts f = FactsOf(m, ctx.free_group);
  const double t_max = ThrottleLimit(m.constraints, cls.tr_sat);
  return SegmentwiseBoundPieces(ctx, f, mp, Drive(mp, ideal), t_max, motor, prop, option, esc_mass_kg, threshold, rule,
                                stop_when_unprovable);
}

}  // namespace dynosize::search_internal
