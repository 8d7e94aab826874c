// The eVTOL-scale importers (issue 51) on the real files of ../shared/data, checked at single
// rows against values worked out by hand from the source rows (skipped when ../shared is absent).
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "catalog/catalog.h"
#include "catalog/conventions.h"
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

std::string Method(const Json& e, const char* key) { return e["source"]["values"][key].get<std::string>(); }

// The importers keep 4-6 significant digits.
constexpr double kFourDigits = 5e-4;

TEST(EvtolScaleImportTest, KdeDatasheetMotorAsPrinted) {
  if (!Have("heavy_lift_motors")) GTEST_SKIP() << "no ../shared/data/heavy_lift_motors";
  const ImportedDataset d = ImportHeavyLiftMotors(kData + "/heavy_lift_motors");
  // 21 KDE tables + 60 T-Motor + 5 KDE G3 rows of the corpus (15 corpus KDE rows are KDE's tables).
  EXPECT_EQ(d.motors.size(), 86u);
  EXPECT_EQ(d.report.DroppedCount("motors"), 15u);
  // kde_datasheets.csv, KDE10218XF-105: 105 RPM/V, 0.023 ohm, Io 1.0 A at 10 V, 1180 g with
  // wires, 142 A and 7355 W for 180 s, up to 60.9 V.
  const Json* m = FindId(d.motors, "hl_m_kde10218xf_105");
  ASSERT_NE(m, nullptr);
  EXPECT_EQ((*m)["name"], "KDE10218XF-105");
  EXPECT_DOUBLE_EQ((*m)["kv_rpm_per_v"].get<double>(), 105.0);
  EXPECT_DOUBLE_EQ((*m)["rm_dc_ohm"].get<double>(), 0.023);
  EXPECT_NEAR((*m)["rm_ohm"].get<double>(), RmsCircuitResistanceFromDc(0.023), kFourDigits * 0.023);
  EXPECT_NEAR((*m)["io_a"].get<double>(), RmsNoLoadCurrentFromDc(1.0), kFourDigits);
  EXPECT_DOUBLE_EQ((*m)["mass_kg"].get<double>(), 1.18);
  EXPECT_DOUBLE_EQ((*m)["max_current_a"].get<double>(), 142.0);
  EXPECT_DOUBLE_EQ((*m)["vdc_max_v"].get<double>(), 60.9);
  // The corpus's G3 row with its peak ratings: KDE700XF-455-G3, 135 A / 248 A peak.
  const Json* g3 = FindId(d.motors, "hl_m_kde700xf_455_g3");
  ASSERT_NE(g3, nullptr);
  EXPECT_DOUBLE_EQ((*g3)["max_current_a"].get<double>(), 135.0);
  EXPECT_DOUBLE_EQ((*g3)["peak_current_a"].get<double>(), 248.0);
}

TEST(EvtolScaleImportTest, EmraxStatedAndEstimatedValues) {
  if (!Have("evtol_motors") || !Have("heavy_lift_motors")) GTEST_SKIP() << "no ../shared/data/evtol_motors";
  const ImportedDataset d = ImportEvtolMotors(kData + "/evtol_motors");
  EXPECT_EQ(d.motors.size() + d.report.DroppedCount("motors"), 142u);  // every row kept or dropped
  // evtol_motors.csv line 2, EMRAX 188 HV / AC: Kv 17.73, phase resistance 0.01437 ohm (phase to
  // phase, halved: R_dc = 0.02874), 100 A continuous / 190 A peak phase rms, 27 / 60 kW (S2 2 min).
  const Json* m = FindId(d.motors, "ev_m_emrax_188_hv_ac");
  ASSERT_NE(m, nullptr);
  EXPECT_DOUBLE_EQ((*m)["kv_rpm_per_v"].get<double>(), 17.73);
  EXPECT_NEAR((*m)["rm_dc_ohm"].get<double>(), 0.02874, kFourDigits * 0.02874);
  EXPECT_EQ(Method(*m, "rm_dc_ohm"), "derived");
  EXPECT_EQ(Method(*m, "io_a"), "estimated");  // EMRAX states no Io
  EXPECT_DOUBLE_EQ((*m)["peak_duration_s"].get<double>(), 120.0);
  EXPECT_DOUBLE_EQ((*m)["max_power_w"].get<double>(), 27000.0);
  EXPECT_DOUBLE_EQ((*m)["peak_power_w"].get<double>(), 60000.0);
  EXPECT_DOUBLE_EQ((*m)["max_current_a"].get<double>(), 100.0);
  EXPECT_EQ((*m)["source"]["tier"], "estimated");
  // The estimate's range holds its value.
  const Json& io = (*m)["estimate_ranges"]["io_a"];
  EXPECT_LE(io[0].get<double>(), (*m)["io_a"].get<double>());
  EXPECT_GE(io[1].get<double>(), (*m)["io_a"].get<double>());
}

TEST(EvtolScaleImportTest, KdePropellerFromTheSheetsMeetsMomentumTheory) {
  if (!Have("kde_direct_mfr_sheets")) GTEST_SKIP() << "no ../shared/data/kde_direct_mfr_sheets";
  const ImportedDataset d = ImportKdeSheetsCatalog(kData + "/kde_direct_mfr_sheets");
  ASSERT_EQ(d.escs.size(), 1u);
  EXPECT_EQ(d.escs[0]["name"], "KDE-UAS125UVC");
  EXPECT_DOUBLE_EQ(d.escs[0]["deadband"].get<double>(), -0.162);
  EXPECT_EQ(d.props.size(), 15u);
  const Json* p = FindId(d.props, "kde_p_30.5x9.7x2");
  ASSERT_NE(p, nullptr);
  EXPECT_NEAR((*p)["diameter_m"].get<double>(), 30.5 * 0.0254, 1e-12);
  EXPECT_EQ((*p)["blades"], 2);
  // Every bin's static figure of merit CT^1.5/(sqrt(2)*CP) is a carbon propeller's: above the
  // UIUC envelope's p10 (0.39) and at most 1 (momentum theory).
  for (const auto& e : d.props) {
    const Json& st = e["static_table"];
    for (std::size_t k = 0; k < st["ct"].size(); ++k) {
      const double fm = std::pow(st["ct"][k].get<double>(), 1.5) / (std::sqrt(2.0) * st["cp"][k].get<double>());
      EXPECT_GT(fm, 0.39) << e["id"];
      EXPECT_LE(fm, 1.0) << e["id"];
    }
  }
}

TEST(EvtolScaleImportTest, ControllersAndPacks) {
  if (!Have("hv_controllers") || !Have("packs_and_cells")) GTEST_SKIP() << "no ../shared/data/hv_controllers";
  const ImportedDataset c = ImportHvControllers(kData + "/hv_controllers");
  // 72 rows: 33 FAST-UAV (in fastuav.json), 2 DC/DC converters, 2 generator/hybrid controllers.
  EXPECT_EQ(c.escs.size(), 35u);
  const Json* mc110 = FindId(c.escs, "hv_e_embention_veronte_mc110_v2.0");
  ASSERT_NE(mc110, nullptr);
  EXPECT_DOUBLE_EQ((*mc110)["vdc_max_v"].get<double>(), 800.0);
  EXPECT_DOUBLE_EQ((*mc110)["peak_duration_s"].get<double>(), 5.0);
  // BRUSA DMC524 states 97 % at 79 kW and 225 A: RESC = (1/0.97 - 1)*79e3/(sqrt(27/10)*225^2).
  const Json* brusa = FindId(c.escs, "hv_e_brusa_dmc524");
  ASSERT_NE(brusa, nullptr);
  const double r = (1 / 0.97 - 1) * 79e3 / (std::sqrt(2.7) * 225.0 * 225.0);
  EXPECT_NEAR((*brusa)["resc_ohm"].get<double>(), r, 2e-3 * r);  // 3 significant digits
  EXPECT_EQ(Method(*brusa, "resc_ohm"), "derived");
  const ImportedDataset b = ImportPacksAndCells(kData + "/packs_and_cells");
  EXPECT_EQ(b.batteries.size(), 17u);  // 10 Tattu packs, 7 cells
  const Json* cell = FindId(b.batteries, "pc_b_molicel_inr21700_p45b");
  ASSERT_NE(cell, nullptr);
  EXPECT_EQ((*cell)["chemistry"], "liion");
  EXPECT_EQ((*cell)["cells_series"], 1);
}

}  // namespace
}  // namespace dynosize
