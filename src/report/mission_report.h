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

// pareto_front.png: every evaluated combination (objective vs propulsion mass), the
// non-dominated front and the top picks. Returns the PNG path.
std::string WriteParetoFigure(const Mission& mission, const SearchResult& s, const std::string& dir);

// efficiency_map_<segment>.png per distinct segment: the drive's system efficiency over torque
// and speed at the segment's end voltage with every segment's point marked. Returns the paths.
std::vector<std::string> WriteSegmentMaps(const Mission& mission, const Combination& c,
                                          const MissionResult& r, const std::string& dir);

}  // namespace dynosize
