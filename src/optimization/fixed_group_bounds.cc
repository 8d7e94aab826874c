// G1 (docs/search.md#g1): lower bounds of the power a fixed propulsion group draws, tabulated
// on a mass grid, and the power bound of a wing-borne cruise with a free airspeed.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "mission/flight.h"
#include "model/physics.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "optimization/prop_bounds.h"
#include "optimization/search_stages.h"

namespace dynosize::search_internal {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// R2, R12's top and R3 over a fixed group's free-airspeed cruise sg at every vehicle of at least
// mass_min_kg (FreeCruiseRangeRule with the group's own drive, the samples taken at that mass:
// a bound for every heavier vehicle, M1, M3): the rule every airspeed breaks, or null.
const char* FixedCruiseRangeRule(const Mission& m, const Segment& sg, const GroupParts& parts, const PropModel& model,
                                  const BatteryOption& bo, double mass_min_kg) {
  const MotorParams mp = ScenarioMotorParams(*parts.motor, m);
  const EscParams ep = ScenarioEscParams(*parts.esc, m.objective.ranking);
  const CruisePropBound pb{parts.prop, &model, PropAdjustmentFor(*parts.prop, m.objective.ranking),
                           DriveIsLossy(mp, ep.c1, ep.c0)};
  const FreeCruiseSamples s = SampleFreeCruise(m, sg, pb, mass_min_kg, true);
  return FreeCruiseRangeRule(m.constraints, Drive(mp, ep), s, bo.v_full, ThrottleLimit(m.constraints, ep.tr_sat),
                              ep.max_current_a);
}

// R7 and R6 as mass floors (mass_floors.h) of the fixed groups' segments, each on its group's
// own propeller, scanned up from mass_min_kg: the highest (a feasible vehicle passes them all).
// A free-airspeed cruise that breaks R2, R12's top or R3 at every mass (FixedCruiseRangeRule) is
// a floor beyond any vehicle.
MassFloor FixedGroupsMassFloor(const SearchContext& ctx, const BatteryOption& bo, double mass_min_kg) {
  const Mission& m = *ctx.mission;
  const auto& props = ctx.catalog->props();
  MassFloor out;
  for (const Segment& sg : m.segments) {
    if (sg.group == ctx.free_group) continue;
    const GroupParts& parts = ctx.fixed_parts[static_cast<std::size_t>(sg.group)];
    if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free() && sg.lift_to_drag > 0) {
      const PropModel& model = *ctx.fixed_models[static_cast<std::size_t>(sg.group)];
      if (const char* rule = FixedCruiseRangeRule(m, sg, parts, model, bo, mass_min_kg)) return MassFloor{kInf, rule};
    }
    // The grids are the catalog's: a fixed propeller outside it gets no floor (M1 unchecked).
    const std::ptrdiff_t pi = parts.prop - props.data();
    if (pi < 0 || pi >= static_cast<std::ptrdiff_t>(props.size())) continue;
    const MassFloor f = SegmentMassFloorKg(m, sg, *parts.prop, *ctx.fixed_models[static_cast<std::size_t>(sg.group)],
                                           ctx.grids[static_cast<std::size_t>(pi)].monotone, mass_min_kg);
    if (f.kg > out.kg) out = f;
  }
  return out;
}

// The heaviest the vehicle may be for the fixed groups' free-airspeed cruises to pass R2, R12's
// top and R3 (FixedCruiseRangeRule; docs/search.md#g1-torque-floor): the rule read at a mass
// holds for every heavier vehicle, so the rule that fails at some mass fails at every heavier
// one. Bisection on the mass ratio from mass_min_kg (which passes) up to
// kCeilingSpan times it: the ceiling is a mass at which the rule fails, at most kCeilingRel
// above the heaviest that passes. {+inf, null} when none fails within the span.
MassFloor FixedGroupsMassCeiling(const SearchContext& ctx, const BatteryOption& bo, double mass_min_kg) {
  constexpr double kCeilingSpan = 64.0;  // a vehicle 64 times the lightest: beyond any pack
  constexpr double kCeilingRel = 1e-4;   // the bisection's resolution, of the mass
  const Mission& m = *ctx.mission;
  MassFloor out{kInf, nullptr};
  for (const Segment& sg : m.segments) {
    if (sg.group == ctx.free_group || sg.type != SegmentType::kCruise || !sg.airspeed_m_s.free() ||
        !(sg.lift_to_drag > 0)) {
      continue;
    }
    const GroupParts& parts = ctx.fixed_parts[static_cast<std::size_t>(sg.group)];
    const PropModel& model = *ctx.fixed_models[static_cast<std::size_t>(sg.group)];
    const double hi_kg = std::min(out.kg, kCeilingSpan * mass_min_kg);
    const char* rule = FixedCruiseRangeRule(m, sg, parts, model, bo, hi_kg);
    if (!rule) continue;
    double lo = mass_min_kg, hi = hi_kg;  // lo passes, hi fails
    while (hi - lo > kCeilingRel * lo) {
      const double mid = std::sqrt(lo * hi);
      if (const char* r = FixedCruiseRangeRule(m, sg, parts, model, bo, mid)) {
        hi = mid;
        rule = r;
      } else {
        lo = mid;
      }
    }
    out = MassFloor{hi, rule};
  }
  return out;
}

}  // namespace

namespace {

// DriveRule's checks in their order on a point's throttle, Irms and PAC (read only when the
// mission enforces the motor's power rating).
template <class PacW>
const char* DriveRuleOf(const MissionConstraints& k, const MotorParams& mp, double throttle, double irms_a,
                        const PacW& pac_w, double tr_max, double esc_max_current_a) {
  const double margin = 1.0 - k.current_margin;
  if (throttle > tr_max) return "throttle";
  if (irms_a > mp.max_current_a * margin) return "motor_current";
  if (k.enforce_motor_power && pac_w() > mp.max_power_w) return "motor_power";
  if (irms_a > esc_max_current_a * margin) return "esc_current";
  return nullptr;
}

}  // namespace

const char* DriveRule(const MissionConstraints& k, const MotorParams& mp, const OperatingPoint& hi, double tr_max,
                      double esc_max_current_a) {
  return DriveRuleOf(k, mp, hi.throttle, hi.irms_a, [&] { return hi.pac_w; }, tr_max, esc_max_current_a);
}

const char* DriveRule(const MissionConstraints& k, const MotorParams& mp, const Drive& drive, double vdc_v,
                      const Drive::InverseCurrents& hi, double torque_nm, double omega_rad_s, double tr_max,
                      double esc_max_current_a) {
  return DriveRuleOf(
      k, mp, hi.throttle, hi.irms_a, [&] { return drive.InverseAcPower(vdc_v, hi, torque_nm, omega_rad_s); }, tr_max,
      esc_max_current_a);
}

const char* FreeCruiseRangeRule(const MissionConstraints& k, const Drive& drive, const FreeCruiseSamples& s,
                                double v_full_v, double tr_max, double esc_max_current_a, double* irms_lb) {
  double q = s.torque_floor_nm, w = s.omega_floor_rad_s;
  if (s.points && s.point_rises) {
    q = std::max(q, s.torque[0]);
    w = std::max(w, s.omega[0]);
  }
  if (w > s.omega_ub_rad_s) return s.omega_ub_rule;  // R2, R12's top
  if (!(q > 0) && !(w > 0)) return nullptr;
  const OperatingPoint lo = drive.Inverse(v_full_v, q, w);
  if (irms_lb) *irms_lb = std::max(*irms_lb, lo.irms_a);
  return DriveRule(k, drive.motor(), lo, tr_max, esc_max_current_a);
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

// Rule G1 (docs/search.md#g1): a fixed group's segment draws at least its own drive's PDC at
// the lightest vehicle mass (M1, M3), tabulated on a mass grid read at or below a pair's mass.
void FixedGroupPowerBounds(SearchContext* ctx) {
  const Mission& m = *ctx->mission;
  ctx->fixed_power_lb_w.clear();
  ctx->fixed_power_mass_kg.clear();
  ctx->fixed_mass_floor.clear();
  ctx->fixed_mass_ceiling.clear();
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
    ctx->fixed_mass_floor.push_back(FixedGroupsMassFloor(*ctx, bo, mass_min));
    // (A floor beyond any vehicle refuses everything already.)
    ctx->fixed_mass_ceiling.push_back(ctx->fixed_mass_floor.back().kg < kInf ? FixedGroupsMassCeiling(*ctx, bo, mass_min)
                                                                             : MassFloor{kInf, nullptr});
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
        const double pdc = std::min(d.InversePdcW(bo.v_full, q, lo), d.InversePdcW(bo.v_cut, q, lo));
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

}  // namespace dynosize::search_internal
