// The readers of importers/reference_motors.h: conventions on the real files (skipped when
// ../shared/data is absent) and the error text on a bad cell.
#include "importers/reference_motors.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "common/error.h"

namespace dynosize {
namespace {

const std::string kData = DYNOSIZE_SHARED_DIR "/data";

// Values are copied from the CSV text; 2*r_phase is exact in binary to a few ulps.
constexpr double kCopiedRelTol = 1e-12;

TEST(ReferenceMotorsTest, RealFilesFollowTheConventions) {
  if (!std::filesystem::is_directory(kData + "/evtol_motors")) GTEST_SKIP() << "no ../shared/data/evtol_motors";
  const auto refs = ReadReferenceMotors(kData);
  int emrax = 0, neu = 0, kde = 0, swapped_seen = 0;
  for (const auto& r : refs) {
    EXPECT_TRUE(std::isnan(r.stated.kv_rpm_per_v)) << r.where;  // the constant is the truth, not stated
    if (r.stated.maker == "EMRAX") ++emrax;
    if (r.stated.maker == "KDE Direct") ++kde;
    if (r.stated.maker == "NeuMotors") ++neu;
    if (r.stated.model == "EMRAX 228" && r.kv_rpm_per_v == 10.14) {  // r_phase 0.01548 ohm
      EXPECT_NEAR(r.r_dc_ohm, 2 * 0.01548, kCopiedRelTol);
      EXPECT_TRUE(std::isnan(r.io_dc_a));
    }
    if (r.stated.model == "8830" && r.kv_rpm_per_v == 7.0 && r.io_dc_a == 0.102) {
      EXPECT_EQ(r.r_dc_ohm, 6.32);  // 88xx: printed Rm 0.102, Io 6.32: swapped back
      ++swapped_seen;
    }
  }
  EXPECT_EQ(emrax, 45);
  EXPECT_EQ(neu, 464);
  EXPECT_EQ(kde, 26);  // 21 datasheets + 5 corpus-only G3 rows
  EXPECT_EQ(swapped_seen, 1);
}

TEST(ReferenceMotorsTest, BadCellNamesFileLineColumnAndValue) {
  const auto path = std::filesystem::temp_directory_path() / "dynosize_reference_motors_test.csv";
  {
    std::ofstream out(path);
    out << "motor,mass_kg,p_max_w,v_max_v,kv_rpm_per_v,rm_ohm,io_a,io_test_v\n"
        << "KDE1,0.3,900,50,330,0.044,0.7,10\n"
        << "KDE2,0.3,900,50,33o,0.044,0.7,10\n";
  }
  try {
    ReadKdeDatasheetMotors(path.string());
    FAIL() << "no DataError";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ":3: column 'kv_rpm_per_v' = '33o': not a number"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace dynosize
