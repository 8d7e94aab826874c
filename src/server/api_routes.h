// The JSON API of `dynosize serve` (docs/web.md) as plain functions of a request: no sockets, no
// HTTP library. Every answer is the document the CLI prints with --json for the same input, made
// by the same src/api call; a request that breaks a rule gets the CLI's one-line message.
//
//   GET  /api/catalog?kind=&kv_min=&kv_max=&mass_max_kg=&current_min_a=   catalog list --json
//   GET  /api/catalog/ID                                                    catalog show ID
//   POST /api/simulate  {"motor", "esc", "vdc_v", "throttle", "torque_nm", "rpm", "torque_law",
//                        "prop", "thrust_n", "rho_kg_m3"}                   simulate --json
//   POST /api/evaluate  {"mission": {...}, "motor", "esc", "prop", "battery", "pick": [...],
//                        "cells"}                                           evaluate --json
//   POST /api/optimize  {"mission": {...}, "top", "threads", "variants", "time_limit_s"}
//                                                                           optimize --json
//   POST /api/sweep     {"mission": {...}, "vary": ["KEY=START:STOP:STEP", ...], "top", "threads",
//                        "variants", "time_limit_s", "yes"}                sweep --json
//   POST /api/calibrate, /api/diagnose: the logs in the body (server/log_routes.h)
#pragma once

#include <atomic>
#include <map>
#include <string>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "optimization/search_options.h"

namespace dynosize::server {

// A request as the routes see it: the method, the path without its query, the query's
// parameters (decoded) and the body (POST: JSON text).
struct ApiCall {
  std::string method;
  std::string path;
  std::multimap<std::string, std::string> query;
  std::string body;
};

// An answer: the HTTP status and a JSON document. Errors are {"error": "<the CLI's message,
// without its 'dynosize: ' prefix>", "exit_code": <the CLI's exit code>}.
struct ApiAnswer {
  int status = 200;
  std::string body;
};

// What the routes share: the catalog loaded once, the longest an optimize may run (its
// and a sweep's time_limit_s are held to it) and a flag that stops every running search (the server stopping).
struct ApiContext {
  const Catalog* catalog = nullptr;
  double max_search_s = 300.0;
  const std::atomic<bool>* stop = nullptr;
};

// An optimize request's mission and search options, checked (the route's and the jobs' of
// server/jobs.h): the time limit held to max_search_s, the stop flag the context's.
struct OptimizeWork {
  Mission mission;
  SearchOptions options;
};
OptimizeWork OptimizeWorkOf(const ApiContext& context, const std::string& body);

// Whether the path is one of the routes above that needs a job slot (the solving POSTs).
bool IsJobRoute(const std::string& path);

// Answers one call; never throws for bad input (400, 404, 405), only a broken invariant is a 500.
ApiAnswer HandleApi(const ApiContext& context, const ApiCall& call);

// {"error": message, "exit_code": code} as JSON text.
std::string ErrorBody(const std::string& message, int exit_code);

}  // namespace dynosize::server
