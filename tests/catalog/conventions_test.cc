// The resistance convention of catalog/conventions.h: a motor stated in DC-model terms (Kv,
// R_dc, Io_dc: VDC = R_dc*IDC + n/Kv, Q = (IDC - Io_dc)/Kv_SI) and converted to the rms
// circuit (rm = 0.7492*R_dc, io = Io_dc/1.1095) is the same machine at full throttle.
#include "catalog/conventions.h"

#include <gtest/gtest.h>

#include <cmath>

#include "catalog/catalog.h"
#include "model/drive.h"

namespace dynosize {
namespace {

// Drive solves eq (48) in closed form; the DC model here is solved by hand: a few operations,
// so agreement to 1e-9 relative is far above rounding (1e-15) and far below any physical effect.
constexpr double kSameMachineRel = 1e-9;

TEST(ResistanceConvention, FactorIsKTimesIdealEsc) {
  // K = 3/(sqrt(2)*pi) (eq 46), g = (3/pi)*sqrt(27/20) (eq 56).
  const double k = 3.0 / (std::sqrt(2.0) * M_PI), g = 3.0 / M_PI * std::sqrt(27.0 / 20.0);
  EXPECT_NEAR(kRmsPerDcResistance, k * g, 1e-15);
  EXPECT_NEAR(kRmsPerDcResistance, 0.7491946, 1e-7);
  // The copper loss is kept: sqrt(27/10)*Rm*Irms^2 = R_dc*IDC^2 with IDC = g*Irms.
  EXPECT_NEAR(std::sqrt(2.7) * kRmsPerDcResistance, g * g, 1e-12);
}

TEST(ResistanceConvention, RmsModelEqualsDcModelAtFullThrottle) {
  // A 920 Kv outrunner stated as R_dc = 0.12 ohm, Io_dc = 0.6 A (datasheet style).
  const double kv = 920.0, r_dc = 0.12, io_dc = 0.6, vdc = 14.8;
  MotorParams m;
  m.ke_v_s_per_rad = KeFromKvBldc(kv);
  m.kt_nm_per_a = kPacPerVllIrms * m.ke_v_s_per_rad;  // section 5
  m.rm_ohm = RmsCircuitResistanceFromDc(r_dc);
  m.io_a = RmsNoLoadCurrentFromDc(io_dc);
  EscParams ideal;  // eq (56): c1 = 1.1095, c0 = 0, no resistance, no saturation
  const Drive drive(m, ideal);
  const double kv_si = kv * M_PI / 30.0;  // rad/s per volt
  for (double q : {0.0, 0.05, 0.2, 0.5}) {
    // DC model: IDC = Io_dc + Q*Kv_SI; n = Kv*(VDC - R_dc*IDC).
    const double idc = io_dc + q * kv_si;
    const double omega = kv_si * (vdc - r_dc * idc);
    const OperatingPoint p = drive.AtTorque(vdc, 1.0, q);
    EXPECT_NEAR(p.idc_a, idc, kSameMachineRel * idc) << "Q = " << q;
    EXPECT_NEAR(p.omega_rad_s, omega, kSameMachineRel * omega) << "Q = " << q;
    // The same DC power goes in: the conversion changes no energy.
    EXPECT_NEAR(p.pdc_w, vdc * idc, kSameMachineRel * vdc * idc);
  }
  // Without the conversion (rm = R_dc) the rms model is slower at the same torque: the error
  // the issue measured on the T-Motor tables.
  MotorParams unconverted = m;
  unconverted.rm_ohm = r_dc;
  const OperatingPoint wrong = Drive(unconverted, ideal).AtTorque(vdc, 1.0, 0.5);
  const OperatingPoint right = drive.AtTorque(vdc, 1.0, 0.5);
  EXPECT_LT(wrong.omega_rad_s, right.omega_rad_s * 0.99);
}

TEST(MotorPowerLaw, EstimateFollowsTheDocumentedLaw) {
  // 10.8116 * 100^0.8777 = 10.8116 * 56.88 = 615 W for a 100 g outrunner.
  EXPECT_NEAR(EstimatedMotorPowerW(0.1), 10.8116 * std::pow(100.0, 0.8777), 1e-9);
  EXPECT_NEAR(EstimatedMotorPowerW(0.1), 615.0, 1.0);
  // Specific power falls with size (exponent < 1).
  EXPECT_GT(EstimatedMotorPowerW(0.02) / 0.02, EstimatedMotorPowerW(0.5) / 0.5);
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// The current law is the FAST-UAV catalogue's: ln(I_max) on ln(m) and ln(Kv), least squares
// over the 204 fu_m_ motors with mass, Kv and I_max (3x3 normal equations of well-scaled logs).
TEST(MotorCurrentLaw, IsTheFastUavFit) {
  const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  double a[3][4] = {};
  int n = 0;
  for (const MotorEntry& m : cat.motors()) {
    if (m.id.rfind("fu_m_", 0) != 0 || !m.mass_kg || !m.kv_rpm_per_v || !std::isfinite(m.params.max_current_a)) continue;
    const double row[3] = {1.0, std::log(*m.mass_kg), std::log(*m.kv_rpm_per_v)};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) a[i][j] += row[i] * row[j];
      a[i][3] += row[i] * std::log(m.params.max_current_a);
    }
    ++n;
  }
  ASSERT_EQ(n, DefaultMotorCurrentLaw().sample_size);
  for (int i = 0; i < 3; ++i) {  // Gauss-Jordan with partial pivoting
    int piv = i;
    for (int r = i + 1; r < 3; ++r) {
      if (std::fabs(a[r][i]) > std::fabs(a[piv][i])) piv = r;
    }
    for (int k = 0; k < 4; ++k) std::swap(a[i][k], a[piv][k]);
    for (int r = 0; r < 3; ++r) {
      if (r == i) continue;
      const double f = a[r][i] / a[i][i];
      for (int k = 0; k < 4; ++k) a[r][k] -= f * a[i][k];
    }
  }
  // The constants are printed to 4 significant digits.
  constexpr double kRounding = 5e-4;
  EXPECT_NEAR(EstimatedMotorCurrentA(1.0, 1.0), std::exp(a[0][3] / a[0][0]), kRounding);
  EXPECT_NEAR(DefaultMotorCurrentLaw().mass_exponent, a[1][3] / a[1][1], kRounding);
  EXPECT_NEAR(DefaultMotorCurrentLaw().kv_exponent, a[2][3] / a[2][2], kRounding);
}

}  // namespace
}  // namespace dynosize
