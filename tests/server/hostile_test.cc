// `dynosize serve` against hostile and broken requests (docs/web.md, "Safety"): each gets its
// status and a one-line JSON error, and the server still answers afterwards. In-process (no
// executable): run under the sanitizers too.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.h"
#include "common/json_file.h"
#include "server/job_queue.h"
#include "server/served.h"
#include "server/web_server.h"

namespace dynosize {
namespace {

using testing_util::RunningServer;

const Json kPair = {{"motor", "emax_1900kv_paper"}, {"esc", "multistar_30a_paper"}, {"vdc_v", 7.2}};

// The server answers a plain request after whatever came before.
void ExpectAlive(const RunningServer& s) {
  const auto res = s.Client()->Get("/api/catalog/emax_1900kv_paper");
  ASSERT_TRUE(res) << "the server no longer answers";
  EXPECT_EQ(res->status, 200);
}

// A status and a JSON body {"error": "...", "exit_code": n} whose message is one line.
void ExpectError(const httplib::Result& res, int status, const std::string& part = "") {
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, status) << res->body;
  const Json j = Json::parse(res->body);
  ASSERT_TRUE(j.contains("error")) << res->body;
  const std::string message = j["error"];
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(message.find(part), std::string::npos) << message;
}

httplib::Result PostText(const RunningServer& s, const std::string& path, const std::string& body,
                         const std::string& type = "application/json") {
  return s.Client()->Post(path.c_str(), body, type.c_str());
}

TEST(ServerHostile, BrokenJsonAndBadValuesAre400) {
  const RunningServer s;
  const std::pair<std::string, std::string> cases[] = {
      {"{", "simulate request body:1:2"},
      {"", "simulate request body"},
      {R"({"motor": NaN})", "invalid literal"},
      {R"({"motor": "m", "vdc_v": 1e999})", "number overflow"},
      {R"({"motor": "a", "motor": "b"})", "duplicate"},
      {"[1, 2]", "must be a JSON object"},
      {R"({"motor": "emax_1900kv_paper", "esc": "multistar_30a_paper", "vdc_v": "7.2"})", "vdc_v \"7.2\": must be a number"},
      {R"({"motor": "emax_1900kv_paper", "esc": "multistar_30a_paper", "vdc": 7.2})", "unknown key 'vdc' (valid: esc, motor"},
      {R"({"motor": "emax_1900kv_paper", "esc": "multistar_30a_paper", "vdc_v": 7.2, "throttle": -0.5, "rpm": 100})",
       "--throttle -0.5: must be between 0 and 1"},
      {std::string(40, '[') + std::string(40, ']'), "deep"},
  };
  for (const auto& [body, part] : cases) {
    ExpectError(PostText(s, "/api/simulate", body), 400, part);
    ExpectAlive(s);
  }
  ExpectError(PostText(s, "/api/optimize", R"({"mission": {"name": 3}, "top": 3})"), 400, "mission");
  ExpectError(PostText(s, "/api/optimize", R"({"mission": {}, "top": 0})"), 400, "--top 0");
  ExpectError(PostText(s, "/api/optimize", R"({"mission": {}, "time_limit_s": -1})"), 400, "--time-limit");
  ExpectError(PostText(s, "/api/evaluate", R"({"mission": "/etc/passwd", "battery": "x"})"), 400, "must be a JSON object");
  for (const char* name : {"../../etc/cron.d/x", "/etc/passwd", ".bashrc", "a/b.csv", "", "x\\y.csv"}) {
    const Json body = {{"log", {{"name", name}, {"text", "a,b\n"}}}};
    ExpectError(PostText(s, "/api/diagnose", body.dump()), 400, "a log's name must be");
  }
  ExpectError(PostText(s, "/api/diagnose", R"({"log": {"name": "x.csv", "base64": "!!"}})"), 400, "not base64");
  ExpectError(PostText(s, "/api/calibrate", R"({"logs": []})"), 400, "'logs' is required");
  ExpectError(PostText(s, "/api/calibrate", R"({"logs": [{"name": "a.csv", "text": ""}, {"name": "a.csv", "text": ""}]})"),
              400, "two logs named");
  ExpectError(s.Client()->Get("/api/catalog?kind=rockets"), 400, "--kind rockets: not in");
  ExpectError(s.Client()->Get("/api/catalog?kind=motors&kv_min=abc"), 400, "kv_min=abc: must be a finite number");
  ExpectError(s.Client()->Get("/api/catalog?kind=motors&kv_min=nan"), 400, "kv_min=nan");
  ExpectError(s.Client()->Get("/api/catalog?kind=escs&kv_min=100"), 400, "--kv-min/--kv-max filter motors");
  ExpectError(s.Client()->Get("/api/catalog?colour=red"), 400, "unknown parameter 'colour'");
  ExpectAlive(s);
}

TEST(ServerHostile, HugeBodyIs413) {
  server::ServeOptions o;
  o.max_body_bytes = 1u << 20;  // 1 MiB here; 16 MiB by default
  const RunningServer s(o);
  const std::string body = "{\"motor\": \"" + std::string(2u << 20, 'x') + "\"}";
  const auto res = PostText(s, "/api/simulate", body);
  if (res) ExpectError(res, 413, "over the server's limit");  // or the connection is cut mid-send
  ExpectAlive(s);
  // Just under the limit: read, then refused as a bad value.
  ExpectError(PostText(s, "/api/simulate", "{\"motor\": \"" + std::string((1u << 20) - 64, 'x') + "\"}"), 400);
  ExpectAlive(s);
}

TEST(ServerHostile, FilesOnlyFromThePageFolder) {
  const RunningServer s;
  const auto index = s.Client()->Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_EQ(index->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_EQ(index->get_header_value("X-Content-Type-Options"), "nosniff");
  EXPECT_FALSE(index->has_header("Access-Control-Allow-Origin"));
  for (const char* f : {"/app.js", "/style.css", "/chart.min.js", "/examples/quadcopter_1p5kg.json"}) {
    const auto res = s.Client()->Get(f);
    ASSERT_TRUE(res) << f;
    EXPECT_EQ(res->status, 200) << f;
  }
  for (const char* path : {"/../../../../etc/passwd", "/%2e%2e/%2e%2e/%2e%2e/etc/passwd", "/..%2f..%2f..%2fetc%2fpasswd",
                           "/examples/../../CMakeLists.txt", "//etc/passwd", "/etc/passwd", "/index.html/..",
                           "/./index.html", "/web/index.html", "/%00", "/app.js%00.png", "/nothing_here"}) {
    const auto res = s.Client()->Get(path);
    if (!res) continue;  // a request line the library refuses outright
    EXPECT_TRUE(res->status == 404 || res->status == 400) << path << " " << res->status;
    EXPECT_EQ(res->body.find("root:"), std::string::npos) << path;
  }
  ExpectError(s.Client()->Get("/api/nothing"), 404, "no such API route");
  ExpectError(s.Client()->Get("/api/simulate"), 405, "use POST");
  ExpectError(s.Client()->Get("/api/catalog/no_such_entry"), 404, "no_such_entry");
  ExpectAlive(s);
}

TEST(ServerHostile, HostHeaderMustNameTheServer) {
  const RunningServer s;
  const std::string port = std::to_string(s.port());
  const std::vector<std::string> refused = {"evil.example:" + port, "evil.example", "127.0.0.1:1",
                                           "localhost.evil.example:" + port, "127.0.0.1.nip.io:" + port, ""};
  for (const std::string& host : refused) {
    ExpectError(s.Client()->Get("/", {{"Host", host}}), 403, "does not name this server");
  }
  const std::vector<std::string> allowed = {"127.0.0.1:" + port, "localhost:" + port, "LOCALHOST:" + port, "[::1]:" + port};
  for (const std::string& host : allowed) {
    const auto res = s.Client()->Get("/", {{"Host", host}});
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200) << host;
  }
  EXPECT_TRUE(server::HostHeaderAllowed("192.168.1.5:8080", "0.0.0.0", 8080));
  EXPECT_TRUE(server::HostHeaderAllowed("mybox:8080", "mybox", 8080));
  EXPECT_FALSE(server::HostHeaderAllowed("attacker.example:8080", "0.0.0.0", 8080));
  EXPECT_FALSE(server::HostHeaderAllowed("192.168.1.5:8080", "127.0.0.1", 8080));
  EXPECT_TRUE(server::HostHeaderAllowed("localhost", "127.0.0.1", 80));
  EXPECT_FALSE(server::HostHeaderAllowed("localhost", "127.0.0.1", 8080));
}

TEST(ServerHostile, PostsOnlyAsJson) {
  const RunningServer s;
  for (const char* type : {"text/plain", "application/x-www-form-urlencoded", "multipart/form-data; boundary=x",
                           "application/jsonp", ""}) {
    ExpectError(PostText(s, "/api/simulate", kPair.dump(), type), 415, "Content-Type: application/json");
  }
  const auto ok = PostText(s, "/api/simulate", kPair.dump(), "application/json; charset=utf-8");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200) << ok->body;
}

TEST(ServerHostile, JobQueueRefusesBeyondItsBound) {
  server::JobQueue q(1, 1);
  std::promise<bool> second;
  std::thread waiter;
  {
    const server::JobQueue::Ticket first(q);
    EXPECT_TRUE(first.admitted());
    waiter = std::thread([&] {
      const server::JobQueue::Ticket t(q);  // waits for the first's slot
      second.set_value(t.admitted());
    });
    while (q.waiting() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const server::JobQueue::Ticket third(q);  // running and waiting both full
    EXPECT_FALSE(third.admitted());
    EXPECT_EQ(q.running(), 1);
  }  // the first's slot is freed: the waiting one gets it
  EXPECT_TRUE(second.get_future().get());
  waiter.join();
  EXPECT_EQ(q.running(), 0);
  EXPECT_EQ(q.waiting(), 0);
}

// Parallel optimizes beyond the queue get 503 at once; the running one ends by the server's
// search limit with its best so far; the server answers throughout and after.
TEST(ServerHostile, ParallelOptimizesBeyondTheQueueAre503) {
  server::ServeOptions o;
  o.jobs_running = 1;
  o.jobs_waiting = 0;
  o.max_search_s = 1.5;
  const RunningServer s(o);
  const auto path = testing_util::LongSearchMission("server_queue");
  const std::string body = Json{{"mission", ReadJsonFile(path.string())}, {"top", 1}}.dump();
  std::filesystem::remove(path);
  auto first = std::async(std::launch::async, [&] { return PostText(s, "/api/optimize", body); });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  for (int i = 0; i < 3; ++i) ExpectError(PostText(s, "/api/optimize", body), 503, "the server is busy");
  ExpectAlive(s);  // a catalog request needs no job slot
  const auto res = first.get();
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200) << res->body;
  EXPECT_TRUE(Json::parse(res->body)["interrupted"].get<bool>());
  const auto again = PostText(s, "/api/simulate", kPair.dump());
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 200);
}

// Stop() while a search runs: the search stops with its best so far and Stop returns promptly.
TEST(ServerHostile, StopEndsARunningSearch) {
  auto s = std::make_unique<RunningServer>();
  const auto path = testing_util::LongSearchMission("server_stop");
  const std::string body = Json{{"mission", ReadJsonFile(path.string())}, {"top", 1}}.dump();
  std::filesystem::remove(path);
  auto running = std::async(std::launch::async, [&] { return PostText(*s, "/api/optimize", body); });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto t0 = std::chrono::steady_clock::now();
  s->Stop();
  // The search looks at its stop flag between chunks: about 2 s here in Release, 9 s under
  // ASan (its set-up before the first chunk); the bound says it returns, not how fast.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 60.0);
  const auto res = running.get();
  if (res) {  // or the connection closed with the server
    EXPECT_TRUE(Json::parse(res->body)["interrupted"].get<bool>()) << res->body;
  }
}

// A job cancelled mid-search finishes with its best so far; unknown jobs are 404.
TEST(ServerHostile, OptimizeJobsCancelAndBounds) {
  const RunningServer s;
  const auto path = testing_util::LongSearchMission("server_job");
  const std::string body = Json{{"mission", ReadJsonFile(path.string())}, {"top", 1}}.dump();
  std::filesystem::remove(path);
  const auto started = PostText(s, "/api/jobs/optimize", body);
  ASSERT_TRUE(started);
  ASSERT_EQ(started->status, 202) << started->body;
  const std::string id = Json::parse(started->body)["job"];
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto cancelled = PostText(s, "/api/jobs/" + id + "/cancel", "{}");
  ASSERT_TRUE(cancelled);
  EXPECT_EQ(cancelled->status, 200);
  Json st;
  for (int i = 0; i < 400; ++i) {
    const auto res = s.Client()->Get(("/api/jobs/" + id).c_str());
    ASSERT_TRUE(res);
    st = Json::parse(res->body);
    if (st["state"] == "done") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_EQ(st["state"], "done") << st.dump();
  EXPECT_TRUE(st["cancelled"].get<bool>());
  EXPECT_TRUE(st["result"]["interrupted"].get<bool>());
  ExpectError(s.Client()->Get("/api/jobs/0123456789abcdef0123456789abcdef"), 404, "no such job");
  ExpectError(s.Client()->Get("/api/jobs/optimize"), 405, "use POST");
  ExpectError(PostText(s, "/api/jobs/optimize", R"({"mission": {}, "top": -3})"), 400, "--top -3");
  ExpectAlive(s);
}

// 200 hostile requests of every kind in a row; the server answers each and the next.
TEST(ServerHostile, TwoHundredHostileRequests) {
  const RunningServer s;
  const std::string port = std::to_string(s.port());
  for (int i = 0; i < 200; ++i) {
    auto c = s.Client();
    const auto send = [&]() -> httplib::Result {
      switch (i % 8) {
        case 0: return PostText(s, "/api/simulate", "{\"motor\": [" + std::string(static_cast<std::size_t>(i), '1'));
        case 1: return PostText(s, "/api/simulate", R"({"motor": NaN, "vdc_v": Infinity})");
        case 2: return PostText(s, "/api/optimize", R"({"mission": {"vehicle": {"mass_kg": -1}}})");
        case 3: return c->Get("/../../../etc/shadow");
        case 4: return c->Get("/", {{"Host", "rebind.example:" + port}});
        case 5: return PostText(s, "/api/evaluate", "mission=1", "application/x-www-form-urlencoded");
        case 6: return c->Get(("/api/catalog/" + std::string(1000, 'a')).c_str());
        default:
          return PostText(s, "/api/simulate", R"({"motor": "emax_1900kv_paper", "esc": "multistar_30a_paper", )"
                                              R"("vdc_v": 1e308, "throttle": 1, "rpm": 1e308})");
      }
    };
    const auto res = send();
    ASSERT_TRUE(res) << i;
    EXPECT_GE(res->status, 400) << i << " " << res->body;
    EXPECT_LT(res->status, 500) << i << " " << res->body;
  }
  ExpectAlive(s);
}

}  // namespace
}  // namespace dynosize
