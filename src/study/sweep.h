// Trade studies: a mission swept over a full-factorial grid of values set at
// JSON paths of its document, each grid point flown by the catalog search (search.h).
//
// A grid point is the mission document with the point's values set (MissionAt), read by the
// mission's own reader (ParseMission: its rules apply) and searched (SearchCatalog). A point
// whose values break a mission rule, or that no combination flies, is a row with its reason, not
// an error. RunPoint is a pure function of (mission document, catalog, grid, index, options):
// the same row wherever it runs (a thread of RunSweep, or one task of a distributed study).
//
// Grid order: the last key varies fastest (index = ((i_0 * n_1) + i_1) * n_2 + i_2 ...), as
// nested loops over the keys in the order given.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/unmet_requirement.h"

namespace dynosize::study {

// Grids larger than this need the caller's confirmation (the CLI's --yes).
inline constexpr std::size_t kLargeGridPoints = 1000000;

// One swept key: a JSON path into the mission ("vehicle.mass_kg", "segments[2].duration_s")
// and its values in order (numbers, or strings / booleans for keys that hold them).
struct VaryKey {
  std::string key;
  std::vector<Json> values;
};

// Parses "KEY=START:STOP:STEP" (START, START+STEP, ... up to STOP within a step's 1e-9: STEP
// non-zero and pointing from START to STOP; written with the decimals of START and STEP, so
// 0.1 steps give 0.3, not 0.30000000000000004; integers when all three are) or
// "KEY=v1,v2,v3" (numbers where they parse as one, else strings; true/false as booleans).
// UsageError naming the spec and the rule.
VaryKey ParseVary(const std::string& spec);

// Checks the keys against the mission document (its JSON as read, before ParseMission):
//  - each path exists up to its last step (else "unknown key", with the nearest valid keys);
//  - its last step names a number, string or boolean (not an object or array), or a key the
//    document does not hold but its object may (the mission's reader decides);
//  - a value's type matches the one held (a number for a number);
//  - no key is given twice;
//  - at least one of each key's values, set alone, gives a mission its reader accepts (else the
//    key cannot be set: the reader's rule for the first value).
// UsageError (one line: the key, the value, the rule).
void CheckKeys(const Json& mission_doc, const std::string& mission_name, const std::vector<VaryKey>& keys);

// The number of grid points (the product of the value counts); UsageError when it overflows.
std::size_t GridSize(const std::vector<VaryKey>& keys);

// A sweep checked before it runs (the CLI and the Python module make the same checks): the
// mission document as read, its name in messages, the keys and the grid's size.
struct SweepPlan {
  Json doc;
  std::string name;
  std::vector<VaryKey> keys;
  std::size_t points = 0;
};

// The mission read by its reader (ParseMission), at least one key, the grid within
// kLargeGridPoints unless allow_large (the CLI's --yes), then CheckKeys; UsageError otherwise.
SweepPlan PlanSweep(Json mission_doc, std::string mission_name, std::vector<VaryKey> keys, bool allow_large);

// The missions of the plan's grid points that parse (one that does not is a "failed" row of
// RunSweep): the catalog of a sweep holds the sized propellers any of them offers
// (api::MissionCatalog).
std::vector<Mission> PointMissions(const SweepPlan& plan);

// The values of grid point `index` (< GridSize), one per key.
std::vector<Json> GridPoint(const std::vector<VaryKey>& keys, std::size_t index);

// The mission document with point[i] set at keys[i].key; UsageError (unknown key, the nearest
// valid keys) when a path is not in the document.
Json MissionAt(const Json& mission_doc, const std::vector<VaryKey>& keys, const std::vector<Json>& point);

// One pick of a grid point's search (rank 1 = the best).
struct SweepPick {
  int rank = 1;
  std::string objective_unit;       // "min", "Wh" or "%" (DisplayUnit without its space)
  std::vector<std::string> groups;  // the propulsion groups' names ("" for a mission without)
  bool feasible = false;
  // The objective in the unit the CLI prints (min, Wh, %; DisplayObjective) and its range under
  // the data-uncertainty model (optimize's objective_range, AddObjectiveRange): low/high NaN
  // where that end cannot fly.
  double objective = 0, objective_low = 0, objective_high = 0;
  std::vector<std::string> motor, esc, prop;  // per propulsion group (one without groups)
  std::string battery;
  int cells = 0;
  double capacity_ah = 0, total_mass_kg = 0, thrust_to_weight = 0;
  // The limit that holds the design: for a feasible pick of a max_endurance mission the
  // constraint that ends the stretched segment (reserve_soc when the pack runs down), else the
  // tightest segment limit ("" when none is within 10 % of its limit); for an infeasible one (a
  // relaxed thrust-to-weight, SearchResult::relaxed_constraint) the constraint it breaks.
  std::string binding_limit;
};

struct SweepRow {
  std::size_t index = 0;
  std::vector<Json> values;  // one per key
  // "ok" (picks found), "failed" (reason: a mission rule broken, nothing flies) or "stopped"
  // (the search was stopped before it finished: RunSweep leaves such rows out).
  std::string status;
  std::string reason;
  std::vector<SweepPick> picks;  // best first, at most PointOptions::top
  // "failed" because nothing flies: the requirements no part of the catalog meets
  // (SearchResult::no_design_because, optimization/no_design.h); `reason` lists them too.
  std::vector<UnmetRequirement> no_design_because;
  double seconds = 0;            // the point's wall time (not part of its result)
};

struct PointOptions {
  int top = 1;             // picks per point (SearchOptions::top_n)
  int search_threads = 1;  // the search's threads (the answer does not depend on it)
  bool distinct_designs = true;  // as optimize (SearchOptions::distinct_designs)
  // A stop request (SearchOptions::stop, deadline): a point stopped mid-search is "stopped".
  const std::atomic<bool>* stop = nullptr;
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
};

// Grid point `index`: MissionAt, ParseMission (mission_name in its messages), SearchCatalog.
// UsageError when index >= GridSize(keys) or a key's path is not in the document (MissionAt);
// the other checks of CheckKeys are the caller's (RunSweep makes them): without them a value
// the mission rejects is a failed row.
SweepRow RunPoint(const Json& mission_doc, const std::string& mission_name, const Catalog& catalog,
                  const std::vector<VaryKey>& keys, std::size_t index, const PointOptions& options);

struct SweepProgress {
  std::size_t done = 0, total = 0, failed = 0;
  double seconds = 0;
};

struct SweepOptions {
  PointOptions point;       // stop and deadline apply to the whole sweep
  int threads = 2;          // points run at once (one when the mission NeedsOneThread)
  // Called after each finished point (from the worker that finished it, one call at a time).
  std::function<void(const SweepProgress&)> progress;
};

struct SweepResult {
  std::vector<SweepRow> rows;  // the finished points, in grid order
  std::size_t total = 0;       // grid points
  bool interrupted = false;    // stopped (stop flag or deadline) before every point was done
  double seconds = 0;
};

// Every grid point (CheckKeys first), points[i] on `threads` workers, each point's search on one
// thread; rows identical to RunPoint's.
SweepResult RunSweep(const Json& mission_doc, const std::string& mission_name, const Catalog& catalog,
                     const std::vector<VaryKey>& keys, const SweepOptions& options);

}  // namespace dynosize::study
