// The objective range of a result under the data-uncertainty model (optimization/credibility.h):
// the combination flown again under the pessimistic, optimistic and as-given data scenarios.
// Above the evaluator (it runs MissionEvaluator::Solve), so that credibility.h, which the
// evaluator flies, stays below it.
#pragma once

#include "mission/mission.h"
#include "optimization/mission_eval.h"

namespace dynosize {

// Fills result->range: the objective re-solved under the pessimistic, optimistic and as-given
// scenarios (three more MissionEvaluator::Solve runs; the search calls it for its top N only).
void AddObjectiveRange(const Mission& mission, const Combination& combination, MissionResult* result);

}  // namespace dynosize
