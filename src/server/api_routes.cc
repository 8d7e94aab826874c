#include "server/api_routes.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <vector>

#include "api/catalog_json.h"
#include "api/mission_catalog.h"
#include "api/mission_run.h"
#include "api/simulate_request.h"
#include "common/error.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/search.h"
#include "report/mission_report.h"
#include "report/sweep_report.h"
#include "study/sweep.h"
#include "server/log_routes.h"
#include "server/request_body.h"
#include "server/simulate_arrays.h"

namespace dynosize::server {

namespace {

constexpr std::size_t kMaxIdChars = 200;

// A number of the query string, the whole text read (no trailing characters).
std::optional<double> QueryNumber(const ApiCall& call, const char* key) {
  const auto it = call.query.find(key);
  if (it == call.query.end() || it->second.empty()) return std::nullopt;
  const std::string& text = it->second;
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) {
    throw UsageError(std::string("catalog: ") + key + "=" + text + ": must be a finite number");
  }
  return v;
}

Json CatalogList(const ApiContext& ctx, const ApiCall& call) {
  static const std::set<std::string> kKeys = {"kind", "kv_min", "kv_max", "mass_max_kg", "current_min_a"};
  for (const auto& [k, v] : call.query) {
    if (!kKeys.count(k)) {
      throw UsageError("catalog: unknown parameter '" + k + "' (valid: current_min_a, kind, kv_max, kv_min, mass_max_kg)");
    }
  }
  api::CatalogListRequest r;
  if (const auto it = call.query.find("kind"); it != call.query.end()) r.kind = it->second;
  if (!r.kind.empty() && r.kind != "motors" && r.kind != "escs" && r.kind != "props" && r.kind != "batteries") {
    throw UsageError("--kind " + r.kind + ": not in {motors, escs, props, batteries}");  // as the Python module
  }
  r.kv_min = QueryNumber(call, "kv_min");
  r.kv_max = QueryNumber(call, "kv_max");
  r.mass_max_kg = QueryNumber(call, "mass_max_kg");
  r.current_min_a = QueryNumber(call, "current_min_a");
  api::CheckCatalogListRequest(r);
  return api::CatalogListJson(*ctx.catalog, r);
}

Json Simulate(const ApiContext& ctx, const ApiCall& call) {
  const RequestBody b(call.body, "simulate",
               {"motor", "esc", "vdc_v", "throttle", "torque_nm", "rpm", "torque_law", "prop", "thrust_n", "rho_kg_m3"});
  api::SimulateRequest r;
  r.motor_id = b.Text("motor");
  r.esc_id = b.Text("esc");
  if (r.motor_id.empty() || r.esc_id.empty()) throw UsageError("simulate: 'motor' and 'esc' are required (catalog ids)");
  if (HasPointArrays(b)) return SimulateArrays(*ctx.catalog, b);  // the Python module's batch
  r.vdc_v = b.Number("vdc_v");
  r.throttle = b.Number("throttle");
  r.torque_nm = b.Number("torque_nm");
  r.rpm = b.Number("rpm");
  r.torque_law = b.Numbers("torque_law");
  r.prop_id = b.Text("prop");
  r.thrust_n = b.Number("thrust_n");
  if (const auto rho = b.Number("rho_kg_m3")) r.rho_kg_m3 = *rho;
  return api::SimulateJson(*ctx.catalog, r);
}

Json Evaluate(const ApiContext& ctx, const ApiCall& call) {
  const RequestBody b(call.body, "evaluate", {"mission", "motor", "esc", "prop", "battery", "pick", "cells"});
  const Mission mission = b.MissionOf();
  api::EvaluateRequest r;
  r.motor_id = b.Text("motor");
  r.esc_id = b.Text("esc");
  r.prop_id = b.Text("prop");
  r.battery_id = b.Text("battery");
  if (r.battery_id.empty()) throw UsageError("evaluate: 'battery' is required (a catalog battery id)");
  r.picks = b.Texts("pick");
  const long long cells = b.Integer("cells").value_or(0);
  if (cells < 0 || cells > kMaxCellsSeries) {
    throw UsageError("--cells " + std::to_string(cells) + ": must be in [1 - " + std::to_string(kMaxCellsSeries) + "]");
  }
  r.cells = static_cast<int>(cells);
  const api::MissionCatalog cat(*ctx.catalog, mission);  // with the mission's sized propellers
  const Combination c = api::ChooseCombination(mission, cat.get(), r);
  return MissionResultJson(mission, c, api::EvaluateCombination(mission, c));
}

Json Optimize(const ApiContext& ctx, const ApiCall& call) {
  const OptimizeWork w = OptimizeWorkOf(ctx, call.body);
  const api::MissionCatalog cat(*ctx.catalog, w.mission);  // with the mission's sized propellers
  return SearchResultJson(w.mission, SearchCatalog(w.mission, cat.get(), w.options));
}

// sweep --json: "vary" holds the CLI's --vary strings (KEY=START:STOP:STEP or KEY=v1,v2,...).
Json Sweep(const ApiContext& ctx, const ApiCall& call) {
  const RequestBody b(call.body, "sweep", {"mission", "vary", "top", "threads", "variants", "time_limit_s", "yes"});
  const Json* doc = b.Find("mission");
  if (!doc || !doc->is_object()) throw UsageError("sweep: 'mission' is required (a JSON object: the mission file's content)");
  const std::vector<std::string> vary = b.Texts("vary");
  if (vary.empty()) throw UsageError("sweep: 'vary' is required: [\"KEY=START:STOP:STEP\" or \"KEY=v1,v2,...\", ...]");
  const long long top = b.Integer("top").value_or(1);
  if (top < 1 || top > 1000) throw UsageError("--top " + std::to_string(top) + ": must be in [1 - 1000]");
  const long long threads = b.Integer("threads").value_or(2);
  if (threads < 1 || threads > 64) throw UsageError("--threads " + std::to_string(threads) + ": must be in [1 - 64]");
  study::SweepOptions so;
  so.point.deadline = std::min(api::DeadlineAfter(b.Number("time_limit_s").value_or(ctx.max_search_s)),
                               api::DeadlineAfter(ctx.max_search_s));
  so.point.stop = ctx.stop;
  so.point.top = static_cast<int>(top);
  so.point.distinct_designs = !b.Flag("variants");
  so.threads = static_cast<int>(threads);
  std::vector<study::VaryKey> keys;
  for (const std::string& spec : vary) keys.push_back(study::ParseVary(spec));
  const study::SweepPlan plan = study::PlanSweep(*doc, "mission", std::move(keys), b.Flag("yes"));
  const Mission base = ParseMission(plan.doc, plan.name);
  const api::MissionCatalog cat(*ctx.catalog, study::PointMissions(plan));  // with the points' sized propellers
  return study::SweepJson(base, study::RunSweep(plan.doc, plan.name, cat.get(), plan.keys, so), plan.keys);
}

ApiAnswer Answer(const Json& doc) {
  ApiAnswer a;
  a.body = DumpJson(doc);  // checks every number is finite (InternalError otherwise), as the CLI's
  return a;
}

ApiAnswer Route(const ApiContext& ctx, const ApiCall& call) {
  const std::string& p = call.path;
  const bool get = call.method == "GET" || call.method == "HEAD";
  const auto need = [&](const char* method) {
    if (call.method != method && !(get && std::string(method) == "GET")) {
      ApiAnswer a;
      a.status = 405;
      a.body = ErrorBody(p + ": use " + method, static_cast<int>(ExitCode::kUsage));
      return std::optional<ApiAnswer>(a);
    }
    return std::optional<ApiAnswer>();
  };
  if (p == "/api/catalog") {
    if (auto bad = need("GET")) return *bad;
    return Answer(CatalogList(ctx, call));
  }
  if (p.rfind("/api/catalog/", 0) == 0) {
    if (auto bad = need("GET")) return *bad;
    const std::string id = p.substr(std::string("/api/catalog/").size());
    // The "did you mean" of an unknown id compares it with every id (0.2 s for 1000 characters):
    // no entry has an id this long, so a longer one is answered at once.
    if (id.size() > kMaxIdChars) {
      return {404, ErrorBody("catalog: an id of " + std::to_string(id.size()) + " characters: no entry has one over " +
                                 std::to_string(kMaxIdChars),
                             static_cast<int>(ExitCode::kUsage))};
    }
    try {
      return Answer(api::CatalogShowJson(*ctx.catalog, id));
    } catch (const UsageError& e) {  // an unknown id: the resource is not there
      return {404, ErrorBody(e.what(), static_cast<int>(e.code()))};
    }
  }
  const std::pair<const char*, Json (*)(const ApiContext&, const ApiCall&)> posts[] = {
      {"/api/simulate", &Simulate},
      {"/api/evaluate", &Evaluate},
      {"/api/optimize", &Optimize},
      {"/api/sweep", &Sweep},
      {"/api/calibrate", [](const ApiContext& c, const ApiCall& q) { return CalibrateRoute(c, q.body); }},
      {"/api/diagnose", [](const ApiContext& c, const ApiCall& q) { return DiagnoseRoute(c, q.body); }}};
  for (const auto& [route, run] : posts) {
    if (p != route) continue;
    if (auto bad = need("POST")) return *bad;
    return Answer(run(ctx, call));
  }
  return {404, ErrorBody(p + ": no such API route (GET /api/catalog, /api/catalog/ID; POST /api/simulate, "
                              "/api/evaluate, /api/optimize, /api/sweep, /api/calibrate, /api/diagnose)",
                         static_cast<int>(ExitCode::kUsage))};
}

}  // namespace

OptimizeWork OptimizeWorkOf(const ApiContext& ctx, const std::string& body) {
  const RequestBody b(body, "optimize", {"mission", "top", "threads", "variants", "time_limit_s"});
  api::OptimizeRequest r;
  const long long top = b.Integer("top").value_or(5);
  if (top < 1 || top > 1000) throw UsageError("--top " + std::to_string(top) + ": must be in [1 - 1000]");
  const long long threads = b.Integer("threads").value_or(2);
  if (threads < 1 || threads > 64) throw UsageError("--threads " + std::to_string(threads) + ": must be in [1 - 64]");
  r.top = static_cast<int>(top);
  r.threads = static_cast<int>(threads);
  r.variants = b.Flag("variants");
  r.time_limit_s = b.Number("time_limit_s").value_or(std::numeric_limits<double>::infinity());
  SearchOptions options = api::OptimizeSearchOptions(r);  // checks the time limit (> 0), before the mission
  OptimizeWork w{b.MissionOf(), std::move(options)};
  w.options.deadline = std::min(w.options.deadline, api::DeadlineAfter(ctx.max_search_s));
  w.options.stop = ctx.stop;
  return w;
}

bool IsJobRoute(const std::string& path) {
  return path == "/api/simulate" || path == "/api/evaluate" || path == "/api/optimize" || path == "/api/sweep" ||
         path == "/api/calibrate" || path == "/api/diagnose";
}

ApiAnswer HandleApi(const ApiContext& context, const ApiCall& call) {
  try {
    return Route(context, call);
  } catch (const Error& e) {
    int status = 400;
    if (e.code() == ExitCode::kNoInput) status = 404;
    if (e.code() == ExitCode::kUnavailable) status = 501;
    if (e.code() == ExitCode::kInternal) status = 500;
    return {status, ErrorBody(e.what(), static_cast<int>(e.code()))};
  } catch (const std::exception& e) {
    return {500, ErrorBody(std::string("internal error: ") + e.what(), static_cast<int>(ExitCode::kInternal))};
  }
}

}  // namespace dynosize::server
