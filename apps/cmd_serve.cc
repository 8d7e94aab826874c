// `dynosize serve`: the web page and its JSON API on this machine (src/server, docs/web.md).
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <thread>

#include "catalog/catalog.h"
#include "commands.h"
#include "interrupt.h"
#include "server/page_files.h"
#include "server/web_server.h"

namespace dynosize::cli {

namespace {

// SIGTERM (a service manager stopping it) stops the server as Ctrl-C does.
std::atomic<bool> g_sigterm{false};
extern "C" void OnSigterm(int) { g_sigterm.store(true); }

class SigtermToFlag {
 public:
  SigtermToFlag() {
    struct sigaction sa = {};
    sa.sa_handler = OnSigterm;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGTERM, &sa, &previous_);
  }
  ~SigtermToFlag() { sigaction(SIGTERM, &previous_, nullptr); }
  SigtermToFlag(const SigtermToFlag&) = delete;
  SigtermToFlag& operator=(const SigtermToFlag&) = delete;

 private:
  struct sigaction previous_;
};

}  // namespace

int RunServe(const ServeCliOptions& o) {
  const SigintToFlag sigint;  // Ctrl-C stops the server (running searches return their best so far)
  const SigtermToFlag sigterm;
  const Catalog catalog = Catalog::Load(o.catalog);
  server::ServeOptions so;
  so.host = o.host;
  so.port = o.port;
  so.page_dir = o.web_dir.empty() ? server::DefaultPageDir() : o.web_dir;
  so.jobs_running = o.jobs;
  so.jobs_waiting = o.queue;
  so.max_search_s = o.max_search_s;
  so.log_requests = !o.quiet;
  server::WebServer web(catalog, so);
  web.Bind();
  if (!server::IsLoopbackHost(o.host)) {
    std::cerr << "warning: listening on " << o.host << ", not loopback: anyone who can reach this machine can "
              << "use the server (and its CPU); there is no login\n";
  }
  std::cout << "dynosize serve: listening on " << web.Url() << " (" << catalog.motors().size() << " motors, "
            << catalog.escs().size() << " ESCs, " << catalog.props().size() << " propellers, "
            << catalog.batteries().size() << " batteries; page " << so.page_dir << "; Ctrl-C stops)" << std::endl;
  std::thread runner([&web] { web.Run(); });
  while (!SigintToFlag::Received() && !g_sigterm.load()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  web.Stop();
  runner.join();
  std::cerr << "dynosize serve: stopped\n";
  return 0;
}

}  // namespace dynosize::cli
