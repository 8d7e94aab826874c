// Numerical guards: at the edges of the accepted ranges the model still
// gives finite results, printed as numbers (text) or checked JSON - never "nan" or "inf" - and
// a result is either a success or an infeasible point with its violated limits named.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "common/json_file.h"

namespace dynosize::reliability {
namespace {

bool HasNonFiniteText(const std::string& s) {
  for (const char* bad : {"nan", "NaN", "inf", "Inf"}) {
    if (s.find(bad) != std::string::npos) return true;
  }
  return false;
}

// The paper's pair, from a catalog folder holding only its file (a quicker load than the
// bundled catalog, which matters in sanitizer builds).
std::string Pair() {
  namespace fs = std::filesystem;
  static const std::string dir = [] {
    const fs::path d = fs::path(::testing::TempDir()) / ("dynosize_guards_" + std::to_string(getpid()));
    fs::create_directories(d);
    fs::copy_file(fs::path(DYNOSIZE_SOURCE_DIR) / "catalog" / "paper_brown_chopra.json",
                  d / "paper_brown_chopra.json", fs::copy_options::overwrite_existing);
    return d.string();
  }();
  return "--catalog " + dir + " simulate --motor emax_1900kv_paper --esc multistar_30a_paper ";
}

// Corners of the accepted ranges (points_csv.h kMaxRequest*): zero load, zero throttle, the
// largest voltage, torque and speed, the inverse at standstill, zero and huge torque laws.
const std::vector<std::string> kEdgeRequests = {
    "--vdc 7.2 --throttle 0 --torque 0",
    "--vdc 7.2 --throttle 0 --rpm 0",
    "--vdc 7.2 --throttle 1 --torque 0",
    "--vdc 7.2 --throttle 1 --torque 1000000",
    "--vdc 7.2 --throttle 0.1 --rpm 10000000",
    "--vdc 100000 --throttle 1 --torque 0",
    "--vdc 1e-300 --throttle 0.5 --torque 0",
    "--vdc 7.2 --torque 0 --rpm 0",
    "--vdc 7.2 --torque 1000000 --rpm 10000000",
    "--vdc 7.2 --throttle 0.5 --torque-law 0,0,0",
    "--vdc 7.2 --throttle 0.5 --torque-law 1000000,1000000,1000000",
    "--vdc 7.2 --throttle 0.5 --torque-law=-1000000,0,0",
    "--vdc 100000",
    "--vdc 1e-300",
};

TEST(NumericalGuards, EdgeRequestsGiveFiniteJson) {
  for (const auto& req : kEdgeRequests) {
    const auto r = testing_util::RunCli(Pair() + req + " --json");
    ASSERT_EQ(r.code, 0) << req << "\n" << r.err;
    Json j;
    ASSERT_NO_THROW(j = ParseJsonText(r.out, "stdout")) << req;
    EXPECT_NO_THROW(CheckJsonFinite(j, req));
    EXPECT_FALSE(HasNonFiniteText(r.out)) << req;
    if (j.contains("feasible") && !j["feasible"].get<bool>()) {
      EXPECT_FALSE(j["limits"].empty()) << req << ": an infeasible point names its limits";
    }
  }
}

TEST(NumericalGuards, EdgeRequestsPrintNumbersInText) {
  for (const auto& req : kEdgeRequests) {
    const auto r = testing_util::RunCli(Pair() + req);
    ASSERT_EQ(r.code, 0) << req << "\n" << r.err;
    EXPECT_FALSE(HasNonFiniteText(r.out)) << req << "\n" << r.out;
  }
}

}  // namespace
}  // namespace dynosize::reliability
