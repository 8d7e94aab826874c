// Every endpoint of `dynosize serve` answers what the CLI prints with --json for the same input
// (timing keys aside), and its errors carry the CLI's one-line message and exit code. Runs the
// executable: a whole_run suite (CMakeLists.txt).
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "cli_runner.h"
#include "common/json_file.h"
#include "server/served.h"

namespace dynosize {
namespace {

using testing_util::RunCli;
using testing_util::RunningServer;

const std::string kSource = DYNOSIZE_SOURCE_DIR;

// The CLI's --json document (exit 0 expected).
Json CliJson(const std::string& args) {
  const auto r = RunCli(args);
  EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
  return Json::parse(r.out);
}

Json Get(const RunningServer& s, const std::string& path, int status = 200) {
  const auto res = s.Client()->Get(path.c_str());
  EXPECT_TRUE(res) << path;
  if (!res) return Json();
  EXPECT_EQ(res->status, status) << path << "\n" << res->body;
  return Json::parse(res->body);
}

Json Post(const RunningServer& s, const std::string& path, const Json& body, int status = 200) {
  const auto res = s.Client()->Post(path.c_str(), body.dump(), "application/json");
  EXPECT_TRUE(res) << path;
  if (!res) return Json();
  EXPECT_EQ(res->status, status) << path << " " << body.dump() << "\n" << res->body;
  return Json::parse(res->body);
}

TEST(ServerCli, CatalogListAndShowEqualTheCli) {
  const RunningServer s;
  EXPECT_EQ(Get(s, "/api/catalog?kind=escs&current_min_a=30"),
            CliJson("catalog list --kind escs --current-min-a 30 --json"));
  EXPECT_EQ(Get(s, "/api/catalog?kind=motors&kv_min=700&kv_max=1000&mass_max_kg=0.08"),
            CliJson("catalog list --kind motors --kv-min 700 --kv-max 1000 --mass-max-kg 0.08 --json"));
  EXPECT_EQ(Get(s, "/api/catalog?kind=batteries"), CliJson("catalog list --kind batteries --json"));
  for (const char* id : {"dc_m_365", "emax_1900kv_paper", "dc_p_231", "dc_b_363"}) {
    EXPECT_EQ(Get(s, std::string("/api/catalog/") + id), CliJson(std::string("catalog show ") + id)) << id;
  }
}

TEST(ServerCli, SimulateEqualsTheCliInEveryMode) {
  const RunningServer s;
  const Json pair = {{"motor", "emax_1900kv_paper"}, {"esc", "multistar_30a_paper"}, {"vdc_v", 7.2}};
  const std::string flags = "simulate --motor emax_1900kv_paper --esc multistar_30a_paper --vdc 7.2 --json";
  struct Case {
    Json extra;
    std::string args;
  };
  const Case cases[] = {
      {Json::object(), ""},                                                        // the table over throttle
      {{{"throttle", 0.8}, {"torque_nm", 0.05}}, " --throttle 0.8 --torque 0.05"},  // forward
      {{{"torque_nm", 0.05}, {"rpm", 9000}}, " --torque 0.05 --rpm 9000"},          // inverse
      {{{"throttle", 0.6}, {"torque_law", {0.001, 0.0, 1e-7}}}, " --throttle 0.6 --torque-law 0.001,0,1e-7"},
      {{{"prop", "fu_p_apc_8x3.8sf"}}, " --prop fu_p_apc_8x3.8sf"},                 // the propeller's table
      {{{"prop", "fu_p_apc_8x3.8sf"}, {"thrust_n", 2.0}}, " --prop fu_p_apc_8x3.8sf --thrust-n 2"},
      {{{"prop", "fu_p_apc_8x3.8sf"}, {"throttle", 0.7}, {"rho_kg_m3", 1.1}},
       " --prop fu_p_apc_8x3.8sf --throttle 0.7 --rho-kg-m3 1.1"},
  };
  for (const Case& c : cases) {
    Json body = pair;
    body.update(c.extra);
    EXPECT_EQ(Post(s, "/api/simulate", body), CliJson(flags + c.args)) << c.args;
  }
}

TEST(ServerCli, EvaluateAndOptimizeEqualTheCli) {
  const RunningServer s;
  const std::string mission_file = kSource + "/examples/missions/quadcopter_1p5kg.json";
  const Json mission = ReadJsonFile(mission_file);
  const Json evaluated = Post(s, "/api/evaluate",
                              {{"mission", mission}, {"motor", "dc_m_365"}, {"esc", "dc_e_56"}, {"prop", "dc_p_231"},
                               {"battery", "dc_b_363"}, {"cells", 4}});
  EXPECT_EQ(evaluated, CliJson("evaluate " + mission_file +
                               " --motor dc_m_365 --esc dc_e_56 --prop dc_p_231 --battery dc_b_363 --cells 4 --json"));
  Json served = Post(s, "/api/optimize", {{"mission", mission}, {"top", 3}});
  Json cli = CliJson("optimize " + mission_file + " --top 3 --json");
  ASSERT_TRUE(served.contains("seconds"));
  served.erase("seconds");  // the wall time: the one key that differs
  cli.erase("seconds");
  EXPECT_EQ(served, cli);
  EXPECT_EQ(served["results"][0]["motor"], "dc_m_365");
  Json swept = Post(s, "/api/sweep", {{"mission", mission}, {"vary", {"battery.capacity_ah=3:5:1"}}});
  Json cli_sweep = CliJson("sweep " + mission_file + " --vary battery.capacity_ah=3:5:1 --json");
  swept.erase("seconds");
  cli_sweep.erase("seconds");
  EXPECT_EQ(swept, cli_sweep);
}

// An optimize as a job: polled until done, its result is the CLI's.
TEST(ServerCli, OptimizeJobEqualsTheCli) {
  const RunningServer s;
  const std::string mission_file = kSource + "/examples/missions/quadcopter_1p5kg.json";
  const Json started =
      Post(s, "/api/jobs/optimize", {{"mission", ReadJsonFile(mission_file)}, {"top", 3}}, 202);
  const std::string id = started["job"];
  EXPECT_EQ(id.size(), 32u);
  Json st;
  for (int i = 0; i < 600; ++i) {
    st = Get(s, "/api/jobs/" + id);
    if (st["state"] == "done" || st["state"] == "failed") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_EQ(st["state"], "done") << st.dump();
  EXPECT_EQ(st["progress"]["fraction"], 1.0);
  // The Pareto figure's data beside the result: the front's best is the pick's objective.
  const Json& front = st["pareto"]["front"];
  ASSERT_FALSE(front.empty());
  EXPECT_EQ(st["pareto"]["unit"], " min");
  EXPECT_NEAR(front.back()[1].get<double>(), st["result"]["results"][0]["objective"].get<double>() / 60.0, 0.5);
  Json result = st["result"];
  Json cli = CliJson("optimize " + mission_file + " --top 3 --json");
  result.erase("seconds");
  cli.erase("seconds");
  EXPECT_EQ(result, cli);
}

// The logs travel in the body; the answer is the CLI's for a file of that name.
TEST(ServerCli, CalibrateAndDiagnoseEqualTheCli) {
  const RunningServer s;
  const std::string log_file = kSource + "/examples/dyno_log.csv";
  std::ifstream in(log_file);
  std::stringstream text;
  text << in.rdbuf();
  const Json log = {{"name", "dyno_log.csv"}, {"text", text.str()}};
  EXPECT_EQ(Post(s, "/api/calibrate", {{"logs", {log}}, {"motor_id", "my_motor"}, {"esc_id", "my_esc"}}),
            CliJson("calibrate " + log_file + " --motor-id my_motor --esc-id my_esc --json"));
  EXPECT_EQ(Post(s, "/api/calibrate",
                 {{"logs", {log}}, {"motor_id", "m"}, {"esc_id", "e"}, {"kv_label", 2500}, {"loo", true}}),
            CliJson("calibrate " + log_file + " --motor-id m --esc-id e --kv-label 2500 --loo --json"));
  Json cli = CliJson("diagnose " + log_file + " --motor emax_1900kv_paper --json");
  ASSERT_EQ(cli["file"], log_file);
  cli["file"] = "dyno_log.csv";  // the CLI names the file as given; the server as uploaded
  EXPECT_EQ(Post(s, "/api/diagnose", {{"log", log}, {"motor", "emax_1900kv_paper"}}), cli);
  // A log that is not one: the reader's message names the log as uploaded, never the temporary
  // folder. ("QUJD" is base64 of "ABC": how bytes that are not UTF-8 travel.)
  const Json bad = Post(s, "/api/diagnose", {{"log", {{"name", "abc.csv"}, {"base64", "QUJD"}}}}, 400);
  const std::string message = bad["error"];
  EXPECT_EQ(message.rfind("abc.csv", 0), 0u) << message;
  EXPECT_EQ(message.find("dynosize-serve-"), std::string::npos) << message;
}

// `dynosize serve` refuses a port out of range (64) and a port in use (73) with one line.
TEST(ServerCli, ServeCommandErrors) {
  const auto range = RunCli("serve --port 70000");
  EXPECT_EQ(range.code, 64) << range.err;
  EXPECT_NE(range.err.find("--port"), std::string::npos) << range.err;
  const RunningServer s;  // holds a port
  const auto busy = RunCli("serve --port " + std::to_string(s.port()));
  EXPECT_EQ(busy.code, 73) << busy.err;
  EXPECT_EQ(busy.err, "dynosize: serve: cannot listen on 127.0.0.1:" + std::to_string(s.port()) +
                          " (the port is in use, or the address is not this machine's)\n");
  const auto no_page = RunCli("serve --port 0 --web-dir /nonexistent");
  EXPECT_EQ(no_page.code, 66) << no_page.err;
  EXPECT_NE(no_page.err.find("does not hold index.html"), std::string::npos) << no_page.err;
}

// A bad value gets the CLI's message (without "dynosize: ") and exit code.
TEST(ServerCli, ErrorsAreTheCliLines) {
  const RunningServer s;
  struct Case {
    Json body;
    std::string args;
  };
  const Case cases[] = {
      {{{"motor", "emax_1900kv_paper"}, {"esc", "multistar_30a_paper"}, {"vdc_v", -1}}, "--vdc -1"},
      {{{"motor", "emax_1900kv_paper"}, {"esc", "multistar_30a_paper"}, {"vdc_v", 7.2}, {"throttle", 1.5},
        {"torque_nm", 0.01}},
       "--vdc 7.2 --throttle 1.5 --torque 0.01"},
      {{{"motor", "no_such_motor"}, {"esc", "multistar_30a_paper"}, {"vdc_v", 7.2}}, "--vdc 7.2"},
      {{{"motor", "emax_1900kv_paper"}, {"esc", "multistar_30a_paper"}}, ""},
      {{{"motor", "emax_1900kv_paper"}, {"esc", "multistar_30a_paper"}, {"vdc_v", 7.2}, {"thrust_n", 2}},
       "--vdc 7.2 --thrust-n 2"},
  };
  for (const Case& c : cases) {
    const Json served = Post(s, "/api/simulate", c.body, 400);
    const std::string motor = c.body["motor"];
    const auto r = RunCli("simulate --motor " + motor + " --esc multistar_30a_paper " + c.args + " --json");
    ASSERT_EQ(r.err.rfind("dynosize: ", 0), 0u) << r.err;
    EXPECT_EQ(served["error"].get<std::string>() + "\n", r.err.substr(10)) << c.args;
    EXPECT_EQ(served["exit_code"], r.code) << c.args;
  }
}

}  // namespace
}  // namespace dynosize
