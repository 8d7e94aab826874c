#include "optimization/objective_range.h"

#include <algorithm>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "catalog/prop_credibility.h"
#include "catalog/prop_reynolds.h"
#include "common/text_format.h"
#include "optimization/credibility.h"

namespace dynosize {

void AddObjectiveRange(const Mission& m, const Combination& c, MissionResult* r) {
  ObjectiveRange& g = r->range;
  g = ObjectiveRange{};
  auto why = [](const EntryBase& e) { return std::string(e.tier_stated ? "source.tier" : "source.values"); };
  g.tiers.push_back({"motor", c.motor->id, c.motor->tier, why(*c.motor)});
  g.tiers.push_back({"ESC", c.esc->id, c.esc->tier, why(*c.esc)});
  g.tiers.push_back({"propeller", c.prop->id, c.prop->tier, why(*c.prop)});
  g.tiers.push_back({"battery", c.battery->id, c.battery->tier, why(*c.battery)});
  bool estimated = false, excluded = false;
  const MotorParams rated = ScenarioMotorParams(*c.motor, m, &estimated, &excluded);
  g.motor_rating = estimated ? "none in the source: " + FixedText(rated.max_power_w, 0) + " W, " +
                                   FixedText(rated.max_current_a, 1) +
                                   " A estimated from the mass and Kv (assumed; catalog/conventions.h)"
                   : excluded ? "none in the source: excluded (constraints.unrated_motors = exclude)"
                              : "catalog";
  // One scenario: its objective with the mission's limits relaxed to physics (*flies: that
  // run is feasible) and what it breaks under the mission's own limits.
  // Every propulsion group's motor and ESC without ratings (reserved: the pointers stay valid).
  constexpr double kNoRating = 1e300;  // finite: the motor counts as rated (no estimate)
  std::vector<MotorEntry> motors_free;
  std::vector<EscEntry> escs_free;
  motors_free.reserve(c.groups.size() + 1);
  escs_free.reserve(c.groups.size() + 1);
  auto free_motor = [&](const MotorEntry* e) {
    motors_free.push_back(*e);
    motors_free.back().params.max_current_a = motors_free.back().params.max_power_w = kNoRating;
    return &motors_free.back();
  };
  auto free_esc = [&](const EscEntry* e) {
    escs_free.push_back(*e);
    escs_free.back().params.max_current_a = kNoRating;
    return &escs_free.back();
  };
  BatteryEntry battery_free = *c.battery;
  battery_free.max_current_a = kNoRating;
  battery_free.peak_current_a = kNoRating;
  Combination c_free = c;
  c_free.motor = free_motor(c.motor);
  c_free.esc = free_esc(c.esc);
  c_free.battery = &battery_free;
  for (GroupParts& p : c_free.groups) {
    p.motor = p.motor == c.motor ? c_free.motor : free_motor(p.motor);
    p.esc = p.esc == c.esc ? c_free.esc : free_esc(p.esc);
  }
  auto solve = [&](DataScenario s, bool* flies, std::string* breaks) {
    Mission ms = m;
    ms.objective.ranking = s;
    const MissionResult x = MissionEvaluator(ms, c).Solve(std::numeric_limits<double>::infinity(), false);
    for (const Violation& v : x.violations) *breaks += (breaks->empty() ? "" : ", ") + v.constraint;
    *flies = x.feasible;
    if (x.feasible) return x.objective;
    ms.constraints.max_throttle = 1.0;
    ms.constraints.min_hover_throttle = 0.0;
    ms.constraints.allow_esc_saturation = true;
    ms.constraints.enforce_motor_power = false;
    ms.constraints.current_margin = 0.0;
    ms.constraints.min_thrust_to_weight = 0.0;  // design margins, not physics (mission.h)
    ms.constraints.max_winding_temp_c = std::numeric_limits<double>::infinity();
    const MissionResult y = MissionEvaluator(ms, c_free).Solve(std::numeric_limits<double>::infinity(), false);
    *flies = y.feasible;
    return y.objective;
  };
  bool pess_flies = false, opt_flies = false;
  std::string pess_breaks, opt_breaks;
  const double pess = solve(DataScenario::kPessimistic, &pess_flies, &pess_breaks);
  const double opt = solve(DataScenario::kOptimistic, &opt_flies, &opt_breaks);
  if (m.objective.ranking == DataScenario::kAsGiven) {
    g.as_given = r->objective;
    g.as_given_feasible = r->feasible;
  } else {
    Mission ms = m;
    ms.objective.ranking = DataScenario::kAsGiven;
    const MissionResult x = MissionEvaluator(ms, c).Solve(std::numeric_limits<double>::infinity(), false);
    g.as_given = x.objective;
    g.as_given_feasible = x.feasible;
    for (const Violation& v : x.violations) g.as_given_breaks += (g.as_given_breaks.empty() ? "" : ", ") + v.constraint;
  }
  // Larger is better for max_*: the pessimistic data give the low end; min_energy the high end.
  const bool larger_better = m.objective.type != ObjectiveType::kMinEnergy;
  const double lo_v = larger_better ? pess : opt, hi_v = larger_better ? opt : pess;
  const bool lo_ok = larger_better ? pess_flies : opt_flies, hi_ok = larger_better ? opt_flies : pess_flies;
  g.low_breaks = larger_better ? pess_breaks : opt_breaks;
  g.high_breaks = larger_better ? opt_breaks : pess_breaks;
  // A feasible result lies inside its range (the solver's tolerance could put it a hair
  // outside); an infeasible one's objective is not a value to bracket.
  const double mid = r->feasible ? r->objective : (lo_ok ? lo_v : hi_v);
  g.low = lo_ok ? std::min(lo_v, mid) : mid;
  g.high = hi_ok ? std::max(hi_v, mid) : mid;
  g.low_flies = lo_ok;
  g.high_flies = hi_ok;
  g.complete = lo_ok && hi_ok;
  const FmEnvelopeClass& k = FmEnvelopeFor(c.prop->diameter_m);
  const DataTier pt = g.tiers[2].tier;
  std::ostringstream b;
  if (pt == DataTier::kMeasured) {
    b << "propeller measured: shaft power +-" << FixedText(100 * kMeasuredPowerBand, 0) << " %";
  } else if (pt == DataTier::kManufacturerComputed) {
    b << "propeller manufacturer_computed: static FM x " << FixedText(kComputedFmRatio.min, 2) << "-"
      << FixedText(kComputedFmRatio.max, 2) << " (credible " << FixedText(kComputedFmRatio.median, 2) << "), measured/computed of "
      << kComputedFmRatio.pairs << " APC products, at most the p90 " << FixedText(k.p90, 2) << " of " << k.n_props
      << " measured props of " << k.label;
    if (c.prop->power_derate_factor > 1.0) {
      b << " (of the raw data: the catalog's derating x" << FixedText(c.prop->power_derate_factor, 3) << " counts toward it)";
    }
  } else {
    b << "propeller " << TierName(pt) << ": static FM held to the p10-p90 (" << FixedText(k.p10, 2) << "-"
      << FixedText(k.p90, 2) << ") of " << k.n_props << " measured props of " << k.label << " (credible: p50 "
      << FixedText(k.p50, 2) << ")";
  }
  double re_ratio = 1.0;  // the lowest speed over the data's low edge flown (Reynolds band)
  for (const SegmentResult& sr : r->segments) {
    if (sr.prop_edge) re_ratio = std::min(re_ratio, sr.prop_edge_eval.reynolds_ratio);
  }
  if (re_ratio < 1.0) {
    const ReynoldsLaw& law = DefaultReynoldsLaw();
    b << "; below its data's lowest speed (down to " << FixedText(re_ratio, 2) << "x) FM x (rpm/rpm_lo)^e, e "
      << FixedText(std::max(law.fm_p10, 0.0), 2) << "-" << FixedText(law.fm_p90, 2) << " (credible " << FixedText(law.fm_exp(), 2)
      << ", catalog/prop_reynolds.h)";
  }
  if (c.motor->datasheet_params) {
    b << "; motor Rm, Io: one motor's p10-p90 about the in-system law (docs/in-system-law.md); ESC RESC";
  } else {
    b << "; motor Rm, Io by their tier (" << TierName(g.tiers[0].tier) << "); ESC RESC";
  }
  if (ValueTier(*c.esc, "c0") == DataTier::kAssumed) b << " and C0 0-" << kAssumedEscC0Pessimistic;
  b << " within the prior's band";
  g.basis = b.str();
  g.computed = true;
}

}  // namespace dynosize
