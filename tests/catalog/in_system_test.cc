// The in-system law (catalog/in_system.h) and its fit (stand/in_system_fit.h): synthetic
// recovery, the catalog's constants against a refit of the data they came from, the law's
// goals by leaving each KDE motor out (skipped without ../shared), and where the law applies.
#include <cmath>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "catalog/catalog.h"
#include "catalog/conventions.h"
#include "catalog/in_system.h"
#include "common/units.h"
#include "importers/kde_sheets.h"
#include "model/drive.h"
#include "stand/in_system_fit.h"

namespace dynosize {
namespace {

const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";
const std::string kKde = DYNOSIZE_SHARED_DIR "/data/kde_direct_mfr_sheets";

// The catalog prints coefficients to 4 significant digits.
constexpr double kPrintedDigits = 1e-3;

std::vector<stand::LawMotor> KdeMotors() {
  std::vector<stand::LawMotor> out;
  for (const auto& k : ReadKdeSheets(kKde)) {
    if (!k.has_torque()) continue;
    stand::LawMotor m{k.name, {k.kv_rpm_per_v, k.r_dc_ohm, k.io_dc_a, k.io_test_voltage_v}, {}};
    for (const auto& r : k.rows) {
      m.points.push_back({r.vdc_v, r.throttle, r.idc_a, r.rpm * kRadPerSecPerRpm, r.torque_nm, r.block});
    }
    out.push_back(std::move(m));
  }
  return out;
}

// Synthetic motors whose sheets were made with a known law (seeded noise of 1 % on the current):
// the fit recovers the law.
TEST(InSystemFitTest, RecoversAKnownLawFromSyntheticSheets) {
  InSystemLaw truth;
  truth.r_scale = 1.8;
  truth.r_add_ohm = 0.02;
  truth.io_scale = 2.5;
  std::mt19937 rng(20261125);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<stand::LawMotor> motors;
  const double kvs[] = {150, 300, 500, 800, 1200};
  const double rs[] = {0.06, 0.05, 0.09, 0.12, 0.08};
  for (int i = 0; i < 5; ++i) {
    stand::LawMotor m{"m" + std::to_string(i), {kvs[i], rs[i], 0.5, 10.0}, {}};
    for (int s = 0; s < 3; ++s) {
      const double vdc = 15.0 + 10.0 * s;
      for (int k = 1; k <= 6; ++k) {
        stand::LawPoint p;
        p.vdc_v = vdc;
        p.sweep = s;
        p.omega_rad_s = 0.12 * k * kvs[i] * vdc * kRadPerSecPerRpm;
        p.torque_nm = 0.02 * k * k * (1000.0 / kvs[i]);
        p.throttle = 0.5;
        p.idc_a = stand::PredictIdc(m, truth, p) * (1.0 + noise(rng));
        m.points.push_back(p);
      }
    }
    motors.push_back(std::move(m));
  }
  const InSystemLaw fit = stand::FitLaw(motors, {true, false});
  // 1 % noise on 90 points, three coefficients: a few percent at most.
  EXPECT_NEAR(fit.r_scale, truth.r_scale, 0.1 * truth.r_scale);
  EXPECT_NEAR(fit.r_add_ohm, truth.r_add_ohm, 0.01);
  EXPECT_NEAR(fit.io_scale, truth.io_scale, 0.05 * truth.io_scale);
}

// The law's values at identity are the datasheet's in the rms circuit (catalog/conventions.h).
TEST(InSystemLawTest, IdentityLawKeepsTheDatasheetAndTheLawScales) {
  MotorParams raw;
  raw.rm_ohm = RmsCircuitResistanceFromDc(0.1);
  raw.io_a = RmsNoLoadCurrentFromDc(0.5);
  const DatasheetMotor ds{500, 0.1, 0.5, 10.0};
  const MotorParams same = InSystemMotorParams(raw, ds, InSystemLaw{}, true, true);
  EXPECT_DOUBLE_EQ(same.rm_ohm, raw.rm_ohm);
  EXPECT_DOUBLE_EQ(same.io_a, raw.io_a);
  InSystemLaw law;
  law.r_scale = 2.0;
  law.r_add_ohm = 0.01;
  law.io_scale = 3.0;
  const MotorParams sys = InSystemMotorParams(raw, ds, law, true, false);
  EXPECT_NEAR(sys.rm_ohm, kRmsPerDcResistance * 0.21, 1e-12);
  EXPECT_DOUBLE_EQ(sys.io_a, raw.io_a);  // apply_io false
}

// tests the constants of in_system.cc against a refit of the bundled catalog's DriveCalc pairs.
TEST(InSystemLawTest, DriveCalcConstantsAreTheRefitOfTheBundledCatalog) {
  const Catalog raw = Catalog::Load(kCatalog, /*in_system_law=*/false);
  const auto pairs = stand::DriveCalcRefitPairs(raw);
  ASSERT_GT(pairs.size(), 1000u);
  const InSystemLaw fit = stand::FitLawFromRefits(pairs);
  const InSystemLaw& law = DriveCalcDatabaseLaw();
  EXPECT_NEAR(fit.r_scale, law.r_scale, kPrintedDigits * law.r_scale);
  EXPECT_NEAR(fit.r_add_ohm, law.r_add_ohm, kPrintedDigits * law.r_add_ohm);
  EXPECT_NEAR(fit.io_scale, law.io_scale, kPrintedDigits * law.io_scale);
  EXPECT_NEAR(fit.r_ratio_p90, law.r_ratio_p90, kPrintedDigits * law.r_ratio_p90);
  EXPECT_EQ(fit.motors, law.motors);
}

TEST(InSystemLawTest, KdeConstantsAreTheRefitOfTheSheets) {
  if (!std::filesystem::is_directory(kKde)) GTEST_SKIP() << "no ../shared/data/kde_direct_mfr_sheets";
  const auto motors = KdeMotors();
  ASSERT_EQ(motors.size(), 9u);
  const InSystemLaw fit = stand::FitLaw(motors, {false, false});
  const InSystemLaw& law = KdeDatasheetLaw();
  EXPECT_NEAR(fit.r_scale, law.r_scale, kPrintedDigits * law.r_scale);
  EXPECT_EQ(law.r_add_ohm, 0.0);
  EXPECT_NEAR(fit.io_scale, law.io_scale, kPrintedDigits * law.io_scale);
}

// The in-system law's goals on the KDE sheets, each motor left out of the law, its spreads and its
// throttle prior: DC current at the measured speed and torque <= 5 % (median over sweeps),
// bias within +-2 %, p10-p90 coverage 70-90 %, forward speed from the command <= 5 %; and the
// datasheet numbers as they are (the plain DC model) miss by more than 10 %, low.
TEST(InSystemLawTest, LeavingEachKdeMotorOutMeetsTheGoals) {
  if (!std::filesystem::is_directory(kKde)) GTEST_SKIP() << "no ../shared/data/kde_direct_mfr_sheets";
  const stand::LawReport r = stand::LeaveOneMotorOut(KdeMotors(), {false, false});
  EXPECT_LE(r.law_error, 0.05);
  EXPECT_LE(std::fabs(r.law_bias), 0.02);
  EXPECT_GE(r.coverage, 0.70);
  EXPECT_LE(r.coverage, 0.90);
  EXPECT_LE(r.rpm_error_forward, 0.05);
  EXPECT_GT(r.datasheet_error, 0.10);
  EXPECT_LT(r.datasheet_bias, -0.10);
  EXPECT_EQ(r.points, 832);
}

TEST(InSystemLawTest, AppliesToKdeAndDriveCalcDatasheetsOnly) {
  const Catalog cat = Catalog::Load(kCatalog);
  const MotorEntry& kde = cat.motor("fu_m_115");  // KDE5215XF-330, FAST-UAV's copy of KDE's datasheet
  ASSERT_TRUE(kde.datasheet_params.has_value());
  EXPECT_EQ(InSystemLawFor(kde), &KdeDatasheetLaw());
  EXPECT_NEAR(kde.params.rm_ohm, kRmsPerDcResistance * KdeDatasheetLaw().r_scale * 0.044, 1e-9);
  EXPECT_NEAR(kde.params.io_a, KdeDatasheetLaw().io_scale * kde.datasheet_params->io_a, 1e-9);
  EXPECT_FALSE(cat.motor("fu_m_23").datasheet_params.has_value());  // AXI 2814/20: no law
  const MotorEntry& db = cat.motor("dc_m_6");  // DriveCalc's database
  ASSERT_TRUE(db.datasheet_params.has_value());
  EXPECT_EQ(InSystemLawFor(db), &DriveCalcDatabaseLaw());
  EXPECT_FALSE(cat.motor("dc_m_2_fit").datasheet_params.has_value());  // fitted: already in a system
  for (const auto& m : cat.motors()) {
    if (m.tier == DataTier::kMeasured) {
      EXPECT_FALSE(m.datasheet_params.has_value()) << m.id;
    }
  }
  // Without the law the file's numbers.
  const Catalog raw = Catalog::Load(kCatalog, false);
  EXPECT_DOUBLE_EQ(raw.motor("fu_m_115").params.rm_ohm, kde.datasheet_params->rm_ohm);
}

// A value lies inside its range: the nominal point between the spread's ends, for every motor
// the law changed and for one it did not.
TEST(InSystemLawTest, SpreadEndsBracketTheNominalCurrent) {
  const Catalog cat = Catalog::Load(kCatalog);
  for (const char* id : {"fu_m_115", "dc_m_6", "fu_m_23"}) {
    const MotorEntry& m = cat.motor(id);
    const EscParams esc;
    const double q = 0.3 * m.params.kt_nm_per_a, w = 500.0;
    const double nominal = Drive(m.params, esc).Inverse(20.0, q, w).idc_a;
    const double lo = Drive(MotorSpreadParams(m, false), esc).Inverse(20.0, q, w).idc_a;
    const double hi = Drive(MotorSpreadParams(m, true), esc).Inverse(20.0, q, w).idc_a;
    EXPECT_LE(lo, nominal) << id;
    EXPECT_GE(hi, nominal) << id;
    EXPECT_LT(lo, hi) << id;
  }
}

}  // namespace
}  // namespace dynosize
