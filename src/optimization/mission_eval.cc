#include "optimization/mission_eval.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/units.h"
#include "mission/flight.h"
#include "model/physics.h"
#include "optimization/prop_bounds.h"
#include "optimization/shaft.h"
#include "solvers/solver.h"

namespace dynosize {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kSubsteps = 8;           // per fixed segment (midpoint rule in SOC)
constexpr int kStretchSubsteps = 16;   // for the stretched max_endurance segment
// An active limit is named when its relative slack is below this.
constexpr double kActiveSlack = 0.10;

std::string Num(double x, int precision = 4) {
  std::ostringstream o;
  o.precision(precision);
  o << x;
  return o.str();
}

// A simulated point as the 1-D search compares and fits it: where, and its outcome.
struct ResultKey {
  double x = 0.0;
  bool feasible = false;
  double score = 0.0, min_slack = 0.0;
  static ResultKey Of(const MissionResult& r, double x) { return {x, r.feasible, r.score, r.min_slack}; }
};

// Which of two simulated results is better: a feasible one with the lower score, else (both
// infeasible) the one closer to feasibility (larger smallest relative slack).
bool Better(const ResultKey& a, const ResultKey& b) {
  if (a.feasible != b.feasible) return a.feasible;
  return a.feasible ? a.score < b.score : a.min_slack > b.min_slack;
}
bool Better(const MissionResult& a, const MissionResult& b) { return Better(ResultKey::Of(a, 0), ResultKey::Of(b, 0)); }

// Brent's minimization (Brent 1973, "Algorithms for Minimization without Derivatives", ch. 5)
// on [a, b] from its best point x (result best) and two more simulated points w (second best)
// and v: a step to the vertex of the parabola through x, w and v when the three are alike (all
// feasible: fitting the score; all infeasible: fitting the smallest slack, negated) and the
// step is safe (inside [a, b], less than half the step before last), else a golden-section
// step into the larger side. It keeps the golden section's bracket invariant, so it ends in
// the same tolerance, in fewer simulations on the smooth score of a capacity or an airspeed.
template <typename Simulate, typename Enough>
MissionResult BrentPolish(const Simulate& simulate, const Enough& enough, double a, double b, double x0,
                          MissionResult best, ResultKey w, ResultKey v, double tolerance) {
  constexpr double kGoldenStep = 0.3819660112501051;  // (3 - sqrt(5))/2
  ResultKey x = ResultKey::Of(best, x0);
  if (Better(v, w)) std::swap(v, w);
  const double tol1 = 0.25 * tolerance, tol2 = 2.0 * tol1;  // ends with b - a <= tolerance
  double d = 0.0, e = b - a;  // the last step and the one before: the grid's neighbours
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (a + b);
    if (std::fabs(x.x - m) <= tol2 - 0.5 * (b - a)) break;
    bool parabolic = false;
    if (std::fabs(e) > tol1 && x.feasible == w.feasible && x.feasible == v.feasible) {
      auto f = [](const ResultKey& k) { return k.feasible ? k.score : -k.min_slack; };
      const double r = (x.x - w.x) * (f(x) - f(v));
      double q = (x.x - v.x) * (f(x) - f(w));
      double p = (x.x - v.x) * q - (x.x - w.x) * r;
      q = 2.0 * (q - r);
      if (q > 0) p = -p;
      q = std::fabs(q);
      if (std::fabs(p) < std::fabs(0.5 * q * e) && p > q * (a - x.x) && p < q * (b - x.x)) {
        e = d;
        d = p / q;
        const double u = x.x + d;
        if (u - a < tol2 || b - u < tol2) d = m >= x.x ? tol1 : -tol1;
        parabolic = true;
      }
    }
    if (!parabolic) {
      e = x.x >= m ? a - x.x : b - x.x;
      d = kGoldenStep * e;
    }
    const double ux = std::fabs(d) >= tol1 ? x.x + d : x.x + (d >= 0 ? tol1 : -tol1);
    MissionResult ru = simulate(ux);
    if (enough(ru)) return ru;
    const ResultKey u = ResultKey::Of(ru, ux);
    if (!Better(x, u)) {  // u is no worse: the new best
      (ux >= x.x ? a : b) = x.x;
      v = w; w = x; x = u;
      best = std::move(ru);
    } else {
      (ux < x.x ? a : b) = ux;
      if (!Better(w, u) || w.x == x.x) { v = w; w = u; }
      else if (!Better(v, u) || v.x == x.x || v.x == w.x) v = u;
    }
  }
  return best;
}

// The best result over x in [0, 1] of one scaled variable: a 9-point grid brackets the best
// point, then Brent's method (BrentPolish) on [x_best - 1/8, x_best + 1/8] down to a width of
// 1e-6; a best on an end of the range is settled by one point inside it. Infeasible points
// compare worse than every feasible one, so an optimum on a constraint boundary is approached
// from the feasible side. The result is the best point simulated, never worse than the grid's.
// The variable's function is taken to be unimodal on the bracket, as any bracketing method
// takes it.
//
// bounded_after_grid(best, a, b): called once after the grid with the grid's best and the
// bracket; true when it proves that neither the grid's best nor any point of [a, b] can beat
// the caller's cutoff. The polish only simulates points of [a, b], so the result could not
// beat the cutoff either: the search stops there (a result with bounded_out set).
// enough(r): true when r settles the caller's question (Solve's decide); r is then returned
// at once. top_first: the grid from x = 1 down (only how soon `enough` is met changes).
template <typename Simulate, typename Bounded, typename Enough>
MissionResult SolveOneVariable(const Simulate& simulate, const Bounded& bounded_after_grid, const Enough& enough,
                               bool top_first) {
  constexpr int kGrid = 9;
  constexpr double kTolerance = 1e-6;  // of the scaled variable's range
  MissionResult best;
  double best_x = -1.0;
  int best_k = 0;
  std::array<ResultKey, kGrid> grid_keys;
  for (int i = 0; i < kGrid; ++i) {
    const int k = top_first ? kGrid - 1 - i : i;
    const double x = k / double(kGrid - 1);
    MissionResult r = simulate(x);
    if (enough(r)) return r;
    grid_keys[k] = ResultKey::Of(r, x);
    // Of equal points the lowest x, so that the grid's best does not depend on the order.
    if (best_x < 0 || Better(r, best) || (!Better(best, r) && x < best_x)) {
      best = std::move(r);
      best_x = x;
      best_k = k;
    }
  }
  double a = std::max(0.0, best_x - 1.0 / (kGrid - 1)), b = std::min(1.0, best_x + 1.0 / (kGrid - 1));
  if (bounded_after_grid(best, a, b)) {
    MissionResult out;
    out.bounded_out = true;
    out.score = kInf;
    return out;
  }
  // The grid's best on an end of the range: one point a tolerance inside it settles it. If
  // that point is worse, the variable's unimodal function (the golden section's assumption)
  // has its best within the tolerance of the end, and every point the golden section would
  // simulate is worse than the end itself: its answer would be the grid's best.
  if (best_x == 0.0 || best_x == 1.0) {
    MissionResult r_in = simulate(best_x == 0.0 ? kTolerance : 1.0 - kTolerance);
    if (enough(r_in)) return r_in;
    if (Better(best, r_in)) return best;
  }
  return BrentPolish(simulate, enough, a, b, best_x, std::move(best), grid_keys[best_k - 1 < 0 ? 0 : best_k - 1],
                     grid_keys[std::min(best_k + 1, kGrid - 1)], kTolerance);
}

// Propeller speed for a required thrust: the root of T(omega) - T_req on [0, w_hi], in closed
// form for coefficients and power laws (PropModel::StaticSpeedForThrust: their thrust does not
// depend on the inflow), else by the Illinois variant of regula falsi (T(0) = 0 < T_req).
// Returns false when T(w_hi) < T_req.
bool PropSpeedForThrust(const PropModel& prop, double thrust_n, double rho, double airspeed,
                        double w_hi, double* omega, PropEvaluation* ev) {
  if (double w = 0; prop.StaticSpeedForThrust(thrust_n, rho, &w)) {
    const bool ok = w <= w_hi;
    *omega = ok ? w : w_hi;
    *ev = prop.Evaluate(*omega, rho, airspeed);
    return ok;
  }
  double a = 0.0, fa = -thrust_n;
  PropEvaluation eb = prop.Evaluate(w_hi, rho, airspeed);
  double b = w_hi, fb = eb.thrust_n - thrust_n;
  if (fb < 0) {
    *omega = w_hi;
    *ev = eb;
    return false;
  }
  int side = 0;
  for (int it = 0; it < 200; ++it) {
    const double c = (a * fb - b * fa) / (fb - fa);
    const PropEvaluation ec = prop.Evaluate(c, rho, airspeed);
    const double fc = ec.thrust_n - thrust_n;
    if (fc > 0) {
      b = c; fb = fc; eb = ec;
      if (side == 1) fa *= 0.5;
      side = 1;
    } else {
      a = c; fa = fc;
      if (side == -1) fb *= 0.5;
      side = -1;
      if (fc == 0) { b = c; eb = ec; break; }
    }
    if (b - a < 1e-12 * b) break;
  }
  *omega = b;
  *ev = eb;
  return true;
}

// For the report of a point that creates energy: the efficiency (> 1) of the stage that does,
// eta_esc = PAC/PDC or eta_motor = Pmech/PAC; when that stage's input is not positive,
// 1 + output/|output| = 2 (a finite stand-in for "power out of nothing").
double CreatedEnergyRatio(const OperatingPoint& op) {
  auto ratio = [](double out_w, double in_w) { return in_w > 0 ? out_w / in_w : 2.0; };
  double r = 1.0;
  if (op.pesc_w < 0) r = std::max(r, ratio(op.pac_w, op.pdc_w));
  if (op.pmech_w > op.pac_w) r = std::max(r, ratio(op.pmech_w, op.pac_w));
  return r;
}

}  // namespace

namespace eval_internal {

// Tracks slacks and violations of one simulation.
class Tracker {
 public:
  // stretch_phase (RunState::in_stretch): when set, the checks also go into stretch_slacks.
  explicit Tracker(MissionResult* r, const bool* stretch_phase = nullptr) : r_(r), stretch_phase_(stretch_phase) {}
  // value <= limit (or >= when `at_least`); relative slack (limit - value)/|limit|.
  // `name` and `unit` are literals: no string is built unless the check fails.
  void Check(const char* name, const std::string& segment, double value, double limit,
             const char* unit, bool at_least = false, SegmentResult* seg = nullptr) {
    if (!std::isfinite(limit)) return;
    double slack = (limit - value) / std::max(std::fabs(limit), 1e-12);
    if (at_least) slack = -slack;
    if (std::isnan(slack)) slack = -kInf;
    r_->min_slack = std::min(r_->min_slack, slack);
    if (stretch_phase_ && *stretch_phase_) r_->stretch_slacks.Add(name, slack);
    if (seg && slack < seg->active_limit_slack) {
      seg->active_limit_slack = slack;
      seg->active_limit_id = name;
    }
    if (slack < 0) {
      for (Violation& v : r_->violations) {
        if (v.constraint == name) {
          const double rel_old = std::fabs(v.excess()) / std::max(std::fabs(v.limit), 1e-12);
          if (-slack > rel_old) v = Violation{name, segment, value, limit, unit, at_least};
          return;
        }
      }
      r_->violations.push_back(Violation{name, segment, value, limit, unit, at_least});
    }
  }

 private:
  MissionResult* r_;
  const bool* stretch_phase_;
};

}  // namespace eval_internal

namespace {

using eval_internal::Tracker;

// A propeller segment's shaft point: the speed where the propeller gives the required thrust
// per rotor (static or in the axial inflow), its torque, and the propeller's own checks (data
// held at an edge, static-only data in inflow, momentum theory, max rpm, the hover throttle at
// full charge). False when even four times the motor's no-load speed does not give the thrust
// (a "thrust" violation is recorded).
bool PropellerPoint(const Mission& m, const Segment& s, const RotorLoad& load, const Drive& drive,
                    const PropModel& prop, const PropEntry& prop_entry, const PropAdjustment& adj,
                    double v_full, double w_motor_max, Tracker* track, SegmentResult* seg, double* omega,
                    double* torque) {
  const MissionConstraints& k = m.constraints;
  PropEvaluation ev;
  const double w_hi = 4.0 * w_motor_max;
  if (!PropSpeedForThrust(prop, load.thrust_per_rotor_n, m.rho_kg_m3,
                          load.axial_airspeed_m_s, w_hi, omega, &ev)) {
    // Even four times the motor's no-load speed does not give the thrust.
    const PropEvaluation at_nl = prop.Evaluate(w_motor_max, m.rho_kg_m3, load.axial_airspeed_m_s);
    track->Check("thrust", s.name, load.thrust_per_rotor_n, at_nl.thrust_n, "N", false, seg);
    return false;
  }
  if (!ev.InData()) {  // the note is written from these numbers when read (FillPropNotes)
    seg->prop_edge = true;
    seg->prop_edge_eval = ev;
  }
  // Static-only data (DriveCalc power laws, static coefficients) say nothing about the
  // thrust lost to inflow; held at J = 0 they grossly over-state a propeller in fast axial
  // flow. Up to the mission's max_static_advance_ratio (default 0.2) the static values
  // are accepted as an approximation (and noted); beyond it the point fails.
  if (ev.no_forward_flight_data) {
    track->Check("prop_no_forward_flight_data", s.name, ev.j, k.max_static_advance_ratio, "", false, seg);
  }
  // Momentum theory bounds a rotor's shaft power from below: an actuator disk of area A in
  // axial flow V needs P_ideal = T*(V/2 + sqrt((V/2)^2 + T/(2*rho*A))) (Leishman,
  // Principles of Helicopter Aerodynamics, 2nd ed., eqs 2.14 and 2.91; figure of merit
  // <= 1). Propeller data below it are not physical (some DriveCalc power laws are), and
  // would fly on impossible efficiency. The ratio P_ideal/P is the figure of merit (static) or
  // its axial-flow analogue; above the mission's max_figure_of_merit (default 0.8: small
  // propellers measure 0.5-0.75, Brandt & Selig 2011) the point fails
  // "prop_figure_of_merit".
  {
    // Static-only data evaluated in axial flow (flagged in prop_note) are held to the
    // static bound: they cannot see the climb power, which the note says.
    const double v_ax = ev.no_forward_flight_data ? 0.0 : load.axial_airspeed_m_s;
    // Positive thrust for no power: 1e3, far above any limit (a finite value to print).
    const double fom = ev.power_w > 0 ? FigureOfMerit(load.thrust_per_rotor_n, ev.power_w, prop_entry.diameter_m,
                                                      m.rho_kg_m3, v_ax)
                                      : (load.thrust_per_rotor_n > 0 ? 1e3 : 0.0);
    track->Check("prop_figure_of_merit", s.name, fom, k.max_figure_of_merit, "", false, seg);
  }
  // The scenario's propeller power (credibility.h: the credible value by default), after the
  // momentum-theory check, which judges the data as given.
  AdjustPropEvaluation(adj, prop_entry.diameter_m, &ev);
  *torque = ev.torque_nm;
  if (prop_entry.max_rpm) {
    track->Check("prop_max_rpm", s.name, RadPerSecToRpm(*omega), *prop_entry.max_rpm, "rpm", false, seg);
  }
  // The propeller's speed window around its data (mission.h): beyond it the data do not rank.
  // The bottom is not checked in a descent (a climb segment with a negative rate): the rotors
  // unload below the weight for the seconds of a landing, a dip the Reynolds correction covers,
  // and a limit there would exclude a propeller for its landing, not for what it is ranked on.
  const PropValidRange& data = prop.valid_range();
  if (k.prop_below_data_factor > 0 && !(s.type == SegmentType::kClimb && s.climb_rate_m_s < 0)) {
    track->Check("prop_below_data", s.name, RadPerSecToRpm(*omega), k.prop_below_data_factor * data.rpm_lo, "rpm",
                 true, seg);
  }
  if (k.prop_above_data_factor > 0) {
    track->Check("prop_above_data", s.name, RadPerSecToRpm(*omega), k.prop_above_data_factor * data.rpm_hi, "rpm",
                 false, seg);
  }
  if (s.type == SegmentType::kHover && k.min_hover_throttle > 0) {
    // At the full-charge voltage without sag: the lowest throttle this hover can need, and
    // the same at every moment of the mission (so the stretch stays monotone).
    const OperatingPoint full = drive.Inverse(v_full, *torque, *omega);
    track->Check("min_hover_throttle", s.name, full.throttle, k.min_hover_throttle, "", true, seg);
  }
  return true;
}

}  // namespace

GroupParts FixedGroupParts(const Mission& m, const Catalog& cat, int g) {
  if (m.groups.empty() || !m.groups[g].fixed()) return {};
  const PropulsionGroup& grp = m.groups[g];
  auto look = [&](const char* key, const std::string& id, auto lookup) {
    try {
      return lookup(id);
    } catch (const Error& e) {
      throw DataError(m.file + ": $.propulsion." + grp.name + "." + key + ": \"" + id +
                      "\": not in the catalog (" + e.what() + ")");
    }
  };
  GroupParts p;
  p.motor = look("motor", grp.motor_id, [&](const std::string& id) { return &cat.motor(id); });
  p.esc = look("esc", grp.esc_id, [&](const std::string& id) { return &cat.esc(id); });
  p.prop = look("prop", grp.prop_id, [&](const std::string& id) { return &cat.prop(id); });
  return p;
}

MissionEvaluator::MissionEvaluator(const Mission& mission, const Combination& c,
                                   const PropModel* prop_model,
                                   const std::vector<const PropModel*>* group_prop_models)
    : m_(mission), c_(c) {
  const BatteryEntry& b = *c.battery;
  if (c.cells < 1 || c.cells % b.cells_series != 0) {
    throw UsageError("battery '" + b.id + "' has " + std::to_string(b.cells_series) +
                     " cells in series: --cells " + std::to_string(c.cells) +
                     " must be a positive multiple of it");
  }
  pack_base_ = PackFromEntry(b, c.cells / b.cells_series, 1);
  base_capacity_ah_ = pack_base_.cell_capacity_ah * pack_base_.n_parallel;
  for (const auto& k : pack_base_.assumed) assumed_.push_back("battery " + b.id + ": " + k);
  if (!b.mass_kg) throw DataError("battery '" + b.id + "' has no mass_kg: the mission needs it");
  if (!c.groups.empty() && static_cast<int>(c.groups.size()) != GroupCount(m_)) {
    throw UsageError("the combination has parts for " + std::to_string(c.groups.size()) +
                     " propulsion groups; the mission has " + std::to_string(GroupCount(m_)));
  }
  fixed_mass_kg_ = m_.vehicle.mass_kg;
  for (int g = 0; g < GroupCount(m_); ++g) {
    const GroupParts parts = c.Parts(g);
    if (!parts.motor || !parts.esc || !parts.prop) {
      throw UsageError("propulsion group '" + GroupName(m_, g) + "' has no motor, ESC or propeller");
    }
    // PropModels built by the caller: prop_model serves the group of c.prop, group_prop_models
    // the others; any group without one builds its own.
    const PropModel* given = prop_model && parts.prop == c.prop ? prop_model : nullptr;
    if (!given && group_prop_models && g < static_cast<int>(group_prop_models->size())) {
      given = (*group_prop_models)[g];
    }
    // The mission's data scenario (credibility.h): the motor's ratings estimated from its mass
    // when no source states them, the bands' ends in the pessimistic/optimistic scenarios.
    bool rating_estimated = false, motor_excluded = false;
    const MotorParams motor_params = ScenarioMotorParams(*parts.motor, m_, &rating_estimated, &motor_excluded);
    groups_.push_back(GroupDrive{parts, Drive(motor_params, ScenarioEscParams(*parts.esc, m_.objective.ranking)),
                                 given ? nullptr : std::make_unique<PropModel>(*parts.prop), nullptr, 0.0, {},
                                 false, false, false});
    GroupDrive& gd = groups_.back();
    gd.prop = given ? given : gd.owned_prop.get();
    gd.prop_adj = PropAdjustmentFor(*parts.prop, m_.objective.ranking);
    gd.folding_refused = FoldingPropRefused(*parts.prop, m_);
    gd.rating_estimated = rating_estimated;
    gd.motor_excluded = motor_excluded;
    if (rating_estimated) {
      assumed_.push_back("motor " + parts.motor->id +
                         (std::isfinite(parts.motor->params.max_power_w)
                              ? ": max_current_a (from mass and Kv)"
                              : ": max_power_w, max_current_a (from mass and Kv)"));
    }
    if (!parts.motor->mass_kg) {
      throw DataError("motor '" + parts.motor->id + "' has no mass_kg: the mission needs it");
    }
    const double motor_mass = *parts.motor->mass_kg;
    const ComponentMass esc_mass = EscMass(*parts.esc);
    if (esc_mass.assumed) assumed_.push_back("ESC " + parts.esc->id + ": mass_kg");
    const ComponentMass prop_mass = PropMass(*parts.prop);
    if (prop_mass.assumed) assumed_.push_back("propeller " + parts.prop->id + ": mass_kg");
    for (const auto& k : parts.motor->assumed_keys) assumed_.push_back("motor " + parts.motor->id + ": " + k);
    for (const auto& k : parts.esc->assumed_keys) assumed_.push_back("ESC " + parts.esc->id + ": " + k);
    for (const auto& k : parts.prop->assumed_keys) assumed_.push_back("propeller " + parts.prop->id + ": " + k);
    fixed_mass_kg_ += GroupRotors(m_, g) * (motor_mass + esc_mass.kg + prop_mass.kg);
    if (parts.motor->params.rth_k_per_w > 0) {
      gd.rth_k_per_w = parts.motor->params.rth_k_per_w;
    } else {
      gd.rth_k_per_w = AssumedMotorRthKPerW(motor_mass);
      assumed_.push_back("motor " + parts.motor->id + ": rth_k_per_w");
    }
  }
  lift_rotors_ = LiftRotors(m_);
  lift_group_ = std::max(0, LiftGroup(m_));
}

double MissionEvaluator::BatteryMassKg(double capacity_ah) const {
  return PackAt(capacity_ah).cell_mass_kg * pack_base_.n_series * pack_base_.n_parallel;
}

BatteryPackParams MissionEvaluator::PackAt(double capacity_ah) const {
  BatteryPackParams p = pack_base_;
  if (capacity_ah > 0) {
    // Sizing: the same cell technology at another capacity keeps its specific energy
    // (mass ~ capacity), its C-rate (current rating ~ capacity) and its R*capacity product.
    const double k = capacity_ah / base_capacity_ah_;
    p.cell_capacity_ah *= k;
    p.cell_mass_kg *= k;
    p.cell_ri_ohm /= k;
    p.cell_max_current_a *= k;
    p.cell_peak_current_a *= k;
  }
  return p;
}

// What Run carries from one segment to the next.
struct MissionEvaluator::RunState {
  BatteryPack pack;
  double cutoff_v = 0, v_full = 0, q_c = 0, current_factor = 1;
  double soc = 1.0, time_s = 0, energy_j = 0;
  bool in_stretch = false;  // past the first point of the max-endurance stretch (WithEndurance)
};

// Mission-wide checks of the parts: ESC voltage, the frame, and the lift group's credibility
// checks (credibility.h).
void MissionEvaluator::CheckParts(const RunState& st, eval_internal::Tracker* track) const {
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    const GroupDrive& gd = groups_[g];
    track->Check("esc_voltage", "", st.v_full, gd.drive.esc().vdc_max_v, "V");
    if (const auto d_max = GroupMaxPropDiameterM(m_, g)) {
      track->Check("prop_diameter", "", gd.parts.prop->diameter_m, *d_max, "m");
    }
    if (g != lift_group_) continue;  // credibility.h: the lift group's parts only
    if (gd.folding_refused) track->Check("prop_folding", "", 1.0, 0.0, "");
    if (gd.motor_excluded) track->Check("motor_unrated", "", 1.0, 0.0, "");
    track->Check("motor_voltage", "", st.v_full, MotorMaxVoltageV(*gd.parts.motor), "V");
  }
}

// The shaft's speed and torque of segment si (shaft segments: Ipopt; propeller segments:
// PropellerPoint). False when the propeller cannot give the thrust.
bool MissionEvaluator::SegmentShaftPoint(std::size_t si, const RunState& st, const RotorLoad& load,
                                         eval_internal::Tracker* track, SegmentResult* seg, double* omega,
                                         double* torque) const {
  const Segment& s = m_.segments[si];
  const GroupDrive& gd = groups_[s.group];
  const Drive& drive = gd.drive;
  const MissionConstraints& k = m_.constraints;
  if (s.type == SegmentType::kShaft) {
    const MotorParams& mp = drive.motor();
    const EscParams& ep = drive.esc();
    ShaftRequest q;
    q.vdc_v = st.v_full;
    q.power_w = s.shaft_power_w;
    q.torque_nm = s.shaft_torque_nm;
    q.omega_rad_s = s.shaft_omega_rad_s;
    q.max_throttle = std::min(k.max_throttle, k.allow_esc_saturation ? 1.0 : ep.tr_sat);
    const double lim = std::min(mp.max_current_a, ep.max_current_a) * st.current_factor;
    q.max_current_a = std::isfinite(lim) ? lim : 1e300;
    const ShaftSolution sol = SolveShaftSpeed(drive, q, "ipopt");
    *omega = sol.omega_rad_s;
    *torque = sol.point.torque_nm;
    seg->shaft_solver = sol.algorithm + ": " + sol.message;
    return true;
  }
  const double w_motor_max = std::max(drive.NoLoadSpeed(st.v_full, 1.0), 1.0);
  return PropellerPoint(m_, s, load, drive, *gd.prop, *gd.parts.prop, gd.prop_adj, st.v_full, w_motor_max, track,
                        seg, omega, torque);
}

// Flies segment si at the shaft point (omega, torque) from st.soc: the pack's sag per instant,
// the constraints at every sub-step's end, SOC by the midpoint rule. False when the pack cannot
// deliver the power (a battery_power violation is recorded).
bool MissionEvaluator::IntegrateSegment(std::size_t si, bool stretched, double omega, double torque,
                                        RunState* st, eval_internal::Tracker* track, SegmentResult* seg) const {
  const Segment& s = m_.segments[si];
  const GroupDrive& gd = groups_[s.group];
  const Drive& drive = gd.drive;
  const MotorParams& mp = gd.drive.motor();  // the scenario's (credibility.h)
  const EscParams& ep = gd.drive.esc();
  const MissionConstraints& k = m_.constraints;
  const BatteryPack& pack = st->pack;
  const int n_active = seg->rotors;
  double last_sag_v = 0.0;
  // The power asked of the pack at the last voltage tried, and the most it can give then
  // (a source OCV behind R delivers at most OCV^2/(4*R)).
  double demanded_w = 0.0, deliverable_w = 0.0;
  // The operating point at a state of charge: the terminal voltage V solves
  //   V = OCV(soc) - R*I_batt,  V*I_batt = N*PDC(V) + P_avionics.
  // PDC = C1*U*Irms/kv + C0*VDC*Irms (eqs 57, 59) depends on V only through the C0 term (and
  // saturation), so each step solves the quadratic V^2 - OCV*V + R*P = 0 for its upper (stable)
  // root with P at the current V: exact in one step when C0 = 0, a fast contraction otherwise.
  // No real root: the pack cannot deliver the power.
  // The iteration needs only IDC (Drive::InverseLight, the same numbers as Inverse); the whole
  // point is computed once, at the voltage of the last one, and only when op is not null (the
  // midpoints need IDC alone: the shaft point, hence Pmech, is the segment's).
  auto point_at = [&](double soc_now, OperatingPoint* op, double* v, double* i_batt) {
    const double ocv = pack.OcvV(soc_now);
    const double r_pack = pack.ri_ohm();
    // Warm start from the previous instant's sag (the current changes little in a segment).
    double vv = last_sag_v > 0 && last_sag_v < 0.5 * ocv ? ocv - last_sag_v : ocv;
    double v_op = vv, idc_op = 0.0;  // the last InverseLight's voltage and IDC
    for (int it = 0; it < 30; ++it) {
      idc_op = drive.InverseLight(vv, torque, omega).idc_a;
      v_op = vv;
      const double p_w = n_active * idc_op * vv + m_.vehicle.avionics_power_w;
      const double disc = ocv * ocv - 4.0 * r_pack * p_w;
      demanded_w = p_w;
      deliverable_w = ocv * ocv / (4.0 * r_pack);
      if (!(disc >= 0.0)) {
        if (op) *op = drive.Inverse(v_op, torque, omega);
        return false;
      }
      const double next = 0.5 * (ocv + std::sqrt(disc));
      // Converged: the point at vv, whose IDC was just computed; the pack's equation holds
      // there to 1e-10 of the OCV.
      if (std::fabs(next - vv) < 1e-10 * ocv) break;
      vv = next;
    }
    if (op) {
      *op = drive.Inverse(v_op, torque, omega);
      idc_op = op->idc_a;
    }
    *i_batt = n_active * idc_op + m_.vehicle.avionics_power_w / vv;
    *v = vv;
    last_sag_v = ocv - vv;
    return true;
  };
  auto check_point = [&](const OperatingPoint& op, double v, double i_batt) {
    track->Check("max_throttle", s.name, op.throttle, k.max_throttle, "", false, seg);
    if (!k.allow_esc_saturation) track->Check("esc_saturation", s.name, op.throttle, ep.tr_sat, "", false, seg);
    const double i = std::max(op.idc_a, op.irms_a);
    track->Check("motor_current", s.name, i, mp.max_current_a * st->current_factor, "A", false, seg);
    track->Check("esc_current", s.name, i, ep.max_current_a * st->current_factor, "A", false, seg);
    if (k.enforce_motor_power) track->Check("motor_power", s.name, op.pac_w, mp.max_power_w, "W", false, seg);
    track->Check("battery_current", s.name, i_batt, pack.max_current_a() * st->current_factor, "A", false, seg);
    track->Check("battery_cutoff", s.name, v, st->cutoff_v, "V", true, seg);
    const double temp_c = WindingTempC(op, s.group);
    seg->winding_temp_c = std::max(seg->winding_temp_c, temp_c);
    track->Check("max_winding_temp_c", s.name, temp_c, k.max_winding_temp_c, "C", false, seg);
    // Physics is the contract: a point where the ESC or the motor puts out more power than
    // it takes in (model.md section 10; Drive::Flag sets the bit through model/physics.h)
    // is never feasible, whatever the objective gains from it.
    if (op.limits & kLimitCreatesEnergy) {
      track->Check("creates_energy", s.name, CreatedEnergyRatio(op), 1.0, "", false, seg);
    }
  };
  double& soc = st->soc;
  seg->soc_start = soc;
  OperatingPoint op;
  double v = 0, ib = 0;
  bool ok = point_at(soc, &op, &v, &ib);
  if (ok) check_point(op, v, ib);
  // From here on the checks depend on the stretch's duration (WithEndurance's root function).
  if (stretched) st->in_stretch = true;
  seg->battery_current_start_a = ib;
  seg->vdc_min_v = seg->vdc_max_v = v;
  seg->throttle_min = seg->throttle_max = op.throttle;
  seg->idc_min_a = seg->idc_max_a = op.idc_a;
  const int steps = stretched ? kStretchSubsteps : kSubsteps;
  const double dt = seg->duration_s / steps;
  double e_seg = 0, e_mech = 0;
  // Pmech = KT(I)*(I - Io)*omega at the segment's fixed shaft point (eqs 42, 50): the same at
  // every voltage, so the midpoints take it from the first point.
  const double pmech_w = op.pmech_w;
  for (int j = 0; ok && j < steps && dt > 0; ++j) {
    // Midpoint rule: predict SOC at mid-step with the start current, draw the mid current.
    double vm = 0, im = 0;
    ok = point_at(soc - 0.5 * ib * dt / st->q_c, nullptr, &vm, &im);
    if (!ok) break;
    soc -= im * dt / st->q_c;
    e_seg += vm * im * dt;
    e_mech += n_active * pmech_w * dt;
    ok = point_at(soc, &op, &v, &ib);
    if (!ok) break;
    check_point(op, v, ib);
    seg->vdc_min_v = std::min(seg->vdc_min_v, v);
    seg->vdc_max_v = std::max(seg->vdc_max_v, v);
    seg->throttle_min = std::min(seg->throttle_min, op.throttle);
    seg->throttle_max = std::max(seg->throttle_max, op.throttle);
    seg->idc_min_a = std::min(seg->idc_min_a, op.idc_a);
    seg->idc_max_a = std::max(seg->idc_max_a, op.idc_a);
  }
  if (!ok) {
    // The pack cannot deliver this power.
    track->Check("battery_power", s.name, demanded_w, deliverable_w, "W", false, seg);
    return false;
  }
  seg->point = op;
  seg->battery_current_a = ib;
  seg->soc_end = soc;
  seg->energy_j = e_seg;
  seg->eta_average = e_seg > 0 ? e_mech / (e_seg - m_.vehicle.avionics_power_w * seg->duration_s) : op.eta_system;
  if (dt <= 0) seg->eta_average = op.eta_system;
  if (seg->active_limit_slack > kActiveSlack) seg->active_limit_id = nullptr;
  st->time_s += seg->duration_s;
  st->energy_j += e_seg;
  return true;
}

// After the last segment: the reserve, the thrust-to-weight, the objective and the score.
void MissionEvaluator::FinishRun(const RunState& st, eval_internal::Tracker* track, MissionResult* out) const {
  MissionResult& r = *out;
  const MissionConstraints& k = m_.constraints;
  r.final_soc = st.soc;
  track->Check("reserve_soc", "", st.soc, m_.battery.reserve_soc, "", true);
  // Thrust-to-weight at full throttle on the lowest pack voltage of the mission (its end: the
  // SOC only falls) with the sag at that current. Falls as the stretch lengthens (less charge,
  // lower OCV), so the stretch's slack stays monotone.
  r.lift_rotors = lift_rotors_;
  if (k.min_thrust_to_weight > 0 && lift_rotors_ > 0) {
    FullThrottle ft;
    const double weight_n = r.total_mass_kg * kStandardGravity;
    r.thrust_to_weight = FullThrottleAt(st.pack, st.soc, &ft) ? lift_rotors_ * ft.thrust_per_rotor_n / weight_n : 0.0;
    track->Check("min_thrust_to_weight", "", r.thrust_to_weight, k.min_thrust_to_weight, "", true);
  }
  r.endurance_s = st.time_s;
  r.energy_wh = st.energy_j / 3600.0;
  r.feasible = r.min_slack >= 0;
  switch (m_.objective.type) {
    case ObjectiveType::kMaxEndurance:
      r.objective = st.time_s;
      r.objective_unit = "s";
      r.score = -st.time_s;
      break;
    case ObjectiveType::kMinEnergy:
      r.objective = r.energy_wh;
      r.objective_unit = "Wh";
      r.score = r.energy_wh;
      break;
    case ObjectiveType::kMaxEfficiency:
      r.objective = r.segments[m_.objective.segment_index].eta_average;
      r.objective_unit = "";
      r.score = -r.objective;
      break;
  }
  if (!r.feasible) r.score = kInf;
}

double ObjectiveOfScore(ObjectiveType type, double score) {
  return type == ObjectiveType::kMinEnergy ? score : -score;
}

// A Run stopped before segment `next`: everything Run has at that point (the segments before
// `next` do not depend on the stretch, so WithEndurance flies them once per set of variables).
struct MissionEvaluator::RunPrefix {
  MissionResult r;
  RunState st;
  std::size_t next = 0;
  bool finished = false;  // the run ended early (r is its final result)
};

MissionEvaluator::RunPrefix MissionEvaluator::RunUpTo(const ContinuousVars& vars, std::size_t end, bool screen) const {
  RunPrefix p{MissionResult{}, RunState{BatteryPack(PackAt(vars.capacity_ah))}, 0, false};
  MissionResult& r = p.r;
  RunState& st = p.st;
  r.min_slack = kInf;
  r.segments.reserve(m_.segments.size());
  Tracker track(&r);
  const BatteryPack& pack = st.pack;
  r.capacity_ah = pack.capacity_ah();
  r.total_mass_kg = fixed_mass_kg_ + pack.mass_kg();
  r.propulsion_mass_kg = r.total_mass_kg - m_.vehicle.mass_kg;
  DischargeOptions dopt;
  if (m_.battery.cutoff_cell_v) dopt.cutoff_cell_v = *m_.battery.cutoff_cell_v;
  st.cutoff_v = pack.cutoff_v(dopt);
  st.v_full = pack.OcvV(1.0);
  st.q_c = AhToCoulomb(pack.capacity_ah());
  st.current_factor = 1.0 - m_.constraints.current_margin;
  CheckParts(st, &track);
  RunSegments(vars, 0.0, screen, end, &p);
  return p;
}

// Flies the segments from p->next up to `end` (exclusive); sets p->finished when the run ends
// early (a segment that cannot be flown, or a violation when screening).
void MissionEvaluator::RunSegments(const ContinuousVars& vars, double stretch_s, bool screen, std::size_t end,
                                   RunPrefix* p) const {
  MissionResult& r = p->r;
  Tracker track(&r, &p->st.in_stretch);
  for (std::size_t si = p->next; si < end && !p->finished; ++si) {
    const Segment& s = m_.segments[si];
    SegmentResult seg;
    seg.group = s.group;
    seg.name = s.name;
    seg.type = s.type;
    seg.active_limit_slack = kInf;
    seg.winding_temp_c = m_.air_temperature_c;
    seg.airspeed_m_s = s.type == SegmentType::kCruise
                           ? (si < vars.airspeed_m_s.size() && vars.airspeed_m_s[si] > 0
                                  ? vars.airspeed_m_s[si]
                                  : s.airspeed_m_s.lo)
                           : 0.0;
    const bool stretched = m_.objective.type == ObjectiveType::kMaxEndurance &&
                           static_cast<int>(si) == m_.objective.segment_index;
    seg.duration_s = stretched ? stretch_s : SegmentDurationS(s, seg.airspeed_m_s);
    const RotorLoad load = SegmentRotorLoad(m_, s, r.total_mass_kg, seg.airspeed_m_s);
    seg.rotors = load.rotors;
    seg.thrust_per_rotor_n = s.type == SegmentType::kShaft ? 0.0 : load.thrust_per_rotor_n;
    seg.tilt_deg = load.tilt_rad * 180.0 / kPi;
    double omega = 0, torque = 0;
    const bool ok = SegmentShaftPoint(si, p->st, load, &track, &seg, &omega, &torque) &&
                    IntegrateSegment(si, stretched, omega, torque, &p->st, &track, &seg);
    if (seg.active_limit_id) seg.active_limit = seg.active_limit_id;
    r.segments.push_back(std::move(seg));
    p->next = si + 1;
    // Not ok: even four times the motor's no-load speed does not give the thrust, or the pack
    // cannot deliver the power.
    if (!ok || (screen && !r.violations.empty())) {
      r.feasible = false;
      r.score = kInf;
      p->finished = true;
    }
  }
}

MissionResult MissionEvaluator::RunFrom(RunPrefix p, const ContinuousVars& vars, double stretch_s, bool screen) const {
  RunSegments(vars, stretch_s, screen, m_.segments.size(), &p);
  if (p.finished) return std::move(p.r);
  Tracker track(&p.r, &p.st.in_stretch);
  FinishRun(p.st, &track, &p.r);
  return std::move(p.r);
}

MissionResult MissionEvaluator::Run(const ContinuousVars& vars, double stretch_s, bool screen) const {
  return RunFrom(RunUpTo(vars, 0, screen), vars, stretch_s, screen);
}

double MissionEvaluator::StretchStartCurrent(const MissionResult& r) const {
  return r.segments[m_.objective.segment_index].battery_current_start_a;
}

MissionResult MissionEvaluator::WithEndurance(ContinuousVars vars, double decide_cutoff) const {
  if (m_.objective.type != ObjectiveType::kMaxEndurance) return Run(vars, 0.0);
  // The longest stretch that keeps every constraint. Feasibility at T rests on the checks
  // before the stretch and at its first point, which do not depend on T (the segments before
  // it, the shaft points, the full-charge hover throttle), and on the rest, each of whose
  // slacks falls with T (SOC and voltage only fall). Once the first part holds (at T = 0),
  // the end of the feasible stretches is bracketed and closed in on by Illinois regula falsi
  // on the slack of one constraint: the one that fails worst at the bracket's infeasible end
  // (switched when a probe fails by another). That slack is smooth in T; the smallest slack
  // of all is not: a limit that does not move with T sits as a floor near 0 on the feasible
  // side (a thrust-to-weight held at the current rating, the class ESC's voltage limit, which
  // is exactly the pack's) and slows the regula falsi below a bisection.
  // The segments before the stretch do not depend on it: flown once.
  const RunPrefix prefix = RunUpTo(vars, static_cast<std::size_t>(m_.objective.segment_index), false);
  auto run = [&](double t) { return RunFrom(prefix, vars, t, false); };
  auto flown = [&](const MissionResult& r) { return r.segments.size() == m_.segments.size(); };
  // The watched constraint's slack; -1 where the pack gave out (no slack to read).
  const char* watch = nullptr;
  auto slack = [&](const MissionResult& r) { return flown(r) ? r.stretch_slacks.Of(watch) : -1.0; };
  MissionResult lo_r = run(0.0);
  if (lo_r.min_slack < 0 || !flown(lo_r)) return lo_r;
  // lo_r is feasible from here on and its stretch only grows (its score only falls).
  auto decided = [&]() { return lo_r.feasible && lo_r.score < decide_cutoff; };
  if (decided()) return lo_r;
  double lo = 0.0;
  // First guess: the charge left above the reserve at the stretched segment's start current.
  // The stretched segment draws at least its start current (the voltage only falls, the power
  // does not), so the charge above the reserve lasts at most this long: an infeasible end.
  const double q_c = AhToCoulomb(lo_r.capacity_ah);
  const double i_start = std::max(StretchStartCurrent(lo_r), 1e-9);
  double hi = std::max(1.0, q_c * std::max(lo_r.final_soc - m_.battery.reserve_soc, 1e-4) / i_start * 1.0001);
  MissionResult hi_r = run(hi);
  for (int i = 0; i < 40 && hi_r.feasible; ++i) {
    lo = hi; lo_r = std::move(hi_r);
    if (decided()) return lo_r;
    hi *= 2;
    hi_r = run(hi);
  }
  watch = hi_r.stretch_slacks.Worst();
  double f_lo = slack(lo_r), f_hi = slack(hi_r);
  int side = 0;
  for (int it = 0; it < 60 && hi - lo > 1e-6 * hi; ++it) {
    double t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    MissionResult tr = run(t);
    if (tr.feasible) {
      lo = t; f_lo = slack(tr); lo_r = std::move(tr);
      if (decided()) return lo_r;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else if (const char* fails = tr.stretch_slacks.Worst(); flown(tr) && !SameConstraint(fails, watch)) {
      watch = fails;  // another limit ends the stretch first: follow it from here
      hi = t; f_hi = slack(tr); f_lo = slack(lo_r);
      side = 0;
    } else {
      hi = t; f_hi = slack(tr);
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return lo_r;
}

namespace {

// A voltage at or below the lowest at which `drive` holds (torque, omega) with a throttle of at
// most t_max (< 1): the throttle that holds a point falls as the voltage rises (eq 48: the
// ESC must give U = (Rm + RESC)*I + KE*omega, U = kv*VDC*TR_eff, TR rising with TR_eff), so
// bisection keeps throttle(lo) > t_max. Returns v_hi when even v_hi needs more than t_max, 0
// when nothing is known.
double MinVoltageForThrottle(const Drive& drive, double torque_nm, double omega_rad_s, double v_hi, double t_max) {
  if (!(v_hi > 0) || !(drive.InverseLight(v_hi, torque_nm, omega_rad_s).throttle <= t_max)) return v_hi;
  double lo = 0.0, hi = v_hi;
  for (int i = 0; i < 50 && hi - lo > 1e-9 * v_hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (drive.InverseLight(mid, torque_nm, omega_rad_s).throttle > t_max ? lo : hi) = mid;
  }
  return lo;
}

// An SOC at or below the lowest SOC in [floor_soc, 1] whose OCV (rising with SOC) reaches v:
// bisection keeping OCV(lo) < v; floor_soc when OCV(floor_soc) >= v already.
double SocBelowOcv(const BatteryPack& pack, double v, double floor_soc) {
  if (pack.OcvV(floor_soc) >= v) return floor_soc;
  if (pack.OcvV(1.0) < v) return 1.0;
  double lo = floor_soc, hi = 1.0;
  for (int i = 0; i < 50 && hi - lo > 1e-9; ++i) {
    const double mid = 0.5 * (lo + hi);
    (pack.OcvV(mid) < v ? lo : hi) = mid;
  }
  return lo;
}

// Constraints that cannot recover with a larger capacity: the ESC voltage and the frame do not
// depend on it, and the thrust, propeller speed and PAC = sqrt(27/10)*(Rm*I + KE*omega)*I
// (eqs 41, 42, 47, 48) depend only on the shaft's speed and torque, which rise with the mass
// (search.cc, M3); so does the winding temperature (its losses kp*Rm*I^2 + KT*Io*omega depend
// only on them). Violated at one capacity, they are violated at every larger one. Throttle
// and IDC are not in the list: a larger pack also sags less, which lowers both.
bool RisesWithMass(const std::string& constraint) {
  static const char* const kNames[] = {"esc_voltage", "prop_diameter", "thrust", "motor_power", "prop_max_rpm",
                                       "prop_above_data",
                                       "max_winding_temp_c", "prop_folding", "motor_unrated",
                                       "motor_voltage"};
  for (const char* name : kNames) {
    if (constraint == name) return true;
  }
  return false;
}

}  // namespace

double MissionEvaluator::EnduranceUpperBound(double target_s, double from_ah, double to_ah) const {
  // max_endurance with the stretched segment at a fixed airspeed (hover, or cruise with one
  // airspeed): over capacities C in a piece [C_a, C_b] of the range,
  //   t_total(C) <= t_fixed_max + Q(C_b)*integral of OCV over [reserve, 1] / P_stretch(C_a)
  // because more capacity means more mass and so no less power in every segment (M3 of
  // search.cc), and the terminal energy is at most the OCV-weighted charge above the reserve.
  // P_stretch(C_a) is the terminal power at the start of the stretch, from one Run, less the
  // part of it that may fall as the voltage sags (voltage_dependent_w below: with C0 > 0 or
  // a supply resistance, eqs 57, 59), so that it is the least power over the stretch and over
  // the larger capacities.
  // When the ESC has C0 = 0 and no supply resistance, every segment's terminal power
  // N*PDC + P_avionics = N*C1*U*Irms/kv + P_avionics (eqs 48, 57, 59) does not depend on the
  // voltage, so the other segments' energy at C_a, E_other(C_a), is a lower bound of theirs at
  // any larger capacity (M3), and the stretch gets only what is left of the budget:
  //   t_total(C) <= t_fixed_max + (Q(C_b)*integral of OCV - E_other(C_a)) / P_stretch(C_a).
  // The OCV curve per SOC does not depend on the capacity (PackAt scales charge, mass,
  // resistance and rating only), so the integral is computed once.
  // The range starts in kBoundPieces pieces; while the largest piece bound is at least
  // `target_s`, that piece is halved (one more Run), up to kMaxBoundRuns Runs: the bound only
  // tightens as far as it takes to prove "cannot reach target_s".
  constexpr int kBoundPieces = 2;
  // Past a few halvings a piece rarely proves anything more (capacity-sized quadcopter: 24
  // runs, 8.4 s of CPU; 8 runs, 7.45 s, 5,154 -> 5,193 exact evaluations).
  constexpr int kMaxBoundRuns = 8;
  const Segment& st = m_.segments[m_.objective.segment_index];
  if (st.type == SegmentType::kCruise && st.airspeed_m_s.free()) return kInf;
  const double t_fixed_max = LongestFixedDurationS(m_);
  const bool free_c = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  double c_lo = m_.battery.capacity_ah ? m_.battery.capacity_ah->lo : base_capacity_ah_;
  double c_hi = m_.battery.capacity_ah ? m_.battery.capacity_ah->hi : base_capacity_ah_;
  if (free_c && to_ah > 0) {  // a part of the range (SolveOneVariable's bracket)
    c_lo = std::max(c_lo, from_ah);
    c_hi = std::min(c_hi, to_ah);
  }
  const double ocv_integral_v = OcvIntegralUpperBound(BatteryPack(PackAt(c_lo)), m_.battery.reserve_soc);
  bool energy_fixed = true;
  for (const GroupDrive& g : groups_) {
    energy_fixed &= g.drive.esc().c0 == 0.0 && g.drive.esc().rsupply_ohm == 0.0;
  }
  int runs = 0;
  double infeasible_from = kInf;  // every capacity from here up breaks a RisesWithMass constraint
  // Throttle floor (a second bound per piece): every checked point of the stretch holds the
  // stretch's (torque, speed), which rise with the mass (M3), within the throttle limit t_max
  // (max_throttle, and the ESC's knee when saturation is not allowed), and the throttle needed
  // for a (torque, speed) falls as the voltage rises (M2). So the terminal voltage at the
  // stretch's end is at least V_min, where the drive at C_a's point needs exactly t_max
  // (MinVoltageForThrottle), and at least the cut-off; the OCV (rising with SOC) is above the
  // terminal voltage, so the stretch ends at an SOC s >= s_min with OCV(s_min) = V_min. Up to
  // that end the pack gives at most Q(C_b)*integral of OCV over [s_min, 1], of which the
  // segments before the stretch take at least E_before(C_a) (energy_fixed, as above):
  //   t_total(C) <= t_fixed_max + (Q(C_b)*integral of OCV over [s_min, 1] - E_before(C_a)) / P_stretch(C_a).
  const GroupDrive& stretch_drive = groups_[st.group];
  double t_max = m_.constraints.max_throttle;
  if (!m_.constraints.allow_esc_saturation) t_max = std::min(t_max, stretch_drive.drive.esc().tr_sat);
  const BatteryPack pack_lo(PackAt(c_lo));
  DischargeOptions dopt;
  if (m_.battery.cutoff_cell_v) dopt.cutoff_cell_v = *m_.battery.cutoff_cell_v;
  const double v_cut = pack_lo.cutoff_v(dopt);
  // The part of one rotor's PDC at the stretch's start point that may fall as the pack sags or
  // with a larger, stiffer pack. The stretch holds one (torque, speed), so U and Irms are fixed
  // (eqs 42, 48), and PDC = VDC*(C1*TR_eff + C0)*I with U = kv*(VDC - rsupply*IDC)*TR_eff
  // (eqs 47, 57, 59, section 9) is C1*U*I/kv + C1*TR_eff*rsupply*IDC*I + C0*VDC*I: the first
  // term is fixed (and rises with the mass, M3), the second is left out, the third is counted
  // at the cut-off (every checked point has VDC >= v_cut, battery_cutoff). 0 for C0 = 0 and no
  // supply resistance, where the start power is the least.
  const EscParams& stretch_esc = stretch_drive.drive.esc();
  auto voltage_dependent_w = [&](const OperatingPoint& op) {
    double w = stretch_esc.c0 * op.irms_a * std::max(0.0, op.vdc_v - v_cut);
    if (stretch_esc.rsupply_ohm != 0.0) {
      w += stretch_esc.c1 * op.throttle_effective * stretch_esc.rsupply_ohm * op.idc_a * op.irms_a;
    }
    return w;
  };
  struct Piece {
    double ca, cb, p_ca, e_other_ca, e_before_ca = 0;
    double torque_nm = 0, omega_rad_s = 0;  // the stretch's point at C_a
    bool floor_done = false;                 // the throttle floor is computed only when needed
    double ocv_integral_smin_v = kInf;
  };
  // The piece [c, cb] (P_stretch and E_other at c; P = 0 when no bound can be given there);
  // sets infeasible_from.
  auto piece_at = [&](double c, double cb) {
    Piece pc{c, cb, 0.0, 0.0};
    ContinuousVars v;
    v.capacity_ah = c;
    v.airspeed_m_s.assign(m_.segments.size(), 0.0);
    for (std::size_t k = 0; k < m_.segments.size(); ++k) v.airspeed_m_s[k] = m_.segments[k].airspeed_m_s.lo;
    ++runs;
    // Without energy_fixed only the stretch's start is read: the segments after it are not
    // flown (their violations would only add to infeasible_from, which may miss some).
    const MissionResult r =
        energy_fixed ? Run(v, 0.0) : RunUpTo(v, static_cast<std::size_t>(m_.objective.segment_index) + 1, false).r;
    for (const Violation& x : r.violations) {
      if (RisesWithMass(x.constraint)) infeasible_from = std::min(infeasible_from, c);
    }
    if (r.segments.size() <= static_cast<std::size_t>(m_.objective.segment_index)) return pc;
    const SegmentResult& s = r.segments[m_.objective.segment_index];
    const double p = s.battery_current_start_a * s.vdc_max_v - s.rotors * voltage_dependent_w(s.point);
    pc.p_ca = p > 0 ? p : 0.0;
    if (energy_fixed && r.segments.size() == m_.segments.size()) {
      for (const SegmentResult& x : r.segments) pc.e_other_ca += x.energy_j;  // the stretch: 0 s
      for (int k = 0; k < m_.objective.segment_index; ++k) pc.e_before_ca += r.segments[k].energy_j;
    }
    pc.torque_nm = s.point.torque_nm;
    pc.omega_rad_s = s.point.omega_rad_s;
    return pc;
  };
  auto bound_of = [&](Piece& pc) {
    if (pc.ca >= infeasible_from) return -kInf;
    if (!(pc.p_ca > 0)) return kInf;
    const double by_reserve = t_fixed_max + std::max(0.0, ocv_integral_v * AhToCoulomb(pc.cb) - pc.e_other_ca) / pc.p_ca;
    if (by_reserve < target_s) return by_reserve;  // enough: the floor could only lower it
    if (!pc.floor_done && t_max < 1.0 && pc.omega_rad_s > 0) {
      const double v_min = std::max(v_cut, MinVoltageForThrottle(stretch_drive.drive, pc.torque_nm, pc.omega_rad_s,
                                                                 pack_lo.OcvV(1.0), t_max));
      pc.ocv_integral_smin_v = OcvIntegralUpperBound(pack_lo, SocBelowOcv(pack_lo, v_min, m_.battery.reserve_soc));
    }
    pc.floor_done = true;
    if (!std::isfinite(pc.ocv_integral_smin_v)) return by_reserve;
    const double by_throttle =
        t_fixed_max + std::max(0.0, pc.ocv_integral_smin_v * AhToCoulomb(pc.cb) - pc.e_before_ca) / pc.p_ca;
    return std::min(by_reserve, by_throttle);
  };
  std::vector<Piece> pieces;
  const int n0 = free_c ? kBoundPieces : 1;
  for (int i = 0; i < n0; ++i) {
    const double ca = c_lo + (c_hi - c_lo) * i / n0;
    const double cb = c_lo + (c_hi - c_lo) * (i + 1) / n0;
    pieces.push_back(piece_at(ca, cb));
  }
  while (true) {
    std::size_t worst = 0;
    for (std::size_t i = 1; i < pieces.size(); ++i) {
      if (bound_of(pieces[i]) > bound_of(pieces[worst])) worst = i;
    }
    const double ub = bound_of(pieces[worst]);
    if (!free_c || ub < target_s || runs >= kMaxBoundRuns || !std::isfinite(ub)) return ub;
    const Piece pc = pieces[worst];
    const double mid = 0.5 * (pc.ca + pc.cb);
    pieces[worst].cb = mid;
    pieces.push_back(piece_at(mid, pc.cb));
  }
}

void MissionEvaluator::FillPropNotes(MissionResult* r) {
  for (SegmentResult& s : r->segments) {
    if (s.prop_edge && s.prop_note.empty()) s.prop_note = s.prop_edge_eval.Message();
  }
}

MissionResult MissionEvaluator::Solve(double cutoff_score, bool explain, bool decide, bool search) const {
  MissionResult r = SolveContinuous(cutoff_score, explain, decide && std::isfinite(cutoff_score), search);
  if (explain) FillPropNotes(&r);
  return r;
}

// The propeller data window (PropellerPoint's prop_above_data, prop_below_data) decided without
// a solve. The speed of a segment at a fixed inflow rises with the vehicle's mass (its thrust
// per rotor does, M3 of search.cc, and the speed that gives it, M1). So a segment above the
// window at the lightest vehicle the continuous variables allow (the smallest capacity of a
// range, else the mission's) is above it at every capacity (prop_above_data is in RisesWithMass),
// and a hover below it at the heaviest (the largest capacity of a free range) is below it at
// every capacity. Segments with a free airspeed are left to the full solve (their inflow is not
// fixed). In the search many propellers hover inside their data and climb or cruise above it,
// or hover below it, each for a whole solve before.
bool MissionEvaluator::DataWindowRefuses(bool below_too, MissionResult* out) const {
  const MissionConstraints& k = m_.constraints;
  const bool free_capacity = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  for (int pass = 0; pass < 2; ++pass) {
    const bool above = pass == 0;
    if (above ? !(k.prop_above_data_factor > 0) : !(below_too && k.prop_below_data_factor > 0)) continue;
    const double capacity_ah = !m_.battery.capacity_ah         ? 0.0
                               : (!above && free_capacity) ? m_.battery.capacity_ah->hi
                                                           : m_.battery.capacity_ah->lo;
    const BatteryPack pack(PackAt(capacity_ah));
    const double mass_kg = fixed_mass_kg_ + pack.mass_kg();
    const double v_full = pack.OcvV(1.0);
    for (const Segment& s : m_.segments) {
      if (s.type == SegmentType::kShaft || (s.type == SegmentType::kCruise && s.airspeed_m_s.free())) continue;
      if (!above && s.type != SegmentType::kHover) continue;
      const GroupDrive& gd = groups_[s.group];
      const RotorLoad load = SegmentRotorLoad(m_, s, mass_kg, s.type == SegmentType::kCruise ? s.airspeed_m_s.lo : 0.0);
      double omega = 0;
      PropEvaluation ev;
      const double w_motor_max = std::max(gd.drive.NoLoadSpeed(v_full, 1.0), 1.0);
      if (!PropSpeedForThrust(*gd.prop, load.thrust_per_rotor_n, m_.rho_kg_m3, load.axial_airspeed_m_s,
                              4.0 * w_motor_max, &omega, &ev)) {
        continue;  // the full solve names the thrust
      }
      const double rpm = RadPerSecToRpm(omega);
      const double limit = above ? k.prop_above_data_factor * gd.prop->valid_range().rpm_hi
                                 : k.prop_below_data_factor * gd.prop->valid_range().rpm_lo;
      if (above ? rpm > limit : rpm < limit) {
        MissionResult r;
        r.capacity_ah = pack.capacity_ah();
        r.total_mass_kg = mass_kg;
        r.propulsion_mass_kg = mass_kg - m_.vehicle.mass_kg;
        r.violations.push_back(Violation{above ? "prop_above_data" : "prop_below_data", s.name, rpm, limit, "rpm", !above});
        r.min_slack = (above ? limit - rpm : rpm - limit) / limit;
        r.feasible = false;
        r.score = kInf;
        *out = std::move(r);
        return true;
      }
    }
  }
  return false;
}

// min_hover_throttle from below and min_thrust_to_weight from above, without a run (EarlyExit;
// only in a search: the result is infeasible, as the full search's would be, and says so with
// the constraint the proof rests on).
// min_hover_throttle is checked at the full-charge OCV (PropellerPoint), which does not depend
// on the capacity, with the hover's torque and speed, which rise with the mass (M3 of
// search.cc); the throttle that holds them rises with them (M2). So the hover throttle rises
// with the capacity: below the limit at a capacity C_h, it is below it at every capacity up to
// C_h. Without a capacity range the check at the mission's capacity decides it outright: the
// hover's mass, thrust and full-charge OCV depend on nothing else that is free (the stretch's
// duration and the cruise airspeeds do not enter them). In the search nearly every real ESC that
// passes the virtual one's bound fails this limit (issue 14: 96 % of the quadcopter's real-ESC
// evaluations), each for a whole 1-D search before.
// min_thrust_to_weight is checked at the run's end (FinishRun) with the lift rotors' thrust at
// full throttle at the terminal voltage there, which is at most the full-charge OCV (the OCV
// rises with the SOC, the sag only lowers it); that thrust rises with the voltage
// (ThrustToWeightMassCeilingKg), so every vehicle heavier than the ceiling m_t fails it, at any
// capacity, stretch and airspeed. The two together: when the hover throttle is below its limit
// at C_h, the lightest capacity whose vehicle weighs at least m_t (or the range's top, when none
// does), every capacity up to C_h fails the first and every capacity above it the second (its
// vehicle is heavier than m_t: the pack's mass rises with the capacity, PackAt). (The capacity-
// sized quadcopter's search: 3,834 of its 3,950 solves whose every point was infeasible failed
// both, each a whole 1-D search of infeasible points before.)
// with_weight = false: min_hover_throttle at the range's top alone (C_h = the top).
bool MissionEvaluator::HoverOrWeightRefuses(bool with_weight, MissionResult* out) const {
  const bool capacity_free = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  // The range's ends (the mission's own capacity, as Run flies it, without a range).
  const double c_lo = !m_.battery.capacity_ah ? 0.0 : m_.battery.capacity_ah->lo;
  const double c_hi = !m_.battery.capacity_ah ? 0.0 : capacity_free ? m_.battery.capacity_ah->hi : c_lo;
  auto refuse = [&](double capacity_ah, Violation v) {
    MissionResult r;
    const BatteryPack pack(PackAt(capacity_ah));
    r.capacity_ah = pack.capacity_ah();
    r.total_mass_kg = fixed_mass_kg_ + pack.mass_kg();
    r.propulsion_mass_kg = r.total_mass_kg - m_.vehicle.mass_kg;
    r.min_slack = v.at_least ? (v.value - v.limit) / v.limit : (v.limit - v.value) / v.limit;
    r.violations.push_back(std::move(v));
    r.feasible = false;
    r.score = kInf;
    *out = std::move(r);
    return true;
  };
  const double m_t = with_weight ? ThrustToWeightMassCeilingKg() : kInf;
  if (with_weight && !std::isfinite(m_t)) return false;  // the check below was made without it
  if (fixed_mass_kg_ + BatteryMassKg(c_lo) > m_t) {  // every capacity's vehicle is too heavy
    const double mass_kg = fixed_mass_kg_ + BatteryMassKg(c_lo);
    const double limit = m_.constraints.min_thrust_to_weight;
    return refuse(c_lo, Violation{"min_thrust_to_weight", "", limit * m_t / mass_kg, limit, "", true});
  }
  if (!(m_.constraints.min_hover_throttle > 0)) return false;
  // C_h: the range's top, or the lightest capacity of the range whose vehicle weighs at least
  // m_t (bisection keeping that side; the pack's mass rises with the capacity).
  double c_h = c_hi;
  if (capacity_free && fixed_mass_kg_ + BatteryMassKg(c_hi) > m_t) {
    double lo = c_lo, hi = c_hi;
    for (int i = 0; i < 60 && hi - lo > 1e-12 * c_hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (fixed_mass_kg_ + BatteryMassKg(mid) >= m_t ? hi : lo) = mid;
    }
    c_h = hi;
  } else if (with_weight) {
    return false;  // C_h is the top, where the check was made without the weight
  }
  const BatteryPack pack(PackAt(c_h));
  const double mass_kg = fixed_mass_kg_ + pack.mass_kg();
  const double v_full = pack.OcvV(1.0);
  for (const Segment& s : m_.segments) {
    if (s.type != SegmentType::kHover) continue;
    const GroupDrive& gd = groups_[s.group];
    const RotorLoad load = SegmentRotorLoad(m_, s, mass_kg, 0.0);
    double omega = 0;
    PropEvaluation ev;
    const double w_motor_max = std::max(gd.drive.NoLoadSpeed(v_full, 1.0), 1.0);
    if (!PropSpeedForThrust(*gd.prop, load.thrust_per_rotor_n, m_.rho_kg_m3, load.axial_airspeed_m_s,
                            4.0 * w_motor_max, &omega, &ev)) {
      continue;  // no hover point: the check says nothing here
    }
    AdjustPropEvaluation(gd.prop_adj, gd.parts.prop->diameter_m, &ev);
    const double throttle = gd.drive.Inverse(v_full, ev.torque_nm, omega).throttle;
    if (throttle < m_.constraints.min_hover_throttle) {
      return refuse(c_h, Violation{"min_hover_throttle", s.name, throttle, m_.constraints.min_hover_throttle, "", true});
    }
  }
  return false;
}

// The lift rotors' full-throttle thrust (FullThrottleAt) rises with the terminal voltage v: the
// throttle that holds a (torque, speed) falls as v rises (M2 of search.cc), so at full throttle
// the motor holds at least the torque at every speed from a higher v, and the equilibrium with
// the propeller's torque, which rises with the speed (M1), moves to a higher speed. Where the
// current rating caps it, the capped speed rises too: along the propeller's curve Irms depends
// only on the torque (eq 48) and IDC = PDC/VDC = C1*U*Irms/(kv*VDC) + C0*Irms (eqs 57, 59; no
// supply resistance) falls as VDC rises. The thrust rises with the speed (M1). The terminal
// voltage at every state of charge is at most the full-charge OCV, so the thrust from that OCV
// with no sag (times 1 + kCeilingMargin against the root finders' tolerance, 1e-10 of the
// speed) bounds the thrust-to-weight check of every run from above.
double MissionEvaluator::ThrustToWeightMassCeilingKg() const {
  constexpr double kCeilingMargin = 1e-6;
  if (!(m_.constraints.min_thrust_to_weight > 0) || lift_rotors_ <= 0 ||
      groups_[lift_group_].drive.esc().rsupply_ohm != 0.0) {
    return kInf;
  }
  FullThrottle ft;
  if (!FullThrottleFrom(BatteryPack(pack_base_).OcvV(1.0), 0.0, &ft)) return kInf;
  return lift_rotors_ * ft.thrust_per_rotor_n * (1.0 + kCeilingMargin) /
         (kStandardGravity * m_.constraints.min_thrust_to_weight);
}

// The early exits of a search (a finite cutoff, or `search`), each a proof stated at its block: a
// result (bounded out, infeasible, or the answer itself) in *out and true, or false to go on.
// The exits that end in an infeasible result need no cutoff, only a caller that reads nothing
// of an infeasible result but the constraint (Solve's search); the bounds need a finite cutoff.
bool MissionEvaluator::EarlyExit(double cutoff_score, bool explain, bool search, MissionResult* out) const {
  const bool capacity_free = m_.battery.capacity_ah && m_.battery.capacity_ah->free();
  const bool bounds = std::isfinite(cutoff_score);
  const bool screens = bounds || search;
  if (screens && DataWindowRefuses(true, out)) return true;
  if (screens && HoverOrWeightRefuses(false, out)) return true;
  if (screens && m_.objective.type == ObjectiveType::kMaxEndurance) {
    // One simulation decides most candidates of a search: infeasible before any stretch.
    // With a capacity range it is run at the smallest capacity (the lightest vehicle), and
    // decides only through constraints that no larger capacity can cure (RisesWithMass).
    ContinuousVars v0;
    v0.airspeed_m_s.assign(m_.segments.size(), 0.0);
    if (m_.battery.capacity_ah) v0.capacity_ah = m_.battery.capacity_ah->lo;
    bool airspeed_free = false;
    for (const Segment& s : m_.segments) airspeed_free |= s.type == SegmentType::kCruise && s.airspeed_m_s.free();
    if (!airspeed_free) {
      MissionResult r0 = Run(v0, 0.0, true);
      if (!r0.feasible) {
        if (!capacity_free) { *out = std::move(r0); return true; }
        for (const Violation& v : r0.violations) {
          if (RisesWithMass(v.constraint)) { *out = r0; return true; }
        }
      }
    }
  }
  // After the screening above, whose exits through constraints that a heavier ESC cannot cure
  // let the search skip the ESCs this one dominates (search.cc, R5); this one's rests on
  // min_hover_throttle, which a heavier ESC may meet, and does not. Only with a capacity range:
  // without one the run above (max_endurance) or below (min_energy) checks the mission's own
  // thrust-to-weight.
  if (screens && capacity_free && HoverOrWeightRefuses(true, out)) return true;
  if (bounds && m_.objective.type == ObjectiveType::kMaxEndurance) {
    const double ub = EnduranceUpperBound(-cutoff_score);
    if (-ub >= cutoff_score) {
      MissionResult r;
      r.bounded_out = true;
      r.score = -ub;
      *out = std::move(r);
      return true;
    }
  }
  if (std::isfinite(cutoff_score) && m_.objective.type == ObjectiveType::kMinEnergy &&
      std::all_of(groups_.begin(), groups_.end(), [&](const GroupDrive& g) {
        return g.drive.esc().c0 == 0.0 && (!capacity_free || g.drive.esc().rsupply_ohm == 0.0);
      })) {
    // min_energy with free cruise airspeeds: every other segment's energy does not depend on
    // them (terminal power N*PDC + P_avionics, and PDC = C1*U*I/kv does not depend on the
    // voltage when C0 = 0, eqs 57, 59), and a wing-borne cruise needs at least the propulsive
    // work T*d (electrical >= shaft >= thrust power) plus the avionics, T = W/(L/D) plus the
    // added drag at the lowest airspeed of the range (flight.h: the least thrust of the range).
    // With a capacity range the run is at the smallest capacity: a larger pack only adds mass,
    // so every segment's thrust, speed, torque and so its PDC (no supply resistance: the
    // terminal power does not depend on the pack's voltage) rise with it (M3 of search.cc), and
    // the wing-borne thrust W/(L/D) + added drag too: the same sum bounds the energy at every capacity of the range.
    ContinuousVars v0;
    v0.airspeed_m_s.assign(m_.segments.size(), 0.0);
    if (m_.battery.capacity_ah) v0.capacity_ah = m_.battery.capacity_ah->lo;
    bool airspeed_free = false;
    for (const Segment& s : m_.segments) airspeed_free |= s.type == SegmentType::kCruise && s.airspeed_m_s.free();
    const bool nothing_free = !airspeed_free && !capacity_free;
    const MissionResult r0 = Run(v0, 0.0, nothing_free);
    if (nothing_free && !r0.feasible) { *out = std::move(r0); return true; }  // nothing free: this is the answer
    if (r0.segments.size() == m_.segments.size()) {
      double e_lb = 0;
      for (std::size_t i = 0; i < m_.segments.size(); ++i) {
        const Segment& s = m_.segments[i];
        if (s.type == SegmentType::kCruise && s.airspeed_m_s.free()) {
          const double d = s.distance_m ? *s.distance_m : *s.duration_s * s.airspeed_m_s.lo;
          const double t_min = s.distance_m ? d / s.airspeed_m_s.hi : *s.duration_s;
          const double thrust =
              s.lift_to_drag > 0 ? SegmentRotorLoad(m_, s, r0.total_mass_kg, s.airspeed_m_s.lo).thrust_total_n : 0.0;
          double e_prop = thrust * d + m_.vehicle.avionics_power_w * t_min;
          const GroupDrive& gd = groups_[s.group];
          const MotorParams& mp = gd.drive.motor();
          const EscParams& ep = gd.drive.esc();
          // Tighter, cell by cell over the airspeed range (prop_bounds.h): momentum theory when
          // no stage creates energy, and this group's own drive at the pack's voltage range;
          // at the smallest capacity's mass, which every larger pack only adds to (M3).
          const bool lossy = mp.kt_nm_per_a <= MaxKtPerKe(mp.type) * mp.ke_v_s_per_rad && mp.rm_ohm >= 0 &&
                             mp.io_a >= 0 && mp.io1_a_s_per_rad >= 0 && ep.c0 >= 0 &&
                             ep.c1 + ep.c0 >= IdealIdcPerIrmsPerThrottle(mp.type);
          const CruisePropBound pb{gd.parts.prop, gd.prop, gd.prop_adj, lossy};
          const BatteryPack pack(PackAt(v0.capacity_ah));
          DischargeOptions dopt;
          if (m_.battery.cutoff_cell_v) dopt.cutoff_cell_v = *m_.battery.cutoff_cell_v;
          const CruiseDriveBound db{&gd.drive, pack.OcvV(1.0), pack.cutoff_v(dopt)};
          const double p_rotors = FreeCruiseRotorPowerLowerBoundW(m_, s, pb, &db, r0.total_mass_kg);
          e_prop = std::max(e_prop, (p_rotors + m_.vehicle.avionics_power_w) * t_min);
          e_lb += e_prop;
        } else {
          e_lb += r0.segments[i].energy_j;
        }
      }
      if (e_lb / 3600.0 >= cutoff_score) {
        MissionResult r;
        r.bounded_out = true;
        r.score = e_lb / 3600.0;
        *out = std::move(r);
        return true;
      }
      if (nothing_free) {
        // Nothing to optimise: r0 (feasible, so the screening never stopped it) is the very
        // simulation the code below would run again (WithEndurance = Run for min_energy).
        MissionResult r = r0;
        if (explain) {
          Summarize(&r);
          AddWarnings(&r);
        }
        *out = std::move(r);
        return true;
      }
    }
  }
  return false;
}

std::vector<MissionEvaluator::FreeVar> MissionEvaluator::FreeVariables() const {
  std::vector<FreeVar> free;
  if (m_.battery.capacity_ah && m_.battery.capacity_ah->free()) {
    free.push_back({-1, m_.battery.capacity_ah->lo, m_.battery.capacity_ah->hi});
  }
  for (std::size_t i = 0; i < m_.segments.size(); ++i) {
    const Segment& s = m_.segments[i];
    if (s.type == SegmentType::kCruise && s.airspeed_m_s.free()) {
      free.push_back({static_cast<int>(i), s.airspeed_m_s.lo, s.airspeed_m_s.hi});
    }
  }
  return free;
}

ContinuousVars MissionEvaluator::VarsAt(const std::vector<FreeVar>& free, const double* x) const {
  ContinuousVars v;
  v.airspeed_m_s.assign(m_.segments.size(), 0.0);
  if (m_.battery.capacity_ah) v.capacity_ah = m_.battery.capacity_ah->lo;
  for (std::size_t i = 0; i < free.size(); ++i) {
    const double val = free[i].lo + std::clamp(x[i], 0.0, 1.0) * (free[i].hi - free[i].lo);
    if (free[i].segment < 0) v.capacity_ah = val;
    else v.airspeed_m_s[free[i].segment] = val;
  }
  return v;
}

MissionResult MissionEvaluator::SolveContinuous(double cutoff_score, bool explain, bool decide, bool search) const {
  if (MissionResult early; EarlyExit(cutoff_score, explain, search, &early)) return early;
  const std::vector<FreeVar> free = FreeVariables();  // each scaled to [0, 1]
  if (free.size() == 1) return SolveOneFree(free, cutoff_score, explain, decide);
  if (free.size() > 1) return SolveManyFree(free, cutoff_score, explain, decide);
  // decide: a feasible point that beats the cutoff answers the caller (Solve).
  MissionResult r = WithEndurance(VarsAt(free, nullptr), decide ? cutoff_score : -kInf);
  if (decide && r.feasible && r.score < cutoff_score) return r;
  if (explain) {
    Summarize(&r);
    AddWarnings(&r);
  }
  return r;
}

// One free variable (the usual case: the capacity, or one cruise airspeed): a bracketed 1-D
// search, which also finds an optimum that sits on a constraint boundary (a heavier pack breaking
// a current or thrust-to-weight limit), where COBYLA tends to end just on the infeasible side and
// fall back to its coarse start.
MissionResult MissionEvaluator::SolveOneFree(const std::vector<FreeVar>& free, double cutoff_score, bool explain,
                                             bool decide) const {
  auto enough = [&](const MissionResult& r) { return decide && r.feasible && r.score < cutoff_score; };
  const double decide_cutoff = decide ? cutoff_score : -kInf;  // for WithEndurance
  auto vars_at = [&](const double* x) { return VarsAt(free, x); };
  // With a cutoff (max_endurance, the capacity free): after the grid, the bound of
  // EnduranceUpperBound over the golden section's bracket decides whether it can still
  // produce a score below the cutoff.
  const bool bound_bracket = std::isfinite(cutoff_score) && m_.objective.type == ObjectiveType::kMaxEndurance &&
                             free[0].segment < 0;
  // min_energy with the capacity free and a voltage-independent terminal power (C0 = 0, no
  // supply resistance, as in the check above): every segment's energy rises with the
  // capacity (M3), so the energy at the bracket's low end bounds every point of it.
  const bool energy_bracket = std::isfinite(cutoff_score) && m_.objective.type == ObjectiveType::kMinEnergy &&
                              free[0].segment < 0 &&
                              std::all_of(groups_.begin(), groups_.end(), [](const GroupDrive& g) {
                                return g.drive.esc().c0 == 0.0 && g.drive.esc().rsupply_ohm == 0.0;
                              });
  // Deciding (only whether some point beats the cutoff): the grid from the largest capacity
  // down for max_endurance, where a larger pack is the usual optimum. The order changes only
  // how soon a point that beats the cutoff is met, not which point is the grid's best.
  const bool top_first_decides = m_.objective.type == ObjectiveType::kMaxEndurance && free[0].segment < 0;
  auto bounded = [&](const MissionResult& grid_best, double a, double b) {
    if (grid_best.feasible && grid_best.score < cutoff_score) return false;
    if (energy_bracket) {
      const MissionResult ra = Run(vars_at(&a), 0.0);
      return ra.segments.size() == m_.segments.size() && ra.energy_wh >= cutoff_score;
    }
    if (!bound_bracket) return false;
    const double ub = EnduranceUpperBound(-cutoff_score, free[0].lo + a * (free[0].hi - free[0].lo),
                                          free[0].lo + b * (free[0].hi - free[0].lo));
    return -ub >= cutoff_score;
  };
  MissionResult r =
      SolveOneVariable([&](double x) { return WithEndurance(vars_at(&x), decide_cutoff); }, bounded, enough,
                       decide && top_first_decides);
  if (enough(r)) return r;
  if (r.bounded_out) return r;
  if (!explain) return r;
  std::ostringstream msg;
  msg << "bracketed 1-D search (9-point grid, golden section to 1e-6 of the range); "
      << (free[0].segment < 0 ? std::string("capacity_ah")
                              : m_.segments[free[0].segment].name + ".airspeed_m_s")
      << " = " << Num(free[0].segment < 0 ? r.capacity_ah : r.segments[free[0].segment].airspeed_m_s, 6);
  r.solver = msg.str();
  Summarize(&r);
  AddWarnings(&r);
  return r;
}

// Several free variables: a coarse grid (5 levels per variable, at most 125 points) picks the
// start; COBYLA (derivative-free: the objective passes through tabulated propeller data) polishes it.
MissionResult MissionEvaluator::SolveManyFree(const std::vector<FreeVar>& free, double cutoff_score, bool explain,
                                              bool decide) const {
  auto enough = [&](const MissionResult& r) { return decide && r.feasible && r.score < cutoff_score; };
  const double decide_cutoff = decide ? cutoff_score : -kInf;  // for WithEndurance
  auto vars_at = [&](const double* x) { return VarsAt(free, x); };
  const int n = static_cast<int>(free.size());
  const int levels = 5;
  int total = 1;
  for (int i = 0; i < n && i < 3; ++i) total *= levels;
  Eigen::VectorXd best_x = Eigen::VectorXd::Constant(n, 0.5);
  double best_score = kInf, best_slack = -kInf;
  std::vector<double> x(n, 0.5);
  for (int g = 0; g < total; ++g) {
    int code = g;
    for (int i = 0; i < n; ++i) {
      x[i] = i < 3 ? (code % levels) / double(levels - 1) : 0.5;
      code /= levels;
    }
    MissionResult r = WithEndurance(vars_at(x.data()), decide_cutoff);
    if (enough(r)) return r;
    const bool better = r.feasible ? r.score < best_score
                                   : (best_score == kInf && r.min_slack > best_slack);
    if (better) {
      best_score = r.feasible ? r.score : kInf;
      best_slack = r.min_slack;
      best_x = Eigen::Map<Eigen::VectorXd>(x.data(), n);
    }
  }
  Problem p;
  p.name = "combination continuous variables";
  p.num_variables = n;
  p.initial_point = best_x;
  p.lower_bounds = Eigen::VectorXd::Zero(n);
  p.upper_bounds = Eigen::VectorXd::Ones(n);
  for (const FreeVar& v : free) {
    p.variable_names.push_back(v.segment < 0 ? "capacity_ah" : m_.segments[v.segment].name + ".airspeed_m_s");
  }
  // Scale of the objective: the grid's best score (so that the solver sees O(1) values).
  const double scale = std::isfinite(best_score) && best_score != 0 ? std::fabs(best_score) : 1.0;
  // NLopt asks for the objective and the constraint at the same x one after the other: one
  // simulation serves both.
  Eigen::VectorXd memo_x;
  double memo_score = 0, memo_slack = 0;
  auto at = [&](const Eigen::VectorXd& xv) {
    if (memo_x.size() != xv.size() || memo_x != xv) {
      const MissionResult r = WithEndurance(vars_at(xv.data()));
      memo_x = xv;
      memo_score = std::isfinite(r.score) ? r.score / scale : 1e3;
      memo_slack = std::isfinite(r.min_slack) ? r.min_slack : -1.0;
    }
  };
  p.objective = [&](const Eigen::VectorXd& xv, Eigen::VectorXd*) {
    at(xv);
    return memo_score;
  };
  p.num_inequality_constraints = 1;
  p.inequality_names = {"-min constraint slack"};
  p.inequality_constraints = [&](const Eigen::VectorXd& xv, Eigen::VectorXd* g, Eigen::MatrixXd*) {
    at(xv);
    (*g)[0] = -memo_slack;
  };
  SolverOptions o;
  o.algorithm = "nlopt_cobyla";
  o.relative_tolerance = 1e-6;
  o.max_evaluations = 80;
  o.max_solver_time_in_seconds = 10.0;
  const SolverResult sr = dynosize::Solve(p, o);
  Eigen::VectorXd xs = best_x;
  if (sr.x.size() == n && sr.x.allFinite()) xs = sr.x;
  MissionResult r = WithEndurance(vars_at(xs.data()));
  const MissionResult grid = WithEndurance(vars_at(best_x.data()));
  if (!(r.feasible && r.score <= grid.score) && grid.feasible) r = grid;  // never worse than the grid
  if (!explain) return r;
  std::ostringstream msg;
  msg << sr.BriefReport();
  for (int i = 0; i < n; ++i) msg << (i ? ", " : "; ") << p.variable_names[i] << " = "
                                  << Num(free[i].lo + std::clamp(xs[i], 0.0, 1.0) * (free[i].hi - free[i].lo), 6);
  r.solver = msg.str();
  Summarize(&r);
  AddWarnings(&r);
  return r;
}

MissionResult MissionEvaluator::Simulate(const ContinuousVars& vars) const {
  MissionResult r = WithEndurance(vars);
  FillPropNotes(&r);
  Summarize(&r);
  AddWarnings(&r);
  return r;
}

double MissionEvaluator::WindingTempC(const OperatingPoint& p, int group) const {
  constexpr double kAlphaCuPerK = 0.00393;  // copper, at 20-25 C (IEC 60028)
  constexpr double kRmReferenceC = 25.0;    // datasheet resistance at room temperature (assumed)
  constexpr double kRunawayTempC = 1000.0;  // "no steady state": far above any limit, finite
  const MotorParams& mp = groups_[group].drive.motor();
  const double rth_k_per_w_ = groups_[group].rth_k_per_w;
  const double kp = MaxKtPerKe(mp.type);
  const double i = p.irms_a;
  const double p_cu_ref = kp * mp.rm_ohm * i * i;              // copper loss at Rm, W
  // The motor's own no-load loss: its shaft power is the propeller's plus the gear loss, which
  // heats the gearbox, not the winding (model/gear.h; direct drive: pmech_w itself).
  const Gear& gear = groups_[group].parts.motor->gear;
  const double p_shaft = gear.geared() ? MotorShaftOf(p.omega_rad_s, p.torque_nm, gear).power_w : p.pmech_w;
  const double p_other = std::max(0.0, p.pac_w - p_shaft - p_cu_ref);  // no-load loss, W
  const double t_air = m_.air_temperature_c;
  // T - t_air = Rth*(p_cu_ref*(1 + a*(T - T_ref)) + p_other), linear in T.
  const double denom = 1.0 - kAlphaCuPerK * rth_k_per_w_ * p_cu_ref;
  if (!(denom > 0.0)) return kRunawayTempC;
  const double rise = rth_k_per_w_ * (p_cu_ref * (1.0 + kAlphaCuPerK * (t_air - kRmReferenceC)) + p_other) / denom;
  return std::min(t_air + std::max(rise, 0.0), kRunawayTempC);
}

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
    const bool done = std::fabs(next - v) < 1e-9 * ocv;
    v = next;
    if (done) break;
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
      r->warnings.push_back("segment '" + v.segment + "': throttle " + Num(100 * v.value, 3) +
                            " % above the " + Num(100 * v.limit, 3) +
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
        r->warnings.push_back("segment '" + s.name + "': current " + Num(i, 3) + " A is " +
                              Num(100 * i / rating, 3) + " % of the " + what + " rating " +
                              Num(rating, 3) + " A");
      }
    };
    near("motor", mp.max_current_a);
    near("ESC", ep.max_current_a);
    if (s.throttle_max > ep.tr_sat) {
      r->warnings.push_back("segment '" + s.name + "': ESC in saturation (throttle up to " +
                            Num(100 * s.throttle_max, 3) + " % > knee " + Num(100 * ep.tr_sat, 3) +
                            " %): the speed per throttle step falls");
    }
    if (s.type != SegmentType::kShaft && p.throttle > 0 && p.throttle <= 1) {
      // On the segment's throttle line the efficiency peaks at MaxEfficiencySpeed (eq 14
      // analogue); running well above that speed means a light load for this motor.
      const double w_opt = drive.MaxEfficiencySpeed(p.vdc_v, p.throttle);
      const OperatingPoint best = drive.AtSpeed(p.vdc_v, p.throttle, w_opt);
      if (p.omega_rad_s > w_opt && p.eta_system < best.eta_system - 0.10) {
        r->warnings.push_back("segment '" + s.name + "': motor running below the current of "
                              "optimal efficiency (" + Num(p.irms_a, 3) + " A vs " +
                              Num(best.irms_a, 3) + " A, system efficiency " +
                              Num(100 * p.eta_system, 3) + " % vs " + Num(100 * best.eta_system, 3) +
                              " %): a smaller motor would do");
      }
    }
    if (p.throttle > 0 && p.throttle < 0.2) {
      r->warnings.push_back("segment '" + s.name + "': throttle only " + Num(100 * p.throttle, 3) +
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
                            "ratings " + Num(mp.max_power_w, 3) + " W, " + Num(mp.max_current_a, 3) +
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
