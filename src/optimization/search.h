// The catalog search: the best N combinations (motor, ESC, propeller, battery cell,
// cells in series) for a mission, exactly as MissionEvaluator::Solve scores each, found by
// branch and bound with pruning rules that can only remove combinations that are infeasible or
// cannot enter the top N. With several free propulsion groups each picks its own motor, ESC and
// propeller (the joint search, joint_search.h, rule G2). The rules and their proofs are in docs/search.md;
// they rest on the monotonicity of the model (stated there) and are checked end to end by
// tests/optimization/search_test.cc against exhaustive evaluation.
#pragma once

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "optimization/search_options.h"
#include "optimization/search_result.h"
#include "optimization/search_summary.h"

namespace dynosize {

// Throws UsageError when a mission battery id is not in the catalog or no cell count in the
// range fits it.
SearchResult SearchCatalog(const Mission& mission, const Catalog& catalog,
                           const SearchOptions& options = {});

}  // namespace dynosize
