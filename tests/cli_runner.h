// Runs the dynosize executable for end-to-end tests: exit code, stdout and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace dynosize::testing_util {

struct CliRun {
  int code = -1;
  std::string out, err;
};

// `args` is appended to the executable's path and run by the shell.
inline CliRun RunCli(const std::string& args) {
  namespace fs = std::filesystem;
  // One stderr file per process and call: ctest -j runs tests of one binary concurrently.
  static int calls = 0;
  const fs::path err_file = fs::temp_directory_path() /
                            ("dynosize_cli_stderr_" + std::to_string(getpid()) + "_" +
                             std::to_string(++calls) + ".txt");
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

}  // namespace dynosize::testing_util
