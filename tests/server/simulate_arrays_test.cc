// POST /api/simulate with arrays (server/simulate_arrays.h): every point equals the same point
// asked alone (the scalar request, simulate --json's point), bit for bit, as the Python module's
// tests check its batch against the CLI.
#include <gtest/gtest.h>

#include <string>

#include "common/json_file.h"
#include "server/served.h"

namespace dynosize {
namespace {

using testing_util::RunningServer;

Json Post(const RunningServer& s, const Json& body, int status = 200) {
  const auto res = s.Client()->Post("/api/simulate", body.dump(), "application/json");
  EXPECT_TRUE(res);
  if (!res) return Json();
  EXPECT_EQ(res->status, status) << body.dump() << "\n" << res->body;
  return Json::parse(res->body);
}

TEST(ServerSimulateArrays, EveryPointEqualsTheScalarRequest) {
  const RunningServer s;
  const Json pair = {{"motor", "emax_1900kv_paper"}, {"esc", "multistar_30a_paper"}};
  const Json throttles = {0.2, 0.5, 0.8, 1.0};
  Json forward = pair;
  forward["vdc_v"] = 7.2;
  forward["throttle"] = throttles;
  forward["torque_nm"] = 0.02;
  const Json a = Post(s, forward);
  ASSERT_EQ(a["rpm"].size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    Json one = pair;
    one["vdc_v"] = 7.2;
    one["throttle"] = throttles[i];
    one["torque_nm"] = 0.02;
    const Json p = Post(s, one);
    for (const char* key : {"rpm", "idc_a", "irms_a", "pdc_w", "eta_system", "throttle_effective"}) {
      EXPECT_EQ(a[key][i], p[key]) << key << " at " << i;
    }
    EXPECT_EQ(a["feasible"][i], p["feasible"]) << i;
  }
  // With a propeller, one of throttle, rpm or thrust_n per point.
  Json prop = pair;
  prop["prop"] = "fu_p_apc_8x3.8sf";
  prop["vdc_v"] = 7.2;
  prop["thrust_n"] = {1.0, 2.0, 3.0};
  const Json b = Post(s, prop);
  ASSERT_EQ(b["thrust_n"].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    Json one = prop;
    one["thrust_n"] = prop["thrust_n"][i];
    const Json p = Post(s, one);
    EXPECT_NEAR(b["thrust_n"][i].get<double>(), prop["thrust_n"][i].get<double>(), 1e-6) << i;
    EXPECT_NEAR(b["rpm"][i].get<double>(), p["rpm"].get<double>(), 1e-9 * p["rpm"].get<double>()) << i;
  }
  EXPECT_EQ(b["limits"].size(), 3u);
}

TEST(ServerSimulateArrays, BadArraysAre400) {
  const RunningServer s;
  const Json pair = {{"motor", "emax_1900kv_paper"}, {"esc", "multistar_30a_paper"}, {"vdc_v", 7.2}};
  Json lengths = pair;
  lengths["throttle"] = {0.1, 0.2, 0.3};
  lengths["torque_nm"] = {0.01, 0.02};
  EXPECT_EQ(Post(s, lengths, 400)["error"], "torque_nm: 2 values where the other arrays have 3");
  Json range = pair;
  range["throttle"] = {0.5, 1.5};
  range["torque_nm"] = 0.01;
  const std::string message = Post(s, range, 400)["error"];
  EXPECT_EQ(message.rfind("simulate: point:1: ", 0), 0u) << message;
  Json text = pair;
  text["throttle"] = {0.5, "x"};
  text["torque_nm"] = 0.01;
  EXPECT_EQ(Post(s, text, 400)["error"], "simulate: throttle \"x\": must be a number");
  Json law = pair;
  law["throttle"] = {0.5};
  law["torque_law"] = {0.0, 0.0, 1e-7};
  EXPECT_NE(Post(s, law, 400)["error"].get<std::string>().find("do not go with arrays"), std::string::npos);
  Json empty = pair;
  empty["throttle"] = Json::array();
  empty["torque_nm"] = 0.01;
  EXPECT_EQ(Post(s, empty, 400)["error"], "simulate: throttle: an empty array");
}

}  // namespace
}  // namespace dynosize
