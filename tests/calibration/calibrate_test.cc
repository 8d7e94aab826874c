// Calibration against synthetic logs made by the model (known parameters, seeded noise).
//
// Tolerances: with relative noise s on every column and N = 60 rows, a parameter determined by
// the whole data set carries an error of roughly s*k/sqrt(N) where k (1..30) is its
// sensitivity factor (small for KE, large for Io and RESC which are small differences of large
// quantities). The checks use the fit's own standard error: |fitted - true| < 5 sigma (+ a
// floor of 0.5 % of the value for the noise-free bias of the input noise on VDC), so they
// neither pass by luck nor fail by chance; the fit's stated errors are themselves checked to be
// small where the data determine the parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "calibration/calibrate.h"
#include "calibration/synthetic_log.h"
#include "common/error.h"

namespace dynosize::calibration {
namespace {

using logs::Column;
using testing_util::DefaultSpec;
using testing_util::MakeSyntheticLog;
using testing_util::SyntheticSpec;

double TrueValue(const SyntheticSpec& s, Param p) {
  switch (p) {
    case Param::kKe: return s.motor.ke_v_s_per_rad;
    case Param::kKt: return s.motor.kt_nm_per_a;
    case Param::kRm: return s.motor.rm_ohm;
    case Param::kIo: return s.motor.io_a;
    case Param::kResc: return s.esc.resc_ohm;
    case Param::kC1: return s.esc.c1;
    case Param::kC0: return s.esc.c0;
    case Param::kTrSat: return s.esc.tr_sat;
    case Param::kSatSlope: return s.esc.sat_slope;
    case Param::kDeadband: return s.esc.deadband;
    default: break;  // diagnose's extensions: calibrate does not fit them
  }
  return 0.0;
}

// |fit - true| within 5 standard errors plus `floor_rel` of the true value (plus an absolute
// floor for parameters whose true value is near 0).
void ExpectRecovered(const CalibrationResult& r, const SyntheticSpec& s, Param p, double floor_rel,
                     double floor_abs = 0.0) {
  const auto& e = r.param(p);
  const double truth = TrueValue(s, p);
  const double se = std::isfinite(e.standard_error) ? e.standard_error : 0.0;
  EXPECT_NEAR(e.value, truth, 5.0 * se + floor_rel * std::fabs(truth) + floor_abs)
      << ParamName(p) << " se " << e.standard_error;
}

TEST(Calibrate, RecoversAllParametersFromAcColumns) {
  SyntheticSpec s = DefaultSpec();
  s.noise_rel = 0.005;
  const auto t = MakeSyntheticLog(s);
  const CalibrationResult r = Calibrate(t);
  std::cout << r.FullReport();
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.mode, "ac");
  for (int k = 0; k < kBaseParamCount; ++k) {
    const Param p = static_cast<Param>(k);
    if (p == Param::kDeadband) continue;  // no offset in this log: tested, not kept
    EXPECT_TRUE(r.param(p).identifiable) << ParamName(p) << ": " << r.param(p).note;
  }
  EXPECT_FALSE(r.param(Param::kDeadband).fitted) << r.param(Param::kDeadband).note;
  ExpectRecovered(r, s, Param::kKe, 0.005);
  ExpectRecovered(r, s, Param::kKt, 0.005);
  ExpectRecovered(r, s, Param::kRm, 0.02);
  ExpectRecovered(r, s, Param::kIo, 0.02);
  ExpectRecovered(r, s, Param::kResc, 0.02, 0.002);
  ExpectRecovered(r, s, Param::kC1, 0.01);
  ExpectRecovered(r, s, Param::kC0, 0.0, 0.01);
  EXPECT_NEAR(r.esc.tr_sat, 0.9, 0.021);  // one grid step
  ExpectRecovered(r, s, Param::kSatSlope, 0.05);
  for (const auto& f : r.fit) EXPECT_LT(f.rmse_percent, 2.0) << logs::ColumnName(f.column);
}

TEST(Calibrate, RobustToOutliers) {
  SyntheticSpec s = DefaultSpec();
  s.noise_rel = 0.003;
  s.outliers = 3;
  const auto t = MakeSyntheticLog(s);
  const CalibrationResult r = Calibrate(t);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.points_dropped, 3u) << r.FullReport();
  ExpectRecovered(r, s, Param::kKe, 0.005);
  ExpectRecovered(r, s, Param::kC1, 0.01);
  ExpectRecovered(r, s, Param::kC0, 0.0, 0.01);
}

TEST(Calibrate, DcOnlyWithTorque_SplitUnidentifiable) {
  SyntheticSpec s = DefaultSpec();
  s.ac = false;
  s.motor.kt_nm_per_a = kPacPerVllIrms * s.motor.ke_v_s_per_rad;  // the tie holds exactly
  s.noise_rel = 0.005;
  const auto t = MakeSyntheticLog(s);
  const CalibrationResult r = Calibrate(t);
  std::cout << r.FullReport();
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.mode, "dc");
  EXPECT_FALSE(r.param(Param::kRm).identifiable);
  EXPECT_FALSE(r.param(Param::kResc).identifiable);
  EXPECT_FALSE(r.param(Param::kKt).identifiable);  // tied to KE
  EXPECT_TRUE(r.param(Param::kKe).identifiable);
  EXPECT_TRUE(r.param(Param::kIo).identifiable);
  ExpectRecovered(r, s, Param::kKe, 0.005);
  ExpectRecovered(r, s, Param::kIo, 0.03);
  EXPECT_NEAR(r.r_total_ohm, s.motor.rm_ohm + s.esc.resc_ohm,
              5.0 * r.r_total_standard_error + 0.02 * (s.motor.rm_ohm + s.esc.resc_ohm));
  ExpectRecovered(r, s, Param::kC1, 0.01);
  ExpectRecovered(r, s, Param::kC0, 0.0, 0.01);
}

TEST(Calibrate, DcOnlyWithoutTorque_EscRatioHeld) {
  SyntheticSpec s = DefaultSpec();
  s.ac = false;
  s.torque = false;
  s.esc.c1 = kIdealIdcPerIrmsPerThrottle;  // the assumption the fit has to make
  s.esc.c0 = 0.0;
  s.noise_rel = 0.005;
  const auto t = MakeSyntheticLog(s);
  const CalibrationResult r = Calibrate(t);
  std::cout << r.FullReport();
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_FALSE(r.param(Param::kC1).fitted);
  EXPECT_FALSE(r.param(Param::kIo).fitted);
  EXPECT_FALSE(r.param(Param::kRm).identifiable);
  ExpectRecovered(r, s, Param::kKe, 0.01);
  EXPECT_NEAR(r.r_total_ohm, s.motor.rm_ohm + s.esc.resc_ohm,
              5.0 * r.r_total_standard_error + 0.03 * (s.motor.rm_ohm + s.esc.resc_ohm));
}

TEST(Calibrate, OneThrottleLevel_SaturationNotIdentifiable) {
  SyntheticSpec s = DefaultSpec();
  s.throttles = {0.7};
  s.vdc_v = {10.0, 11.1, 12.6, 14.8, 16.8};
  s.prop_c = {1.5e-7, 2.0e-7, 2.6e-7, 3.2e-7};
  const auto t = MakeSyntheticLog(s);
  const CalibrationResult r = Calibrate(t);
  EXPECT_FALSE(r.param(Param::kTrSat).identifiable);
  EXPECT_FALSE(r.param(Param::kSatSlope).identifiable);
  EXPECT_FALSE(r.param(Param::kC1).identifiable);
  EXPECT_FALSE(r.param(Param::kC0).identifiable);
  EXPECT_DOUBLE_EQ(r.esc.tr_sat, 1.0);
  bool warned = false;
  for (const auto& w : r.warnings) warned = warned || w.find("one throttle level") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(Calibrate, NoThrottleColumn_FullThrottleEquivalent) {
  SyntheticSpec s = DefaultSpec();
  s.ac = false;
  s.torque = false;
  s.throttle_column = false;
  s.throttles = {1.0};
  s.esc = EscParams{};  // ideal, unsaturated: the assumption of the no-throttle fit
  s.vdc_v = {9.0, 10.0, 11.0, 12.0};
  s.prop_c = {1.0e-7, 2.0e-7, 3.0e-7};
  const auto t = MakeSyntheticLog(s);
  const CalibrationResult r = Calibrate(t);
  std::cout << r.FullReport();
  EXPECT_EQ(r.mode, "dc_no_throttle");
  ExpectRecovered(r, s, Param::kKe, 0.01);
  EXPECT_NEAR(r.r_total_ohm, s.motor.rm_ohm, 5.0 * r.r_total_standard_error + 0.03 * s.motor.rm_ohm);
  EXPECT_FALSE(r.param(Param::kC1).identifiable);
  EXPECT_FALSE(r.param(Param::kTrSat).identifiable);
}

// DriveCalc keeps no-load points whose speed was not measured (omega = 0): their current alone
// fixes Io (eq 42 at Q = 0), and they must not disturb KE and R.
TEST(Calibrate, NoLoadRowWithoutSpeedFixesIo) {
  SyntheticSpec s = DefaultSpec();
  s.ac = false;
  s.torque = false;
  s.throttle_column = false;
  s.throttles = {1.0};
  s.esc = EscParams{};
  s.vdc_v = {9.0, 10.0, 11.0, 12.0};
  s.prop_c = {1.0e-7, 2.0e-7, 3.0e-7};
  s.noise_rel = 0.0;
  logs::SteadyTable t = MakeSyntheticLog(s);
  auto& nl_info = t.info[static_cast<int>(logs::Column::kNoLoad)];
  nl_info.present = true;
  t.Mutable(logs::Column::kNoLoad).assign(t.rows(), 0.0);
  // The appended no-load row: speed not measured, IDC = (C1*TR + C0)*Io (eq 57, ideal ESC).
  const double idc_no_load = (kIdealIdcPerIrmsPerThrottle * 1.0) * s.motor.io_a;
  for (int c = 0; c < logs::kColumnCount; ++c) {
    if (t.info[c].present) t.columns[c].push_back(0.0);
  }
  t.Mutable(logs::Column::kVdcV).back() = 11.0;
  t.Mutable(logs::Column::kIdcA).back() = idc_no_load;
  t.Mutable(logs::Column::kNoLoad).back() = 1.0;
  t.source_line.push_back(t.source_line.back() + 1);
  t.samples.push_back(1);
  const CalibrationResult r = Calibrate(t);
  EXPECT_EQ(r.points_used, t.rows());
  EXPECT_TRUE(r.param(Param::kIo).fitted);
  // Noise-free data: only the solver's tolerance separates the fit from the truth.
  EXPECT_NEAR(r.motor.io_a, s.motor.io_a, 1e-3 * s.motor.io_a);
  ExpectRecovered(r, s, Param::kKe, 1e-3);
  const CrossValidation cv = LeaveOneOut(t, {}, false);
  EXPECT_EQ(cv.idc_error_percent.size(), t.rows());           // the no-load row's current counts
  EXPECT_EQ(cv.omega_from_idc_error_percent.size(), t.rows() - 1);  // its speed does not
}

TEST(Calibrate, BadLogsGiveClearErrors) {
  SyntheticSpec s = DefaultSpec();
  auto t = MakeSyntheticLog(s);
  {
    auto u = t;
    u.info[static_cast<int>(Column::kOmegaRadS)].present = false;
    u.Mutable(Column::kOmegaRadS).clear();
    try {
      Calibrate(u);
      ADD_FAILURE() << "no error";
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find("synthetic.csv: column omega_rad_s (shaft speed) is absent"),
                std::string::npos)
          << e.what();
    }
  }
  {
    auto u = t;
    for (double& v : u.Mutable(Column::kIdcA)) v = 0.0;
    try {
      Calibrate(u);
      ADD_FAILURE() << "no error";
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find("idc_a is zero in every row"), std::string::npos) << e.what();
    }
  }
  {
    auto u = t;
    for (int c = 0; c < logs::kColumnCount; ++c) {
      if (u.info[c].present) u.columns[c].resize(1);
    }
    u.source_line.resize(1);
    u.samples.resize(1);
    try {
      Calibrate(u);
      ADD_FAILURE() << "no error";
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find("only 1 row(s) with the motor turning: calibration needs at least 2"),
                std::string::npos)
          << e.what();
    }
  }
  {
    CalibrationOptions o;
    o.knee_step = 0.0;
    EXPECT_THROW(Calibrate(t, o), UsageError);
  }
}

TEST(Calibrate, UntouchedResultSaysSo) {
  CalibrationResult r;
  EXPECT_EQ(r.BriefReport(), "Calibrate was not called.");
}

TEST(Calibrate, LeaveOneThrottleOutPredictsWithinNoise) {
  SyntheticSpec s = DefaultSpec();
  s.noise_rel = 0.003;
  const auto t = MakeSyntheticLog(s);
  const CrossValidation cv = LeaveOneOut(t, CalibrationOptions(), true);
  EXPECT_EQ(cv.failed_folds, 0u);
  std::vector<double> a;
  for (double e : cv.idc_error_percent) a.push_back(std::fabs(e));
  std::sort(a.begin(), a.end());
  ASSERT_FALSE(a.empty());
  EXPECT_LT(a[a.size() / 2], 1.5);  // a few times the 0.3 % noise
}

}  // namespace
}  // namespace dynosize::calibration
