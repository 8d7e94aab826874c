// Physics at the door (docs/model.md section 10): the catalog refuses ESCs and motors that create
// energy and propellers that beat momentum theory inside their valid range; trust tiers; the
// figure-of-merit envelope of measured propellers; the bundled catalog obeys all of it.
#include "catalog/prop_credibility.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "common/units.h"
#include "mission/mission.h"
#include "cli_runner.h"

namespace dynosize {
namespace {

const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";

std::vector<std::string> Problems(const std::string& doc_text, Catalog* c = nullptr) {
  Catalog local;
  std::vector<std::string> problems;
  (c ? c : &local)->AddDocument(ParseJsonText(doc_text, "t.json"), "t.json", &problems);
  return problems;
}

std::string Esc(const std::string& c1, const std::string& c0) {
  return R"({"escs": [{"id": "e1", "name": "ESC", "resc_ohm": 0.01, "c1": )" + c1 +
         R"(, "c0": )" + c0 + R"(, "tr_sat": 0.9, "sat_slope": 0.6, "source": {"dataset": "t"}}]})";
}

// A 10 in power-law propeller: T = a*(rpm/1000)^2 N, P = c*(rpm/1000)^p W.
std::string LawProp(double a, double c, double p_exp, const std::string& extra = "") {
  return R"({"props": [{"id": "p1", "name": "law prop", "diameter_m": 0.254, "thrust_law_n": )" +
         std::to_string(a) + R"(, "thrust_law_exp": 2, "power_law_w": )" + std::to_string(c) +
         R"(, "power_law_exp": )" + std::to_string(p_exp) + R"(, "law_rho_kg_m3": 1.225)" + extra +
         R"(, "source": {"dataset": "t"}}]})";
}

TEST(PhysicsAtTheDoor, EscThatCreatesEnergyIsRefused) {
  // c1 + c0 = 1.0 < 1.1095: PDC < PAC at full throttle.
  auto p = Problems(Esc("1.0", "0.0"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p[0].find("escs[0] id=e1"), std::string::npos) << p[0];
  EXPECT_NE(p[0].find("creates energy"), std::string::npos) << p[0];
  EXPECT_NE(p[0].find("c1 + c0 = 1"), std::string::npos) << p[0];
  // c0 < 0: PESC < 0 at low throttle, even with a large c1.
  p = Problems(Esc("1.3", "-0.05"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p[0].find("c0 = -0.05"), std::string::npos) << p[0];
  // The ideal ESC of eq (56) sits on the boundary and loads.
  Catalog c;
  EXPECT_TRUE(Problems(Esc("1.10953", "0"), &c).empty());
  EXPECT_EQ(c.escs().size(), 1u);
}

TEST(PhysicsAtTheDoor, MotorWithKtAboveTheRuleIsRefused) {
  const std::string doc = R"({"motors": [{"id": "m1", "name": "m", "type": "bldc",
    "ke_v_s_per_rad": 0.01, "kt_nm_per_a": 0.02, "rm_ohm": 0.1, "io_a": 0.5,
    "source": {"dataset": "t"}}]})";
  const auto p = Problems(doc);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p[0].find("kt/ke = 2"), std::string::npos) << p[0];
}

TEST(PhysicsAtTheDoor, PropellerBeatingMomentumTheoryIsRefused) {
  // T = 5 N at 1000 rpm on D = 0.254 m needs P_ideal = 5^1.5/sqrt(2*1.225*0.050671) = 31.7 W;
  // the law promises 20 W at every speed (FM ~ k^(3 - 3)): FM = 1.59.
  const double ideal_w = std::pow(5.0, 1.5) / std::sqrt(2 * 1.225 * M_PI * 0.254 * 0.254 / 4);
  EXPECT_NEAR(ideal_w, 31.7, 0.1);
  const auto p = Problems(LawProp(5.0, 20.0, 3.0, R"(, "rpm_min": 2000, "rpm_max": 8000)"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p[0].find("props[0] id=p1"), std::string::npos) << p[0];
  EXPECT_NE(p[0].find("beats momentum theory"), std::string::npos) << p[0];
  // Constant coefficients: FM = CT^1.5/(CP*sqrt(pi/2)) = 0.2^1.5/(0.05*1.2533) = 1.43.
  const auto q = Problems(R"({"props": [{"id": "p2", "name": "c", "diameter_m": 0.2,
    "ct_static": 0.2, "cp_static": 0.05, "source": {"dataset": "t"}}]})");
  ASSERT_EQ(q.size(), 1u);
  EXPECT_NE(q[0].find("figure of merit 1.42"), std::string::npos) << q[0];
}

TEST(PhysicsAtTheDoor, OnlyTheValidRangeCounts) {
  // P = c*k^2.6 with T = a*k^2: FM ~ k^0.4 rises with speed. a = 1 N, c = 8 W at 1000 rpm:
  // FM(k) = 1/(8*0.44042) * k^0.4 = 0.2838*k^0.4, which reaches 1 at k = 23.3 (23 300 rpm).
  const std::string in_range = LawProp(1.0, 8.0, 2.6, R"(, "rpm_min": 2000, "rpm_max": 9000)");
  Catalog c;
  EXPECT_TRUE(Problems(in_range, &c).empty());
  const PropFmScan s = ScanFigureOfMerit(c.prop("p1"));
  const double fm9 = 1.0 / (8.0 * std::sqrt(2 * 1.225 * M_PI * 0.254 * 0.254 / 4)) * std::pow(9.0, 0.4);
  EXPECT_NEAR(s.fm_max, fm9, 1e-9);
  EXPECT_NEAR(s.rpm_at_max, 9000, 1e-6);
  // The same law stated up to 30 000 rpm beats momentum theory at the top of its range.
  EXPECT_EQ(Problems(LawProp(1.0, 8.0, 2.6, R"(, "rpm_min": 2000, "rpm_max": 30000)")).size(), 1u);
  // rpm_max below rpm_min is refused with both numbers.
  const auto p = Problems(LawProp(1.0, 8.0, 2.6, R"(, "rpm_min": 9000, "rpm_max": 2000)"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p[0].find("rpm_max"), std::string::npos) << p[0];
}

TEST(PropValidRange, DefaultsToTheTipSpeedBandCappedByMaxRpm) {
  Catalog c;
  ASSERT_TRUE(Problems(LawProp(1.0, 8.0, 2.6, R"(, "max_rpm": 10000)"), &c).empty());
  const PropValidRange r = ValidRange(c.prop("p1"));
  EXPECT_TRUE(r.rpm_assumed);
  // 40 m/s at 0.127 m radius = 315 rad/s = 3008 rpm; 230 m/s = 17 294 rpm, capped at 10 000.
  EXPECT_NEAR(r.rpm_lo, 40.0 / 0.127 * 30 / M_PI, 1e-6);
  EXPECT_NEAR(r.rpm_hi, 10000, 1e-9);
}

TEST(Tiers, StatedInferredAndChecked) {
  Catalog c;
  ASSERT_TRUE(Problems(R"({"motors": [
    {"id": "a", "name": "a", "type": "bldc", "kv_rpm_per_v": 900, "rm_ohm": 0.1, "io_a": 0.5,
     "source": {"dataset": "t", "tier": "manufacturer_computed"}},
    {"id": "b", "name": "b", "type": "bldc", "kv_rpm_per_v": 900, "rm_ohm": 0.1, "io_a": 0.5,
     "exclude": "no rating", "source": {"dataset": "t", "values": {"rm_ohm": "fitted"}}},
    {"id": "c", "name": "c", "type": "bldc", "kv_rpm_per_v": 900, "rm_ohm": 0.1, "io_a": 0.5,
     "source": {"dataset": "t"}},
    {"id": "d", "name": "d", "type": "bldc", "kv_rpm_per_v": 900, "rm_ohm": 0.1, "io_a": 0.5,
     "source": {"dataset": "DriveCalc MData", "values": {"rm_ohm": "fitted"}}}]})", &c).empty());
  EXPECT_EQ(c.motor("d").tier, DataTier::kUserContributed);  // DriveCalc: user submissions
  EXPECT_EQ(c.motor("a").tier, DataTier::kManufacturerComputed);
  EXPECT_TRUE(c.motor("a").tier_stated);
  EXPECT_EQ(c.motor("b").tier, DataTier::kMeasured);  // fitted -> measured
  EXPECT_FALSE(c.motor("b").tier_stated);
  EXPECT_EQ(c.motor("b").exclude_reason, "no rating");
  EXPECT_EQ(c.motor("c").tier, DataTier::kAssumed);  // nothing said
  EXPECT_STREQ(TierName(DataTier::kUserContributed), "user_contributed");
  const auto p = Problems(R"({"motors": [{"id": "d", "name": "d", "type": "bldc",
    "kv_rpm_per_v": 900, "rm_ohm": 0.1, "io_a": 0.5, "source": {"dataset": "t", "tier": "gold"}}]})");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p[0].find("source.tier"), std::string::npos) << p[0];
  EXPECT_NE(p[0].find("user_contributed"), std::string::npos) << p[0];
}

TEST(FmEnvelope, ClassesCoverEveryDiameter) {
  EXPECT_STREQ(FmEnvelopeFor(0.05).label, "D < 6 in");
  EXPECT_STREQ(FmEnvelopeFor(0.254).label, "9 in <= D < 12 in");
  EXPECT_STREQ(FmEnvelopeFor(2.0).label, "D >= 12 in");
  for (const FmEnvelopeClass& c : FmEnvelope()) {
    EXPECT_LT(c.p10, c.p50);
    EXPECT_LT(c.p50, c.p90);
    EXPECT_LE(c.p90, c.max);
    EXPECT_LT(c.max, 0.8);  // docs/model.md section 10: the largest median is 0.753
  }
}

TEST(Folding, ByName) {
  EXPECT_TRUE(NameSaysFolding("Jamara Folding 6x4"));
  EXPECT_TRUE(NameSaysFolding("AeroCarbon 12.5x10.0"));
  EXPECT_TRUE(NameSaysFolding("ancf 12.5x9.0 "));
  EXPECT_FALSE(NameSaysFolding("APC E 10x7"));
}

bool HaveBundled() { return std::filesystem::exists(kCatalog + "/uiuc_propdb.json"); }

// UIUC's measured propellers alone (catalog/uiuc_propdb.json), loaded without a problem.
void LoadUiuc(Catalog* c) {
  std::vector<std::string> problems;
  c->AddDocument(ReadJsonFile(kCatalog + "/uiuc_propdb.json"), "uiuc_propdb.json", &problems);
  ASSERT_TRUE(problems.empty()) << problems[0];
}

// The constants of FmEnvelope() are what ComputeFmEnvelope finds on the bundled UIUC entries.
TEST(FmEnvelope, ConstantsMatchTheMeasuredPropellers) {
  if (!HaveBundled()) GTEST_SKIP() << "no catalog/uiuc_propdb.json";
  Catalog c;
  ASSERT_NO_FATAL_FAILURE(LoadUiuc(&c));
  std::vector<const PropEntry*> measured;
  for (const auto& p : c.props()) measured.push_back(&p);
  const auto fresh = ComputeFmEnvelope(measured);
  const auto& table = FmEnvelope();
  ASSERT_EQ(fresh.size(), table.size());
  int total = 0;
  for (std::size_t i = 0; i < table.size(); ++i) {
    // The table holds 4 decimals.
    EXPECT_EQ(fresh[i].n_props, table[i].n_props) << table[i].label;
    EXPECT_NEAR(fresh[i].p10, table[i].p10, 6e-5) << table[i].label;
    EXPECT_NEAR(fresh[i].p50, table[i].p50, 6e-5) << table[i].label;
    EXPECT_NEAR(fresh[i].p90, table[i].p90, 6e-5) << table[i].label;
    EXPECT_NEAR(fresh[i].max, table[i].max, 6e-5) << table[i].label;
    total += fresh[i].n_props;
  }
  EXPECT_EQ(total, 239);  // the static tests of volumes 1-3
}

// The axial-flow analogue of the figure of merit (ideal power in axial flow over the shaft
// power, physics.h) over UIUC's measured forward-flight sweeps, against the static envelope
// above: a well-loaded propeller in cruise reaches a larger share of the ideal power than any
// measured propeller does at rest, so the static limit (max_figure_of_merit, 0.8) would refuse
// measured cruise points of many propellers; the mission's limit in axial flow
// (max_axial_figure_of_merit, mission.h) is above every one of them (docs/model.md section 11).
// The figures docs/model.md quotes.
TEST(FmEnvelope, MeasuredSweepsInAxialFlowGoAboveTheStaticEnvelope) {
  if (!HaveBundled()) GTEST_SKIP() << "no catalog/uiuc_propdb.json";
  Catalog c;
  ASSERT_NO_FATAL_FAILURE(LoadUiuc(&c));
  std::vector<double> axial_max;
  for (const auto& p : c.props()) {
    if (p.j_tables.empty()) continue;
    axial_max.push_back(ScanFigureOfMerit(p).axial_fm_max);
  }
  std::sort(axial_max.begin(), axial_max.end());
  const auto above = std::count_if(axial_max.begin(), axial_max.end(), [](double a) { return a > 0.8; });
  // Each propeller's largest value over its sweeps; 5e-4: the figures as docs/model.md rounds them.
  EXPECT_EQ(axial_max.size(), 242u);  // volumes 1-3 with forward-flight sweeps
  EXPECT_EQ(above, 76);
  EXPECT_NEAR(SortedQuantile(axial_max, 0.5), 0.764, 5e-4);
  EXPECT_NEAR(SortedQuantile(axial_max, 0.9), 0.847, 5e-4);
  EXPECT_NEAR(axial_max.back(), 0.937, 5e-4);
  EXPECT_LT(axial_max.back(), MissionConstraints{}.max_axial_figure_of_merit);
  double static_max = 0;
  for (const FmEnvelopeClass& k : FmEnvelope()) static_max = std::max(static_max, k.max);
  EXPECT_LT(static_max, SortedQuantile(axial_max, 0.5));  // 0.753: below half the propellers' axial maxima
}

// Every propeller of the bundled catalog: FM <= 1 in its valid range (the loader checks it),
// and every non-measured one at or below its class envelope after the importer's derating.
TEST(BundledCatalogCredibility, NoPropellerAboveItsEnvelope) {
  if (!HaveBundled()) GTEST_SKIP() << "no bundled catalog";
  const Catalog c = Catalog::Load(kCatalog);
  int derated = 0, folding = 0;
  for (const auto& p : c.props()) {
    const PropFmScan s = ScanFigureOfMerit(p);
    EXPECT_LE(s.fm_max, 1.0) << p.id;
    if (p.tier != DataTier::kMeasured) {
      // The derated power data are stored with 7 digits (5e-7 relative).
      EXPECT_LE(s.fm_max, FmEnvelopeFor(p.diameter_m).max * (1 + 1e-6)) << p.id;
    }
    EXPECT_TRUE(p.tier_stated) << p.id;
    derated += p.power_derate_factor > 1.0;
    folding += p.folding;
  }
  EXPECT_GT(derated, 0);
  EXPECT_GT(folding, 0);
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// `dynosize catalog validate` on a folder with an ESC that creates energy and a propeller that
// beats momentum theory: exit 65 (bad data), one line each naming file, entry and rule; and
// every other command refuses to load the folder.
TEST(PhysicsAtTheDoorCli, ValidateNamesEachRefusal) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dynosize_physics_door_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "bad.json") << R"({"escs": [{"id": "e_bad", "name": "ESC", "resc_ohm": 0.01,
    "c1": 1.0, "c0": 0.0, "tr_sat": 0.9, "sat_slope": 0.6, "source": {"dataset": "t"}}],
    "props": [{"id": "p_bad", "name": "c", "diameter_m": 0.2, "ct_static": 0.2,
    "cp_static": 0.05, "source": {"dataset": "t"}}]})";
  const auto v = testing_util::RunCli("catalog validate " + dir.string());
  EXPECT_EQ(v.code, 65) << v.err;
  EXPECT_NE(v.out.find("bad.json: escs[0] id=e_bad: creates energy: c1 + c0 = 1 < 1.1095"),
            std::string::npos) << v.out;
  EXPECT_NE(v.out.find("bad.json: props[0] id=p_bad: static figure of merit 1.427"),
            std::string::npos) << v.out;
  EXPECT_NE(v.err.find("2 problems"), std::string::npos) << v.err;
  const auto l = testing_util::RunCli("--catalog " + dir.string() + " catalog list");
  EXPECT_EQ(l.code, 65) << l.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dynosize
