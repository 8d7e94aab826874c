// Motor constant per frame family (catalog/motor_credibility.h): the family key, the outlier
// rule on hand-made families, and the bundled catalog, where every motor above the rule is
// excluded by default.
#include "catalog/motor_credibility.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "catalog/catalog.h"
#include "catalog/conventions.h"

namespace dynosize {
namespace {

const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";

TEST(MotorCredibilityTest, MotorConstantIsKtOverSqrtR) {
  // Kv 1000 rpm/V: KT_dc = 60/(2*pi*1000) = 9.549e-3 N*m/A; R 0.25 ohm -> Km = 0.019099.
  EXPECT_NEAR(MotorConstantDc(1000.0, 0.25), 60.0 / (2.0 * M_PI * 1000.0) / 0.5, 1e-12);
  EXPECT_EQ(MotorConstantDc(0.0, 0.25), 0.0);
  EXPECT_EQ(MotorConstantDc(1000.0, 0.0), 0.0);
}

TEST(MotorCredibilityTest, FrameFamilyDropsTheWindingGearAndParentheses) {
  EXPECT_EQ(FrameFamily("AXI 2212-34"), "axi 2212");
  EXPECT_EQ(FrameFamily("AXI 2212/20 GOLD LINE"), "");  // the winding token is not last
  EXPECT_EQ(FrameFamily("Kontronik KIRA 480-31/5.2:1"), "kontronik kira 480");
  EXPECT_EQ(FrameFamily("Hacker A30-28S"), "hacker a30 s");  // stack length kept
  EXPECT_EQ(FrameFamily("Medusa MR-028-032-4200"), "medusa mr-028-032");
  EXPECT_EQ(FrameFamily("RS-E 435-40 (18/5/058)"), "rs-e 435");
  EXPECT_EQ(FrameFamily("Turnigy 3648 1450kv"), "");
}

TEST(MotorCredibilityTest, OnlyTheWindingNoFrameCanHaveIsAnOutlier) {
  // One frame, windings of 12, 20, 26 and 34 turns: KT ~ N and R ~ N^2 give one Km; the last
  // stores an R 5x too small (Km x sqrt(5) = 2.24 > kFamilyKmRatioMax).
  std::vector<MotorKmInput> m;
  for (double n : {12.0, 20.0, 26.0, 34.0}) m.push_back({"Frame 2212-" + std::to_string(static_cast<int>(n)), 24000.0 / n, 1e-4 * n * n});
  EXPECT_TRUE(FrameFamilyOutliers(m).empty());
  m.back().r_dc_ohm /= 5.0;
  const auto out = FrameFamilyOutliers(m);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].index, 3u);
  EXPECT_NEAR(out[0].ratio, std::sqrt(5.0), 1e-9);
  EXPECT_NE(FamilyOutlierReason(out[0]).find("'frame 2212'"), std::string::npos);
  // Two members are not a family: nothing to compare with.
  m.resize(2);
  m.back().r_dc_ohm /= 100.0;
  EXPECT_TRUE(FrameFamilyOutliers(m).empty());
}

// The DriveCalc AXI 2212-34 stores R = 0.051 ohm; DriveCalc's own measurements of it give six
// times more (dc_m_56_fit). It was the quadcopter example's pick before this rule.
TEST(MotorCredibilityTest, BundledCatalogExcludesEveryFamilyOutlier) {
  const Catalog c = Catalog::Load(kCatalog);
  std::vector<MotorKmInput> in;
  std::vector<const MotorEntry*> entries;
  for (const auto& e : c.motors()) {
    if (e.json["source"]["dataset"] != c.motor("dc_m_56").json["source"]["dataset"]) continue;
    const double r_dc = e.json.contains("rm_dc_ohm") ? e.json["rm_dc_ohm"].get<double>()
                                                    : e.params.rm_ohm / kRmsPerDcResistance;
    in.push_back({e.name, e.json.value("kv_rpm_per_v", 0.0), r_dc});
    entries.push_back(&e);
  }
  const auto out = FrameFamilyOutliers(in);
  ASSERT_FALSE(out.empty());
  bool axi = false;
  for (const auto& o : out) {
    EXPECT_FALSE(entries[o.index]->exclude_reason.empty()) << entries[o.index]->id;
    axi = axi || entries[o.index]->id == "dc_m_56";
  }
  EXPECT_TRUE(axi);
  EXPECT_FALSE(c.motor("dc_m_55").exclude_reason.size() > 0 &&
               c.motor("dc_m_55").exclude_reason.find("motor constant") != std::string::npos);
}

}  // namespace
}  // namespace dynosize
