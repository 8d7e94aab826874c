// The importers on the real files of ../shared/data, checked at single rows against values
// computed by hand from the source text (skipped when ../shared is absent).
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "importers/importers.h"

namespace dynosize {
namespace {

const std::string kData = DYNOSIZE_SHARED_DIR "/data";
bool Have(const std::string& d) { return std::filesystem::is_directory(kData + "/" + d); }

const Json* FindId(const Json& arr, const std::string& id) {
  for (const auto& e : arr) {
    if (e["id"] == id) return &e;
  }
  return nullptr;
}

// The importers keep 4-6 significant digits.
constexpr double kFourDigits = 5e-4;

TEST(RealDataImportTest, ApcPer3RowToCoefficients) {
  if (!Have("apc_per3_subset")) GTEST_SKIP() << "no ../shared/data/apc_per3_subset";
  const ImportedDataset d = ImportApcPer3(kData + "/apc_per3_subset");
  EXPECT_EQ(d.props.size(), 38u);
  const Json* p = FindId(d.props, "apc_per3_10x45mr");
  ASSERT_NE(p, nullptr);
  EXPECT_NEAR((*p)["diameter_m"].get<double>(), 0.254, 1e-12);
  EXPECT_NEAR((*p)["pitch_m"].get<double>(), 4.5 * 0.0254, 1e-12);
  // PER3_10x45MR.csv, 5000 rpm, V = 0: torque 0.057 N*m, thrust 0.3866763879612304 kg.
  // n = 83.333 rev/s, D = 0.254 m, rho = 1.225:
  //   CT = 0.38668*9.80665/(1.225*83.333^2*0.254^4) = 0.10754
  //   CP = 2*pi*0.057/(1.225*83.333^2*0.254^5)      = 0.04134
  const double n = 5000.0 / 60, dd = 0.254;
  const double ct = 0.3866763879612304 * 9.80665 / (1.225 * n * n * std::pow(dd, 4));
  const double cp = 2 * M_PI * 0.057 / (1.225 * n * n * std::pow(dd, 5));
  const Json& st = (*p)["static_table"];
  // APC's static FM (0.768) is above the best measured 9-12 in propeller's (0.719): the
  // importer raised CP by power_derate_factor (catalog/prop_credibility.h).
  const double derate = (*p)["power_derate_factor"].get<double>();
  EXPECT_GT(derate, 1.05);
  EXPECT_LT(derate, 1.08);
  bool found = false;
  for (std::size_t i = 0; i < st["rpm"].size(); ++i) {
    if (st["rpm"][i].get<double>() != 5000.0) continue;
    found = true;
    EXPECT_NEAR(st["ct"][i].get<double>(), ct, kFourDigits * ct);
    EXPECT_NEAR(st["cp"][i].get<double>(), cp * derate, kFourDigits * cp * derate);
  }
  EXPECT_EQ((*p)["source"]["tier"], "manufacturer_computed");
  EXPECT_TRUE(found);
  EXPECT_EQ((*p)["source"]["values"]["static_table"], "computed");
}

TEST(RealDataImportTest, UiucPropTables) {
  if (!Have("uiuc_propdb")) GTEST_SKIP() << "no ../shared/data/uiuc_propdb";
  const ImportedDataset d = ImportUiuc(kData + "/uiuc_propdb");
  EXPECT_EQ(d.props.size(), 242u);  // 139 + 63 + 40 (README)
  const Json* p = FindId(d.props, "uiuc_v1_ance_8.5x6.0_2");
  ASSERT_NE(p, nullptr);
  EXPECT_NEAR((*p)["diameter_m"].get<double>(), 8.5 * 0.0254, 1e-12);
  EXPECT_EQ((*p)["blades"], 2);
  // volume1_exp.csv: first static row 2489 rpm CT 0.1046 CP 0.0567; first sweep 4000 rpm
  // starts at J = 0.165, CT 0.0993, CP 0.0539 (lines 2-).
  const Json& st = (*p)["static_table"];
  EXPECT_EQ(st["rpm"][0].get<double>(), 2489.0);
  EXPECT_EQ(st["ct"][0].get<double>(), 0.1046);
  EXPECT_EQ(st["cp"][0].get<double>(), 0.0567);
  bool found = false;
  for (const auto& sw : (*p)["j_tables"]) {
    if (std::abs(sw["rpm"].get<double>() - 4000.0) > 0.03 * 4000) continue;
    for (std::size_t i = 0; i < sw["j"].size(); ++i) {
      if (sw["j"][i].get<double>() == 0.165) {
        found = true;
        EXPECT_EQ(sw["ct"][i].get<double>(), 0.0993);
      }
    }
  }
  EXPECT_TRUE(found);
}

// The flat CSV lost a decimal point in four Aeronaut CAM folder sizes: 12.5x6.0 and
// 12.5x9.0 had pitch 0.6 and 0.9 in, 12x6.5 and 13x6.5 had diameter 1.2 and 1.3 in.
TEST(RealDataImportTest, UiucFolderSizesDecodedFromTheName) {
  if (!Have("uiuc_propdb")) GTEST_SKIP() << "no ../shared/data/uiuc_propdb";
  const ImportedDataset d = ImportUiuc(kData + "/uiuc_propdb");
  const struct {
    const char* id;
    double d_in, p_in;
  } cases[] = {{"uiuc_v3_ancf_125.0x6.0_2", 12.5, 6.0}, {"uiuc_v3_ancf_125.0x9.0_2", 12.5, 9.0},
               {"uiuc_v3_ancf_12.0x65.0_2", 12.0, 6.5}, {"uiuc_v3_ancf_13.0x65.0_2", 13.0, 6.5},
               {"uiuc_v3_ancf_125.0x75.0_2", 12.5, 7.5}, {"uiuc_v3_ancf_10.0x4.0_2", 10.0, 4.0}};
  for (const auto& c : cases) {
    const Json* p = FindId(d.props, c.id);
    ASSERT_NE(p, nullptr) << c.id;
    EXPECT_NEAR((*p)["diameter_m"].get<double>(), c.d_in * 0.0254, 1e-12) << c.id;
    EXPECT_NEAR((*p)["pitch_m"].get<double>(), c.p_in * 0.0254, 1e-12) << c.id;
    EXPECT_TRUE((*p)["folding"].get<bool>()) << c.id;  // Aeronaut CAM folding blades
    EXPECT_EQ((*p)["source"]["tier"], "measured");
  }
  // Other families are left alone.
  double dd = 9.0, pp = 6.0;
  EXPECT_FALSE(DecodeUiucFolderSize("apcsp 9.0x6.0", &dd, &pp));
  EXPECT_EQ(pp, 6.0);
}

TEST(RealDataImportTest, FastUavMotorAndEsc) {
  if (!Have("fastuav_catalogues")) GTEST_SKIP() << "no ../shared/data/fastuav_catalogues";
  const ImportedDataset d = ImportFastUav(kData + "/fastuav_catalogues");
  // Motors_Data.csv row 1: AXI 2203/RACE GOLD LINE; Kv 2300; Io 0.55 A; R 0.22 ohm; 18.5 g.
  const Json* m = FindId(d.motors, "fu_m_1");
  ASSERT_NE(m, nullptr);
  EXPECT_EQ((*m)["name"], "AXI 2203/RACE GOLD LINE");
  EXPECT_EQ((*m)["kv_rpm_per_v"].get<double>(), 2300.0);
  // Datasheet R is the DC circuit's: kept as rm_dc_ohm, rm_ohm = 0.7491946*R (conventions.h).
  EXPECT_EQ((*m)["rm_dc_ohm"].get<double>(), 0.22);
  EXPECT_NEAR((*m)["rm_ohm"].get<double>(), 0.7491946 * 0.22, 5e-6 * 0.165);
  EXPECT_EQ((*m)["source"]["tier"], "manufacturer_stated");
  EXPECT_NEAR((*m)["io_a"].get<double>(), 0.55 / 1.1095280, kFourDigits);  // 0.4957 rms
  EXPECT_NEAR((*m)["mass_kg"].get<double>(), 0.0185, 1e-12);
  // ESC_data.csv row 1: Jive 80+ LV, 80 A, 84 g: prior R = 79.18*80^-0.8467 mOhm = 1.93 mOhm.
  const Json* e = FindId(d.escs, "fu_e_1");
  ASSERT_NE(e, nullptr);
  EXPECT_EQ((*e)["name"], "Jive 80+ LV");
  const double r = 79.18e-3 * std::pow(80.0, -0.8467);
  EXPECT_NEAR((*e)["resc_ohm"].get<double>(), r, 5e-3 * r);
  EXPECT_EQ((*e)["source"]["values"]["resc_ohm"], "assumed");
  // 21 real packs (n_series = n_parallel = 1) + 2 models recovered from their smallest
  // augmented combination (TP6000-4SPX25, KOKAM SLPB68106100).
  EXPECT_EQ(d.batteries.size(), 23u);
}

TEST(RealDataImportTest, ManufacturerTableFitByHand) {
  if (!Have("sjkim_mfr_motor_tables")) GTEST_SKIP() << "no ../shared/data/sjkim_mfr_motor_tables";
  const ImportedDataset d = ImportSjkimTables(kData + "/sjkim_mfr_motor_tables");
  const Json* m = FindId(d.motors, "sj_m_scorpion_1100kv");
  ASSERT_NE(m, nullptr);
  // Scorpion_1100kv.csv full-throttle row: 22.6 V, 58.5 A, 19862 rpm:
  //   R = (22.6 - 19862/1100)/58.5 = 0.07767 ohm;  io = 0.0215*58.5/1.1095 = 1.134 A (2 digits).
  EXPECT_NEAR((*m)["rm_dc_ohm"].get<double>(), (22.6 - 19862.0 / 1100) / 58.5, 1e-3 * 0.0777);
  // The rms circuit's resistance gives the same full-throttle line (catalog/conventions.h).
  EXPECT_NEAR((*m)["rm_ohm"].get<double>(), 0.7491946 * (22.6 - 19862.0 / 1100) / 58.5,
              1e-3 * 0.0582);
  EXPECT_NEAR((*m)["io_a"].get<double>(), 1.1, 1e-12);
  EXPECT_EQ((*m)["test_points"].size(), 7u);
  EXPECT_EQ((*m)["max_current_a"].get<double>(), 58.5);  // the table's largest current
  EXPECT_EQ((*m)["source"]["values"]["rm_dc_ohm"], "fitted");
  EXPECT_EQ((*m)["source"]["values"]["rm_ohm"], "derived");
  EXPECT_EQ((*m)["source"]["values"]["io_a"], "assumed");
}

}  // namespace
}  // namespace dynosize
