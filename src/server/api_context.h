// What the routes of `dynosize serve` take and give (server/api_routes.h, server/log_routes.h,
// server/jobs.h): a request without HTTP, an answer, and what the routes share.
#pragma once

#include <atomic>
#include <map>
#include <string>

#include "catalog/catalog.h"

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

// What the routes share: the catalog loaded once, the longest an optimize or a sweep may run
// (their time_limit_s is held to it) and a flag that stops every running search (the server
// stopping).
struct ApiContext {
  const Catalog* catalog = nullptr;
  double max_search_s = 300.0;
  const std::atomic<bool>* stop = nullptr;
};

// {"error": message, "exit_code": code} as JSON text.
std::string ErrorBody(const std::string& message, int exit_code);

}  // namespace dynosize::server
