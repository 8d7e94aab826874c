// The catalog search's entry (search.h): one free group runs the stages (search_stages.h),
// several the joint search (joint_search.h); then the objective ranges and, when nothing
// reaches the thrust-to-weight, the search without that limit; when nothing flies, why
// (no_design.h).
#include "optimization/search.h"

#include "common/error.h"

#include <limits>
#include <set>
#include <string>
#include <utility>

#include "optimization/credibility.h"
#include "optimization/joint_search.h"
#include "optimization/no_design.h"
#include "optimization/objective_range.h"
#include "optimization/search_stages.h"

namespace dynosize {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One free group: stages 0-5 (R0-R11, G1); several: the joint search (G2, joint_search.h).
SearchResult SearchExactly(const Mission& m, const Catalog& cat, const SearchOptions& opt) {
  SearchResult out = FreeGroupCount(m) > 1 ? search_internal::JointSearch(m, cat, opt)
                                           : search_internal::SearchOneGroup(m, cat, opt, kInf, nullptr);
  for (RankedCombination& b : out.best) AddObjectiveRange(m, b.combination, &b.result);  // credibility.h
  return out;
}

}  // namespace

SearchResult SearchCatalog(const Mission& m, const Catalog& cat, const SearchOptions& opt) {
  // A searched group's sized propellers must be in the catalog (api/mission_catalog.h adds them):
  // otherwise the search would quietly leave them out.
  std::set<std::string> ids;
  for (const PropEntry& p : cat.props()) {
    if (IsSizedPropId(p.id)) ids.insert(p.id);
  }
  for (int g = 0; g < GroupCount(m); ++g) {
    for (const PropSize& size : OfferedSizes(m, cat.prop_families(), g)) {
      const std::string id = SizedPropId(size);
      if (ids.count(id) == 0) {
        throw UsageError(m.file + (m.groups.empty() ? ": $.vehicle" : ": $.propulsion." + GroupName(m, g)) +
                         ": the sized propeller " + id + " is not in the catalog searched (run the mission on api::MissionCatalog)");
      }
    }
  }
  SearchResult out = SearchExactly(m, cat, opt);
  // Stopped: what was found (nothing may mean "not yet"), not the relaxed search.
  if (out.interrupted || !out.best.empty()) return out;
  // Nothing flies: say which requirements nothing in the catalog meets (no_design.h).
  auto nothing = [&](SearchResult r) {
    if (!r.interrupted) r.no_design_because = UnmetRequirements(m, cat);
    return r;
  };
  if (!(m.constraints.min_thrust_to_weight > 0)) return nothing(std::move(out));
  // No combination reaches the thrust-to-weight (or nothing flies at all): the designer still
  // needs the candidates and how far each falls short. Search again without that limit and
  // return its best, each marked infeasible with the thrust-to-weight it reaches (computed by
  // Summarize at the mission's end, as the limit is checked).
  Mission relaxed = m;
  relaxed.constraints.min_thrust_to_weight = 0.0;
  SearchResult r = SearchExactly(relaxed, cat, opt);
  if (r.best.empty()) {
    out.interrupted = r.interrupted;  // the search without the limit did not finish
    return nothing(std::move(out));
  }
  for (RankedCombination& b : r.best) {
    MissionResult& x = b.result;
    x.feasible = false;
    x.violations.push_back(Violation{"min_thrust_to_weight", "", x.thrust_to_weight,
                                     m.constraints.min_thrust_to_weight, "", true});
  }
  r.relaxed_constraint = "min_thrust_to_weight";
  r.seconds += out.seconds;
  return r;
}

}  // namespace dynosize
