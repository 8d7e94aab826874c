// No lost data: a write killed at any moment leaves the earlier file whole,
// and runs that add entries to the same catalog at the same time all land.
//
// Kill moments are drawn from seeded generators; each test also checks that some kills did
// land in the middle of a write (a temporary file left behind), so that it cannot pass by
// killing only between writes.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "calibration/synthetic_log.h"
#include "catalog/catalog.h"
#include "common/json_file.h"
#include "common/text_file.h"
#include "reliability/bad_input_table.h"

namespace dynosize::reliability {
namespace {

namespace fs = std::filesystem;

std::string Slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

fs::path FreshDir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) /
                     ("dynosize_no_lost_data_" + std::to_string(getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// A valid catalog document with `motors` motors whose ids carry `tag`.
std::string LargeCatalog(int motors, const std::string& tag) {
  std::string s = "{\n  \"motors\": [\n";
  for (int k = 0; k < motors; ++k) {
    s += std::string(k ? ",\n" : "") + "    {" + MotorBody("0.12", tag + "_" + std::to_string(k)) + "}";
  }
  return s + "\n  ]\n}\n";
}

std::size_t TempFilesIn(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename().string().find(".tmp-") != std::string::npos) ++n;
  }
  return n;
}

void RemoveTempFiles(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename().string().find(".tmp-") != std::string::npos) fs::remove(e.path());
  }
}

// Seeds of the kill moments; the number of kills per test.
constexpr unsigned kSeeds[] = {1, 2, 3, 4, 5, 6, 7, 8};

TEST(NoLostData, WriterKilledMidWriteLeavesOldOrNewFileWhole) {
  const fs::path dir = FreshDir("kill_library");
  const fs::path path = dir / "catalog.json";
  std::string current = LargeCatalog(20000, "v0");  // about 2.7 MB: a write takes milliseconds
  WriteFileAtomic(path.string(), current);
  std::size_t interrupted = 0;
  for (const unsigned seed : kSeeds) {
    const std::string next = LargeCatalog(20000, "v" + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> delay_us(200, 40000);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      // Rewrites the file until killed; never returns into the test framework.
      for (;;) {
        try {
          WriteFileAtomic(path.string(), next);
        } catch (...) {
          _exit(3);
        }
      }
    }
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the writer failed by itself (status " << status << ")";
    const std::string got = Slurp(path);
    ASSERT_TRUE(got == current || got == next)
        << "seed " << seed << ": the file is neither the earlier nor the new version ("
        << got.size() << " bytes)";
    EXPECT_NO_THROW(ParseJsonText(got, path.string()));
    interrupted += TempFilesIn(dir) > 0 ? 1 : 0;
    RemoveTempFiles(dir);
    current = got;
  }
  EXPECT_GT(interrupted, 0u) << "no kill landed during a write: the test proved nothing";
}

// Runs `dynosize ARGS...` as a child process (no shell, so the pid is dynosize's own).
pid_t Spawn(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(DYNOSIZE_EXE));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    // stdout and stderr to /dev/null: the test reads the files.
    if (FILE* f = freopen("/dev/null", "w", stdout)) (void)f;
    if (FILE* f = freopen("/dev/null", "w", stderr)) (void)f;
    execv(DYNOSIZE_EXE, argv.data());
    _exit(127);
  }
  return pid;
}

int Wait(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

// A canonical log the calibration fits (made by the model, calibration/synthetic_log.h).
std::string WriteLog(const fs::path& dir) {
  using logs::Column;
  const auto t = calibration::testing_util::MakeSyntheticLog(calibration::testing_util::DefaultSpec());
  const fs::path p = dir / "log.csv";
  std::ofstream f(p);
  f << "time_s,vdc_v,throttle,omega_rad_s,torque_nm,idc_a\n" << std::setprecision(10);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    f << t.Get(Column::kTimeS)[i] << "," << t.Get(Column::kVdcV)[i] << ","
      << t.Get(Column::kThrottle)[i] << "," << t.Get(Column::kOmegaRadS)[i] << ","
      << t.Get(Column::kTorqueNm)[i] << "," << t.Get(Column::kIdcA)[i] << "\n";
  }
  return p.string();
}

TEST(NoLostData, CalibrateKilledWhileWritingALargeCatalogLeavesItLoadable) {
  const fs::path dir = FreshDir("kill_cli");
  const std::string log = WriteLog(dir);
  const fs::path cat = dir / "cat";
  fs::create_directories(cat);
  const fs::path out = cat / "big.json";
  WriteFileAtomic(out.string(), LargeCatalog(10000, "old"));
  // How long one run takes here (sanitizer builds are several times slower): the shorter of
  // two runs, since the first one also pays for a cold cache and the kills below must land
  // before the run ends.
  double run_us = 0.0;
  for (int k = 0; k < 2; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_EQ(Wait(Spawn({"calibrate", log, "--motor-id", "m_new", "--esc-id", "e_new", "--out",
                          out.string(), "--force"})),
              0);
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    run_us = k == 0 ? us : std::min(run_us, us);
  }
  std::size_t killed = 0;
  for (const unsigned seed : kSeeds) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> at(0.2, 1.0);  // mostly late in the run: the write
    const pid_t pid = Spawn({"calibrate", log, "--motor-id", "m_new", "--esc-id", "e_new",
                             "--out", out.string(), "--force"});
    std::this_thread::sleep_for(std::chrono::microseconds(static_cast<long>(at(rng) * run_us)));
    kill(pid, SIGKILL);
    killed += Wait(pid) == -SIGKILL ? 1 : 0;
    // Whatever the moment, the catalog loads and keeps all the earlier entries.
    Catalog c;
    ASSERT_NO_THROW(c = Catalog::Load(cat.string())) << "seed " << seed;
    EXPECT_EQ(c.motors().size(), 10001u) << "seed " << seed;
    RemoveTempFiles(cat);
  }
  EXPECT_GT(killed, 0u) << "every run finished before the kill: the test proved nothing";
}

TEST(NoLostData, ConcurrentRunsAddingToOneCatalogAllLand) {
  const fs::path dir = FreshDir("concurrent");
  const std::string log = WriteLog(dir);
  const fs::path cat = dir / "cat";
  fs::create_directories(cat);
  const fs::path out = cat / "shared.json";
  WriteFileAtomic(out.string(), LargeCatalog(2000, "base"));
  constexpr int kRuns = 6;
  std::vector<pid_t> pids;
  for (int k = 0; k < kRuns; ++k) {
    pids.push_back(Spawn({"calibrate", log, "--motor-id", "m" + std::to_string(k), "--esc-id",
                          "e" + std::to_string(k), "--out", out.string()}));
  }
  for (const pid_t p : pids) EXPECT_EQ(Wait(p), 0);
  const Catalog c = Catalog::Load(cat.string());
  EXPECT_EQ(c.motors().size(), 2000u + kRuns);
  EXPECT_EQ(c.escs().size(), static_cast<std::size_t>(kRuns));
  for (int k = 0; k < kRuns; ++k) {
    EXPECT_NO_THROW((void)c.motor("m" + std::to_string(k)));
    EXPECT_NO_THROW((void)c.esc("e" + std::to_string(k)));
  }
  EXPECT_EQ(TempFilesIn(cat), 0u);
}

}  // namespace
}  // namespace dynosize::reliability
