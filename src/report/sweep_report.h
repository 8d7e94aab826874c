// Output of `dynosize sweep` (study/sweep.h): the rows as JSON and as CSV, and the figures (the
// objective with its range against each varied key; a carpet plot of two keys).
#pragma once

#include <string>
#include <vector>

#include "common/json_file.h"
#include "mission/mission.h"
#include "study/sweep.h"

namespace dynosize::study {

// {"index", "values": {KEY: value, ...}, "status", "reason" (failed rows), "no_design_because"
//  (rows where nothing flies and some requirement is out of the catalog's reach:
//  UnmetRequirementsJson, report/mission_report.h), "picks": [{"rank",
//  "feasible", "objective", "objective_unit", "objective_range": [low, high] (null: that end
//  cannot fly), "parts": [{"group" (with groups), "motor", "esc", "prop"}], "battery", "cells",
//  "capacity_ah", "total_mass_kg", "thrust_to_weight", "binding_limit"}]}. The point's wall
// time is left out: the same point gives the same document wherever it runs.
Json SweepRowJson(const SweepRow& row, const std::vector<VaryKey>& keys);

// sweep --json: {"mission", "objective_type", "objective_unit", "keys": [{"key", "values"}],
// "points", "done", "failed", "interrupted", "seconds", "rows": [...]}.
Json SweepJson(const Mission& base, const SweepResult& result, const std::vector<VaryKey>& keys);

// The same document from rows already written by SweepRowJson (a distributed study gathers
// them from its tasks): `points` grid points, the rows in grid order.
Json SweepDocument(const Mission& base, const std::vector<VaryKey>& keys, std::size_t points, Json rows,
                   bool interrupted, double seconds);

// The CSV (header line first): index, the keys, status, rank, feasible, objective_<unit>,
// objective_low, objective_high, the parts (motor, esc, prop; GROUP_motor ... with groups),
// battery, cells, capacity_ah, total_mass_kg, thrust_to_weight, binding_limit, reason. One line
// per pick (--top N: N lines per point), one for a failed point (its reason, no pick).
std::string SweepCsv(const Mission& base, const SweepResult& result, const std::vector<VaryKey>& keys);

// objective_vs_<KEY>.png per key (the best pick's objective and its low-high range against the
// key, a line per combination of the other keys) and, with two keys or more, carpet_<A>_<B>.png
// for the first two (the other keys at their first value). Returns the PNG paths.
std::vector<std::string> WriteSweepFigures(const Mission& base, const SweepResult& result,
                                           const std::vector<VaryKey>& keys, const std::string& dir);

}  // namespace dynosize::study
