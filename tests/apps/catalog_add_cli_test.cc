// End-to-end: the user's own parts on top of the bundled catalog (--catalog-add, --override,
// DYNOSIZE_CATALOG_PATH; docs/catalog.md).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_runner.h"
#include "common/json_file.h"

namespace dynosize {
namespace {

namespace fs = std::filesystem;
using testing_util::CliRun;
using testing_util::RunCli;

const std::string kPoint = "--vdc 11.1 --throttle 0.8 --torque 0.05 --json";
const std::string kBundled = std::string(DYNOSIZE_SOURCE_DIR) + "/catalog";

class CatalogAddCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dynosize_catalog_add_" + std::to_string(getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    unsetenv("DYNOSIZE_CATALOG_PATH");
  }
  void TearDown() override {
    fs::remove_all(dir_);
    unsetenv("DYNOSIZE_CATALOG_PATH");
  }
  // The bundled paper's file with the EMAX 1900 KV's resistance changed, in dir_/sub.
  std::string PaperCopy(const std::string& sub, const std::string& rm_ohm) {
    std::ifstream in(kBundled + "/paper_brown_chopra.json");
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    const auto at = text.find("\"rm_ohm\": 0.12,");  // the first motor's (emax_1900kv_paper)
    EXPECT_NE(at, std::string::npos);
    text.replace(at, 15, "\"rm_ohm\": " + rm_ohm + ",");
    fs::create_directories(dir_ / sub);
    std::ofstream(dir_ / sub / "paper_brown_chopra.json") << text;
    return (dir_ / sub).string();
  }
  fs::path dir_;
};

double Idc(const CliRun& r) { return ParseJsonText(r.out, "stdout")["idc_a"].get<double>(); }

TEST_F(CatalogAddCli, ClashingIdIsExit65NamingBothFiles) {
  const std::string mine = PaperCopy("mine", "0.2");
  const CliRun r = RunCli("--catalog-add " + mine +
                          " simulate --motor emax_1900kv_paper --esc multistar_30a_paper " + kPoint);
  EXPECT_EQ(r.code, 65) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("dynosize: " + mine + "/paper_brown_chopra.json: motors[0] id=emax_1900kv_paper"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("clashes with " + kBundled + "/paper_brown_chopra.json: motors[0] id=emax_1900kv_paper"),
            std::string::npos) << r.err;
  // catalog validate reads the same folders and says the same.
  const CliRun v = RunCli("catalog validate --catalog-add " + mine);
  EXPECT_EQ(v.code, 65);
  EXPECT_NE(v.out.find("clashes with"), std::string::npos) << v.out;
}

TEST_F(CatalogAddCli, OverrideLetsTheAddedEntryWin) {
  const std::string pair = "simulate --motor emax_1900kv_paper --esc multistar_30a_paper " + kPoint;
  const CliRun bundled = RunCli(pair);
  ASSERT_EQ(bundled.code, 0) << bundled.err;
  // The same numbers added again change nothing; a larger resistance draws more current at the
  // same torque (more copper loss, docs/model.md eq 48).
  const CliRun same = RunCli(pair + " --catalog-add " + PaperCopy("same", "0.12") + " --override");
  ASSERT_EQ(same.code, 0) << same.err;
  EXPECT_EQ(Idc(same), Idc(bundled));
  const CliRun hot = RunCli(pair + " --catalog-add " + PaperCopy("hot", "0.3") + " --override");
  ASSERT_EQ(hot.code, 0) << hot.err;
  EXPECT_GT(Idc(hot), Idc(bundled));
  // The last folder added wins.
  const CliRun both = RunCli(pair + " --catalog-add " + (dir_ / "hot").string() + " --catalog-add " +
                             (dir_ / "same").string() + " --override");
  ASSERT_EQ(both.code, 0) << both.err;
  EXPECT_EQ(Idc(both), Idc(bundled));
}

TEST_F(CatalogAddCli, CalibratedMotorBesideTheBundledCatalog) {
  const std::string mine = (dir_ / "mine").string();
  fs::create_directories(mine);
  const CliRun cal = RunCli("calibrate " + std::string(DYNOSIZE_SOURCE_DIR) +
                            "/examples/dyno_log.csv --motor-id my_motor --esc-id my_esc --out " + mine + "/mine.json");
  ASSERT_EQ(cal.code, 0) << cal.err;
  // Without the folder the motor is unknown; with it, it runs with a bundled ESC.
  const std::string sim = "simulate --motor my_motor --esc multistar_30a_paper " + kPoint;
  EXPECT_EQ(RunCli(sim).code, 64);
  const CliRun r = RunCli(sim + " --catalog-add " + mine);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(Idc(r), 0.0);
  // Every bundled entry is still there, plus the two calibrated ones.
  const CliRun all = RunCli("catalog list --json");
  const CliRun plus = RunCli("catalog list --json --catalog-add " + mine);
  ASSERT_EQ(all.code, 0);
  ASSERT_EQ(plus.code, 0);
  const Json a = ParseJsonText(all.out, "stdout"), p = ParseJsonText(plus.out, "stdout");
  EXPECT_EQ(p["motors"].size(), a["motors"].size() + 1);
  EXPECT_EQ(p["escs"].size(), a["escs"].size() + 1);
  EXPECT_EQ(p["props"].size(), a["props"].size());
}

TEST_F(CatalogAddCli, EnvironmentPathAddsFolders) {
  const std::string mine = (dir_ / "mine").string();
  fs::create_directories(mine);
  ASSERT_EQ(RunCli("calibrate " + std::string(DYNOSIZE_SOURCE_DIR) +
                   "/examples/dyno_log.csv --motor-id my_motor --esc-id my_esc --out " + mine + "/mine.json")
                .code,
            0);
  const std::string sim = "simulate --motor my_motor --esc my_esc " + kPoint;
  setenv("DYNOSIZE_CATALOG_PATH", (":" + mine + ":").c_str(), 1);
  const CliRun r = RunCli(sim);
  EXPECT_EQ(r.code, 0) << r.err;
  // A clash between the environment's folder and --catalog-add is an error too, resolved by
  // --override in favour of the command line.
  const std::string paper = PaperCopy("paper", "0.3");
  setenv("DYNOSIZE_CATALOG_PATH", paper.c_str(), 1);
  const std::string pair = "simulate --motor emax_1900kv_paper --esc multistar_30a_paper " + kPoint;
  EXPECT_EQ(RunCli(pair).code, 65);
  const CliRun hot = RunCli(pair + " --override");
  const CliRun back = RunCli(pair + " --override --catalog-add " + PaperCopy("same", "0.12"));
  unsetenv("DYNOSIZE_CATALOG_PATH");
  const CliRun bundled = RunCli(pair);
  ASSERT_EQ(hot.code, 0) << hot.err;
  ASSERT_EQ(back.code, 0) << back.err;
  EXPECT_GT(Idc(hot), Idc(bundled));
  EXPECT_EQ(Idc(back), Idc(bundled));
  // A folder that does not exist: exit 66 naming it.
  setenv("DYNOSIZE_CATALOG_PATH", "/nonexistent_dynosize_parts", 1);
  const CliRun missing = RunCli(pair);
  EXPECT_EQ(missing.code, 66);
  EXPECT_NE(missing.err.find("/nonexistent_dynosize_parts: no such catalog folder"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace dynosize
