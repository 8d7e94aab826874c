#include "study/sweep.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

#include "common/error.h"
#include "common/numbers.h"
#include "common/worker_threads.h"
#include "mission/mission.h"
#include "optimization/no_design.h"
#include "optimization/search.h"

namespace dynosize::study {

namespace {

// Values one key may hold: beyond, the spec is a typo (a step of 1e-12), not a study.
constexpr double kMaxValuesPerKey = 1e9;
// How far past STOP the last value of a range may fall, in steps (decimal steps such as 0.1
// are not exact in binary).
constexpr double kRangeStepTolerance = 1e-9;

[[noreturn]] void Usage(const std::string& spec, const std::string& rule) {
  throw UsageError("--vary " + spec + ": " + rule);
}

bool IsIntegerText(const std::string& s) {
  std::size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  if (i >= s.size() || s.size() - i > 18) return false;  // fits a long long
  for (; i < s.size(); ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
  }
  return true;
}

// A finite number written in full ("1e999", "nan", "3x": false).
bool ParseNumber(const std::string& s, double* v) {
  if (s.empty() || std::isspace(static_cast<unsigned char>(s[0]))) return false;
  char* end = nullptr;
  errno = 0;
  *v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && errno != ERANGE && std::isfinite(*v);
}

// Digits after the decimal point of a plain decimal ("0.25": 2); -1 with an exponent.
int Decimals(const std::string& s) {
  if (s.find_first_of("eE") != std::string::npos) return -1;
  const auto dot = s.find('.');
  return dot == std::string::npos ? 0 : static_cast<int>(s.size() - dot - 1);
}

Json ValueOf(const std::string& text) {
  double v = 0;
  if (IsIntegerText(text)) return Json(std::stoll(text));
  if (ParseNumber(text, &v)) return Json(v);
  if (text == "true") return Json(true);
  if (text == "false") return Json(false);
  return Json(text);
}

std::vector<Json> RangeValues(const std::string& spec, const std::string& a, const std::string& b,
                              const std::string& c) {
  double start = 0, stop = 0, step = 0;
  if (!ParseNumber(a, &start) || !ParseNumber(b, &stop) || !ParseNumber(c, &step)) {
    Usage(spec, "START:STOP:STEP must be three finite numbers");
  }
  if (step == 0) Usage(spec, "STEP must not be 0");
  const double steps = (stop - start) / step;
  if (!std::isfinite(steps)) Usage(spec, "the range has too many values");
  if (steps < -kRangeStepTolerance) {
    Usage(spec, std::string("STEP ") + c + " never reaches STOP " + b + " from START " + a + " (its sign is wrong)");
  }
  if (steps + 1 > kMaxValuesPerKey) Usage(spec, "the range has more than 10^9 values");
  const std::size_t n = static_cast<std::size_t>(std::floor(steps + kRangeStepTolerance)) + 1;
  const bool integers = IsIntegerText(a) && IsIntegerText(b) && IsIntegerText(c);
  const int decimals = std::max(Decimals(a), Decimals(c));
  const bool round = Decimals(a) >= 0 && Decimals(c) >= 0 && decimals <= 12;
  const double scale = std::pow(10.0, decimals);
  std::vector<Json> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (integers) {
      out.emplace_back(std::stoll(a) + static_cast<long long>(i) * std::stoll(c));
      continue;
    }
    double v = start + static_cast<double>(i) * step;
    if (round) v = std::round(v * scale) / scale;
    out.emplace_back(v);
  }
  return out;
}

// One step of a key's path: an object member or an array element.
struct PathStep {
  std::string name;      // member ("" for an element)
  std::size_t index = 0;
  bool element = false;
};

// "vehicle.mass_kg", "segments[2].duration_s" (an optional leading "$." as the reader's paths).
std::vector<PathStep> ParsePath(const std::string& key) {
  std::string k = key.rfind("$.", 0) == 0 ? key.substr(2) : key;
  std::vector<PathStep> out;
  std::size_t i = 0;
  auto bad = [&]() { Usage(key, "not a JSON path (vehicle.mass_kg, segments[2].duration_s)"); };
  while (i < k.size()) {
    if (k[i] == '[') {
      const auto close = k.find(']', i);
      if (close == std::string::npos || close == i + 1) bad();
      const std::string digits = k.substr(i + 1, close - i - 1);
      if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) bad();
      out.push_back({"", static_cast<std::size_t>(std::stoul(digits)), true});
      i = close + 1;
      if (i < k.size() && k[i] == '.') {
        ++i;
        if (i == k.size()) bad();
      } else if (i < k.size() && k[i] != '[') {
        bad();
      }
      continue;
    }
    const auto end = k.find_first_of(".[", i);
    const std::string name = k.substr(i, end == std::string::npos ? std::string::npos : end - i);
    if (name.empty()) bad();
    out.push_back({name, 0, false});
    i = end == std::string::npos ? k.size() : end;
    if (i < k.size() && k[i] == '.') {
      ++i;
      if (i == k.size()) bad();
    }
  }
  if (out.empty() || out.front().element) bad();
  return out;
}

std::string PathText(const std::vector<PathStep>& p, std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) {
    s += p[i].element ? "[" + std::to_string(p[i].index) + "]" : (i ? "." : "") + p[i].name;
  }
  return s;
}

// Every leaf of the document (number, string, boolean) as a path.
void LeafPaths(const Json& j, const std::string& prefix, std::vector<std::string>* out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      LeafPaths(it.value(), prefix.empty() ? it.key() : prefix + "." + it.key(), out);
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) LeafPaths(j[i], prefix + "[" + std::to_string(i) + "]", out);
  } else {
    out->push_back(prefix);
  }
}

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// The three valid keys nearest to `key` by edit distance.
std::string NearestKeys(const Json& doc, const std::string& key) {
  std::vector<std::string> paths;
  LeafPaths(doc, "", &paths);
  std::stable_sort(paths.begin(), paths.end(), [&](const std::string& x, const std::string& y) {
    return EditDistance(key, x) < EditDistance(key, y);
  });
  std::string s;
  for (std::size_t i = 0; i < paths.size() && i < 3; ++i) s += (i ? ", " : "") + paths[i];
  return s;
}

// The value at the path in `doc` (created when its last member is absent); CheckPath has
// checked the path.
Json& Slot(Json& doc, const std::vector<PathStep>& path) {
  Json* j = &doc;
  for (const PathStep& s : path) j = s.element ? &(*j)[s.index] : &(*j)[s.name];
  return *j;
}

const char* KindName(const Json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "true or false";
  return "a value";
}

// The path's last step's parent, or a usage error naming the first step that is not there.
const Json& CheckPath(const Json& doc, const VaryKey& k, const std::vector<PathStep>& path) {
  const Json* j = &doc;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const PathStep& s = path[i];
    const bool there = s.element ? (j->is_array() && s.index < j->size()) : (j->is_object() && j->contains(s.name));
    if (!there) {
      Usage(k.key, "unknown key: the mission has no " + PathText(path, i + 1) + " (nearest valid keys: " +
                       NearestKeys(doc, k.key) + ")");
    }
    j = s.element ? &(*j)[s.index] : &(*j)[s.name];
  }
  const PathStep& last = path.back();
  const bool fits = last.element ? (j->is_array() && last.index < j->size()) : j->is_object();
  if (!fits) {
    Usage(k.key, "unknown key: the mission has no " + PathText(path, path.size()) + " (nearest valid keys: " +
                     NearestKeys(doc, k.key) + ")");
  }
  return *j;
}

std::string WithoutName(const std::string& message, const std::string& name) {
  const std::string prefix = name + ": ";
  return message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
}

}  // namespace

VaryKey ParseVary(const std::string& spec) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0) Usage(spec, "must be KEY=START:STOP:STEP or KEY=v1,v2,...");
  VaryKey k;
  k.key = spec.substr(0, eq);
  ParsePath(k.key);  // its syntax
  const std::string rhs = spec.substr(eq + 1);
  if (rhs.empty()) Usage(spec, "no values after '='");
  if (rhs.find(':') != std::string::npos) {
    const auto c1 = rhs.find(':');
    const auto c2 = rhs.find(':', c1 + 1);
    if (c2 == std::string::npos || rhs.find(':', c2 + 1) != std::string::npos || rhs.find(',') != std::string::npos) {
      Usage(spec, "a range is START:STOP:STEP");
    }
    k.values = RangeValues(spec, rhs.substr(0, c1), rhs.substr(c1 + 1, c2 - c1 - 1), rhs.substr(c2 + 1));
    return k;
  }
  std::size_t from = 0;
  while (true) {
    const auto comma = rhs.find(',', from);
    const std::string v = rhs.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
    if (v.empty()) Usage(spec, "an empty value in the list");
    k.values.push_back(ValueOf(v));
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  return k;
}

void CheckKeys(const Json& mission_doc, const std::string& mission_name, const std::vector<VaryKey>& keys) {
  std::set<std::string> seen;
  for (const VaryKey& k : keys) {
    const std::vector<PathStep> path = ParsePath(k.key);
    const std::string canonical = PathText(path, path.size());
    if (!seen.insert(canonical).second) Usage(k.key, "the key is given twice");
    if (k.values.empty()) Usage(k.key, "no values");
    const Json& parent = CheckPath(mission_doc, k, path);
    const PathStep& last = path.back();
    const bool absent = !last.element && !parent.contains(last.name);
    if (!absent) {
      const Json& held = last.element ? parent[last.index] : parent[last.name];
      if (held.is_object() || held.is_array()) {
        std::vector<std::string> leaves;
        LeafPaths(held, canonical, &leaves);
        Usage(k.key, std::string("is ") + (held.is_object() ? "an object" : "an array") +
                         ": give one of its values (e.g. " + (leaves.empty() ? canonical : leaves.front()) + ")");
      }
      for (const Json& v : k.values) {
        const bool same = (held.is_number() && v.is_number()) || (held.is_string() && v.is_string()) ||
                          (held.is_boolean() && v.is_boolean()) || held.is_null();
        if (!same) Usage(k.key + "=" + v.dump(), std::string("the mission holds ") + KindName(held) + " here");
      }
    }
    // At least one value gives a mission the reader accepts (a key the document does not hold:
    // the reader decides whether its object may hold it).
    std::string first_rule;
    bool any = false;
    for (const Json& v : k.values) {
      try {
        ParseMission(MissionAt(mission_doc, {k}, {v}), mission_name);
        any = true;
        break;
      } catch (const DataError& e) {
        if (first_rule.empty()) first_rule = WithoutName(e.what(), mission_name);
      }
    }
    if (any) continue;
    if (absent) {
      Usage(k.key, "unknown key: the mission has no " + canonical + " and its reader refuses it (" + first_rule +
                       "; nearest valid keys: " + NearestKeys(mission_doc, k.key) + ")");
    }
    Usage(k.key, "no value gives a valid mission (the first, " + k.values.front().dump() + ": " + first_rule + ")");
  }
}

std::size_t GridSize(const std::vector<VaryKey>& keys) {
  std::size_t n = 1;
  for (const VaryKey& k : keys) {
    if (k.values.empty()) return 0;
    if (n > std::numeric_limits<std::size_t>::max() / k.values.size()) {
      throw UsageError("--vary: the grid has more points than can be counted");
    }
    n *= k.values.size();
  }
  return n;
}

SweepPlan PlanSweep(Json mission_doc, std::string mission_name, std::vector<VaryKey> keys, bool allow_large) {
  if (keys.empty()) throw UsageError("--vary: give at least one KEY=START:STOP:STEP or KEY=v1,v2,...");
  (void)ParseMission(mission_doc, mission_name);
  SweepPlan plan{std::move(mission_doc), std::move(mission_name), std::move(keys), 0};
  plan.points = GridSize(plan.keys);
  if (plan.points > kLargeGridPoints && !allow_large) {
    throw UsageError("--vary: the grid has " + std::to_string(plan.points) +
                     " points, over 10^6: give --yes to run it (or a coarser STEP)");
  }
  CheckKeys(plan.doc, plan.name, plan.keys);
  return plan;
}

std::vector<Mission> PointMissions(const SweepPlan& plan) {
  std::vector<Mission> out;
  for (std::size_t i = 0; i < plan.points; ++i) {
    try {
      out.push_back(ParseMission(MissionAt(plan.doc, plan.keys, GridPoint(plan.keys, i)), plan.name));
    } catch (const DataError&) {
      // RunSweep reports the point as failed
    }
  }
  return out;
}

std::vector<Json> GridPoint(const std::vector<VaryKey>& keys, std::size_t index) {
  std::vector<Json> out(keys.size());
  for (std::size_t i = keys.size(); i-- > 0;) {
    const std::size_t n = keys[i].values.size();
    out[i] = keys[i].values[index % n];
    index /= n;
  }
  return out;
}

Json MissionAt(const Json& mission_doc, const std::vector<VaryKey>& keys, const std::vector<Json>& point) {
  if (point.size() != keys.size()) throw InternalError("MissionAt: one value per key");
  Json doc = mission_doc;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::vector<PathStep> path = ParsePath(keys[i].key);
    CheckPath(doc, keys[i], path);  // a caller that skipped CheckKeys gets its usage error
    Slot(doc, path) = point[i];
  }
  return doc;
}

namespace {

SweepPick PickOf(const Mission& m, const SearchResult& s, std::size_t k) {
  const RankedCombination& b = s.best[k];
  const MissionResult& r = b.result;
  SweepPick p;
  p.rank = static_cast<int>(k) + 1;
  p.feasible = r.feasible;
  p.objective = DisplayObjective(m, r.objective);
  p.objective_unit = DisplayUnit(m) + 1;  // without the leading space
  p.objective_low = r.range.computed && r.range.low_flies ? DisplayObjective(m, r.range.low) : kNaN;
  p.objective_high = r.range.computed && r.range.high_flies ? DisplayObjective(m, r.range.high) : kNaN;
  for (int g = 0; g < GroupCount(m); ++g) {
    const GroupParts parts = b.combination.Parts(g);
    p.groups.push_back(GroupName(m, g));
    p.motor.push_back(parts.motor ? parts.motor->id : "");
    p.esc.push_back(parts.esc ? parts.esc->id : "");
    p.prop.push_back(parts.prop ? parts.prop->id : "");
  }
  p.battery = b.combination.battery ? b.combination.battery->id : "";
  p.cells = b.combination.cells;
  p.capacity_ah = r.capacity_ah;
  p.total_mass_kg = r.total_mass_kg;
  p.thrust_to_weight = r.thrust_to_weight;
  if (!r.feasible) {
    p.binding_limit = !s.relaxed_constraint.empty() ? s.relaxed_constraint
                      : r.violations.empty()        ? ""
                                                    : r.violations.front().constraint;
    return p;
  }
  // max_endurance: the limit that ends the stretched segment (the smallest slack of the checks
  // that fall with its duration, MissionResult::stretch_slacks).
  if (const char* ends = r.stretch_slacks.Worst()) {
    p.binding_limit = ends;
    return p;
  }
  double slack = std::numeric_limits<double>::infinity();
  for (const SegmentResult& seg : r.segments) {
    if (!seg.active_limit.empty() && seg.active_limit_slack < slack) {
      slack = seg.active_limit_slack;
      p.binding_limit = seg.active_limit;
    }
  }
  return p;
}

// A failed row's reason when nothing flies: the search's line, and each requirement no part of
// the catalog meets in short ("hover_thrust_per_rotor 1471 N > 52.1 N"; no_design.h).
std::string NothingFliesReason(const std::vector<UnmetRequirement>& reasons) {
  std::ostringstream o;
  o << "no combination of the catalog flies this mission within its constraints";
  for (std::size_t i = 0; i < reasons.size(); ++i) {
    const UnmetRequirement& r = reasons[i];
    o << (i ? "; " : ": ") << r.requirement << (r.group.empty() ? "" : " (" + r.group + ")") << " needs "
      << RequirementValueText(r.needed, r.unit) << " > best " << RequirementValueText(r.best_available, r.unit);
  }
  return o.str();
}

}  // namespace

SweepRow RunPoint(const Json& mission_doc, const std::string& mission_name, const Catalog& catalog,
                  const std::vector<VaryKey>& keys, std::size_t index, const PointOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  if (index >= GridSize(keys)) {
    throw UsageError("grid point " + std::to_string(index) + ": the grid has " + std::to_string(GridSize(keys)) +
                     " points (0 to " + std::to_string(GridSize(keys)) + " - 1)");
  }
  SweepRow row;
  row.index = index;
  row.values = GridPoint(keys, index);
  auto done = [&](const std::string& status, const std::string& reason) {
    row.status = status;
    row.reason = reason;
    row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return row;
  };
  Mission m;
  try {
    m = ParseMission(MissionAt(mission_doc, keys, row.values), mission_name);
  } catch (const DataError& e) {
    return done("failed", WithoutName(e.what(), mission_name));
  }
  SearchOptions so;
  so.top_n = options.top;
  so.threads = options.search_threads;
  so.distinct_designs = options.distinct_designs;
  so.stop = options.stop;
  so.deadline = options.deadline;
  SearchResult s;
  try {
    s = SearchCatalog(m, catalog, so);
  } catch (const UsageError& e) {  // a battery id or cell count the catalog cannot give
    return done("failed", e.what());
  } catch (const DataError& e) {  // a fixed part not in the catalog, a part without data
    return done("failed", WithoutName(e.what(), mission_name));
  }
  if (s.interrupted) return done("stopped", "the search was stopped before it finished");
  if (s.best.empty()) {
    row.no_design_because = s.no_design_because;
    return done("failed", NothingFliesReason(s.no_design_because));
  }
  for (std::size_t k = 0; k < s.best.size(); ++k) row.picks.push_back(PickOf(m, s, k));
  return done("ok", "");
}

SweepResult RunSweep(const Json& mission_doc, const std::string& mission_name, const Catalog& catalog,
                     const std::vector<VaryKey>& keys, const SweepOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const Mission base = ParseMission(mission_doc, mission_name);
  CheckKeys(mission_doc, mission_name, keys);
  SweepResult out;
  out.total = GridSize(keys);
  PointOptions po = options.point;
  po.search_threads = 1;
  SearchOptions stop_check;
  stop_check.stop = po.stop;
  stop_check.deadline = po.deadline;
  std::vector<SweepRow> rows(out.total);
  std::vector<char> finished(out.total, 0);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> interrupted{false};
  std::mutex mu;
  SweepProgress progress;
  progress.total = out.total;
  // An exception of a point (or of the progress callback) stops the other threads at their next
  // point and is rethrown here once all have joined.
  FirstException error;
  auto work = [&]() {
    error.Capture([&] {
      while (!interrupted.load() && !error.failed()) {
        if (StopRequested(stop_check)) {
          interrupted.store(true);
          break;
        }
        const std::size_t i = next.fetch_add(1);
        if (i >= out.total) break;
        SweepRow row = RunPoint(mission_doc, mission_name, catalog, keys, i, po);
        if (row.status == "stopped") {
          interrupted.store(true);
          break;
        }
        const std::lock_guard<std::mutex> lock(mu);
        rows[i] = std::move(row);
        finished[i] = 1;
        ++progress.done;
        if (rows[i].status == "failed") ++progress.failed;
        progress.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (options.progress) options.progress(progress);
      }
    });
  };
  const int threads = NeedsOneThread(base) ? 1 : std::max(1, options.threads);
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  error.Rethrow();
  for (std::size_t i = 0; i < out.total; ++i) {
    if (finished[i]) out.rows.push_back(std::move(rows[i]));
  }
  out.interrupted = out.rows.size() < out.total;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace dynosize::study
