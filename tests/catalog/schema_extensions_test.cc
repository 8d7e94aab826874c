// The keys added for the real catalog: propeller tables, power laws, batteries, test points.
// Every broken rule is reported with the entry, the key and the rule.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "catalog/catalog.h"

namespace dynosize {
namespace {

std::vector<std::string> Problems(const std::string& json) {
  Catalog c;
  std::vector<std::string> problems;
  c.AddDocument(ParseJsonText(json, "t.json"), "t.json", &problems);
  return problems;
}

bool Has(const std::vector<std::string>& ps, const std::string& text) {
  for (const auto& p : ps) {
    if (p.find(text) != std::string::npos) return true;
  }
  return false;
}

std::string Join(const std::vector<std::string>& ps) {
  std::string s;
  for (const auto& p : ps) s += p + "\n";
  return s;
}

const char* kSrc = R"("source": {"dataset": "test", "values": {"diameter_m": "computed"}})";

// (The sweep's CP must leave the axial-flow figure of merit below 1: at J = 0.4,
// CT*(J/2 + sqrt(J^2/4 + 2*CT/pi))/CP = 0.07*0.491/0.045 = 0.76; catalog/prop_credibility.h.)
TEST(SchemaExtensionsTest, ValidPropWithTablesLoads) {
  const auto ps = Problems(std::string(R"({"props": [{"id": "p", "name": "p", "diameter_m": 0.25,
    "static_table": {"rpm": [2000, 4000], "ct": [0.1, 0.11], "cp": [0.04, 0.042]},
    "j_tables": [{"rpm": 3000, "j": [0.2, 0.4], "ct": [0.09, 0.07], "cp": [0.05, 0.045]}], )") +
                           kSrc + "}]}");
  EXPECT_TRUE(ps.empty()) << Join(ps);
}

TEST(SchemaExtensionsTest, PropTableErrorsNameThePath) {
  const auto ps = Problems(std::string(R"({"props": [{"id": "p", "name": "p", "diameter_m": 0.25,
    "static_table": {"rpm": [4000, 2000], "ct": [0.1], "cp": [0.04, 0.042], "eta": [1]},
    "j_tables": [{"rpm": 3000, "j": [0.2, 0.4], "ct": [0.09, 0.07], "cp": [0.04, 0.03]},
                 {"rpm": 2000, "j": [0.2], "ct": [0.1], "cp": [0.04]}], )") +
                           kSrc + "}]}");
  EXPECT_TRUE(Has(ps, "key 'static_table.rpm': element 1 = 2000 must be greater than the one "
                      "before (strictly increasing)")) << Join(ps);
  EXPECT_TRUE(Has(ps, "key 'static_table.eta': unknown key")) << Join(ps);
  EXPECT_TRUE(Has(ps, "key 'j_tables[1].rpm': sweeps must be sorted by strictly increasing rpm"))
      << Join(ps);
}

TEST(SchemaExtensionsTest, PropNeedsPerformanceDataAndCompleteLaws) {
  auto ps = Problems(std::string(R"({"props": [{"id": "p", "name": "p", "diameter_m": 0.25, )") +
                     kSrc + "}]}");
  EXPECT_TRUE(Has(ps, "a propeller needs performance data")) << Join(ps);
  ps = Problems(std::string(R"({"props": [{"id": "p", "name": "p", "diameter_m": 0.25,
    "thrust_law_n": 0.005, "thrust_law_exp": 2.0, )") + kSrc + "}]}");
  EXPECT_TRUE(Has(ps, "key 'power_law_w': missing: thrust and power laws come together"))
      << Join(ps);
  EXPECT_TRUE(Has(ps, "key 'law_rho_kg_m3': missing: the power laws need it")) << Join(ps);
}

TEST(SchemaExtensionsTest, BatteryRules) {
  const auto ok = Problems(R"({"batteries": [{"id": "b", "name": "b", "chemistry": "lipo",
    "cells_series": 6, "capacity_ah": 5.0, "voltage_nominal_v": 22.2, "ri_ohm": 0.02,
    "source": {"dataset": "t"}}]})");
  EXPECT_TRUE(ok.empty()) << Join(ok);
  const auto ps = Problems(R"({"batteries": [{"id": "b", "name": "b", "chemistry": "lead",
    "cells_series": 1, "capacity_ah": 5.0, "voltage_nominal_v": 22.2,
    "source": {"dataset": "t"}}]})");
  EXPECT_TRUE(Has(ps, "key 'chemistry' = \"lead\": must be a string, one of lipo, liion, "
                      "lifepo4, nimh, nicd")) << Join(ps);
  EXPECT_TRUE(Has(ps, "key 'voltage_nominal_v' = 22.2: gives 22.2 V per cell")) << Join(ps);
}

TEST(SchemaExtensionsTest, MotorTestPointsAndComputedMethod) {
  const auto ps = Problems(R"({"motors": [{"id": "m", "name": "m", "type": "bldc",
    "kv_rpm_per_v": 900, "rm_ohm": 0.1, "io_a": 0.5,
    "test_points": [{"vdc_v": 22.0, "idc_a": 10.0, "throttle": 0.5, "prop": "x"},
                    {"idc_a": 10.0, "throttle": 1.5, "volts": 1}],
    "source": {"dataset": "t", "values": {"rm_ohm": "simulated"}}}]})");
  EXPECT_TRUE(Has(ps, "key 'test_points[1].vdc_v': missing (required)")) << Join(ps);
  EXPECT_TRUE(Has(ps, "key 'test_points[1].throttle': must be a number in [0, 1], found 1.5"))
      << Join(ps);
  EXPECT_TRUE(Has(ps, "key 'test_points[1].volts': unknown key")) << Join(ps);
  EXPECT_TRUE(Has(ps, "must be one of datasheet, measured, computed, fitted, derived, assumed"))
      << Join(ps);
}

}  // namespace
}  // namespace dynosize
