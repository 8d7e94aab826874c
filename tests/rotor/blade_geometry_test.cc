// Blade geometry readers (importers/blade_geometry.h) on UIUC's and APC's real files, checked at
// single rows read by hand (skipped without ../shared).
#include "importers/blade_geometry.h"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "common/units.h"

namespace dynosize {
namespace {

const std::string kData = DYNOSIZE_SHARED_DIR "/data";
constexpr double kDeg = kPi / 180.0;

TEST(BladeGeometryReaders, UiucVolumeOne) {
  const std::string f = kData + "/uiuc_propdb/volume1_geom.csv";
  if (!std::filesystem::exists(f)) GTEST_SKIP() << "no ../shared/data/uiuc_propdb";
  const std::vector<FamilyBlade> blades = ReadUiucGeometry(f);
  ASSERT_GE(blades.size(), 70u);
  const FamilyBlade* apce = nullptr;
  for (const FamilyBlade& b : blades) {
    if (b.geometry.name == "apce 10.0x5.0") apce = &b;
  }
  ASSERT_NE(apce, nullptr);
  EXPECT_EQ(apce->family, "apce");
  EXPECT_NEAR(apce->geometry.radius_m, 0.127, 1e-12);
  EXPECT_EQ(apce->geometry.stations.size(), 18u);
  EXPECT_NEAR(apce->geometry.stations.front().r_over_r, 0.15, 1e-12);
  EXPECT_NEAR(apce->geometry.root_r_over_r, 0.15, 1e-12);
}

TEST(BladeGeometryReaders, UiucSamplesOfOneBladeAreAveraged) {
  const std::string f = kData + "/uiuc_propdb/volume2_geom.csv";
  if (!std::filesystem::exists(f)) GTEST_SKIP() << "no ../shared/data/uiuc_propdb";
  // gwsdd 2.5x0.8 was measured on several samples (rows 308-325, 326-343, ...), c/R at r/R 0.15
  // 0.3088, 0.3176, 0.3225, ...: the blade's first station is their mean, between them.
  for (const FamilyBlade& b : ReadUiucGeometry(f)) {
    if (b.geometry.name != "gwsdd 2.5x0.8") continue;
    EXPECT_EQ(b.geometry.stations.size(), 18u);
    EXPECT_GT(b.geometry.stations[0].chord_over_r, 0.3088);
    EXPECT_LT(b.geometry.stations[0].chord_over_r, 0.33);
    return;
  }
  FAIL() << "gwsdd 2.5x0.8 not read";
}

TEST(BladeGeometryReaders, ApcPe0) {
  const std::string f = kData + "/apc_geometry/geometry/10x5-PERF.PE0";
  if (!std::filesystem::exists(f)) GTEST_SKIP() << "no ../shared/data/apc_geometry";
  const BladeGeometry g = ReadApcPe0(f);
  EXPECT_EQ(g.name, "10x5");
  EXPECT_EQ(g.blades, 2);
  EXPECT_NEAR(g.radius_m, InchToMeter(5.0), 1e-12);
  // First station: 1.2000 in, chord 0.7781 in, thickness ratio 0.2278, twist 30.9941 deg.
  EXPECT_NEAR(g.stations.front().r_over_r, 1.2 / 5.0, 1e-12);
  EXPECT_NEAR(g.stations.front().chord_over_r, 0.7781 / 5.0, 1e-12);
  EXPECT_NEAR(g.stations.front().thickness_ratio, 0.2278, 1e-12);
  EXPECT_NEAR(g.stations.front().beta_rad, 30.9941 * kDeg, 1e-12);
  // The tip row (chord 0.0001 in) is not a station; the one before it (4.98 in) is the last.
  EXPECT_NEAR(g.stations.back().r_over_r, 4.98 / 5.0, 1e-12);
  EXPECT_NEAR(g.root_r_over_r, 1.2 / 5.0, 1e-12);  // HUBTRA 1.20 in = the first station
}

TEST(BladeGeometryReaders, ApcNames) {
  EXPECT_EQ(ApcFileNameOfUiuc("apce", 10.0, 5.0), "10x5E");
  EXPECT_EQ(ApcFileNameOfUiuc("apcsf", 10.0, 4.7), "10x47SF");
  EXPECT_EQ(ApcFileNameOfUiuc("apcsp", 14.0, 13.0), "14x13");
  EXPECT_EQ(ApcFileNameOfUiuc("gwsdd", 9.0, 5.0), "");
  double d = 0.0, p = 0.0;
  ASSERT_TRUE(ParseApcSize("10x45MR", &d, &p));
  EXPECT_EQ(d, 10.0);
  EXPECT_EQ(p, 4.5);
  ASSERT_TRUE(ParseApcSize("95x5MR", &d, &p));
  EXPECT_EQ(d, 9.5);
  EXPECT_EQ(p, 5.0);
  ASSERT_TRUE(ParseApcSize("8x10", &d, &p));
  EXPECT_EQ(d, 8.0);
  EXPECT_EQ(p, 10.0);
  EXPECT_FALSE(ParseApcSize("MRx5", &d, &p));
}

TEST(BladeGeometryReaders, UiucIdToBladeName) {
  EXPECT_EQ(UiucBladeNameOfId("uiuc_v1_apce_10.0x5.0_2"), "apce 10.0x5.0");
  EXPECT_EQ(UiucBladeNameOfId("uiuc_v2_da4022_5.0x3.75_3"), "da4022 5.0x3.75");
  EXPECT_EQ(UiucBladeNameOfId("apc_10x5"), "");
}

}  // namespace
}  // namespace dynosize
