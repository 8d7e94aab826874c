// Runs every row of bad_input_table.h through the dynosize executable: exit code, empty stdout,
// one "dynosize: " line per problem on stderr, and the words naming file, row or JSON path,
// value and rule.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_runner.h"
#include "reliability/bad_input_table.h"

namespace dynosize::reliability {
namespace {

namespace fs = std::filesystem;

std::string Substitute(std::string s, const std::string& dir) {
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"{dir}", dir},
                                   {"{src}", DYNOSIZE_SOURCE_DIR}}) {
    for (std::size_t pos = s.find(key); pos != std::string::npos; pos = s.find(key, pos)) {
      s.replace(pos, key.size(), value);
      pos += value.size();
    }
  }
  return s;
}

class BadInput : public ::testing::TestWithParam<BadInputCase> {};

TEST_P(BadInput, RefusedWithOneClearLine) {
  const BadInputCase& c = GetParam();
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("dynosize_bad_input_" + std::to_string(getpid())) / c.name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const auto& [name, bytes] : c.files) {
    const fs::path p = dir / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  // The paper's catalog file alone in {dir}/paper: a quick load (sanitizer builds).
  fs::create_directories(dir / "paper");
  fs::copy_file(fs::path(DYNOSIZE_SOURCE_DIR) / "catalog" / "paper_brown_chopra.json",
                dir / "paper" / "paper_brown_chopra.json");
  const std::string args = Substitute(c.args, dir.string());
  const auto r = testing_util::RunCli(args);
  EXPECT_EQ(r.code, c.exit_code) << "dynosize " << args << "\nstderr: " << r.err;
  EXPECT_EQ(r.out, "") << "a refusal prints nothing on stdout";
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.back(), '\n');
  std::istringstream lines(r.err);
  std::string line;
  int n = 0;
  while (std::getline(lines, line)) {
    ++n;
    EXPECT_EQ(line.rfind("dynosize: ", 0), 0u) << "line " << n << " of stderr: " << line;
    EXPECT_LT(line.size(), 2000u) << "a refusal is one readable line";
  }
  for (const auto& want : c.message_has) {
    EXPECT_NE(r.err.find(Substitute(want, dir.string())), std::string::npos)
        << "stderr lacks \"" << Substitute(want, dir.string()) << "\":\n" << r.err;
  }
  // No NaN printed by dynosize (an input "nan" may be echoed).
  std::string input = c.args;
  for (const auto& f : c.files) input += f.second;
  if (input.find("nan") == std::string::npos && input.find("NaN") == std::string::npos) {
    std::string err = r.err;
    for (std::size_t p = err.find(dir.string()); p != std::string::npos; p = err.find(dir.string())) {
      err.erase(p, dir.string().size());
    }
    EXPECT_EQ(err.find("nan"), std::string::npos) << err;
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Table, BadInput, ::testing::ValuesIn(BadInputCases()),
                         [](const ::testing::TestParamInfo<BadInputCase>& i) { return i.param.name; });

}  // namespace
}  // namespace dynosize::reliability
