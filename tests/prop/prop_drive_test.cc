#include "prop/prop_drive.h"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "catalog/catalog.h"
#include "common/units.h"

namespace dynosize {
namespace {

const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";

// The fixed point is solved to 1e-10 relative in speed; torque balance then holds to ~1e-8
// (the torque law's slope times the speed error, plus the table's kinks).
constexpr double kBalanceRel = 1e-6;

TEST(PropDriveTest, PaperMotorOnAUiucPropBalancesTorque) {
  if (!std::filesystem::exists(kCatalog + "/uiuc_propdb.json")) GTEST_SKIP() << "no catalog";
  const Catalog c = Catalog::Load(kCatalog);
  const Drive drive(c.motor("emax_935kv_paper").params, c.esc("multistar_30a_paper").params);
  const PropModel prop(c.prop("uiuc_v1_apcsf_10.0x4.7_2"));
  for (double airspeed : {0.0, 6.0}) {
    const PropDrivePoint p = SolveDriveWithProp(drive, prop, 11.1, 0.8, 1.2, airspeed);
    ASSERT_TRUE(p.converged) << p.message;
    EXPECT_LT(p.iterations, 10);
    EXPECT_NEAR(p.drive.torque_nm, p.prop.torque_nm, kBalanceRel * p.prop.torque_nm);
    // Independent check: the drive's torque at the same fixed speed.
    const OperatingPoint at = drive.AtSpeed(11.1, 0.8, p.drive.omega_rad_s);
    EXPECT_NEAR(at.torque_nm, p.prop.torque_nm, kBalanceRel * p.prop.torque_nm);
    EXPECT_GT(p.prop.thrust_n, 0.0);
    EXPECT_TRUE(p.prop.InData()) << p.prop.Message();
  }
}

TEST(PropDriveTest, DriveCalcPowerLawPropConvergesAndFlagsForwardFlight) {
  if (!std::filesystem::exists(kCatalog + "/drivecalc.json")) GTEST_SKIP() << "no catalog";
  const Catalog c = Catalog::Load(kCatalog);
  const Drive drive(c.motor("emax_1900kv_paper").params, c.esc("multistar_30a_paper").params);
  const PropModel prop(c.prop("dc_p_1"));  // APC E 4.1x4.1 power laws
  const PropDrivePoint st = SolveDriveWithProp(drive, prop, 7.2, 0.7, 1.225, 0.0);
  ASSERT_TRUE(st.converged) << st.message;
  EXPECT_NEAR(st.drive.torque_nm, st.prop.torque_nm, kBalanceRel * st.prop.torque_nm);
  const PropDrivePoint fw = SolveDriveWithProp(drive, prop, 7.2, 0.7, 1.225, 10.0);
  EXPECT_TRUE(fw.prop.no_forward_flight_data);
  EXPECT_FALSE(fw.message.empty());
}

// KDE's measured tables are binned medians with kinks: the local quadratic through a kink can
// send the fixed point to a stall. The bracketed fallback then finds the torque balance (the
// KDE4012XF-400 entry through the catalog's law on the 18.5x6.3 three-blade table, KDE's ESC,
// the sheet's 1.117 kg/m^3: commands at which the fixed point alone stalled).
TEST(PropDriveTest, KinkedMeasuredTableIsBracketedWhenTheFixedPointStalls) {
  if (!std::filesystem::exists(kCatalog + "/kde_direct_sheets.json")) GTEST_SKIP() << "no catalog";
  const Catalog c = Catalog::Load(kCatalog);
  const Drive drive(c.motor("hl_m_kde4012xf_400").params, c.esc("kde_e_uas125uvc").params);
  const PropModel prop(c.prop("kde_p_18.5x6.3x3"));
  int bracketed = 0;
  for (double tr : {0.5, 0.625, 0.75, 0.875, 1.0}) {
    const PropDrivePoint p = SolveDriveWithProp(drive, prop, 22.0, tr, 1.117);
    ASSERT_TRUE(p.converged) << "throttle " << tr << ": " << p.message;
    bracketed += p.bracketed ? 1 : 0;
    // Bisection to 1e-10 in speed; the table's slope turns that into ~1e-9 in torque.
    EXPECT_NEAR(p.drive.torque_nm, p.prop.torque_nm, kBalanceRel * p.prop.torque_nm) << "throttle " << tr;
    EXPECT_GT(p.drive.omega_rad_s, 0.0);
  }
  EXPECT_GT(bracketed, 0) << "no command needed the fallback: pick another case";
}

}  // namespace
}  // namespace dynosize
