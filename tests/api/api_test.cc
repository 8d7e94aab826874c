// src/api: the commands as library calls, shared by the CLI and the Python module. The CLI's
// output through them is checked end to end in tests/apps and tests/python; here the calls
// themselves.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "api/catalog_json.h"
#include "api/mission_run.h"
#include "api/simulate.h"
#include "catalog/catalog.h"
#include "common/error.h"
#include "mission/mission.h"

namespace dynosize {
namespace {

const Catalog& Bundled() {
  static const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  return cat;
}

Drive PaperDrive() {
  return Drive(Bundled().motor("emax_1900kv_paper").params, Bundled().esc("multistar_30a_paper").params);
}

// The batch path gives each row what the single-point solve gives, bit for bit, in every mode.
TEST(ApiSimulate, BatchEqualsPointByPoint) {
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<PointRequest> requests;
  for (int i = 0; i < 300; ++i) {
    PointRequest r;
    r.row = static_cast<std::size_t>(i);
    r.vdc_v = 6.0 + 3.0 * u(rng);
    if (i % 3 != 2) r.throttle = 0.1 + 0.9 * u(rng);
    if (i % 3 != 1) r.torque_nm = 0.05 * u(rng);
    if (i % 3 != 0) r.rpm = 1000.0 + 11000.0 * u(rng);
    ASSERT_EQ(CheckPointRequest(r), "") << i;
    requests.push_back(r);
  }
  const Drive drive = PaperDrive();
  const api::BatchResult batch = api::SimulateBatch(Bundled(), drive, requests, "test");
  ASSERT_EQ(batch.size(), requests.size());
  int infeasible = 0;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const OperatingPoint p = api::SolvePoint(drive, requests[i]);
    const OperatingPoint b = batch.point(i);
    EXPECT_EQ(b.idc_a, p.idc_a) << i;
    EXPECT_EQ(b.rpm, p.rpm) << i;
    EXPECT_EQ(b.throttle, p.throttle) << i;
    EXPECT_EQ(b.torque_nm, p.torque_nm) << i;
    EXPECT_EQ(b.eta_system, p.eta_system) << i;
    EXPECT_EQ(b.limits, p.limits) << i;
    EXPECT_EQ(b.saturated, p.saturated) << i;
    EXPECT_FALSE(batch.has_prop(i));
    infeasible += batch.feasible(i) ? 0 : 1;
  }
  EXPECT_GT(infeasible, 0);  // the ranges overload the pair somewhere: limits are carried
}

// Columns (dynosize.simulate's arrays, scalars broadcast) give SimulateBatch's numbers on the
// same points, to the bit, in runs longer than one gathered chunk.
TEST(ApiSimulate, ColumnsEqualTheBatchOfRequests) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::size_t n = 1500;
  std::vector<double> torque(n), rpm(n);
  std::vector<PointRequest> requests(n);
  for (std::size_t i = 0; i < n; ++i) {
    torque[i] = 0.1 * u(rng);
    rpm[i] = 20000.0 * u(rng);
    requests[i].row = i;
    requests[i].vdc_v = 7.4;
    requests[i].torque_nm = torque[i];
    requests[i].rpm = rpm[i];
  }
  const double vdc = 7.4;
  api::BatchColumns in;
  in.n = n;
  in.vdc_v = {&vdc, true};
  in.torque_nm = {torque.data(), false};
  in.rpm = {rpm.data(), false};
  const Drive drive = PaperDrive();
  api::BatchResult want = api::SimulateBatch(Bundled(), drive, requests, "test");
  api::BatchResult got(n);
  api::SimulateColumns(Bundled(), drive, in, "test", got.columns());
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(got.point(i).throttle, want.point(i).throttle) << i;
    EXPECT_EQ(got.point(i).pdc_w, want.point(i).pdc_w) << i;
    EXPECT_EQ(got.point(i).rpm, want.point(i).rpm) << i;
    EXPECT_EQ(got.point(i).limits, want.point(i).limits) << i;
  }
}

// Bad columns: the first point that breaks a rule of CheckPointRequest, with its message.
TEST(ApiSimulate, BadColumnsNameThePointAndTheRule) {
  const std::vector<double> vdc = {7.0, 7.2, std::nan(""), -1.0};
  const double throttle = 0.5, torque = 0.01;
  api::BatchColumns in;
  in.n = 4;
  in.vdc_v = {vdc.data(), false};
  in.throttle = {&throttle, true};
  in.torque_nm = {&torque, true};
  EXPECT_THROW(
      {
        try {
          api::CheckBatchColumns(in, "simulate: point");
        } catch (const UsageError& e) {
          EXPECT_STREQ(e.what(), "simulate: point:2: vdc_v = nan: must be > 0 V and <= 100000 V");
          throw;
        }
      },
      UsageError);
  in.torque_nm = {};  // throttle alone: no load given, every point (so point 0) breaks the rule
  in.vdc_v = {vdc.data(), false};
  in.n = 2;
  try {
    api::CheckBatchColumns(in, "simulate: point");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("simulate: point:0: give exactly two of throttle", 0), 0u) << e.what();
  }
}

// A row naming an unknown propeller is bad data at that row (exit 65), as in the batch file.
TEST(ApiSimulate, UnknownPropellerNamesSourceAndRow) {
  PointRequest r;
  r.row = 7;
  r.vdc_v = 12.0;
  r.throttle = 0.5;
  r.prop = "no_such_prop";
  try {
    api::SimulateBatch(Bundled(), PaperDrive(), {r}, "points.csv");
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("points.csv:7: ", 0), 0u) << e.what();
  }
}

// The range of a point brackets the nominal point's DC current (the spread of the motor's data).
TEST(ApiSimulate, PointRangeBracketsThePoint) {
  PointRequest r;
  r.vdc_v = 11.1;
  r.throttle = 0.8;
  r.torque_nm = 0.05;
  const MotorEntry& m = Bundled().motor("emax_1900kv_paper");
  const EscEntry& e = Bundled().esc("multistar_30a_paper");
  const api::PointRange range = api::SolvePointRange(m, e, r);
  const Json j = api::PointWithRangeJson(m, e, range);
  EXPECT_LE(j["idc_a_range"][0].get<double>(), range.point.idc_a);
  EXPECT_GE(j["idc_a_range"][1].get<double>(), range.point.idc_a);
  EXPECT_EQ(j["motor"], "emax_1900kv_paper");
}

TEST(ApiMission, CombinationErrorsNameTheFlags) {
  const Mission m = ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
  api::EvaluateRequest q{"dc_m_365", "dc_e_56", "", "dc_b_363", {}, 4};
  EXPECT_THROW(
      {
        try {
          api::ChooseCombination(m, Bundled(), q);
        } catch (const UsageError& e) {
          EXPECT_STREQ(e.what(), "--motor, --esc and --prop go together (one group's parts)");
          throw;
        }
      },
      UsageError);
  q.prop_id = "dc_p_231";
  q.cells = 0;  // the mission allows 3 or 4 cells: say which
  EXPECT_THROW(api::ChooseCombination(m, Bundled(), q), UsageError);
  q.cells = 4;
  const Combination c = api::ChooseCombination(m, Bundled(), q);
  EXPECT_EQ(c.motor->id, "dc_m_365");
  EXPECT_EQ(c.cells, 4);
  EXPECT_TRUE(api::EvaluateCombination(m, c).feasible);
}

TEST(ApiMission, TimeLimitMustBePositive) {
  EXPECT_THROW(api::OptimizeSearchOptions({3, 1, false, 0.0}), UsageError);
  EXPECT_THROW(api::OptimizeSearchOptions({3, 1, false, std::nan("")}), UsageError);
  const SearchOptions so = api::OptimizeSearchOptions({3, 1, true, 5.0});
  EXPECT_EQ(so.top_n, 3);
  EXPECT_FALSE(so.distinct_designs);
  EXPECT_LT(so.deadline, std::chrono::steady_clock::time_point::max());
  EXPECT_EQ(api::OptimizeSearchOptions({3, 1, false, std::numeric_limits<double>::infinity()}).deadline,
            std::chrono::steady_clock::time_point::max());
}

TEST(ApiCatalog, ListFiltersAndShow) {
  api::CatalogListRequest q;
  q.kind = "motors";
  q.kv_min = 1000;
  q.kv_max = 1500;
  const Json j = api::CatalogListJson(Bundled(), q);
  ASSERT_TRUE(j.contains("motors"));
  EXPECT_FALSE(j.contains("escs"));
  ASSERT_FALSE(j["motors"].empty());
  for (const auto& m : j["motors"]) {
    EXPECT_GE(m["kv_rpm_per_v"].get<double>(), 1000);
    EXPECT_LE(m["kv_rpm_per_v"].get<double>(), 1500);
  }
  q.kv_min = 2000;
  EXPECT_THROW(api::CheckCatalogListRequest(q), UsageError);  // an empty range
  const Json show = api::CatalogShowJson(Bundled(), "emax_1900kv_paper");
  EXPECT_EQ(show["id"], "emax_1900kv_paper");
  EXPECT_TRUE(show["derived"].contains("kt_over_ke"));
  EXPECT_THROW(api::CatalogShowJson(Bundled(), "no_such_id"), UsageError);
}

}  // namespace
}  // namespace dynosize
