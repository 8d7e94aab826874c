#include "server/web_server.h"

#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <iostream>
#include <sstream>
#include <thread>

#include "common/error.h"
#include "common/json_file.h"
#include "common/text_format.h"
#include "server/api_routes.h"
#include "server/job_queue.h"
#include "server/jobs.h"
#include "server/page_files.h"

namespace dynosize::server {

namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool IsIpv4Literal(const std::string& s) {
  int dots = 0, digits = 0;
  for (char c : s) {
    if (c == '.') {
      if (digits == 0) return false;
      ++dots;
      digits = 0;
    } else if (std::isdigit(static_cast<unsigned char>(c)) && ++digits <= 3) {
      continue;
    } else {
      return false;
    }
  }
  return dots == 3 && digits > 0;
}

// The security headers of every answer: no sniffing, the page's own files only, no framing
// (clickjacking), no referrer; nothing cached (the answers depend on the catalog loaded).
httplib::Headers DefaultHeaders() {
  return {{"X-Content-Type-Options", "nosniff"},
          {"Content-Security-Policy", "default-src 'self'; img-src 'self' data:; frame-ancestors 'none'"},
          {"X-Frame-Options", "DENY"},
          {"Referrer-Policy", "no-referrer"},
          {"Cache-Control", "no-store"}};
}

void SendError(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(ErrorBody(message, static_cast<int>(ExitCode::kUsage)), "application/json");
}

// Answers are compressed with gzip only: the library's brotli runs at its highest quality, 3.8 s
// for the 3.9 MB motor list where gzip takes 0.06 s (browsers offer both). The request is the
// library's own non-const object, handed to this handler as const: changing its headers is
// well-defined.
void DropBrotli(const httplib::Request& req) {
  const std::string offered = req.get_header_value("Accept-Encoding");
  auto& headers = const_cast<httplib::Request&>(req).headers;
  headers.erase("Accept-Encoding");
  if (Lower(offered).find("gzip") != std::string::npos) headers.emplace("Accept-Encoding", "gzip");
}

}  // namespace

bool IsLoopbackHost(const std::string& host) {
  const std::string h = Lower(host);
  return h == "localhost" || h == "::1" || h == "[::1]" || (IsIpv4Literal(h) && h.rfind("127.", 0) == 0);
}

bool HostHeaderAllowed(const std::string& header, const std::string& bound_host, int port) {
  std::string name = Lower(header), port_text;
  if (!name.empty() && name.front() == '[') {  // [v6]:port
    const auto close = name.find(']');
    if (close == std::string::npos) return false;
    if (close + 1 < name.size()) {
      if (name[close + 1] != ':') return false;
      port_text = name.substr(close + 2);
    }
    name = name.substr(0, close + 1);
  } else if (const auto colon = name.find(':'); colon != std::string::npos) {
    port_text = name.substr(colon + 1);
    name = name.substr(0, colon);
  }
  if (port_text.empty() ? port != 80 : port_text != std::to_string(port)) return false;
  if (name.empty()) return false;
  if (IsLoopbackHost(name)) return true;
  if (IsLoopbackHost(bound_host)) return false;  // a loopback server answers to loopback names only
  // Listening beyond loopback: the name it was given, or an address literal (a DNS-rebinding
  // attack needs a name of its own).
  return name == Lower(bound_host) || IsIpv4Literal(name) || name.front() == '[';
}

bool IsJsonContentType(const std::string& header) {
  const std::string h = Lower(header);
  const std::string json = "application/json";
  if (h.compare(0, json.size(), json) != 0) return false;
  return h.size() == json.size() || h[json.size()] == ';' || h[json.size()] == ' ';
}

struct WebServer::Impl {
  Impl(const Catalog& catalog, const ServeOptions& o)
      : options(o), pages(PageFiles::Load(o.page_dir)), jobs(o.jobs_running, o.jobs_waiting) {
    context.catalog = &catalog;
    context.max_search_s = o.max_search_s;
    context.stop = &stopping;
    optimize_jobs = std::make_unique<OptimizeJobs>(context, jobs, kKeptJobs);
  }
  static constexpr int kKeptJobs = 16;
  void Configure();
  httplib::Server::HandlerResponse Screen(const httplib::Request& req, httplib::Response& res);
  void ServeApi(const httplib::Request& req, httplib::Response& res);
  void ServePage(const httplib::Request& req, httplib::Response& res);

  ServeOptions options;
  PageFiles pages;
  JobQueue jobs;
  ApiContext context;
  std::atomic<bool> stopping{false};
  std::unique_ptr<OptimizeJobs> optimize_jobs;  // made once the context is set
  std::atomic<bool> in_run{false};
  httplib::Server http;
  int port = 0;
};

// Before a body is read: the Host header, and a POST's Content-Type.
httplib::Server::HandlerResponse WebServer::Impl::Screen(const httplib::Request& req, httplib::Response& res) {
  DropBrotli(req);
  const std::string host = req.get_header_value("Host");
  if (!HostHeaderAllowed(host, options.host, port)) {
    SendError(res, 403, "Host '" + host + "' does not name this server (" + options.host + ":" + std::to_string(port) +
                            "): refused against DNS rebinding; open the page at its printed address");
    return httplib::Server::HandlerResponse::Handled;
  }
  if (req.method == "POST" && !IsJsonContentType(req.get_header_value("Content-Type"))) {
    SendError(res, 415, req.path + ": the body must be sent as Content-Type: application/json (got '" +
                            req.get_header_value("Content-Type") + "')");
    return httplib::Server::HandlerResponse::Handled;
  }
  return httplib::Server::HandlerResponse::Unhandled;
}

void WebServer::Impl::ServeApi(const httplib::Request& req, httplib::Response& res) {
  ApiCall call;
  call.method = req.method;
  call.path = req.path;
  for (const auto& [k, v] : req.params) call.query.emplace(k, v);
  call.body = req.body;
  ApiAnswer answer;
  if (req.path == "/api/examples" && req.method != "POST") {  // the page's example missions
    Json j;
    j["examples"] = pages.ExampleNames();
    res.set_content(j.dump() + "\n", "application/json");
    return;
  }
  if (auto job_answer = optimize_jobs->Handle(req.method, req.path, req.body)) {  // /api/jobs/...
    res.status = job_answer->status;
    res.set_content(job_answer->body, "application/json");
    return;
  }
  if (IsJobRoute(req.path) && req.method == "POST") {
    const JobQueue::Ticket ticket(jobs);
    if (!ticket.admitted()) {
      SendError(res, 503, "the server is busy: " + std::to_string(jobs.max_running()) + " jobs running and " +
                              std::to_string(jobs.max_waiting()) + " waiting; try again when one has finished");
      res.set_header("Retry-After", "1");
      return;
    }
    answer = HandleApi(context, call);
  } else {
    answer = HandleApi(context, call);
  }
  res.status = answer.status;
  res.set_content(answer.body, "application/json");
}

void WebServer::Impl::ServePage(const httplib::Request& req, httplib::Response& res) {
  const PageFile* f = pages.Find(req.path);
  if (!f) {
    SendError(res, 404, req.path + ": not found (the page is at /, its API under /api/)");
    return;
  }
  res.set_content(f->content, f->content_type.c_str());
}

void WebServer::Impl::Configure() {
  http.new_task_queue = [n = options.jobs_running + options.jobs_waiting + 8] {
    return new httplib::ThreadPool(static_cast<std::size_t>(n));
  };
  // SO_REUSEADDR only: the library's default also sets SO_REUSEPORT, with which a second server
  // binds the same port and the kernel shares the connections between them.
  http.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  http.set_default_headers(DefaultHeaders());
  http.set_payload_max_length(options.max_body_bytes);
  const auto io_us = static_cast<time_t>(options.io_timeout_s * 1e6);
  http.set_read_timeout(io_us / 1000000, io_us % 1000000);
  http.set_write_timeout(io_us / 1000000, io_us % 1000000);
  http.set_keep_alive_timeout(2);
  http.set_pre_routing_handler([this](const httplib::Request& q, httplib::Response& r) { return Screen(q, r); });
  http.Get("/api/.*", [this](const httplib::Request& q, httplib::Response& r) { ServeApi(q, r); });
  http.Post("/api/.*", [this](const httplib::Request& q, httplib::Response& r) { ServeApi(q, r); });
  http.Get(".*", [this](const httplib::Request& q, httplib::Response& r) { ServePage(q, r); });
  // Answers the library makes itself (413 for a body over the limit, 400 for a broken request
  // line, 404 for a method without routes) get a JSON error too.
  http.set_error_handler([](const httplib::Request& q, httplib::Response& r) {
    if (!r.body.empty()) return;
    std::string what = "the request could not be read";
    if (r.status == 413) what = "the request body is over the server's limit";
    if (r.status == 404) what = q.method + " " + q.path + ": not found";
    r.set_content(ErrorBody(what, static_cast<int>(ExitCode::kUsage)), "application/json");
  });
  http.set_exception_handler([](const httplib::Request&, httplib::Response& r, std::exception_ptr ep) {
    std::string what = "unknown exception";
    try {
      std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    r.status = 500;
    r.set_content(ErrorBody("internal error: " + what, static_cast<int>(ExitCode::kInternal)), "application/json");
  });
  if (options.log_requests) {
    http.set_logger([](const httplib::Request& q, const httplib::Response& r) {
      std::ostringstream line;
      line << q.method << " " << q.path << " " << r.status << " " << r.body.size() << " B\n";
      std::cerr << line.str() << std::flush;
    });
  }
}

WebServer::WebServer(const Catalog& catalog, const ServeOptions& options) {
  if (options.port < 0 || options.port > 65535) {
    throw UsageError("--port " + std::to_string(options.port) + ": must be in [0 - 65535] (0: any free port)");
  }
  if (options.jobs_running < 1 || options.jobs_waiting < 0) {
    throw UsageError("serve: jobs running must be >= 1 and jobs waiting >= 0");
  }
  if (!(options.max_search_s > 0.0) || !(options.io_timeout_s > 0.0)) {
    throw UsageError("serve: the time limits must be > 0 s");
  }
  impl_ = std::make_unique<Impl>(catalog, options);
  impl_->Configure();
}

WebServer::~WebServer() { Stop(); }

void WebServer::Bind() {
  Impl& m = *impl_;
  if (m.options.port == 0) {
    m.port = m.http.bind_to_any_port(m.options.host);
  } else if (m.http.bind_to_port(m.options.host, m.options.port)) {
    m.port = m.options.port;
  } else {
    m.port = -1;
  }
  if (m.port <= 0) {
    throw CantCreateError("serve: cannot listen on " + m.options.host + ":" + std::to_string(m.options.port) +
                          " (the port is in use, or the address is not this machine's)");
  }
}

int WebServer::port() const { return impl_->port; }

std::string WebServer::Url() const {
  const std::string& h = impl_->options.host;
  const bool v6 = h.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + h + "]" : h) + ":" + std::to_string(impl_->port) + "/";
}

void WebServer::Run() {
  impl_->in_run.store(true);
  if (!impl_->stopping.load()) impl_->http.listen_after_bind();
  impl_->in_run.store(false);
}

void WebServer::Stop() {
  if (!impl_) return;
  impl_->stopping.store(true);
  impl_->optimize_jobs->CancelAll();
  // A Run() that has not started listening yet would miss the stop: wait until it listens (or
  // has returned).
  while (impl_->in_run.load() && !impl_->http.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  impl_->http.stop();
}

}  // namespace dynosize::server
