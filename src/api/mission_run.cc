#include "api/mission_run.h"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "common/error.h"
#include "mission/flight.h"
#include "optimization/objective_range.h"

namespace dynosize::api {

namespace {

int CellsFor(const Mission& m, const BatteryEntry& b, int cells) {
  if (cells == 0) {
    if (m.battery.cells_min != m.battery.cells_max) {
      throw UsageError("--cells: the mission allows " + std::to_string(m.battery.cells_min) + "-" +
                       std::to_string(m.battery.cells_max) + " cells in series: say which");
    }
    cells = m.battery.cells_min;
  }
  if (cells % b.cells_series != 0) {
    throw UsageError("--cells " + std::to_string(cells) + ": battery '" + b.id + "' has " +
                     std::to_string(b.cells_series) + " cells in series; give a multiple");
  }
  return cells;
}

// The parts of every group: the mission's fixed ones, --pick GROUP=MOTOR,ESC,PROP, and
// --motor/--esc/--prop for the one group left (or for a mission without groups).
void ChooseParts(const Mission& m, const Catalog& cat, const EvaluateRequest& o, Combination* c) {
  const bool single = !o.motor_id.empty() || !o.esc_id.empty() || !o.prop_id.empty();
  if (single && (o.motor_id.empty() || o.esc_id.empty() || o.prop_id.empty())) {
    throw UsageError("--motor, --esc and --prop go together (one group's parts)");
  }
  if (m.groups.empty()) {
    if (!o.picks.empty()) {
      throw UsageError("--pick " + o.picks.front() + ": the mission has no propulsion groups; use --motor, --esc, --prop");
    }
    if (!single) throw UsageError("--motor, --esc and --prop are required");
    c->motor = &cat.motor(o.motor_id);
    c->esc = &cat.esc(o.esc_id);
    c->prop = &cat.prop(o.prop_id);
    return;
  }
  c->groups.assign(m.groups.size(), GroupParts{});
  for (int g = 0; g < GroupCount(m); ++g) c->groups[g] = FixedGroupParts(m, cat, g);
  for (const std::string& pick : o.picks) {
    const auto eq = pick.find('=');
    const auto c1 = pick.find(',', eq == std::string::npos ? 0 : eq);
    const auto c2 = c1 == std::string::npos ? c1 : pick.find(',', c1 + 1);
    if (eq == std::string::npos || c1 == std::string::npos || c2 == std::string::npos ||
        pick.find(',', c2 + 1) != std::string::npos) {
      throw UsageError("--pick \"" + pick + "\": must be GROUP=MOTOR,ESC,PROP");
    }
    const std::string name = pick.substr(0, eq);
    auto it = std::find_if(m.groups.begin(), m.groups.end(), [&](const PropulsionGroup& x) { return x.name == name; });
    if (it == m.groups.end()) {
      std::string valid;
      for (const auto& x : m.groups) valid += (valid.empty() ? "" : ", ") + x.name;
      throw UsageError("--pick \"" + pick + "\": no propulsion group '" + name + "' in the mission (valid: " + valid + ")");
    }
    GroupParts& p = c->groups[it - m.groups.begin()];
    p.motor = &cat.motor(pick.substr(eq + 1, c1 - eq - 1));
    p.esc = &cat.esc(pick.substr(c1 + 1, c2 - c1 - 1));
    p.prop = &cat.prop(pick.substr(c2 + 1));
  }
  std::vector<int> missing;
  for (int g = 0; g < GroupCount(m); ++g) {
    if (!c->groups[g].motor) missing.push_back(g);
  }
  if (single) {
    if (missing.size() != 1) {
      throw UsageError("--motor/--esc/--prop: the mission has " + std::to_string(missing.size()) +
                       " groups without parts; name each with --pick GROUP=MOTOR,ESC,PROP");
    }
    c->groups[missing.front()] = GroupParts{&cat.motor(o.motor_id), &cat.esc(o.esc_id), &cat.prop(o.prop_id)};
    missing.clear();
  }
  if (!missing.empty()) {
    throw UsageError("--pick: propulsion group '" + m.groups[missing.front()].name +
                     "' has no parts: give --pick " + m.groups[missing.front()].name + "=MOTOR,ESC,PROP");
  }
  const GroupParts lift = c->groups[std::max(0, LiftGroup(m))];
  c->motor = lift.motor;
  c->esc = lift.esc;
  c->prop = lift.prop;
}

}  // namespace

Combination ChooseCombination(const Mission& mission, const Catalog& cat, const EvaluateRequest& o) {
  Combination c;
  ChooseParts(mission, cat, o, &c);
  c.battery = &cat.battery(o.battery_id);
  c.cells = CellsFor(mission, *c.battery, o.cells);
  return c;
}

MissionResult EvaluateCombination(const Mission& mission, const Combination& c) {
  const MissionEvaluator ev(mission, c);
  MissionResult r = ev.Solve();
  AddObjectiveRange(mission, c, &r);  // objective_range and tiers (optimization/objective_range.h)
  return r;
}

std::chrono::steady_clock::time_point DeadlineAfter(double time_limit_s) {
  if (!(time_limit_s > 0)) {  // NaN too
    std::ostringstream v;
    v << time_limit_s;
    throw UsageError("--time-limit " + v.str() + ": must be a positive number of seconds");
  }
  constexpr double kNoDeadlineS = 1e9;  // about 30 years: beyond it, no deadline (no overflow)
  if (time_limit_s >= kNoDeadlineS) return std::chrono::steady_clock::time_point::max();
  return std::chrono::steady_clock::now() +
         std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(time_limit_s));
}

SearchOptions OptimizeSearchOptions(const OptimizeRequest& o) {
  SearchOptions so;
  so.deadline = DeadlineAfter(o.time_limit_s);
  so.top_n = o.top;
  so.threads = o.threads;
  so.distinct_designs = !o.variants;
  return so;
}

}  // namespace dynosize::api
