// `dynosize serve`: the page (web/) and the JSON API (server/api_routes.h) over HTTP on one
// address, safe by default (docs/web.md):
//   - it listens on loopback unless told otherwise (the CLI warns for any other address);
//   - the Host header must name this server: localhost, a loopback or other IP literal, or the
//     --host name, with its port (a DNS-rebinding page's own name is refused, 403);
//   - POST bodies only as Content-Type application/json (415 otherwise): a page of another site
//     cannot send one without a CORS preflight, and no CORS header is ever sent;
//   - bodies over max_body_bytes get 413; bad JSON or values 400 with the CLI's message; unknown
//     paths 404; files only from the page's folder, by exact name (server/page_files.h);
//   - solving requests go through a bounded job queue (503 when full) and an optimize runs at
//     most max_search_s;
//   - no request ends the process: every error is an answer.
// The HTTP library (cpp-httplib) stays inside web_server.cc.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "catalog/catalog.h"

namespace dynosize::server {

struct ServeOptions {
  std::string host = "127.0.0.1";          // address to listen on
  int port = 8080;                         // 0: any free port (port() says which)
  std::string page_dir;                    // the page's files (server/page_files.h DefaultPageDir)
  std::size_t max_body_bytes = 16u << 20;  // larger request bodies get 413
  int jobs_running = 2;                    // solving requests at once (the machine's cores)
  int jobs_waiting = 8;                    // more waiting for a slot; beyond that 503
  double max_search_s = 300.0;             // an optimize's time limit is held to this
  double io_timeout_s = 10.0;              // reading a request, writing an answer
  bool log_requests = true;                // one line per request on stderr
};

// True for 127.0.0.0/8, ::1 and "localhost".
bool IsLoopbackHost(const std::string& host);

// Whether a request's Host header names this server (the rules above); `bound_host` is the
// address listened on, `port` its port.
bool HostHeaderAllowed(const std::string& header, const std::string& bound_host, int port);

// Whether a Content-Type header says JSON: application/json, with parameters (charset) or not.
bool IsJsonContentType(const std::string& header);

class WebServer {
 public:
  // Reads the page's files; throws NoInputError when the folder is missing, UsageError for
  // options out of range.
  WebServer(const Catalog& catalog, const ServeOptions& options);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // Binds the address; throws CantCreateError naming it when that fails (in use, not local).
  void Bind();
  int port() const;
  // http://host:port/ (IPv6 addresses in brackets).
  std::string Url() const;
  // Serves until Stop(); returns then.
  void Run();
  // Stops from any thread: running searches stop with their best so far, then Run() returns.
  void Stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dynosize::server
