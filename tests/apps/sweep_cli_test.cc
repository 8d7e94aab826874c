// `dynosize sweep` end to end: the CSV and JSON on the small catalog, the
// figures, and every bad --vary as one line with exit 64.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_runner.h"
#include "common/json_file.h"
#include "optimization/small_catalog.h"

namespace dynosize {
namespace {

namespace fs = std::filesystem;
using testing_util::CliRun;
using testing_util::RunCli;

int Lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

class SweepCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = testing_util::WriteSmallCatalog("sweep_cli");
    std::ofstream(dir_ / "quad.json") << testing_util::kQuad;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string Sweep(const std::string& args) {
    return "--catalog " + (dir_ / "catalog").string() + " sweep " + (dir_ / "quad.json").string() + " " + args;
  }
  static fs::path dir_;
};
fs::path SweepCliTest::dir_;

TEST_F(SweepCliTest, CsvRowPerPointAndTopLinesPerPick) {
  const CliRun r = RunCli(Sweep("--vary vehicle.mass_kg=0.5:0.7:0.1 --vary 'segments[1].distance_m=500,1000' --quiet"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(Lines(r.out), 1 + 6) << r.out;
  EXPECT_EQ(r.out.rfind("index,vehicle.mass_kg,segments[1].distance_m,status,", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\n5,0.7,1000,ok,1,true,"), std::string::npos) << r.out;
  const CliRun top = RunCli(Sweep("--vary vehicle.mass_kg=0.5,0.6 --top 2 --quiet"));
  ASSERT_EQ(top.code, 0) << top.err;
  EXPECT_EQ(Lines(top.out), 1 + 4) << top.out;
}

// The sweep's JSON row of a point equals optimize --json of the same mission edited by hand.
TEST_F(SweepCliTest, JsonRowEqualsOptimizeOfThatMission) {
  const CliRun r = RunCli(Sweep("--vary vehicle.mass_kg=0.5,0.9 --json --quiet"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "sweep");
  ASSERT_EQ(j["rows"].size(), 2u);
  Json m = ParseJsonText(testing_util::kQuad, "quad");
  m["vehicle"]["mass_kg"] = 0.9;
  const fs::path edited = dir_ / "quad_0.9.json";
  std::ofstream(edited) << DumpJson(m);
  const CliRun o = RunCli("--catalog " + (dir_ / "catalog").string() + " optimize " + edited.string() +
                          " --top 1 --json --quiet");
  ASSERT_EQ(o.code, 0) << o.err;
  const Json best = ParseJsonText(o.out, "optimize")["results"][0];
  const Json& pick = j["rows"][1]["picks"][0];
  EXPECT_FALSE(pick.contains("motor"));  // parts are listed per group
  EXPECT_EQ(pick["parts"][0]["motor"], best["motor"]);
  EXPECT_EQ(pick["parts"][0]["esc"], best["esc"]);
  EXPECT_EQ(pick["parts"][0]["prop"], best["prop"]);
  EXPECT_EQ(pick["battery"], best["battery"]);
  EXPECT_EQ(pick["cells"], best["cells"]);
  // optimize prints the objective in SI (s); the sweep in the CLI's unit (min).
  EXPECT_EQ(pick["objective"].get<double>(), best["objective"].get<double>() / 60.0);
  EXPECT_EQ(pick["objective_range"][0].get<double>(), best["objective_range"][0].get<double>() / 60.0);
  EXPECT_EQ(j["rows"][1]["values"]["vehicle.mass_kg"], Json(0.9));
}

TEST_F(SweepCliTest, OutFileAndFigures) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  const fs::path out = dir_ / "rows.csv", plots = dir_ / "plots";
  const CliRun r = RunCli(Sweep("--vary vehicle.mass_kg=0.5,0.6 --vary 'segments[2].duration_s=200,400' --quiet --out " +
                                out.string() + " --plot " + plots.string()));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  std::ifstream f(out);
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(Lines(ss.str()), 5);
  for (const char* png : {"objective_vs_vehicle_mass_kg.png", "objective_vs_segments_2__duration_s.png",
                          "carpet_vehicle_mass_kg_segments_2__duration_s.png"}) {
    EXPECT_GT(fs::file_size(plots / png), 10000u) << png;
  }
}

TEST_F(SweepCliTest, BadInputIsOneLineAndExit64) {
  const std::pair<std::string, std::string> cases[] = {
      {"--vary vehicle.mas_kg=1,2", "nearest valid keys: vehicle.mass_kg"},
      {"--vary vehicle.mass_kg=1:2:0", "STEP must not be 0"},
      {"--vary vehicle.mass_kg=2:1:0.1", "never reaches STOP"},
      {"--vary vehicle=1", "is an object"},
      {"--vary vehicle.mass_kg=-1,-2", "no value gives a valid mission"},
      {"--vary vehicle.mass_kg=0.001:1.001:0.001 --vary vehicle.rotors=1:1000:1", "over 10^6: give --yes"},
      {"--vary vehicle.mass_kg=1 --time-limit 0", "--time-limit 0"},
      {"", "--vary is required"},
  };
  for (const auto& [args, rule] : cases) {
    const CliRun r = RunCli(Sweep(args));
    EXPECT_EQ(r.code, 64) << args << ": " << r.err;
    EXPECT_NE(r.err.find(rule), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(Lines(r.err), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  // --yes lets a large grid past the size check (here to the next check, the unknown key).
  const CliRun yes = RunCli(Sweep("--vary vehicle.mass_kg=0.001:1.001:0.001 --vary vehicle.rotorz=1:1000:1 --yes"));
  EXPECT_EQ(yes.code, 64);
  EXPECT_NE(yes.err.find("unknown key"), std::string::npos) << yes.err;
  const CliRun missing = RunCli("sweep /nonexistent/m.json --vary vehicle.mass_kg=1");
  EXPECT_EQ(missing.code, 66) << missing.err;
}

fs::path LongMission() { return testing_util::LongSearchMission("sweep_long"); }

// stderr: only when the shell's redirection reaches the sweep (not a background job's).
void ExpectCompleteStoppedJson(const CliRun& r, bool check_stderr) {
  Json j;
  ASSERT_NO_THROW(j = Json::parse(r.out)) << r.out.substr(0, 200);
  EXPECT_EQ(j["interrupted"], true);
  EXPECT_EQ(j["points"], Json(2));
  EXPECT_TRUE(j["rows"].empty());  // both points were mid-search: no half-done row
  if (check_stderr) {
    EXPECT_NE(r.err.find("stopped after 0 of 2 points (--time-limit)"), std::string::npos) << r.err;
  }
}

TEST(SweepCliStop, TimeLimitAndSigintWriteTheRowsDoneSoFar) {
  const fs::path m = LongMission();
  const std::string sweep = "sweep " + m.string() + " --vary vehicle.mass_kg=2.4,2.5 --json";
  const CliRun t = RunCli(sweep + " --time-limit 0.5");
  EXPECT_EQ(t.code, 0) << t.err;
  ExpectCompleteStoppedJson(t, true);
  const CliRun r = RunCli(sweep + " & p=$!; sleep 1; kill -INT $p; wait $p");
  EXPECT_EQ(r.code, 130) << r.err;
  ExpectCompleteStoppedJson(r, false);
  fs::remove(m);
}

}  // namespace
}  // namespace dynosize
