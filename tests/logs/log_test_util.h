// Helpers for the log tests: excerpts are written from strings in the test (never copied from
// shared/data) into GoogleTest's temporary folder.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/error.h"
#include "logs/log_reader.h"

namespace dynosize::logs::testing_util {

// Writes `bytes` verbatim (binary) to a fresh file in the test temp folder; returns its path.
inline std::string WriteTemp(const std::string& name, const std::string& bytes) {
  const std::string dir = ::testing::TempDir() + "dynosize_logs_test_" + std::to_string(getpid()) + "/";
  std::filesystem::create_directories(dir);
  const std::string path = dir + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

inline std::string SharedData() { return std::string(DYNOSIZE_SHARED_DIR) + "/data/"; }
inline bool HaveShared() { return std::filesystem::is_directory(SharedData()); }

// Relative error helper.
inline double RelErr(double got, double want) {
  return std::fabs(got - want) / std::max(std::fabs(want), 1e-300);
}

// Values are parsed from short decimal strings and multiplied by one conversion factor: the
// only error is the rounding of one or two double operations.
inline constexpr double kParseRelTol = 1e-14;

// The message ReadLog refuses `path` with, or "(no error)".
inline std::string ErrorOf(const std::string& path, const LogReadOptions& o = LogReadOptions()) {
  try {
    ReadLog(path, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

inline bool Contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace dynosize::logs::testing_util
