// Pathological inputs are refused quickly with a clear message. The big
// files are sparse (truncate(2)): they cost no disk and read as NUL bytes. Speed and memory of
// large valid inputs are measured by bench/limits_bench.cc.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "catalog/catalog.h"
#include "common/error.h"
#include "common/json_file.h"
#include "io/points_csv.h"
#include "logs/log_reader.h"

namespace dynosize::reliability {
namespace {

namespace fs = std::filesystem;

// "Quickly": the reader stops after about max_line_bytes, or before reading at all; 5 s leaves
// room for a loaded CI machine and sanitizer builds (a full read of 1 GiB would take longer).
constexpr double kQuickSeconds = 5.0;

std::string SparseFile(const std::string& name, const std::string& head, long long size) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("dynosize_limits_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string p = (dir / name).string();
  std::ofstream(p, std::ios::binary) << head;
  if (truncate(p.c_str(), size) != 0) return "";
  return p;
}

template <typename F>
double SecondsToRefuse(F f, std::string* message) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    f();
  } catch (const DataError& e) {
    *message = e.what();
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

TEST(Limits, GigabyteLogLineRefusedQuickly) {
  const std::string p = SparseFile("line.csv", "time_s,vdc_v,throttle,rpm,torque_nm,idc_a\n", 1LL << 30);
  if (p.empty()) GTEST_SKIP() << "no sparse files here";
  std::string m;
  const double s = SecondsToRefuse([&] { (void)logs::ReadLog(p); }, &m);
  EXPECT_LT(s, kQuickSeconds);
  EXPECT_NE(m.find(p + ": line 2: longer than 1048576 bytes: not a text log"), std::string::npos) << m;
  fs::remove(p);
}

TEST(Limits, GigabyteJsonRefusedBeforeReading) {
  const std::string p = SparseFile("big.json", "{\"motors\": [", 1LL << 30);
  if (p.empty()) GTEST_SKIP() << "no sparse files here";
  std::string m;
  const double s = SecondsToRefuse([&] { (void)ReadJsonFile(p); }, &m);
  EXPECT_LT(s, kQuickSeconds);
  EXPECT_NE(m.find("1073741824 bytes: larger than the limit of 67108864 bytes"), std::string::npos) << m;
  fs::remove(p);
}

TEST(Limits, GigabytePointFileRefusedBeforeReading) {
  const std::string p = SparseFile("points.csv", "vdc_v,throttle,torque_nm\n", 1LL << 30);
  if (p.empty()) GTEST_SKIP() << "no sparse files here";
  std::string m;
  const double s = SecondsToRefuse([&] { (void)ReadPointsCsv(p); }, &m);
  EXPECT_LT(s, kQuickSeconds);
  EXPECT_NE(m.find("larger than the limit"), std::string::npos) << m;
  fs::remove(p);
}

TEST(Limits, MillionLevelJsonRefusedAtTheDepthLimit) {
  const std::string text = std::string(1000000, '[') + std::string(1000000, ']');
  std::string m;
  const double s = SecondsToRefuse([&] { (void)ParseJsonText(text, "deep.json"); }, &m);
  EXPECT_LT(s, kQuickSeconds);
  EXPECT_NE(m.find("deep.json: /0/0/0"), std::string::npos) << m.substr(0, 200);
  EXPECT_NE(m.find("nesting deeper than 32 levels"), std::string::npos);
}

TEST(Limits, LongestAcceptedLineIsTheLimit) {
  // A line of exactly max_line_bytes is read (a cell that long is then not a number); one byte
  // more is refused as not a text log.
  logs::LogReadOptions o;
  o.max_line_bytes = 4096;
  const std::string head = "time_s,vdc_v,throttle,rpm,torque_nm,idc_a\n";
  const std::string p = SparseFile("limit.csv", head + std::string(4096, '7') + "\n", 0);
  std::ofstream(p, std::ios::binary) << head << std::string(4096, '7') << "\n";
  std::string m;
  SecondsToRefuse([&] { (void)logs::ReadLog(p, o); }, &m);
  EXPECT_NE(m.find("line 2: 1 cells, the header has 6"), std::string::npos) << m;
  std::ofstream(p, std::ios::binary) << head << std::string(4097, '7') << "\n";
  SecondsToRefuse([&] { (void)logs::ReadLog(p, o); }, &m);
  EXPECT_NE(m.find("line 2: longer than 4096 bytes"), std::string::npos) << m;
}

}  // namespace
}  // namespace dynosize::reliability
