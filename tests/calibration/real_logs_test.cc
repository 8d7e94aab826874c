// Calibration of the real public logs in ../shared/data (skipped when absent). What is checked
// is what the data support (docs/validation.md has the numbers): the DriveCalc refit is physical
// for every motor and beats the plain U = n/Kv + R*I fit in leave-one-out prediction; logs whose
// throttle maps linearly to voltage give datasheet-like Kv; on the others a parameter pushed to
// its physical bound is never silent: the result carries a warning naming it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "calibration/calibrate.h"
#include "calibration/drivecalc_refit.h"
#include "common/error.h"
#include "common/units.h"
#include "logs/log_reader.h"
#include "model/physics.h"

namespace dynosize::calibration {
namespace {

std::string Shared() { return std::string(DYNOSIZE_SHARED_DIR) + "/data/"; }

#define REQUIRE_SHARED() \
  if (!std::filesystem::is_directory(Shared())) GTEST_SKIP() << "shared data folder " << Shared() << " not found"

double MedianAbs(std::vector<double> v) {
  for (double& x : v) x = std::fabs(x);
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() / 2];
}

double KvOf(const CalibrationResult& r) { return kVllRmsPerVdc / (r.motor.ke_v_s_per_rad * kRadPerSecPerRpm); }

// Every parameter at a bound is named in a warning.
void ExpectBoundsWarned(const CalibrationResult& r, const std::string& what) {
  for (int k = 0; k < kBaseParamCount; ++k) {
    if (!r.params[k].at_bound) continue;
    const std::string name = ParamName(static_cast<Param>(k));
    const bool warned = std::any_of(r.warnings.begin(), r.warnings.end(),
                                    [&](const std::string& w) { return w.rfind(name + " is at its bound", 0) == 0; });
    EXPECT_TRUE(warned) << what << ": " << name;
  }
}

TEST(CalibrateRealLogs, DriveCalcRefitPhysicalAndBeatsBaseline) {
  REQUIRE_SHARED();
  logs::LogReadOptions o;
  o.format = logs::LogFormat::kDriveCalc;
  o.drivecalc_keep_no_load_without_speed = true;
  const auto t = logs::ReadLog(Shared() + "drivecalc/MData.csv", o);
  const DriveCalcRefit all = RefitDriveCalc(t);
  // shared/data/drivecalc/README.md: 1,290 motors with a no-load point and >= 3 loaded points.
  EXPECT_EQ(all.fits.size(), 1290u);
  EXPECT_TRUE(all.failures.empty());
  for (const auto& f : all.fits) {
    EXPECT_GT(f.result.motor.ke_v_s_per_rad, 1e-6) << f.motor_id;
    EXPECT_GT(f.result.motor.rm_ohm, 0.0) << f.motor_id;
    EXPECT_GE(f.result.motor.io_a, 0.0) << f.motor_id;
  }
  const DriveCalcLooErrors e = DriveCalcLeaveOneOut(t, all);
  const double model_i = MedianAbs(e.model_idc_loaded), base_i = MedianAbs(e.baseline_idc_loaded);
  const double model_w = MedianAbs(e.model_omega), base_w = MedianAbs(e.baseline_omega);
  std::cout << "[real] DriveCalc LOO median |err|: current " << model_i << " % (baseline " << base_i << " %), rpm "
            << model_w << " % (baseline " << base_w << " %)\n";
  EXPECT_LT(model_i, base_i);
  EXPECT_LT(model_i, 3.0);   // aim
  EXPECT_LT(model_w, 1.5);   // aim
}

TEST(CalibrateRealLogs, TMotorAt3520MatchesDatasheetKv) {
  REQUIRE_SHARED();
  logs::LogReadOptions o;
  o.column_map = {"throttle=throttle", "vdc_v=voltage_V", "idc_a=current_A", "rpm=rpm", "torque_nm=torque_Nm"};
  const auto t = logs::ReadLog(Shared() + "sjkim_mfr_motor_tables/TMotor_AT3520_550kv.csv", o);
  const CalibrationResult r = Calibrate(t);
  EXPECT_TRUE(r.converged);
  // Datasheet 550 rpm/V. The base fit now includes the throttle offset of docs/model.md section 9
  // when the F test keeps it (here it does), and the offset trades with KE and the knee: the
  // fitted Kv lands about 9 % below the label, well inside the 25 % of docs/model.md section 10.
  constexpr double kKvRelTol = 0.10;
  EXPECT_NEAR(KvOf(r), 550.0, kKvRelTol * 550.0);
  EXPECT_GT(r.motor.io_a, 0.0);
  EXPECT_GT(r.r_total_ohm, 0.0);
  EXPECT_TRUE(r.param(Param::kTrSat).identifiable);  // two props, 11 throttle levels
  for (int k = 0; k < kBaseParamCount; ++k) EXPECT_FALSE(r.params[k].at_bound) << ParamName(static_cast<Param>(k));
}

// The baseline to beat: on the same held-out throttle levels the plain DC model (label Kv, R and
// Io fitted on the same rows; identification/dc_fit.h) misses the AT4125 table, whose ESC output
// is not proportional to its command, several times more than dynosize (docs/validation.md:
// 4.3 % / 3.4 % against 1.5 % / 1.4 %).
TEST(CalibrateRealLogs, HeldOutBeatsThePlainDcModelOnAt4125) {
  REQUIRE_SHARED();
  logs::LogReadOptions o;
  o.column_map = {"throttle=throttle", "vdc_v=voltage_V", "idc_a=current_A", "rpm=rpm", "torque_nm=torque_Nm"};
  const auto t = logs::ReadLog(Shared() + "sjkim_mfr_motor_tables/TMotor_AT4125_540kv.csv", o);
  CalibrationOptions co;
  co.labels.kv_rpm_per_v = 540.0;
  const CrossValidation cv = CrossValidateForVerdict(t, co);
  ASSERT_EQ(cv.dc_idc_error_percent.size(), cv.idc_error_percent.size());
  EXPECT_LT(MedianAbs(cv.idc_error_percent), 0.5 * MedianAbs(cv.dc_idc_error_percent));
  EXPECT_LT(MedianAbs(cv.omega_error_percent), 0.5 * MedianAbs(cv.dc_omega_error_percent));
}

// xNova-TM-MR (RCbenchmark thrust map, one propeller): refused, and the refusal says what the
// fit's current residual follows - speed or command, which one propeller cannot tell apart - and
// the measurement that would (issue: a refusal that points only at a parameter on its bound).
TEST(CalibrateRealLogs, ARefusalNamesTheTrendTheFitLeaves) {
  REQUIRE_SHARED();
  const auto t = logs::ReadLog(Shared() + "aerostack2_xnova_thrustmap/xNova-TM-MR.csv");
  const CalibrationOptions co;
  const CalibrationResult r = Calibrate(t, co);
  const CrossValidation cv = CrossValidateForVerdict(t, co);
  const identification::Verdict v = JudgeCalibration(r, t, co, &cv);
  ASSERT_NE(v.status, identification::Status::kOk) << v.summary;
  EXPECT_NE(v.advice.find("residual is not noise"), std::string::npos) << v.advice;
  EXPECT_NE(v.advice.find("second propeller"), std::string::npos) << v.advice;
}

TEST(CalibrateRealLogs, EveryLogWithThrottleCalibratesAndFlagsBounds) {
  REQUIRE_SHARED();
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(Shared() + "strawson_fpv_motor_prop/rawdata")) {
    files.push_back(e.path().string());
  }
  for (const auto& e : std::filesystem::directory_iterator(Shared() + "alspitz_esc_test/data/rcbench")) {
    files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  int calibrated = 0;
  for (const auto& f : files) {
    const auto t = logs::ReadLog(f);
    CalibrationResult r;
    try {
      r = Calibrate(t);
    } catch (const Error& e) {
      ADD_FAILURE() << f << ": " << e.what();
      continue;
    }
    ++calibrated;
    ExpectBoundsWarned(r, f);
    if (!t.Has(logs::Column::kThrottle)) {
      // alspitz logs without throttle (ESC driven externally): the full-throttle assumption
      // fails and the result must say so.
      const bool warned = std::any_of(r.warnings.begin(), r.warnings.end(), [](const std::string& w) {
        return w.find("do not look like full-throttle points") != std::string::npos;
      });
      EXPECT_TRUE(warned) << f;
    }
  }
  EXPECT_EQ(calibrated, static_cast<int>(files.size()));
}

// The sjkim AT2814 table: before the physical constraints, the fit gave c1 = 0.30, c0 = 0.23 (eta_esc 1.76 at
// 15 V) and Kv 2460 against the label 1200. With physics as constraints, the label prior and
// the throttle offset, the entry is physical, near the label and passes every check.
TEST(CalibrateRealLogs, At2814WithLabelIsPhysicalAndOk) {
  REQUIRE_SHARED();
  logs::LogReadOptions ro;
  ro.format = logs::LogFormat::kMapped;
  ro.column_map = {"throttle=Throttle", "vdc_v=Voltage", "idc_a=Current", "rpm=Rpm", "torque_nm=Torque [N*m]"};
  const auto t = logs::ReadLog(Shared() + "sjkim_mfr_motor_tables/TMotor_AT2814_1200kv.csv", ro);
  CalibrationOptions o;
  o.labels.kv_rpm_per_v = 1200.0;
  const CalibrationResult r = Calibrate(t, o);
  EXPECT_GE(EscEnergyMargin(r.esc), 0.0);
  EXPECT_EQ(MotorEnergyViolation(r.motor), "");
  EXPECT_NEAR(KvOf(r), 1200.0, 0.25 * 1200.0);
  const CrossValidation cv = CrossValidateForVerdict(t, o);
  EXPECT_TRUE(cv.leave_one_out);  // 11 throttle levels
  const identification::Verdict v = JudgeCalibration(r, t, o, &cv);
  EXPECT_EQ(v.status, identification::Status::kOk) << v.summary;
  // Held-out current within 3 % (docs/validation.md: about 1 %).
  EXPECT_LT(MedianAbs(cv.idc_error_percent), 3.0);
}

// Strawson sweeps (no torque): whatever the verdict, no fitted pair creates energy, and an "ok"
// verdict always has Kv within 25 % of the label (the Lumenier RX2206-13 2000 kV logs, all 16
// "ok" in docs/validation.md, and the EMAX RS2205S logs whose fits used to put KE on its bound).
TEST(CalibrateRealLogs, StrawsonFitsArePhysicalAndOkMeansNearLabel) {
  REQUIRE_SHARED();
  int ok = 0, n = 0;
  for (const char m : {'a', 'g'}) {
    const double label = m == 'a' ? 2600.0 : 2000.0;
    for (int prop = 1; prop <= 8; ++prop) {
      for (const char* v : {"7", "11"}) {
        const std::string f = Shared() + "strawson_fpv_motor_prop/rawdata/" + m + std::to_string(prop) + "_" + v + ".csv";
        if (!std::filesystem::exists(f)) continue;
        const auto t = logs::ReadLog(f);
        CalibrationOptions o;
        o.labels.kv_rpm_per_v = label;
        const CalibrationResult r = Calibrate(t, o);
        ++n;
        EXPECT_GE(EscEnergyMargin(r.esc), 0.0) << f;
        EXPECT_EQ(MotorEnergyViolation(r.motor), "") << f;
        const identification::Verdict vd = JudgeCalibration(r, t, o, nullptr);
        if (vd.status == identification::Status::kOk) {
          ++ok;
          EXPECT_NEAR(KvOf(r), label, 0.25 * label) << f;
        }
        if (m == 'g') {
          EXPECT_EQ(vd.status, identification::Status::kOk) << f << ": " << vd.summary;
        }
      }
    }
  }
  EXPECT_EQ(n, 32);
  EXPECT_GE(ok, 16);
}

}  // namespace
}  // namespace dynosize::calibration
