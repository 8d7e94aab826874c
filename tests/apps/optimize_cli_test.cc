// optimize's stop: --time-limit and SIGINT print the best so far, complete
// and marked interrupted, with exit 0 and 130; bad --time-limit values are exit 64 with one line.
// Item 5 on the CLI: distinct designs by default, --variants for every combination.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_runner.h"
#include "common/json_file.h"

namespace dynosize {
namespace {

namespace fs = std::filesystem;
using testing_util::CliRun;
using testing_util::RunCli;

const std::string kSource = DYNOSIZE_SOURCE_DIR;

int Lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// A search that outlasts every stop below (cli_runner.h).
fs::path LongMission() { return testing_util::LongSearchMission("long"); }

// bound_known: the stop came after the first pass (a few seconds in), so the bound is a number.
void ExpectCompleteInterruptedJson(const CliRun& r, bool bound_known) {
  Json j;
  ASSERT_NO_THROW(j = Json::parse(r.out)) << r.out.substr(0, 200);
  EXPECT_EQ(j["interrupted"], true);
  ASSERT_TRUE(j.contains("bound_gap"));
  EXPECT_TRUE(j["results"].is_array());
  EXPECT_GT(j["unsettled"].get<long long>(), 0);
  // The proven bound: nothing unsettled beats it (endurance: a number of seconds above the best
  // found); null only when the joint search stopped before its first pass had bounded every
  // outer choice (within its first seconds: the dive's designs, docs/joint-search.md#dive).
  if (!bound_known && j["bound_gap"]["unsettled_bound"].is_null()) return;
  ASSERT_TRUE(j["bound_gap"]["unsettled_bound"].is_number());
  for (const Json& x : j["results"]) EXPECT_LE(x["objective"].get<double>(), j["bound_gap"]["unsettled_bound"].get<double>() + 1e-9);
}

TEST(OptimizeCli, BadTimeLimitIsExit64WithOneLine) {
  for (const std::string v : {"0", "-1", "nan", "-inf"}) {
    const CliRun r = RunCli("optimize " + kSource + "/examples/missions/quadcopter_1p5kg.json --time-limit=" + v);
    EXPECT_EQ(r.code, 64) << v << "\n" << r.err;
    EXPECT_NE(r.err.find("dynosize: --time-limit " + v + ": must be a positive number of seconds"), std::string::npos)
        << v << "\n" << r.err;
    EXPECT_EQ(Lines(r.err), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

TEST(OptimizeCli, TimeLimitPrintsTheBestSoFarAndExitsZero) {
  const fs::path m = LongMission();
  const CliRun r = RunCli("optimize " + m.string() + " --json --time-limit 0.5");
  EXPECT_EQ(r.code, 0) << r.err;
  ExpectCompleteInterruptedJson(r, false);
  const CliRun t = RunCli("optimize " + m.string() + " --time-limit 0.5");
  EXPECT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("interrupted after "), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("bound gap: "), std::string::npos) << t.out;
  fs::remove(m);
}

TEST(OptimizeCli, SigintPrintsTheBestSoFarAndExits130) {
  const fs::path m = LongMission();
  // The shell starts optimize, sends SIGINT after a second (the search takes far longer) and
  // returns its exit status.
  const CliRun r = RunCli("optimize " + m.string() + " --json & p=$!; sleep 1; kill -INT $p; wait $p");
  EXPECT_EQ(r.code, 130) << r.err;
  ExpectCompleteInterruptedJson(r, false);
  fs::remove(m);
}

TEST(OptimizeCli, DistinctDesignsByDefaultAndVariantsOnRequest) {
  const std::string mission = kSource + "/examples/missions/sprayer_hexacopter_25kg.json";
  const CliRun d = RunCli("optimize " + mission + " --json --top 3");
  const CliRun v = RunCli("optimize " + mission + " --json --top 3 --variants");
  ASSERT_EQ(d.code, 0) << d.err;
  ASSERT_EQ(v.code, 0) << v.err;
  const Json jd = Json::parse(d.out), jv = Json::parse(v.out);
  ASSERT_EQ(jd["results"].size(), 3u);
  ASSERT_EQ(jv["results"].size(), 3u);
  EXPECT_EQ(jd["results"][0]["motor"], jv["results"][0]["motor"]);
  EXPECT_EQ(jd["results"][0]["objective"], jv["results"][0]["objective"]);
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t k = 0; k < i; ++k) {
      const Json &a = jd["results"][i], &b = jd["results"][k];
      EXPECT_FALSE(a["motor"] == b["motor"] && a["prop"] == b["prop"]) << i << " repeats the design of " << k;
    }
  }
  // The bundled sprayer's top 3 combinations are one design with three ESCs (measured): the
  // first design lists them as alternatives.
  EXPECT_EQ(jv["results"][1]["motor"], jv["results"][0]["motor"]);
  EXPECT_EQ(jv["results"][1]["prop"], jv["results"][0]["prop"]);
  EXPECT_FALSE(jd["results"][0]["alternatives"].empty());
  EXPECT_EQ(jd["interrupted"], false);
}

// Item 6: with groups every segment row starts with its whole name and its group (the old table
// cut "name/group" at 12 characters: "cruise/cruiscruise"), under headers that say what they hold.
TEST(OptimizeCli, SegmentTableNamesEachSegmentAndItsGroup) {
  const CliRun r = RunCli("evaluate " + kSource + "/examples/missions/evtol_lift_cruise.json --pick "
                          "lift=dc_m_334,dc_e_145,dc_p_318 --battery dc_b_361 --cells 6");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json m = ReadJsonFile(kSource + "/examples/missions/evtol_lift_cruise.json");
  for (const std::string h : {"throttle %", "effective %", "eta_mot", "eta_esc", "eta_sys", "group"}) {
    EXPECT_NE(r.out.find(h), std::string::npos) << h;
  }
  EXPECT_EQ(r.out.find("eff %"), std::string::npos);
  int rows = 0;
  for (const Json& sg : m["segments"]) {
    const std::string name = sg["name"], group = sg["group"];
    std::string row = "\n  " + name + " ";
    const auto at = r.out.find(row);
    ASSERT_NE(at, std::string::npos) << name << "\n" << r.out;
    std::istringstream fields(r.out.substr(at + 1, r.out.find('\n', at + 1) - at - 1));
    std::string first, second;
    fields >> first >> second;
    EXPECT_EQ(first, name);
    EXPECT_EQ(second, group) << name;
    ++rows;
  }
  EXPECT_GE(rows, 4);
}

// Issue 51 item 5: when nothing flies, the text prints one line per requirement no part of the
// catalog meets under "no combination ...", and --json lists them under no_design_because
// (docs/search.md#why-nothing-flies); a mission that flies has the key, empty.
TEST(OptimizeCli, NothingFliesSaysWhy) {
  Json doc = ReadJsonFile(kSource + "/examples/missions/quadcopter_1p5kg.json");
  doc["vehicle"]["mass_kg"] = 150.0;
  const fs::path m = fs::temp_directory_path() / ("dynosize_heavy_quad_" + std::to_string(getpid()) + ".json");
  std::ofstream(m) << doc.dump(2);
  const CliRun t = RunCli("optimize " + m.string() + " --top 1");
  EXPECT_EQ(t.code, 0) << t.err;
  const std::string line = "no combination of the catalog flies this mission within its constraints\n";
  const auto at = t.out.find(line);
  ASSERT_NE(at, std::string::npos) << t.out;
  EXPECT_EQ(t.out.find("  hover_thrust_per_rotor: needs at least ", at), at + line.size()) << t.out;
  EXPECT_NE(t.out.find("  motor_power_per_rotor: needs at least "), std::string::npos) << t.out;
  const CliRun j = RunCli("optimize " + m.string() + " --top 1 --json");
  EXPECT_EQ(j.code, 0) << j.err;
  Json out;
  ASSERT_NO_THROW(out = Json::parse(j.out)) << j.out.substr(0, 200);
  EXPECT_EQ(out["results"], Json::array());
  ASSERT_TRUE(out["no_design_because"].is_array());
  ASSERT_FALSE(out["no_design_because"].empty());
  for (const Json& r : out["no_design_because"]) {
    for (const char* key : {"requirement", "needed", "best_available", "unit", "components"}) {
      EXPECT_TRUE(r.contains(key)) << key << " in " << r.dump();
    }
    EXPECT_GT(r["needed"].get<double>(), r["best_available"].get<double>()) << r.dump();
  }
  fs::remove(m);
  const CliRun f = RunCli("optimize " + kSource + "/examples/missions/quadcopter_1p5kg.json --top 1 --json");
  ASSERT_EQ(f.code, 0) << f.err;
  EXPECT_EQ(Json::parse(f.out)["no_design_because"], Json::array());
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// A mission's sized propellers (sized_props, docs/missions.md): the search sees them beside the
// catalog's, and the air taxi's lift rotors grow past the largest measured propeller (0.90 m).
TEST(OptimizeCli, SizedLiftRotorsOfTheAirTaxi) {
  const testing_util::CliRun r = testing_util::RunCli(
      "optimize " + std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/air_taxi_sized_rotors.json --top 1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  const std::string dump = j.dump();
  EXPECT_NE(dump.find("sized_multirotor_"), std::string::npos) << dump.substr(0, 400);
  EXPECT_EQ(dump.find("\"feasible\":false"), std::string::npos);
}

// The rotor sized by the search (docs/missions.md, "Sizing the rotor"): the cargo octocopter's
// frame takes 1.32 m; the catalog's families are offered within it, and the result says which
// size it took, its family and how far the family's data reach, in --json and in the text.
TEST(OptimizeCli, TheCargoOctocopterSizesItsRotorWithinTheFrame) {
  const std::string mission = std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/cargo_octocopter_150kg.json";
  const testing_util::CliRun r = testing_util::RunCli("optimize " + mission + " --top 1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  ASSERT_EQ(j.at("results").size(), 1u);
  const Json& best = j.at("results")[0];
  ASSERT_TRUE(best.contains("sized_prop")) << best.dump().substr(0, 400);
  const Json& sized = best.at("sized_prop");
  EXPECT_LE(sized.at("diameter_m").get<double>(), 1.32 + 1e-9);
  EXPECT_GE(sized.at("diameter_m").get<double>(), 20 * 0.0254 - 1e-9);
  EXPECT_NE(sized.at("reach").get<std::string>().find("the family"), std::string::npos);
  const testing_util::CliRun t = testing_util::RunCli("optimize " + mission + " --top 1");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("  sized propeller: "), std::string::npos) << t.out.substr(0, 800);
}

}  // namespace
}  // namespace dynosize
