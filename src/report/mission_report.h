// Output of `evaluate` and `optimize`: one combination's mission result as JSON and as text,
// and the figures (Pareto front of the objective against propulsion mass; system-efficiency
// maps of a combination at each segment's voltage with the operating points marked).
#pragma once

#include <string>
#include <vector>

#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/mission_eval.h"
#include "optimization/search.h"

namespace dynosize {

// {"motor", "esc", "prop", "battery", "cells", "objective", "objective_type", "objective_unit",
//  "feasible", "segments": [...], "violations": [...], "warnings": [...], ...}
Json MissionResultJson(const Mission& mission, const Combination& c, const MissionResult& r);

// A human-readable report: objective, masses, one line per segment, limits, warnings.
std::string MissionResultText(const Mission& mission, const Combination& c, const MissionResult& r);

// The objective's axis label in figures ("endurance [min]", "energy drawn [Wh]", ...).
std::string ObjectiveLabel(const Mission& mission);

// For each result of a search, the ranks (1-based) of the other results whose objective ranges
// (ObjectiveRange low-high, credibility.h) overlap its own: not distinguishable on the data.
std::vector<std::vector<int>> IndistinguishableRanks(const SearchResult& s);

// optimize --json: {"results": [...each with "alternatives" and "indistinguishable_from"...],
// "designs", "interrupted", "bound_gap" (when interrupted), "searched", "pruned", "unsettled",
// "combinations", "pruned_by", "seconds", "relaxed_constraint", "no_design_because"}.
// no_design_because (always present; empty unless nothing flies): UnmetRequirementsJson.
Json SearchResultJson(const Mission& mission, const SearchResult& s);
// [{"requirement", "needed", "best_available", "unit", "components", "description",
//   "search_rule", "group"}, ...] (optimization/unmet_requirement.h; values in SI, in `unit`;
// a value that is not finite is null).
Json UnmetRequirementsJson(const std::vector<UnmetRequirement>& reasons);
// The text lines under "no combination of the catalog flies ...": one per requirement
// (UnmetRequirementText, indented), or one saying no single part falls short; "" when `reasons`
// does not apply (a result was found, or the search was stopped).
std::string NoDesignText(const SearchResult& s);
// The text lines of a result's alternatives and of the ranks it cannot be told from ("" if none).
std::string AlternativesText(const Mission& mission, const RankedCombination& r, const std::vector<int>& tied);
// The lines of an interrupted search: why, and the proven bound gap ("" when not interrupted).
std::string InterruptedText(const Mission& mission, const SearchResult& s, int top_n);

// The Pareto figure's data: every evaluated combination as (propulsion mass kg, objective in
// the unit reports print it, DisplayObjective), sorted by mass, and the non-dominated front
// among them (each point better than every lighter one). The web page draws the same.
struct ParetoPoints {
  std::vector<std::pair<double, double>> all, front;
};
ParetoPoints ParetoPointsOf(const Mission& mission, const SearchResult& s);

// pareto_front.png: every evaluated combination (objective vs propulsion mass), the
// non-dominated front and the top picks. Returns the PNG path.
std::string WriteParetoFigure(const Mission& mission, const SearchResult& s, const std::string& dir);

// efficiency_map_<segment>.png per distinct segment: the drive's system efficiency over torque
// and speed at the segment's end voltage with every segment's point marked. Returns the paths.
std::vector<std::string> WriteSegmentMaps(const Mission& mission, const Combination& c,
                                          const MissionResult& r, const std::string& dir);

}  // namespace dynosize
