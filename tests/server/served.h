// A `dynosize serve` server running in the test process on a free loopback port (the bundled
// catalog, the build tree's page folder), and a client for it.
#pragma once

#include <httplib.h>

#include <memory>
#include <string>
#include <thread>

#include "catalog/catalog.h"
#include "catalog/catalog_path.h"
#include "server/web_server.h"

namespace dynosize::testing_util {

// The bundled catalog, loaded once for every server of the test process (as the CLI finds it
// from the build tree).
inline const Catalog& ServedCatalog() {
  static const Catalog cat = Catalog::Load(ResolveCatalogFolders("", {}, false));
  return cat;
}

class RunningServer {
 public:
  explicit RunningServer(server::ServeOptions o = {}) {
    o.host = "127.0.0.1";
    o.port = 0;
    o.page_dir = DYNOSIZE_WEB_DIR;
    o.log_requests = false;
    web_ = std::make_unique<server::WebServer>(ServedCatalog(), o);
    web_->Bind();
    runner_ = std::thread([this] { web_->Run(); });
  }
  ~RunningServer() { Stop(); }
  void Stop() {
    if (!runner_.joinable()) return;
    web_->Stop();
    runner_.join();
  }
  int port() const { return web_->port(); }
  std::string host_header() const { return "127.0.0.1:" + std::to_string(port()); }
  // A client with generous timeouts (an optimize takes about a second) and paths sent as given.
  std::unique_ptr<httplib::Client> Client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", port());
    c->set_read_timeout(120, 0);
    c->set_url_encode(false);
    return c;
  }

 private:
  std::unique_ptr<server::WebServer> web_;
  std::thread runner_;
};

}  // namespace dynosize::testing_util
