// Stage 3 of the catalog search (search_stages.h): per propeller the thrust, torque and figure
// of merit on a speed grid (R2, R6, R10: docs/search.md), and R0's frame rules for propellers.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "common/units.h"
#include "model/physics.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "optimization/search_stages.h"

namespace dynosize::search_internal {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

// Rule R0 (docs/search.md#r0): a propeller over the frame's diameter, or folding for lift, or
// excluded by the catalog fails whatever motor is chosen.
SizedPropOffer::SizedPropOffer(const Mission& m, const Catalog& cat) {
  const auto& props = cat.props();
  offered_.assign(static_cast<std::size_t>(GroupCount(m)), std::vector<char>(props.size(), 1));
  for (int g = 0; g < GroupCount(m); ++g) {
    std::set<std::string> ids;
    for (const PropSize& s : OfferedSizes(m, cat.prop_families(), g)) ids.insert(SizedPropId(s));
    for (std::size_t p = 0; p < props.size(); ++p) {
      if (IsSizedPropId(props[p].id) && ids.count(props[p].id) == 0) offered_[static_cast<std::size_t>(g)][p] = 0;
    }
  }
}

const char* PropFrameRule(const Mission& m, const SizedPropOffer& offer, int group, bool lifts, const Catalog& cat,
                          std::size_t prop_index) {
  if (!offer.Offered(group, prop_index)) return "prop_not_offered";
  const PropEntry& prop = cat.props()[prop_index];
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

// The grids read by R2, R6, R9, R10 (docs/search.md): thrust and torque must rise with speed
// on them (M1, docs/search.md#m1), else the propeller gets no thrust-based pruning.
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

}  // namespace dynosize::search_internal
