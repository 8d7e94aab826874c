// End-to-end tests of the dynosize executable: exit codes, one-line errors, JSON contract.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_runner.h"
#include "catalog/catalog.h"
#include "common/json_file.h"

namespace dynosize {
namespace {

using testing_util::CliRun;

CliRun Exec(const std::string& args) { return testing_util::RunCli(args); }

const std::string kPair = "simulate --motor emax_1900kv_paper --esc multistar_30a_paper ";

int Lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// Every command that reads a log offers every reader (thrustapp included).
TEST(Cli, EveryLogCommandListsEveryFormat) {
  for (const char* cmd : {"calibrate", "diagnose", "validate-stand"}) {
    const CliRun r = Exec(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.out.find("{auto,canonical,rcbenchmark,mapped,drivecalc,thrustapp}"), std::string::npos)
        << cmd << ": " << r.out;
  }
}

TEST(Cli, BadInputGetsOneLineAndExitCode) {
  struct Case {
    std::string args;
    int code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {kPair + "--vdc 7.2 --throttle 1.7 --torque 0.01", 64, "--throttle 1.7: must be between 0 and 1"},
      {kPair + "--vdc=-5 --throttle 0.5 --torque 0.01", 64, "--vdc -5: must be a finite number > 0 V"},
      {kPair + "--vdc nan --throttle 0.5 --torque 0.01", 64, "--vdc nan: must be a finite number > 0 V"},
      {kPair + "--vdc 7.2 --throttle 0.5 --torque -1", 64, "--torque -1: must be a finite number >= 0"},
      {kPair + "--vdc 7.2 --throttle 0.5", 64, "give --throttle with one of --torque"},
      {kPair + "--vdc 7.2 --throttle 0.5 --torque 0.01 --rpm 100", 64, "give --throttle with one of"},
      {kPair + "--vdc abc --throttle 0.5 --torque 0.01", 64, "Could not convert: --vdc = abc"},
      {"simulate --motor nope --esc multistar_30a_paper --vdc 7.2 --throttle 0.5 --torque 0.01", 64,
       "unknown motor id 'nope'; closest:"},
      {kPair + "--vdc 7.2 --throttle 0.5 --torque 0.01 --catalog /nonexistent", 66,
       "/nonexistent: no such catalog folder"},
      {"frobnicate", 64, "unknown subcommand 'frobnicate': valid are simulate, calibrate, diagnose, catalog"},
      {kPair + "--batch /nonexistent.csv", 66, "/nonexistent.csv: no such file"},
  };
  for (const auto& c : cases) {
    const CliRun r = Exec(c.args);
    EXPECT_EQ(r.code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find("dynosize: " + c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(Lines(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
  }
}

TEST(Cli, MalformedCatalogIsExit65AndNamesTheProblem) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / (std::string("dynosize_cli_bad_catalog_" + std::to_string(getpid())));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "bad.json") << R"({"motors": [{"id": "x", "name": "x", "type": "bldc",
    "kv_rpm_per_v": 900, "rm_ohm": 0, "io_a": 0.3, "source": {"dataset": "t"}}]})";
  const CliRun r = Exec(kPair + "--vdc 7.2 --throttle 0.5 --torque 0.01 --catalog " + dir.string());
  EXPECT_EQ(r.code, 65);
  EXPECT_NE(r.err.find("bad.json: motors[0] id=x: key 'rm_ohm' = 0: must be a finite number > 0"),
            std::string::npos) << r.err;
  const CliRun v = Exec("catalog validate " + dir.string());
  EXPECT_EQ(v.code, 65);
  fs::remove_all(dir);
}

TEST(Cli, JsonContract) {
  const CliRun r = Exec(kPair + "--vdc 7.2 --throttle 0.6 --torque 0.04 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "stdout");
  for (const char* key : {"rpm", "omega_rad_s", "torque_nm", "irms_a", "vll_rms_v", "pac_w", "idc_a",
                          "pdc_w", "pesc_w", "pmech_w", "eta_motor", "eta_esc", "eta_system",
                          "throttle", "throttle_effective", "saturated", "feasible"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_NEAR(j["torque_nm"].get<double>(), 0.04, 1e-15);
  // The inverse from the forward result returns the throttle.
  const CliRun inv = Exec(kPair + "--vdc 7.2 --torque 0.04 --rpm " + std::to_string(j["rpm"].get<double>()) + " --json");
  ASSERT_EQ(inv.code, 0) << inv.err;
  EXPECT_NEAR(ParseJsonText(inv.out, "stdout")["throttle"].get<double>(), 0.6, 1e-6);  // rpm printed to 6 digits
}

TEST(Cli, InfeasibleInverseIsReportedNotCrashed) {
  const CliRun r = Exec(kPair + "--vdc 7.2 --torque 0.01 --rpm 30000 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "stdout");
  EXPECT_FALSE(j["feasible"].get<bool>());
  EXPECT_EQ(j["limits"][0].get<std::string>(), "throttle_above_one");
}

TEST(Cli, BatchWritesOneRowPerPoint) {
  namespace fs = std::filesystem;
  const fs::path in = fs::temp_directory_path() / (std::string("dynosize_points_" + std::to_string(getpid()) + ".csv"));
  const fs::path out = fs::temp_directory_path() / (std::string("dynosize_points_out_" + std::to_string(getpid()) + ".csv"));
  std::ofstream(in) << "vdc_v,throttle,torque_nm,rpm\n7.2,0.5,0.02,\n7.2,0.5,,3000\n7.2,,0.02,3000\n";
  CliRun r = Exec(kPair + "--batch " + in.string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream f(out);
  std::string line;
  int rows = 0;
  while (std::getline(f, line)) ++rows;
  EXPECT_EQ(rows, 4);
  std::ofstream(in) << "vdc_v,throttle,torque_nm\n7.2,0.5,abc\n";
  r = Exec(kPair + "--batch " + in.string());
  EXPECT_EQ(r.code, 65);
  EXPECT_NE(r.err.find(":2: column torque_nm = \"abc\": not a finite number"), std::string::npos) << r.err;
  fs::remove(in);
  fs::remove(out);
}

TEST(Cli, PlotWritesTheFiguresAndNoNaNIsPrinted) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / (std::string("dynosize_cli_plot_" + std::to_string(getpid())));
  fs::remove_all(dir);
  const CliRun r = Exec(kPair + "--vdc 7.2 --plot " + dir.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "stdout");
  EXPECT_EQ(j["figures"].size(), 5u);
  for (const auto& f : j["figures"]) EXPECT_GT(fs::file_size(f.get<std::string>()), 10000u) << f;
  EXPECT_EQ(r.out.find("null"), std::string::npos);
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
  fs::remove_all(dir);
}

TEST(Cli, CatalogListJsonIsCatalogEntries) {
  const CliRun r = Exec("catalog list --kind escs --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "stdout");
  ASSERT_TRUE(j.contains("escs"));
  bool found = false;
  for (const auto& e : j["escs"]) found |= e["id"] == "multistar_30a_paper";
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// simulate --prop with a geared motor: the motor's rpm and the propeller's
// prop_rpm side by side, rpm = gear_ratio x prop_rpm, and the propeller's thrust is its data at
// prop_rpm (the propeller turns at its own speed, not the motor's). The bundled catalog's
// KIRA 650-13 with its 6.7:1 gearbox and the 24x10 of the sprayer example.
TEST(Cli, SimulatePropWithAGearedMotorReportsBothSpeeds) {
  const std::string cat = std::string(DYNOSIZE_SOURCE_DIR) + "/catalog";
  const auto r = testing_util::RunCli("simulate --catalog " + cat +
                                      " --motor dc_m_695 --esc dc_e_26 --prop dc_p_304 --vdc 44.4 --throttle 0.4 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "simulate");
  ASSERT_TRUE(j.contains("prop_rpm"));
  EXPECT_DOUBLE_EQ(j["gear_ratio"].get<double>(), 6.7);
  EXPECT_NEAR(j["rpm"].get<double>(), 6.7 * j["prop_rpm"].get<double>(), 1e-9 * j["rpm"].get<double>());
  // The propeller is well below the motor's speed (a 24 in propeller near 3,300 rpm, the motor
  // near 22,000 rpm at 40 % of 44.4 V).
  EXPECT_LT(j["prop_rpm"].get<double>(), 5000.0);
  EXPECT_GT(j["gear_loss_w"].get<double>(), 0.0);
  // The loss closes the power balance: motor shaft = propeller + gear loss; the motor's
  // efficiency stays below 1.
  EXPECT_LT(j["eta_motor"].get<double>(), 1.0);
  // Text: both speeds.
  const auto t = testing_util::RunCli("simulate --catalog " + cat +
                                      " --motor dc_m_695 --esc dc_e_26 --prop dc_p_304 --vdc 44.4 --throttle 0.4");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("propeller rpm"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("geared 6.70:1"), std::string::npos) << t.out;
  // Direct drive: prop_rpm is the motor's rpm.
  const auto d = testing_util::RunCli("simulate --catalog " + cat +
                                      " --motor dc_m_550 --esc dc_e_145 --prop dc_p_349 --vdc 14.8 --throttle 0.5 --json");
  ASSERT_EQ(d.code, 0) << d.err;
  const Json jd = ParseJsonText(d.out, "simulate");
  EXPECT_EQ(jd["rpm"].get<double>(), jd["prop_rpm"].get<double>());
  EXPECT_FALSE(jd.contains("gear_ratio"));
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

TEST(Cli, SimulateWithAPropellerFromItsSize) {
  const testing_util::CliRun r = testing_util::RunCli(
      "simulate --motor hl_m_kde7215xf_135 --esc kde_e_uas125uvc --prop-param 27.5x8.9x2 --vdc 44.4 --throttle 0.7 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j.at("prop").get<std::string>(), "sized_multirotor_27.5x8.9x2");
  EXPECT_GT(j.at("thrust_n").get<double>(), 0.0);
  EXPECT_GT(j.at("prop_torque_nm").get<double>(), 0.0);
  EXPECT_NEAR(j.at("prop_power_w").get<double>(), j.at("pmech_w").get<double>(), 1e-6 * j.at("pmech_w").get<double>());
  EXPECT_EQ(j.at("prop_source").at("tier").get<std::string>(), "estimated");
  EXPECT_NE(j.at("prop_source").at("reference").get<std::string>().find("family multirotor"), std::string::npos);
  const testing_util::CliRun both = testing_util::RunCli(
      "simulate --motor hl_m_kde7215xf_135 --esc kde_e_uas125uvc --prop kde_p_27.5x8.9x2 --prop-param 27.5x8.9 --vdc 44.4");
  EXPECT_EQ(both.code, 64);
  EXPECT_NE(both.err.find("give one propeller"), std::string::npos) << both.err;
  const testing_util::CliRun bad = testing_util::RunCli(
      "simulate --motor hl_m_kde7215xf_135 --esc kde_e_uas125uvc --prop-param 27.5 --vdc 44.4");
  EXPECT_EQ(bad.code, 64);
  EXPECT_NE(bad.err.find("DxP"), std::string::npos) << bad.err;
  const testing_util::CliRun fam = testing_util::RunCli(
      "simulate --motor hl_m_kde7215xf_135 --esc kde_e_uas125uvc --prop-param 27.5x8.9 --prop-family wood --vdc 44.4");
  EXPECT_EQ(fam.code, 64);
  EXPECT_NE(fam.err.find("known are"), std::string::npos) << fam.err;
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// The catalog's propeller families (catalog/prop_families.json): shown like an entry, counted by validate.
TEST(Cli, CatalogShowsThePropellerFamiliesTheSearchSizes) {
  const testing_util::CliRun r = testing_util::RunCli("catalog show fam_evtol_rotor");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j.at("family").get<std::string>(), "evtol_rotor");
  EXPECT_EQ(j.at("diameter_m")[1].get<double>(), 4.0);
  EXPECT_GT(j.at("derived").at("sizes_on_the_grid").get<int>(), 100);
  const testing_util::CliRun v = testing_util::RunCli("catalog validate");
  ASSERT_EQ(v.code, 0) << v.err;
  EXPECT_NE(v.out.find("2 propeller families the search sizes"), std::string::npos) << v.out;
}

// `rotor entry --pe0`: APC's geometry through the blade-element model as a catalog document.
TEST(Cli, RotorEntryWritesACatalogPropellerFromApcsGeometry) {
  const std::string pe0 = std::string(DYNOSIZE_SHARED_DIR) + "/data/apc_geometry/geometry/14x7E-PERF.PE0";
  if (!std::filesystem::exists(pe0)) GTEST_SKIP() << "no ../shared/data/apc_geometry";
  const testing_util::CliRun r = testing_util::RunCli("rotor entry --pe0 " + pe0);
  ASSERT_EQ(r.code, 0) << r.err;
  Catalog c;
  std::vector<std::string> problems;
  c.AddDocument(Json::parse(r.out), "entry.json", &problems);
  ASSERT_TRUE(problems.empty()) << problems.front();
  const PropEntry& p = c.prop("bemt_apc_14x7e");
  EXPECT_NEAR(p.diameter_m, 14 * 0.0254, 1e-3);
  EXPECT_EQ(p.tier, DataTier::kEstimated);
  EXPECT_FALSE(p.static_table.rpm.empty());
  const testing_util::CliRun missing = testing_util::RunCli("rotor entry --pe0 /nonexistent/14x7E-PERF.PE0");
  EXPECT_EQ(missing.code, 66) << missing.err;
}

}  // namespace
}  // namespace dynosize
