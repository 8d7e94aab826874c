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

#include "common/json_file.h"

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

// A mission whose search outlasts any stop a test sends: the eVTOL example with both propulsion
// groups free, the capacity in [2, 8] Ah and the cruise airspeed in [14, 24] m/s, which finds
// nothing feasible within 30 s on the bundled catalog (docs/joint-search.md). A stop after a
// second or less therefore always comes mid-search, however fast the simpler missions become.
// Written to a temporary file named after `tag` and the process; the caller removes it.
inline std::filesystem::path LongSearchMission(const std::string& tag) {
  namespace fs = std::filesystem;
  const fs::path p = fs::temp_directory_path() / ("dynosize_" + tag + "_" + std::to_string(getpid()) + ".json");
  Json m = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/evtol_lift_cruise.json");
  for (Json& group : m["propulsion"]) {
    for (const char* part : {"motor", "esc", "prop"}) group.erase(part);
  }
  m["battery"]["capacity_ah"] = Json::array({2, 8});
  for (Json& s : m["segments"]) {
    if (s["type"] == "cruise") s["airspeed_m_s"] = Json::array({14, 24});
  }
  std::ofstream(p) << DumpJson(m);
  return p;
}

}  // namespace dynosize::testing_util
