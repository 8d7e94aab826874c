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

}  // namespace dynosize::logs::testing_util
