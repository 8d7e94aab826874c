// The designer's view of a mission evaluator's result: the lift rotors at full throttle and in
// hover at a state of charge (also the thrust-to-weight check and its mass ceiling), the summary
// a designer compares with eCalc (Summarize) and the warnings (AddWarnings).
// (MissionEvaluator's other files: mission_eval.cc.)
#include <algorithm>
#include <cmath>
#include <string>

#include "common/text_format.h"
#include "common/units.h"
#include "mission/flight.h"
#include "model/physics.h"
#include "optimization/mission_eval.h"
#include "optimization/mission_eval_internal.h"
#include "optimization/prop_speed.h"

namespace dynosize {


bool MissionEvaluator::FullThrottleAt(const BatteryPack& pack, double soc, FullThrottle* f) const {
  return FullThrottleFrom(pack.OcvV(soc), pack.ri_ohm(), f);
}

bool MissionEvaluator::FullThrottleFrom(double ocv, double r_pack, FullThrottle* f) const {
  const double rho = m_.rho_kg_m3;
  // The drive's current rating (no margin): a motor or ESC is not asked for more for long,
  // whatever the throttle could give.
  const GroupDrive& gd = groups_[lift_group_];
  const Drive& drive = gd.drive;
  const PropModel& prop = *gd.prop;
  // The static propeller of the mission's data scenario, as Run flies it (credibility.h).
  auto prop_at = [&](double w) {
    PropEvaluation e = prop.Evaluate(w, rho, 0.0);
    AdjustPropEvaluation(gd.prop_adj, gd.parts.prop->diameter_m, &e);
    return e;
  };
  const double i_cap = std::min(gd.drive.motor().max_current_a, gd.drive.esc().max_current_a);
  // Illinois regula falsi for the sign change of h on [a, b] (fa = h(a) > 0 > fb = h(b)).
  auto root_in = [](const auto& h, double a, double b, double fa, double fb) {
    int side = 0;
    for (int it = 0; it < 100 && b - a > 1e-10 * b; ++it) {
      double c = (a * fb - b * fa) / (fb - fa);
      if (!(c > a && c < b)) c = 0.5 * (a + b);
      const double fc = h(c);
      if (fc > 0) {
        a = c; fa = fc;
        if (side == 1) fb *= 0.5;
        side = 1;
      } else {
        b = c; fb = fc;
        if (side == -1) fa *= 0.5;
        side = -1;
        if (fc == 0) a = c;
      }
    }
    return 0.5 * (a + b);
  };
  // The root on [lo, hi] (h(lo) > 0 > h(hi)), first tried within 0.1 % of a guess (the
  // previous sag iteration's root: the voltage moves little between them), which brackets it
  // in two evaluations instead of the whole range's ten or more.
  auto root_near = [&](const auto& h, double guess, double lo, double hi) {
    if (guess > lo && guess < hi) {
      const double a = std::max(lo, guess * (1.0 - 1e-3)), b = std::min(hi, guess * (1.0 + 1e-3));
      if (const double fa = h(a); fa > 0) {
        if (const double fb = h(b); fb < 0) return root_in(h, a, b, fa, fb);
      }
    }
    return root_in(h, lo, hi, h(lo), h(hi));
  };
  double v = ocv;
  OperatingPoint op;
  PropEvaluation ev;
  f->current_limited = false;
  double w_full = 0.0, w_capped = 0.0;  // the previous sag iteration's roots (0: none yet)
  // The sag's fixed point v = G(v) (G: the pack's terminal voltage at the drive's power at v),
  // found as the root of G(v) - v by secant steps once two iterates are known (the plain
  // iteration v <- G(v) converges linearly, in about nine steps); a secant step outside
  // (0, OCV] falls back to the plain one. The same stopping rule: |G(v) - v| < 1e-9 OCV.
  double v_prev = 0.0, d_prev = 0.0;  // the previous iterate and its G(v) - v (none: v_prev 0)
  for (int outer = 0; outer < 40; ++outer) {
    // The speed where the motor's full-throttle torque (falling with speed, eqs 42, 48) meets
    // the propeller's static torque (rising, M1 of search.cc).
    const double w_nl = drive.NoLoadSpeed(v, 1.0);
    if (!(w_nl > 0.0)) return false;
    auto g = [&](double w) { return drive.AtSpeed(v, 1.0, w).torque_nm - prop_at(w).torque_nm; };
    if (!(g(0.0) > 0.0) || !(g(w_nl) < 0.0)) return false;
    double w = w_full = root_near(g, w_full, 0.0, w_nl);
    op = drive.AtSpeed(v, 1.0, w);
    f->current_limited = std::max(op.idc_a, op.irms_a) > i_cap;
    if (f->current_limited) {
      // Along the propeller's curve the current rises with speed (M1, M2 of search.cc): the
      // speed where max(IDC, Irms) reaches the rating.
      auto over = [&](double x) {
        const Drive::InverseCurrents p = drive.InverseLight(v, prop_at(x).torque_nm, x);  // Inverse's, bit for bit
        return i_cap - std::max(p.idc_a, p.irms_a);
      };
      if (over(0.0) > 0.0) w = w_capped = root_near(over, w_capped, 0.0, w);
      op = drive.Inverse(v, prop_at(w).torque_nm, w);
    }
    ev = prop_at(w);
    // The pack at that power: the upper root of V^2 - OCV*V + R*P = 0 (as in Run); past the
    // pack's maximum power (no root) the voltage is held at OCV/2, where the power peaks.
    const double p_w = lift_rotors_ * op.idc_a * v + m_.vehicle.avionics_power_w;
    const double disc = ocv * ocv - 4.0 * r_pack * p_w;
    const double next = disc >= 0.0 ? 0.5 * (ocv + std::sqrt(disc)) : 0.5 * ocv;
    const double d = next - v;
    if (std::fabs(d) < 1e-9 * ocv) {
      v = next;
      break;
    }
    double step = next;
    if (v_prev > 0 && d != d_prev) {
      const double secant = v - d * (v - v_prev) / (d - d_prev);
      if (secant > 0 && secant <= ocv) step = secant;
    }
    v_prev = v;
    d_prev = d;
    v = step;
  }
  const double coax = m_.vehicle.coaxial ? std::cbrt(kCoaxialInducedPowerFactor * kCoaxialInducedPowerFactor) : 1.0;
  f->thrust_per_rotor_n = ev.thrust_n / coax;  // flight.h: a coaxial rotor's isolated-data equivalent
  f->pmech_w = op.pmech_w;
  f->vdc_v = v;
  f->battery_current_a = lift_rotors_ * op.idc_a + m_.vehicle.avionics_power_w / v;
  return std::isfinite(f->thrust_per_rotor_n) && f->thrust_per_rotor_n > 0;
}

bool MissionEvaluator::HoverAt(const BatteryPack& pack, double soc, double mass_kg, OperatingPoint* op,
                               double* battery_current_a, double* shaft_w) const {
  const Drive& drive = groups_[lift_group_].drive;
  const PropModel& prop = *groups_[lift_group_].prop;
  Segment hover;
  hover.type = SegmentType::kHover;
  hover.group = lift_group_;
  hover.rotors_active = lift_rotors_;
  const RotorLoad load = SegmentRotorLoad(m_, hover, mass_kg, 0.0);
  const double ocv = pack.OcvV(soc);
  double omega = 0;
  PropEvaluation ev;
  if (!PropSpeedForThrust(prop, load.thrust_per_rotor_n, m_.rho_kg_m3, 0.0,
                          4.0 * std::max(drive.NoLoadSpeed(ocv, 1.0), 1.0), &omega, &ev)) {
    return false;
  }
  AdjustPropEvaluation(groups_[lift_group_].prop_adj, groups_[lift_group_].parts.prop->diameter_m, &ev);
  double v = ocv;
  for (int it = 0; it < 40; ++it) {
    *op = drive.Inverse(v, ev.torque_nm, omega);
    const double p_w = lift_rotors_ * op->idc_a * v + m_.vehicle.avionics_power_w;
    const double disc = ocv * ocv - 4.0 * pack.ri_ohm() * p_w;
    if (!(disc >= 0.0)) return false;
    const double next = 0.5 * (ocv + std::sqrt(disc));
    const bool done = std::fabs(next - v) < 1e-10 * ocv;
    v = next;
    if (done) break;
  }
  *op = drive.Inverse(v, ev.torque_nm, omega);
  *battery_current_a = lift_rotors_ * op->idc_a + m_.vehicle.avionics_power_w / v;
  *shaft_w = ev.power_w;
  return true;
}

void MissionEvaluator::Summarize(MissionResult* r) const {
  DesignSummary& d = r->summary;
  d = DesignSummary{};
  for (const SegmentResult& s : r->segments) d.winding_temp_max_c = std::max(d.winding_temp_max_c, s.winding_temp_c);
  if (lift_rotors_ <= 0 || r->capacity_ah <= 0 || r->total_mass_kg <= 0) return;
  const BatteryPack pack(PackAt(r->capacity_ah));
  constexpr double kMidSoc = 0.5;
  OperatingPoint hover;
  double shaft_hover_w = 0;
  FullThrottle ft;
  if (!HoverAt(pack, kMidSoc, r->total_mass_kg, &hover, &d.hover_battery_current_a, &shaft_hover_w) ||
      !FullThrottleAt(pack, kMidSoc, &ft)) {
    return;
  }
  if (r->thrust_to_weight == 0.0) {  // not checked by the mission: report it all the same
    FullThrottle low;
    if (FullThrottleAt(pack, r->final_soc, &low)) {
      r->thrust_to_weight = lift_rotors_ * low.thrust_per_rotor_n / (r->total_mass_kg * kStandardGravity);
    }
  }
  const double q_above_reserve_c = AhToCoulomb(pack.capacity_ah()) * (1.0 - m_.battery.reserve_soc);
  d.valid = true;
  d.hover_throttle = hover.throttle;
  d.hover_endurance_s = q_above_reserve_c / d.hover_battery_current_a;
  d.full_throttle_battery_current_a = ft.battery_current_a;
  d.full_throttle_endurance_s = q_above_reserve_c / ft.battery_current_a;
  d.reserve_hover_s = AhToCoulomb(pack.capacity_ah()) * std::max(0.0, r->final_soc) / d.hover_battery_current_a;
  d.full_throttle_thrust_n = lift_rotors_ * ft.thrust_per_rotor_n;
  d.full_throttle_current_limited = ft.current_limited;
  d.can_hover = hover.throttle <= 1.0 && d.full_throttle_thrust_n >= r->total_mass_kg * kStandardGravity;
  // The steepest steady climb at the full-throttle shaft power: momentum theory in axial climb
  // (physics.h: P_ideal = T*(Vc/2 + sqrt(Vc^2/4 + T/(2*rho*A))), Leishman sec. 2.7) with the
  // thrust of a climb segment (weight plus body drag at Vc, flight.h) and the hover's figure of
  // merit held: the rate where P_ideal/FM_hover reaches the available shaft power.
  Segment climb;
  climb.type = SegmentType::kClimb;
  climb.group = lift_group_;
  climb.rotors_active = lift_rotors_;
  const double d_m = groups_[lift_group_].parts.prop->diameter_m;
  climb.climb_rate_m_s = 0.0;
  const double fom_hover =
      FigureOfMerit(SegmentRotorLoad(m_, climb, r->total_mass_kg, 0.0).thrust_per_rotor_n, shaft_hover_w, d_m, m_.rho_kg_m3);
  auto shortfall = [&](double vc) {  // available minus needed shaft power per rotor, W
    climb.climb_rate_m_s = vc;
    const RotorLoad ld = SegmentRotorLoad(m_, climb, r->total_mass_kg, 0.0);
    return ft.pmech_w - IdealRotorPowerW(ld.thrust_per_rotor_n, d_m, m_.rho_kg_m3, vc) / fom_hover;
  };
  if (fom_hover > 0 && shortfall(0.0) > 0) {
    double lo = 0.0, hi = 1.0;
    while (shortfall(hi) > 0 && hi < 1e3) hi *= 2;
    for (int i = 0; i < 60; ++i) (shortfall(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
    d.max_climb_rate_m_s = lo;
  }
}

void MissionEvaluator::AddWarnings(MissionResult* r) const {
  FillPropNotes(r);
  r->assumed = assumed_;
  for (const Violation& v : r->violations) {
    if (v.constraint == "max_throttle") {
      r->warnings.push_back("segment '" + v.segment + "': throttle " + SignificantText(100 * v.value, 3) +
                            " % above the " + SignificantText(100 * v.limit, 3) +
                            " % limit (no control authority left)");
    }
  }
  for (const SegmentResult& s : r->segments) {
    const GroupDrive& gd = groups_[s.group];
    const MotorParams& mp = gd.drive.motor();  // the scenario's (credibility.h)
    const EscParams& ep = gd.drive.esc();
    const Drive& drive = gd.drive;
    const OperatingPoint& p = s.point;
    const double i = std::max(p.idc_a, p.irms_a);
    auto near = [&](const char* what, double rating) {
      if (std::isfinite(rating) && i > 0.8 * rating && i <= rating) {
        r->warnings.push_back("segment '" + s.name + "': current " + SignificantText(i, 3) + " A is " +
                              SignificantText(100 * i / rating, 3) + " % of the " + what + " rating " +
                              SignificantText(rating, 3) + " A");
      }
    };
    near("motor", mp.max_current_a);
    near("ESC", ep.max_current_a);
    if (s.throttle_max > ep.tr_sat) {
      r->warnings.push_back("segment '" + s.name + "': ESC in saturation (throttle up to " +
                            SignificantText(100 * s.throttle_max, 3) + " % > knee " + SignificantText(100 * ep.tr_sat, 3) +
                            " %): the speed per throttle step falls");
    }
    if (s.type != SegmentType::kShaft && p.throttle > 0 && p.throttle <= 1) {
      // On the segment's throttle line the efficiency peaks at MaxEfficiencySpeed (eq 14
      // analogue); running well above that speed means a light load for this motor.
      const double w_opt = drive.MaxEfficiencySpeed(p.vdc_v, p.throttle);
      const OperatingPoint best = drive.AtSpeed(p.vdc_v, p.throttle, w_opt);
      if (p.omega_rad_s > w_opt && p.eta_system < best.eta_system - 0.10) {
        r->warnings.push_back("segment '" + s.name + "': motor running below the current of "
                              "optimal efficiency (" + SignificantText(p.irms_a, 3) + " A vs " +
                              SignificantText(best.irms_a, 3) + " A, system efficiency " +
                              SignificantText(100 * p.eta_system, 3) + " % vs " + SignificantText(100 * best.eta_system, 3) +
                              " %): a smaller motor would do");
      }
    }
    if (p.throttle > 0 && p.throttle < 0.2) {
      r->warnings.push_back("segment '" + s.name + "': throttle only " + SignificantText(100 * p.throttle, 3) +
                            " %: coarse speed control; a lower-Kv motor or fewer cells would "
                            "use more of the range");
    }
    if (!s.prop_note.empty()) {
      r->warnings.push_back("segment '" + s.name + "': propeller outside its data: " + s.prop_note);
    }
  }
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    const GroupDrive& gd = groups_[g];
    const MotorParams& mp = gd.drive.motor();  // the scenario's (credibility.h)
    const std::string& motor_id = gd.parts.motor->id;
    if (!std::isfinite(mp.max_current_a) && !std::isfinite(mp.max_power_w)) {
      r->warnings.push_back("motor " + motor_id + " has no current or power rating in the "
                            "catalog: its load could not be checked (the search may favour it)");
    }
    if (gd.rating_estimated) {
      r->warnings.push_back("motor " + motor_id + " has no current or power rating in its source: "
                            "ratings " + SignificantText(mp.max_power_w, 3) + " W, " + SignificantText(mp.max_current_a, 3) +
                            " A estimated from its mass and Kv (laws of hobby outrunners, catalog/conventions.h, "
                            "assumed)");
    }
    if (gd.motor_excluded && g == lift_group_) {
      r->warnings.push_back("motor " + motor_id + " has no current or power rating: excluded "
                            "(constraints.unrated_motors = \"exclude\")");
    }
    if (gd.folding_refused && g == lift_group_) {
      r->warnings.push_back("propeller " + gd.parts.prop->id + " is a folding propeller: not used for multirotor "
                            "lift (constraints.allow_folding_props_for_lift)");
    }
    if (!std::isfinite(gd.drive.esc().max_current_a)) {
      r->warnings.push_back("ESC " + gd.parts.esc->id + " has no current rating: its current was not checked");
    }
  }
  std::vector<const EntryBase*> entries{c_.battery};
  for (const GroupDrive& gd : groups_) {
    for (const EntryBase* e : {static_cast<const EntryBase*>(gd.parts.motor), static_cast<const EntryBase*>(gd.parts.esc),
                               static_cast<const EntryBase*>(gd.parts.prop)}) {
      if (std::find(entries.begin(), entries.end(), e) == entries.end()) entries.push_back(e);
    }
  }
  for (const EntryBase* e : entries) {
    if (!e->exclude_reason.empty()) {
      r->warnings.push_back(e->id + " is excluded from searches by the catalog: " + e->exclude_reason);
    }
  }
  if (!r->assumed.empty()) {
    std::string a;
    for (const auto& x : r->assumed) a += (a.empty() ? "" : "; ") + x;
    r->warnings.push_back("results rest on assumed values (" + a + ")");
  }
}

}  // namespace dynosize
