// `dynosize calibrate` end to end: --json contract, --out / --force, and that a failed run
// leaves the catalog file byte-identical. The log is written by the test from the model
// (synthetic_log.h), never copied from shared/data.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "calibration/synthetic_log.h"
#include "catalog/catalog.h"
#include "common/json_file.h"

namespace dynosize::calibration {
namespace {

namespace fs = std::filesystem;
using logs::Column;

struct CliRun {
  int code = -1;
  std::string out, err;
};

CliRun Exec(const std::string& args) {
  static int calls = 0;
  const fs::path err_file =
      fs::temp_directory_path() / ("dynosize_cal_cli_" + std::to_string(getpid()) + "_" + std::to_string(++calls));
  const std::string cmd = std::string(DYNOSIZE_EXE) + " " + args + " 2> " + err_file.string();
  CliRun r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_file);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  fs::remove(err_file);
  return r;
}

std::string Slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// A canonical CSV (logs/log_reader.h) of a synthetic AC log; returns its path.
std::string WriteCanonicalLog(const std::string& dir) {
  const auto t = testing_util::MakeSyntheticLog(testing_util::DefaultSpec());
  fs::create_directories(dir);
  const std::string path = dir + "/synthetic_ac.csv";
  std::ofstream f(path);
  f << "time_s,vdc_v,throttle,omega_rad_s,torque_nm,idc_a,vll_rms_v,irms_a,pac_w\n" << std::setprecision(10);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    f << t.Get(Column::kTimeS)[i] << "," << t.Get(Column::kVdcV)[i] << "," << t.Get(Column::kThrottle)[i] << ","
      << t.Get(Column::kOmegaRadS)[i] << "," << t.Get(Column::kTorqueNm)[i] << "," << t.Get(Column::kIdcA)[i]
      << "," << t.Get(Column::kVllRmsV)[i] << "," << t.Get(Column::kIrmsA)[i] << "," << t.Get(Column::kPacW)[i]
      << "\n";
  }
  return path;
}

std::string TempDir(const std::string& name) {
  const std::string d = ::testing::TempDir() + "dynosize_cal_cli_" + std::to_string(getpid()) + "/" + name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(CalibrateCli, JsonContract) {
  const std::string dir = TempDir("json");
  const std::string log = WriteCanonicalLog(dir);
  const CliRun r = Exec("calibrate " + log + " --motor-id m_fit --esc-id e_fit --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "stdout");
  for (const char* k : {"motor", "esc", "stderr", "identifiable", "fit", "warnings"}) EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["motor"]["id"], "m_fit");
  EXPECT_EQ(j["motor"]["source"]["values"]["ke_v_s_per_rad"], "fitted");
  EXPECT_EQ(j["motor"]["source"]["dataset"], "synthetic_ac.csv");
  EXPECT_EQ(j["esc"]["source"]["values"]["tr_sat"], "fitted");
  EXPECT_TRUE(j["identifiable"]["resc_ohm"].get<bool>());
  EXPECT_TRUE(j["fit"]["columns"].contains("idc_a"));
  EXPECT_GT(j["fit"]["points_used"].get<int>(), 50);
}

TEST(CalibrateCli, OutForceAndUntouchedOnFailure) {
  const std::string dir = TempDir("out");
  const std::string log = WriteCanonicalLog(dir);
  const std::string cat_dir = dir + "/cat";
  fs::create_directories(cat_dir);
  const std::string out = cat_dir + "/fitted.json";
  const std::string args = "calibrate " + log + " --motor-id m_fit --esc-id e_fit --out " + out;
  CliRun r = Exec(args);
  ASSERT_EQ(r.code, 0) << r.err;
  Catalog cat;
  ASSERT_NO_THROW(cat = Catalog::Load(cat_dir));
  EXPECT_NEAR(cat.motor("m_fit").params.ke_v_s_per_rad, testing_util::DefaultSpec().motor.ke_v_s_per_rad, 1e-4);
  const std::string before = Slurp(out);
  // Same ids again without --force: usage error, file unchanged.
  r = Exec(args);
  EXPECT_EQ(r.code, 64);
  EXPECT_NE(r.err.find("already has id 'm_fit': use --force"), std::string::npos) << r.err;
  EXPECT_EQ(Slurp(out), before);
  // A bad log: data error, file unchanged.
  const std::string bad = dir + "/bad.csv";
  std::ofstream(bad) << "time_s,vdc_v,throttle,rpm,torque_nm,idc_a\n0,12,0.5,5000,0.1,0\n1,12,0.6,6000,0.15,0\n";
  r = Exec("calibrate " + bad + " --motor-id x --esc-id y --force --out " + out);
  EXPECT_EQ(r.code, 65) << r.err;
  EXPECT_EQ(Slurp(out), before);
  // A missing log: exit 66, file unchanged.
  r = Exec("calibrate " + dir + "/nope.csv --motor-id x --esc-id y --out " + out);
  EXPECT_EQ(r.code, 66) << r.err;
  EXPECT_EQ(Slurp(out), before);
  // With --force: replaced, still loads, one entry each.
  r = Exec(args + " --force");
  EXPECT_EQ(r.code, 0) << r.err;
  const Json doc = ReadJsonFile(out);
  EXPECT_EQ(doc["motors"].size(), 1u);
  EXPECT_EQ(doc["escs"].size(), 1u);
  EXPECT_NO_THROW(Catalog::Load(cat_dir));
}

TEST(CalibrateCli, MissingIdsIsUsageError) {
  const std::string dir = TempDir("ids");
  const std::string log = WriteCanonicalLog(dir);
  const CliRun r = Exec("calibrate " + log);
  EXPECT_EQ(r.code, 64);
  EXPECT_NE(r.err.find("--motor-id and --esc-id are required"), std::string::npos) << r.err;
}

TEST(CalibrateCli, PlotWritesFigures) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  const std::string dir = TempDir("plot");
  const std::string log = WriteCanonicalLog(dir);
  const CliRun r = Exec("calibrate " + log + " --motor-id m --esc-id e --plot " + dir + "/fig");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"fit_idc_a.png", "fit_omega_rad_s.png", "fit_vll_rms_v.png", "fit_irms_a.png"}) {
    EXPECT_TRUE(fs::exists(dir + "/fig/" + f)) << f;
  }
}

}  // namespace
}  // namespace dynosize::calibration
