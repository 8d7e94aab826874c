// Batch point files (src/io/points_csv.h): rows that name a propeller.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/points_csv.h"

namespace dynosize {
namespace {

std::string WriteTemp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("dynosize_points_" + std::to_string(getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(PointsCsv, RowsMayNameAPropellerWithOneOfThrottleRpmThrust) {
  const std::string path = WriteTemp("prop.csv",
                                     "vdc_v,throttle,torque_nm,rpm,prop,thrust_n\n"
                                     "12,0.5,0.01,,,\n"
                                     "12,0.6,,,apc_per3_10x5e,\n"
                                     "12,,,5000,apc_per3_10x5e,\n"
                                     "12,,,,apc_per3_10x5e,4.5\n");
  const auto rows = ReadPointsCsv(path);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_TRUE(rows[0].prop.empty());
  EXPECT_EQ(rows[1].prop, "apc_per3_10x5e");
  EXPECT_DOUBLE_EQ(*rows[1].throttle, 0.6);
  EXPECT_DOUBLE_EQ(*rows[2].rpm, 5000.0);
  EXPECT_DOUBLE_EQ(*rows[3].thrust_n, 4.5);
  EXPECT_EQ(rows[3].row, 5u);
  std::filesystem::remove(path);
}

TEST(PointsCsv, PropellerRowRulesNameFileLineAndRule) {
  struct Case {
    std::string text, message;
  };
  const std::vector<Case> cases = {
      {"vdc_v,throttle,torque_nm,prop\n12,0.5,0.01,p\n", ":2: a row with a prop takes its load from the propeller"},
      {"vdc_v,throttle,rpm,prop\n12,0.5,3000,p\n", ":2: a row with a prop gives exactly one of throttle"},
      {"vdc_v,prop\n12,p\n", ":2: a row with a prop gives exactly one of throttle"},
      {"vdc_v,throttle,thrust_n\n12,0.5,3\n", ":2: thrust_n needs a prop"},
      {"vdc_v,prop,thrust_n\n12,p,-3\n", ":2: thrust_n = -3: must be > 0 N"},
      {"vdc_v,propeller\n12,p\n", ":1: unknown column \"propeller\": allowed are vdc_v, throttle, torque_nm, rpm, prop, thrust_n"},
  };
  int k = 0;
  for (const auto& c : cases) {
    const std::string path = WriteTemp("bad" + std::to_string(k++) + ".csv", c.text);
    try {
      ReadPointsCsv(path);
      ADD_FAILURE() << "no error for " << c.text;
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find(path + c.message), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
  }
}

}  // namespace
}  // namespace dynosize
