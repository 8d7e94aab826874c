// Stage 2 of the catalog search (search_stages.h): the ESC classes and, per battery option, the
// ESCs rated for its voltage (R1, docs/search.md#r1).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "optimization/components.h"
#include "optimization/search_stages.h"

namespace dynosize::search_internal {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

// Rule R5 (docs/search.md#r5).
bool EscDominates(const EscEntry& a, const EscEntry& b) {
  // Its current rating at least b's for a segment of any duration (peak and continuous, issue 51).
  EscParams pa = a.params, pb = b.params;
  ApplyPeakRatings(&pa);
  ApplyPeakRatings(&pb);
  const bool current = pa.max_current_a >= pb.max_current_a && pa.continuous_current_a >= pb.continuous_current_a &&
                       (pa.peak_duration_s >= pb.peak_duration_s || pa.continuous_current_a >= pb.max_current_a);
  return EscMassKg(a) <= EscMassKg(b) && a.params.resc_ohm <= b.params.resc_ohm && current &&
         a.params.vdc_max_v >= b.params.vdc_max_v && a.params.vdc_min_v <= b.params.vdc_min_v;
}

// A result that breaks min_hover_throttle or prop_below_data (possibly among others) says
// nothing about a dominated ESC, whose higher throttle, or mass and so speed, may meet it; nor
// does a best infeasible point of a range (another point may fail only those two).
bool RulesOutDominatedEscs(const MissionResult& r) {
  if (!r.violations_everywhere) return false;
  for (const Violation& v : r.violations) {
    if (v.constraint == "min_hover_throttle" || v.constraint == "prop_below_data") return false;
  }
  return true;
}

// Rule R1 (docs/search.md#r1): an ESC rated below the pack's full-charge voltage, or whose least
// supply voltage is above the pack's cut-off (esc_min_voltage: the pack's terminal voltage reaches
// the cut-off; the evaluator checks the same), fails whatever else is chosen (both counted as
// esc_voltage); R0 (docs/search.md#r0): an ESC the catalog excludes.
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
        if (escs[i].params.vdc_max_v >= options[o].v_full && escs[i].params.vdc_min_v <= options[o].v_cut) {  // R1
          ok.push_back(i);
          t.min_mass_kg[o] = std::min(t.min_mass_kg[o], EscMassKg(escs[i]));
          t.max_mass_kg[o] = std::max(t.max_mass_kg[o], EscMassKg(escs[i]));
        }
      }
      std::sort(ok.begin(), ok.end(), [&](int a, int b) {
        const double ma = EscMassKg(escs[a]), mb = EscMassKg(escs[b]);
        if (ma != mb) return ma < mb;
        if (escs[a].params.resc_ohm != escs[b].params.resc_ohm) return escs[a].params.resc_ohm < escs[b].params.resc_ohm;
        return EscReachCurrentA(escs[a]) > EscReachCurrentA(escs[b]);
      });
      n_ok += static_cast<long long>(ok.size());
      std::vector<double> ascending, running_max;
      for (int i : ok) {
        ascending.push_back(EscReachCurrentA(escs[i]));
        running_max.push_back(std::max(running_max.empty() ? -kInf : running_max.back(), EscReachCurrentA(escs[i])));
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

}  // namespace dynosize::search_internal
