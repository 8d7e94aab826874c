// The JSON API of `dynosize serve` (docs/web.md) as plain functions of a request: no sockets, no
// HTTP library. Every answer is the document the CLI prints with --json for the same input, made
// by the same src/api call; a request that breaks a rule gets the CLI's one-line message.
//
//   GET  /api/catalog?kind=&kv_min=&kv_max=&mass_max_kg=&current_min_a=   catalog list --json
//   GET  /api/catalog/ID                                                    catalog show ID
//   POST /api/simulate  {"motor", "esc", "vdc_v", "throttle", "torque_nm", "rpm", "torque_law",
//                        "prop", "thrust_n", "rho_kg_m3"}                   simulate --json
//                       (arrays: the Python module's simulate, server/simulate_arrays.h)
//   POST /api/evaluate  {"mission": {...}, "motor", "esc", "prop", "battery", "pick": [...],
//                        "cells"}                                           evaluate --json
//   POST /api/optimize  {"mission": {...}, "top", "threads", "variants", "time_limit_s"}
//                                                                           optimize --json
//   POST /api/sweep     {"mission": {...}, "vary": ["KEY=START:STOP:STEP", ...], "top", "threads",
//                        "variants", "time_limit_s", "yes"}                sweep --json
//   POST /api/calibrate, /api/diagnose: the logs in the body (server/log_routes.h)
#pragma once

#include <string>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "optimization/search_options.h"
#include "server/api_context.h"

namespace dynosize::server {

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

}  // namespace dynosize::server
