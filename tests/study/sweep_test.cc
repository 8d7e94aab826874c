// Trade studies (study/sweep.h): --vary parsing, grid order, JSON paths set in the mission, every
// bad input, and a real sweep on the small catalog whose rows equal separate searches.
#include "study/sweep.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/error.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/search.h"
#include "optimization/small_catalog.h"
#include "report/mission_report.h"
#include "report/sweep_report.h"

namespace dynosize::study {
namespace {

namespace fs = std::filesystem;

const Json& Quad() {
  static const Json doc = ParseJsonText(testing_util::kQuad, "quad.json");
  return doc;
}

// The message of the UsageError `f` throws ("" when it throws none).
template <typename F>
std::string UsageMessage(F&& f) {
  try {
    f();
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(SweepParseTest, RangeOfIntegersStaysIntegers) {
  const VaryKey k = ParseVary("vehicle.rotors=4:8:2");
  EXPECT_EQ(k.key, "vehicle.rotors");
  ASSERT_EQ(k.values.size(), 3u);
  for (const Json& v : k.values) EXPECT_TRUE(v.is_number_integer()) << v;
  EXPECT_EQ(k.values[2].get<long long>(), 8);
}

TEST(SweepParseTest, DecimalStepsAreWrittenAsTyped) {
  const VaryKey k = ParseVary("vehicle.mass_kg=0.1:0.5:0.1");
  ASSERT_EQ(k.values.size(), 5u);  // 0.5 reached although 0.1 is not exact in binary
  EXPECT_EQ(k.values[2].get<double>(), 0.3);
  EXPECT_EQ(k.values[4].get<double>(), 0.5);
  const VaryKey down = ParseVary("vehicle.mass_kg=1:0:-0.25");
  ASSERT_EQ(down.values.size(), 5u);
  EXPECT_EQ(down.values[4].get<double>(), 0.0);
  const VaryKey one = ParseVary("vehicle.mass_kg=2:2:1");
  EXPECT_EQ(one.values.size(), 1u);
  const VaryKey partial = ParseVary("vehicle.mass_kg=1:2:0.4");  // STOP not reached exactly
  ASSERT_EQ(partial.values.size(), 3u);
  EXPECT_EQ(partial.values[2].get<double>(), 1.8);
}

TEST(SweepParseTest, ListsKeepNumbersStringsAndBooleans) {
  const VaryKey k = ParseVary("objective.type=max_endurance,min_energy");
  ASSERT_EQ(k.values.size(), 2u);
  EXPECT_EQ(k.values[1], Json("min_energy"));
  const VaryKey b = ParseVary("constraints.allow_esc_saturation=true,false");
  EXPECT_TRUE(b.values[0].is_boolean());
  const VaryKey n = ParseVary("segments[2].duration_s=60,1.5e2,300");
  EXPECT_TRUE(n.values[0].is_number_integer());
  EXPECT_EQ(n.values[1].get<double>(), 150.0);
}

TEST(SweepParseTest, BadSpecsAreUsageErrorsNamingTheRule) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"vehicle.mass_kg", "KEY=START:STOP:STEP"},
      {"=1,2", "KEY=START:STOP:STEP"},
      {"vehicle.mass_kg=", "no values"},
      {"vehicle.mass_kg=1:2:0", "STEP must not be 0"},
      {"vehicle.mass_kg=2:1:0.5", "never reaches STOP"},
      {"vehicle.mass_kg=1:2:-1", "never reaches STOP"},
      {"vehicle.mass_kg=1:2", "START:STOP:STEP"},
      {"vehicle.mass_kg=1:2:x", "three finite numbers"},
      {"vehicle.mass_kg=1:1e999:1", "three finite numbers"},
      {"vehicle.mass_kg=0:1:1e-12", "more than 10^9"},
      {"vehicle.mass_kg=1,,2", "empty value"},
      {"vehicle..mass_kg=1", "not a JSON path"},
      {"segments[x].duration_s=1", "not a JSON path"},
      {"segments[2]duration_s=1", "not a JSON path"},
      {"[2].a=1", "not a JSON path"},
  };
  for (const auto& [spec, rule] : cases) {
    const std::string m = UsageMessage([&s = spec] { ParseVary(s); });  // a binding is not capturable (C++17)
    EXPECT_NE(m.find(rule), std::string::npos) << spec << " -> " << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

TEST(SweepGridTest, FullFactorialWithTheLastKeyFastest) {
  const std::vector<VaryKey> keys = {ParseVary("a=1,2"), ParseVary("b=10,20,30"), ParseVary("c=x,y")};
  ASSERT_EQ(GridSize(keys), 12u);
  EXPECT_EQ(GridPoint(keys, 0), (std::vector<Json>{1, 10, "x"}));
  EXPECT_EQ(GridPoint(keys, 1), (std::vector<Json>{1, 10, "y"}));
  EXPECT_EQ(GridPoint(keys, 2), (std::vector<Json>{1, 20, "x"}));
  EXPECT_EQ(GridPoint(keys, 6), (std::vector<Json>{2, 10, "x"}));
  EXPECT_EQ(GridPoint(keys, 11), (std::vector<Json>{2, 30, "y"}));
}

TEST(SweepGridTest, OverflowingGridIsAUsageError) {
  std::vector<VaryKey> keys(65, ParseVary("a=1,2"));  // 2^65 points
  EXPECT_NE(UsageMessage([&] { GridSize(keys); }).find("more points than can be counted"), std::string::npos);
}

TEST(SweepPathTest, SetsNestedMembersArrayElementsAndNewMembers) {
  const std::vector<VaryKey> keys = {ParseVary("vehicle.mass_kg=1.25"), ParseVary("segments[2].duration_s=60"),
                                     ParseVary("battery.cells[1]=6"), ParseVary("battery.capacity_ah=2.5")};
  const Json doc = MissionAt(Quad(), keys, GridPoint(keys, 0));
  EXPECT_EQ(doc["vehicle"]["mass_kg"], Json(1.25));
  EXPECT_EQ(doc["segments"][2]["duration_s"], Json(60));
  EXPECT_EQ(doc["segments"][2]["name"], Json("loiter"));  // the rest of the element kept
  EXPECT_EQ(doc["battery"]["cells"], Json::array({3, 6}));
  EXPECT_EQ(doc["battery"]["capacity_ah"], Json(2.5));
  EXPECT_EQ(Quad()["vehicle"]["mass_kg"], Json(0.75));  // the document itself untouched
  CheckKeys(Quad(), "quad.json", keys);  // all settable
  const Mission m = ParseMission(doc, "quad.json");
  EXPECT_EQ(m.vehicle.mass_kg, 1.25);
  EXPECT_EQ(m.battery.cells_max, 6);
  ASSERT_TRUE(m.battery.capacity_ah.has_value());
  EXPECT_EQ(m.battery.capacity_ah->lo, 2.5);
  EXPECT_EQ(*m.segments[2].duration_s, 60.0);
  // A path not in the document is a usage error here too (a caller that skipped CheckKeys).
  const VaryKey bad = ParseVary("segments[7].duration_s=1");
  EXPECT_NE(UsageMessage([&] { MissionAt(Quad(), {bad}, {Json(1)}); }).find("unknown key"), std::string::npos);
  const VaryKey through = ParseVary("vehicle.mass_kg.x=1");
  EXPECT_NE(UsageMessage([&] { MissionAt(Quad(), {through}, {Json(1)}); }).find("unknown key"), std::string::npos);
  // "$." as in the reader's messages.
  EXPECT_EQ(MissionAt(Quad(), {ParseVary("$.vehicle.rotors=6")}, {Json(6)})["vehicle"]["rotors"], Json(6));
}

TEST(SweepPathTest, BadKeysAreUsageErrorsNamingKeyAndRule) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"vehicle.mas_kg=1", {"vehicle.mas_kg", "unknown key", "nearest valid keys: vehicle.mass_kg"}},
      {"vehicel.mass_kg=1", {"unknown key", "no vehicel", "nearest valid keys: vehicle.mass_kg"}},
      {"segments[9].duration_s=1", {"no segments[9]", "segments[2].duration_s"}},
      {"vehicle.mass_kg.x=1", {"unknown key", "vehicle.mass_kg.x"}},
      {"vehicle=1", {"is an object", "vehicle.mass_kg"}},
      {"battery.cells=3", {"is an array", "battery.cells[0]"}},
      {"vehicle.mass_kg=heavy", {"holds a number"}},
      {"objective.type=1", {"holds a string"}},
      {"vehicle.mass_kg=-1,0", {"vehicle.mass_kg", "no value gives a valid mission", "must be a number > 0"}},
      {"segments[1].duration_s=100", {"exactly one of duration_s and distance_m"}},
  };
  for (const auto& [spec, parts] : cases) {
    const std::string m = UsageMessage([&s = spec] { CheckKeys(Quad(), "quad.json", {ParseVary(s)}); });
    for (const std::string& p : parts) EXPECT_NE(m.find(p), std::string::npos) << spec << " -> " << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  const std::string twice = UsageMessage(
      [&] { CheckKeys(Quad(), "quad.json", {ParseVary("vehicle.mass_kg=1"), ParseVary("$.vehicle.mass_kg=2")}); });
  EXPECT_NE(twice.find("given twice"), std::string::npos) << twice;
  // Some values break the rule: not an error (those points are failed rows).
  CheckKeys(Quad(), "quad.json", {ParseVary("vehicle.mass_kg=-1,1")});
}

class SweepRunTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = testing_util::WriteSmallCatalog("sweep");
    catalog_ = new Catalog(Catalog::Load((dir_ / "catalog").string()));
  }
  static void TearDownTestSuite() {
    delete catalog_;
    fs::remove_all(dir_);
  }
  static fs::path dir_;
  static const Catalog* catalog_;
};
fs::path SweepRunTest::dir_;
const Catalog* SweepRunTest::catalog_ = nullptr;

// Every row of a 2 x 2 sweep equals a separate search of the mission edited by hand (same
// picks, same objective and range, bit for bit: the same code on the same input).
TEST_F(SweepRunTest, RowsEqualSeparateSearches) {
  const std::vector<VaryKey> keys = {ParseVary("vehicle.mass_kg=0.5,0.9"), ParseVary("segments[1].distance_m=500,2000")};
  SweepOptions so;
  so.threads = 2;
  so.point.top = 2;
  const SweepResult r = RunSweep(Quad(), "quad.json", *catalog_, keys, so);
  ASSERT_EQ(r.rows.size(), 4u);
  EXPECT_FALSE(r.interrupted);
  const double masses[] = {0.5, 0.5, 0.9, 0.9}, distances[] = {500, 2000, 500, 2000};
  for (std::size_t i = 0; i < 4; ++i) {
    const SweepRow& row = r.rows[i];
    EXPECT_EQ(row.index, i);
    Json doc = Quad();
    doc["vehicle"]["mass_kg"] = masses[i];
    doc["segments"][1]["distance_m"] = distances[i];
    const Mission m = ParseMission(doc, "by hand");
    SearchOptions opt;
    opt.top_n = 2;
    opt.distinct_designs = true;
    const SearchResult s = SearchCatalog(m, *catalog_, opt);
    ASSERT_EQ(row.status, "ok") << row.reason;
    ASSERT_EQ(row.picks.size(), s.best.size());
    ASSERT_FALSE(s.best.empty());
    for (std::size_t k = 0; k < s.best.size(); ++k) {
      const SweepPick& p = row.picks[k];
      EXPECT_EQ(p.motor.front(), s.best[k].combination.motor->id);
      EXPECT_EQ(p.esc.front(), s.best[k].combination.esc->id);
      EXPECT_EQ(p.prop.front(), s.best[k].combination.prop->id);
      EXPECT_EQ(p.battery, s.best[k].combination.battery->id);
      EXPECT_EQ(p.cells, s.best[k].combination.cells);
      EXPECT_EQ(p.objective, DisplayObjective(m, s.best[k].result.objective));
      EXPECT_EQ(p.objective_low, DisplayObjective(m, s.best[k].result.range.low));
      EXPECT_EQ(p.thrust_to_weight, s.best[k].result.thrust_to_weight);
      EXPECT_EQ(p.objective_unit, "min");
    }
  }
  // Heavier: shorter loiter (the same pick could only lose endurance).
  EXPECT_GT(r.rows[0].picks[0].objective, r.rows[2].picks[0].objective);
  // RunPoint alone (a distributed task) gives the identical row; so does one thread.
  for (std::size_t i = 0; i < 4; ++i) {
    PointOptions po;
    po.top = 2;
    EXPECT_EQ(SweepRowJson(RunPoint(Quad(), "quad.json", *catalog_, keys, i, po), keys),
              SweepRowJson(r.rows[i], keys));
  }
  EXPECT_NE(UsageMessage([&] { RunPoint(Quad(), "quad.json", *catalog_, keys, 4, PointOptions{}); })
                .find("the grid has 4 points"),
            std::string::npos);
  so.threads = 1;
  const SweepResult one = RunSweep(Quad(), "quad.json", *catalog_, keys, so);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(SweepRowJson(one.rows[i], keys), SweepRowJson(r.rows[i], keys));
}

TEST_F(SweepRunTest, FailingPointsAreRowsWithTheirReason) {
  // -1 kg breaks the reader's rule; 40 kg no combination of the small catalog lifts.
  const std::vector<VaryKey> keys = {ParseVary("vehicle.mass_kg=-1,0.6,40")};
  SweepOptions so;
  const SweepResult r = RunSweep(Quad(), "quad.json", *catalog_, keys, so);
  ASSERT_EQ(r.rows.size(), 3u);
  EXPECT_EQ(r.rows[0].status, "failed");
  EXPECT_NE(r.rows[0].reason.find("$.vehicle.mass_kg = -1: must be a number > 0"), std::string::npos)
      << r.rows[0].reason;
  EXPECT_EQ(r.rows[0].reason.find("quad.json"), std::string::npos);  // the file name is the CLI's
  EXPECT_TRUE(r.rows[0].picks.empty());
  EXPECT_EQ(r.rows[1].status, "ok");
  EXPECT_TRUE(r.rows[1].picks[0].feasible);
  EXPECT_EQ(r.rows[1].picks[0].binding_limit, "reserve_soc");
  EXPECT_EQ(r.rows[2].status, "failed");
  EXPECT_NE(r.rows[2].reason.find("no combination"), std::string::npos) << r.rows[2].reason;
  // Why (optimization/no_design.h): the requirements no part meets, in the row and its reason.
  ASSERT_FALSE(r.rows[2].no_design_because.empty()) << r.rows[2].reason;
  for (const UnmetRequirement& u : r.rows[2].no_design_because) {
    EXPECT_GT(u.needed, u.best_available) << u.requirement;
    EXPECT_NE(r.rows[2].reason.find(u.requirement + " needs "), std::string::npos) << r.rows[2].reason;
  }
  EXPECT_TRUE(r.rows[1].no_design_because.empty());
  const Mission base = ParseMission(Quad(), "quad.json");
  const std::string csv = SweepCsv(base, r, keys);
  EXPECT_NE(csv.find("0,-1,failed,"), std::string::npos) << csv;
  // Every line has the header's number of fields (the reason quoted: it holds commas).
  const Json j = SweepJson(base, r, keys);
  EXPECT_EQ(j["failed"], Json(2));
  EXPECT_EQ(j["rows"][0]["values"]["vehicle.mass_kg"], Json(-1));
  EXPECT_TRUE(j["rows"][2]["no_design_because"].is_array());
  EXPECT_FALSE(j["rows"][1].contains("no_design_because"));
}

TEST_F(SweepRunTest, CsvLinesHaveTheHeadersFields) {
  const std::vector<VaryKey> keys = {ParseVary("vehicle.mass_kg=-1,0.6")};
  const SweepResult r = RunSweep(Quad(), "quad.json", *catalog_, keys, SweepOptions{});
  const std::string csv = SweepCsv(ParseMission(Quad(), "quad.json"), r, keys);
  std::vector<int> fields;
  int n = 1;
  bool quoted = false;
  for (char c : csv) {
    if (c == '"') quoted = !quoted;
    if (!quoted && c == ',') ++n;
    if (!quoted && c == '\n') {
      fields.push_back(n);
      n = 1;
    }
  }
  ASSERT_EQ(fields.size(), 3u) << csv;
  EXPECT_EQ(fields[1], fields[0]) << csv;
  EXPECT_EQ(fields[2], fields[0]) << csv;
  EXPECT_EQ(csv.rfind("index,vehicle.mass_kg,status,rank,feasible,objective_min,objective_low,objective_high,motor,", 0),
            0u)
      << csv;
}

// An exception on one of the sweep's threads (here the progress callback's, called on the thread
// that finished the point) reaches RunSweep's caller instead of ending the program.
TEST_F(SweepRunTest, AnExceptionOnAPointsThreadReachesTheCaller) {
  const std::vector<VaryKey> keys = {ParseVary("vehicle.mass_kg=0.5,0.6,0.7,0.8")};
  SweepOptions so;
  so.threads = 2;
  std::atomic<int> calls{0};
  so.progress = [&](const SweepProgress&) {
    ++calls;
    throw std::runtime_error("progress failed");
  };
  try {
    RunSweep(Quad(), "quad.json", *catalog_, keys, so);
    ADD_FAILURE() << "no exception reached the caller";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "progress failed");
  }
  // Each thread stops at its next point: at most one finished point per thread reported.
  EXPECT_GE(calls.load(), 1);
  EXPECT_LE(calls.load(), 2);
}

TEST_F(SweepRunTest, AStopKeepsOnlyFinishedRows) {
  const std::vector<VaryKey> keys = {ParseVary("vehicle.mass_kg=0.5,0.6,0.7")};
  std::atomic<bool> stop{true};
  SweepOptions so;
  so.point.stop = &stop;
  const SweepResult r = RunSweep(Quad(), "quad.json", *catalog_, keys, so);
  EXPECT_TRUE(r.interrupted);
  EXPECT_TRUE(r.rows.empty());
  EXPECT_EQ(r.total, 3u);
  // Stopped after the first point finished: that row, complete, and no other.
  std::atomic<bool> later{false};
  so.point.stop = &later;
  so.threads = 1;
  so.progress = [&](const SweepProgress& p) {
    if (p.done == 1) later.store(true);
  };
  const SweepResult part = RunSweep(Quad(), "quad.json", *catalog_, keys, so);
  EXPECT_TRUE(part.interrupted);
  ASSERT_EQ(part.rows.size(), 1u);
  EXPECT_EQ(part.rows[0].status, "ok");
  EXPECT_EQ(part.rows[0].index, 0u);
}

}  // namespace
}  // namespace dynosize::study
