// `dynosize calibrate` end to end: --json contract, --out / --force, and that a failed run
// leaves the catalog file byte-identical. The log is written by the test from the model
// (synthetic_log.h), never copied from shared/data.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "calibration/synthetic_log.h"
#include "catalog/catalog.h"
#include "cli_runner.h"
#include "common/json_file.h"
#include "common/units.h"

namespace dynosize::calibration {
namespace {

namespace fs = std::filesystem;
using logs::Column;

using dynosize::testing_util::CliRun;

CliRun Exec(const std::string& args) { return dynosize::testing_util::RunCli(args); }

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

// The status contract: --out writes only an "ok" entry; a refused fit exits 65 with one line
// naming the failed check and leaves the catalog file as it was, --force or not.
TEST(CalibrateCli, OutRefusesAFitThatIsNotOk) {
  const std::string dir = TempDir("refuse");
  const std::string log = WriteCanonicalLog(dir);  // a ~900 rpm/V motor
  const std::string out = dir + "/fitted.json";
  // Label 2000 rpm/V: the fit lands far from it (the data determine KE much better than 10 %).
  CliRun r = Exec("calibrate " + log + " --motor-id m --esc-id e --kv-label 2000 --json --out " + out);
  EXPECT_EQ(r.code, 65) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // The log has torque: the label's first contradiction is the log's own torque per ampere
  // (torque_per_ampere_vs_label, listed before the fit's checks); kv_vs_label fails as well.
  EXPECT_NE(r.err.find("not written: status failed, check torque_per_ampere_vs_label failed"), std::string::npos)
      << r.err;
  const Json j = ParseJsonText(r.out, "stdout");
  EXPECT_EQ(j["status"], "failed");
  bool seen = false;
  for (const auto& c : j["checks"]) {
    if (c["name"] == "kv_vs_label") {
      seen = true;
      EXPECT_FALSE(c["passed"].get<bool>());
      EXPECT_DOUBLE_EQ(c["limit"].get<double>(), 25.0);
    }
  }
  EXPECT_TRUE(seen);
  // An existing file stays byte-identical, also with --force.
  r = Exec("calibrate " + log + " --motor-id m --esc-id e --kv-label 900 --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string before = Slurp(out);
  r = Exec("calibrate " + log + " --motor-id m --esc-id e --kv-label 2000 --force --out " + out);
  EXPECT_EQ(r.code, 65) << r.err;
  EXPECT_EQ(Slurp(out), before);
}

// Entries ready for sizing: ratings, mass and the label in the written entries.
TEST(CalibrateCli, RatingsAreStored) {
  const std::string dir = TempDir("ratings");
  const std::string log = WriteCanonicalLog(dir);
  const std::string cat_dir = dir + "/cat";
  fs::create_directories(cat_dir);
  const std::string out = cat_dir + "/fitted.json";
  const CliRun r = Exec("calibrate " + log + " --motor-id m --esc-id e --kv-label 900 --mass-kg 0.085 " +
                        "--max-current-a 30 --max-power-w 400 --esc-max-current-a 35 --esc-vdc-max-v 25.2 --json --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = ParseJsonText(r.out, "stdout");
  EXPECT_EQ(j["status"], "ok") << j["summary"];
  const Catalog cat = Catalog::Load(cat_dir);
  EXPECT_DOUBLE_EQ(cat.motor("m").params.max_current_a, 30.0);
  EXPECT_DOUBLE_EQ(cat.esc("e").params.max_current_a, 35.0);
  const Json doc = ReadJsonFile(out);
  EXPECT_DOUBLE_EQ(doc["motors"][0]["mass_kg"].get<double>(), 0.085);
  EXPECT_DOUBLE_EQ(doc["motors"][0]["kv_rpm_per_v"].get<double>(), 900.0);
  EXPECT_EQ(doc["motors"][0]["source"]["values"]["mass_kg"], "datasheet");
}

// A log with thrust and torque also gives a static propeller entry (--prop-id): CT, CP vs rpm
// that the catalog loads; a thrust that beats momentum theory (FM > 1) is refused with exit 65.
TEST(CalibrateCli, PropEntryFromThrustAndTorque) {
  const std::string dir = TempDir("prop");
  auto t = testing_util::MakeSyntheticLog(testing_util::DefaultSpec());
  // Thrust T = k*omega^2 with k chosen for a figure of merit of 0.6 on the first propeller (10 in):
  // FM = k^1.5/(c*sqrt(2*rho*A)) with Q = c*omega^2.
  const double area = kPi * 0.254 * 0.254 / 4.0, c = 2.0e-7;
  auto write = [&](double fm, const std::string& path) {
    const double k = std::pow(fm * c * std::sqrt(2.0 * 1.225 * area), 2.0 / 3.0);
    std::ofstream f(path);
    f << "time_s,vdc_v,throttle,omega_rad_s,torque_nm,idc_a,thrust_n\n" << std::setprecision(10);
    for (std::size_t i = 0; i < t.rows(); ++i) {
      const double w = t.Get(Column::kOmegaRadS)[i];
      f << t.Get(Column::kTimeS)[i] << "," << t.Get(Column::kVdcV)[i] << "," << t.Get(Column::kThrottle)[i] << ","
        << w << "," << t.Get(Column::kTorqueNm)[i] << "," << t.Get(Column::kIdcA)[i] << "," << k * w * w << "\n";
    }
  };
  const std::string log = dir + "/thrust.csv";
  write(0.6, log);
  const std::string cat_dir = dir + "/cat";
  fs::create_directories(cat_dir);
  const std::string out = cat_dir + "/fitted.json";
  CliRun r = Exec("calibrate " + log + " --motor-id m --esc-id e --kv-label 900 --prop-id p10 --prop-diameter-in 10 " +
                  "--prop-pitch-in 4.5 --json --out " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const Json doc = ReadJsonFile(out);
  ASSERT_EQ(doc["props"].size(), 1u);
  const Json& p = doc["props"][0];
  EXPECT_EQ(p["id"], "p10");
  EXPECT_NEAR(p["diameter_m"].get<double>(), 0.254, 1e-9);
  const auto& rpm = p["static_table"]["rpm"];
  ASSERT_GE(rpm.size(), 3u);
  for (std::size_t k = 1; k < rpm.size(); ++k) EXPECT_GT(rpm[k].get<double>(), rpm[k - 1].get<double>());
  EXPECT_NO_THROW(Catalog::Load(cat_dir));
  // FM = 3 on the first propeller: momentum theory says no; nothing is written.
  const std::string bad = dir + "/fm3.csv";
  write(3.0, bad);
  const std::string before = Slurp(out);
  r = Exec("calibrate " + bad + " --motor-id m2 --esc-id e2 --kv-label 900 --prop-id p10b --prop-diameter-in 10 --out " + out);
  EXPECT_EQ(r.code, 65) << r.err;
  EXPECT_NE(r.err.find("figure of merit"), std::string::npos) << r.err;
  EXPECT_EQ(Slurp(out), before);
}

// A log without a throttle column says so first, naming the column that looks like
// one and the arguments that read it, before any fit result or advice; in --json as the first
// warning.
TEST(CalibrateCli, MissingThrottleIsNamedFirst) {
  const std::string dir = TempDir("no_throttle");
  const std::string canonical = Slurp(WriteCanonicalLog(dir));
  // The same table with its command under a name the synonym table does not know.
  std::string renamed = canonical;
  renamed.replace(0, renamed.find('\n'), "Time (s),vdc_v,command,omega_rad_s,torque_nm,idc_a,vll_rms_v,irms_a,pac_w");
  const std::string path = dir + "/renamed.csv";
  std::ofstream(path) << renamed;
  const CliRun r = Exec("calibrate " + path + " --motor-id m --esc-id e");
  const std::string first = r.err.substr(0, r.err.find('\n'));
  EXPECT_NE(first.find("no throttle column found; \"command\" looks like one"), std::string::npos) << r.err;
  EXPECT_NE(first.find("--map \"throttle=command\""), std::string::npos) << first;
  EXPECT_NE(first.find("every point is then taken at full throttle"), std::string::npos) << first;
  const CliRun j = Exec("calibrate " + path + " --motor-id m --esc-id e --json");
  const Json doc = Json::parse(j.out);
  ASSERT_FALSE(doc["warnings"].empty());
  EXPECT_NE(doc["warnings"][0].get<std::string>().find("no throttle column found"), std::string::npos);
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
