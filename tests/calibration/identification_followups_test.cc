// On the real logs of ../shared/data (skipped when absent): each case was
// reproduced on the file before the change (the numbers in the comments are the old output).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "calibration/calibrate.h"
#include "common/units.h"
#include "diagnosis/diagnose.h"
#include "identification/verdict.h"
#include "logs/log_reader.h"

namespace dynosize::calibration {
namespace {

std::string Shared() { return std::string(DYNOSIZE_SHARED_DIR) + "/data/"; }

#define REQUIRE_SHARED() \
  if (!std::filesystem::is_directory(Shared())) GTEST_SKIP() << "shared data folder " << Shared() << " not found"

// The rows of a table whose source line starts with `prefix` (one motor + propeller of a table
// that lists several).
logs::SteadyTable RowsStartingWith(const logs::SteadyTable& t, const std::string& path, const std::string& prefix) {
  std::ifstream f(path);
  std::vector<std::string> lines(1);
  for (std::string l; std::getline(f, l);) lines.push_back(l);
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (t.source_line[i] < lines.size() && lines[t.source_line[i]].rfind(prefix, 0) == 0) keep.push_back(i);
  }
  return SelectRows(t, keep);
}

identification::Verdict Judge(const logs::SteadyTable& t, const CalibrationOptions& o, CalibrationResult* r) {
  *r = Calibrate(t, o);
  const CrossValidation cv = CrossValidateForVerdict(t, o);
  return JudgeCalibration(*r, t, o, &cv);
}

// CTU-MRS T-Motor 3110 780 kV with the Multistar 1045 (no torque, no no-load rows): io_a was
// written 0 with status ok; now it comes from the no-load prior, flagged.
TEST(IdentificationFollowUps, IoFromTheNoLoadPriorWithoutTorque) {
  REQUIRE_SHARED();
  const std::string path = Shared() + "ctu_mrs_motor_tests/ctu_mrs_motor_tests.csv";
  logs::LogReadOptions ro;
  ro.format = logs::LogFormat::kMapped;
  ro.column_map = {"throttle=throttle_pct_nominal [%]", "vdc_v=voltage_V", "idc_a=current_A", "rpm=rpm"};
  const logs::SteadyTable t = RowsStartingWith(logs::ReadLog(path, ro), path, "T-Motor 3110 780KV,Multistar");
  ASSERT_GE(t.rows(), 4u);
  CalibrationOptions o;
  o.labels.kv_rpm_per_v = 780.0;
  CalibrationResult r;
  const identification::Verdict v = Judge(t, o, &r);
  EXPECT_EQ(r.io_source, "no-load prior");
  // The law's value at this log's largest current and speed (docs/noload-prior.md): about 0.8 A;
  // a 3110 states 0.5-0.7 A at 10 V. Bounds: the law's p10-p90 scatter around it.
  EXPECT_GT(r.motor.io_a, 0.3);
  EXPECT_LT(r.motor.io_a, 2.0);
  EXPECT_FALSE(r.param(Param::kIo).fitted);
  EXPECT_NE(v.summary.find("io_a from the no-load prior"), std::string::npos) << v.summary;
  // A label takes precedence and is not assumed.
  o.labels.io_a = 0.6;
  o.labels.io_v = 10.0;
  const CalibrationResult rl = Calibrate(t, o);
  EXPECT_EQ(rl.io_source, "label");
  EXPECT_NEAR(rl.motor.io_a, identification::IoFromLabel(0.6), 1e-12);
}

// Strawson RS2205 sweeps (RCbenchmark, no torque): io_a was 0.
TEST(IdentificationFollowUps, StrawsonSweepIoNeverZero) {
  REQUIRE_SHARED();
  const std::string dir = Shared() + "strawson_fpv_motor_prop/rawdata/";
  int checked = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().filename().string().rfind("a1_", 0) != 0) continue;
    const logs::SteadyTable t = logs::ReadLog(e.path().string(), {});
    CalibrationOptions o;
    o.labels.kv_rpm_per_v = 2600.0;  // EMAX RS2205S 2600kv (name_map.csv)
    const CalibrationResult r = Calibrate(t, o);
    EXPECT_GT(r.motor.io_a, 0.0) << e.path();
    EXPECT_EQ(r.io_source, "no-load prior") << e.path();
    if (++checked == 2) break;
  }
  EXPECT_EQ(checked, 2);
}

// heinzgerhard Polar_2021-11-19_163733: four optical-rpm spikes (6,700-16,000 rpm) were kept and
// the fit was ok with 44 % rms speed error in-sample. They are now listed and left out.
TEST(IdentificationFollowUps, SpuriousSpeedReadingsAreListedAndLeftOut) {
  REQUIRE_SHARED();
  const logs::SteadyTable t = logs::ReadLog(Shared() + "heinzgerhard_rcb_large_motor/Polar_2021-11-19_163733.csv", {});
  CalibrationOptions o;
  CalibrationResult r;
  const identification::Verdict v = Judge(t, o, &r);
  std::vector<std::size_t> lines;
  for (const auto& d : r.dropped_rows) {
    if (d.reason.rfind("spurious speed reading", 0) == 0) lines.push_back(d.source_line);
  }
  EXPECT_EQ(lines, (std::vector<std::size_t>{53, 54, 56, 58}));
  for (const auto& c : r.fit) {
    // In-sample rms speed error below the held-out limit once the spikes are out (was 44 %).
    if (c.column == logs::Column::kOmegaRadS) {
      EXPECT_LT(c.rmse_percent, identification::kMaxHeldOutSpeedPercent);
    }
  }
  bool speed_check = false;
  for (const auto& c : v.checks) speed_check = speed_check || c.name == "held_out_speed_error";
  EXPECT_TRUE(speed_check);
}

// tytodb AG5008: calibrate was ok (Rm 0.136 ohm), diagnose put Rm on its bound and refused.
TEST(IdentificationFollowUps, CalibrateAndDiagnoseAgreeOnAg5008) {
  REQUIRE_SHARED();
  const logs::SteadyTable t = logs::ReadLog(
      Shared() + "tytodb_tmotor16x54_9motors/T-motor_16x54_static_T-Motor Antigravity 5008-170.csv", {});
  CalibrationOptions o;
  o.labels.kv_rpm_per_v = 170.0;
  CalibrationResult r;
  const identification::Verdict v = Judge(t, o, &r);
  diagnosis::DiagnoseOptions d;
  d.kv_label_rpm_per_v = 170.0;
  const diagnosis::DiagnoseResult dr = diagnosis::Diagnose(t, d);
  EXPECT_EQ(dr.verdict.status, v.status) << v.summary << "\n" << dr.verdict.summary;
  EXPECT_EQ(v.status, identification::Status::kOk) << v.summary;
}

// tytodb MN4014 (T-motor 4014 330 kV): the flat top is the ESC's end point; the advice asked for
// more throttle levels above 80 % and did not name --io-label.
TEST(IdentificationFollowUps, RefusalAdviceNamesTheFlagAndItsValue) {
  REQUIRE_SHARED();
  const std::string path = Shared() + "tytodb_tmotor16x54_9motors/T-motor_16x54_static_T-motor 4014 330 kv.csv";
  CalibrationOptions o;
  o.labels.kv_rpm_per_v = 330.0;
  CalibrationResult r;
  const identification::Verdict v = Judge(logs::ReadLog(path, {}), o, &r);
  ASSERT_NE(v.status, identification::Status::kOk);
  EXPECT_NE(v.advice.find("--esc-max-us 1920"), std::string::npos) << v.advice;
  EXPECT_NE(v.advice.find("--io-label"), std::string::npos) << v.advice;
  // With the end point the advice names, the flat top is gone; the next refusal (Io's standard
  // error 53 % > 50 %) names --io-label.
  logs::LogReadOptions ro;
  ro.esc_max_us = 1920.0;
  CalibrationResult r2;
  const identification::Verdict v2 = Judge(logs::ReadLog(path, ro), o, &r2);
  EXPECT_FALSE(r2.param(Param::kSatSlope).at_bound);
  if (v2.status != identification::Status::kOk) {
    EXPECT_NE(v2.advice.find("--io-label"), std::string::npos) << v2.summary << "\n" << v2.advice;
  }
}

}  // namespace
}  // namespace dynosize::calibration
