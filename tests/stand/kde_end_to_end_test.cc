// KDE Direct's stand sheets end to end (stand/kde_end_to_end.h, issue 51): every sheet row
// predicted forward from its command and supply voltage through the catalog's motor, KDE
// propeller and KDE ESC entries, the in-system law fitted without the motor. Runs on the real
// files (skipped without ../shared/data); docs/validation.md "KDE Direct sheets end to end".
#include <cmath>
#include <filesystem>
#include <iostream>

#include <gtest/gtest.h>

#include "catalog/catalog.h"
#include "catalog/in_system.h"
#include "importers/kde_sheets.h"
#include "stand/kde_end_to_end.h"

namespace dynosize {
namespace {

const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";
const std::string kKde = DYNOSIZE_SHARED_DIR "/data/kde_direct_mfr_sheets";

// Goals of issue 51 for the dynosize column (median over sweeps of the per-sweep median
// |pred/meas - 1|): thrust rests on the speed squared through the propeller entry built from the
// same sheets, so its goal is about twice the speed's.
constexpr double kThrustGoal = 0.08;
constexpr double kCurrentGoal = 0.10;
constexpr double kSpeedGoal = 0.05;
// Measured with every motor held out (docs/validation.md "KDE Direct sheets end to end"):
// thrust 8.5 % and current 15.0 % miss their goals. Forward on a propeller the current goes
// about as the speed cubed, so the 4.3 % speed error (the per-motor scatter of R and Io about
// the law and of the throttle offset about its prior) is about 13 % of current. Until a model
// change closes the gap these bounds keep the result from getting worse: the measured values
// plus half a point (the LM fits' and the medians' sensitivity to a changed solver path).
constexpr double kThrustNow = 0.085 + 0.005;
constexpr double kCurrentNow = 0.150 + 0.005;
// The propeller entries state their density to 3 decimals ("1.117 kg/m^3").
constexpr double kDensityPrinted = 0.0005;

TEST(KdePropIdTest, MapsSheetLabelsToCatalogIds) {
  EXPECT_EQ(stand::KdePropId("30.5x9.7 DUAL"), "kde_p_30.5x9.7x2");
  EXPECT_EQ(stand::KdePropId("15.5x5.3 TRIPLE"), "kde_p_15.5x5.3x3");
  EXPECT_EQ(stand::KdePropId("35.5x12.1 DUAL"), "kde_p_35.5x12.1x2");
  EXPECT_EQ(stand::KdePropId("30.5x9.7"), "");
  EXPECT_EQ(stand::KdePropId("30.5x9.7 QUAD"), "");
  EXPECT_EQ(stand::KdePropId("x9.7 DUAL"), "");
  EXPECT_EQ(stand::KdePropId("3O.5x9.7 DUAL"), "");
}

TEST(KdeEndToEndTest, SheetsForwardThroughCatalogEntriesAgainstTheGoals) {
  if (!std::filesystem::is_directory(kKde)) GTEST_SKIP() << "no ../shared/data/kde_direct_mfr_sheets: nothing to check";
  const auto sheets = ReadKdeSheets(kKde);
  EXPECT_NEAR(stand::KdeSiteDensityKgM3(sheets), stand::kKdeSiteRhoKgM3, kDensityPrinted);
  const Catalog raw = Catalog::Load(kCatalog, /*in_system_law=*/false);
  const stand::KdeEndToEndReport rep = stand::KdeSheetsEndToEnd(sheets, raw);
  std::cout << rep.Table() << rep.Biases();
  for (const auto& s : rep.skipped) std::cout << "skipped: " << s << "\n";
  std::cout << "sweeps " << rep.sweeps << ", skipped for want of a propeller entry " << rep.sweeps_without_prop
            << ", points " << rep.points << ", rows not converged " << rep.unconverged << "\n";

  int left_out = 0;
  for (const auto& m : rep.motors) left_out += m.law_left_out ? 1 : 0;
  EXPECT_EQ(left_out, 9);  // the 9 sheets with torque, each out of its own law
  EXPECT_EQ(rep.unconverged, 0);
  EXPECT_GT(rep.sweeps, 100);
  EXPECT_LE(rep.dynosize.rpm, kSpeedGoal);
  EXPECT_LE(rep.dynosize.thrust, kThrustNow);
  EXPECT_LE(rep.dynosize.idc, kCurrentNow);
  if (rep.dynosize.thrust > kThrustGoal || rep.dynosize.idc > kCurrentGoal) {
    std::cout << "issue 51 goals not met yet: thrust " << rep.dynosize.thrust << " (goal " << kThrustGoal
              << "), current " << rep.dynosize.idc << " (goal " << kCurrentGoal << ")\n";
  }
  // The law and the ESC's offset prior earn their place: better than both datasheet columns on
  // every quantity.
  for (const auto* other : {&rep.plain_dc, &rep.rms_datasheet}) {
    EXPECT_LT(rep.dynosize.thrust, other->thrust);
    EXPECT_LT(rep.dynosize.idc, other->idc);
    EXPECT_LT(rep.dynosize.rpm, other->rpm);
  }
}

}  // namespace
}  // namespace dynosize
