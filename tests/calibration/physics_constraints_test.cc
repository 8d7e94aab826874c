// Physics as constraints of the calibration fit: whatever the data ask for, no fitted
// ESC creates energy and no fitted motor exceeds unit efficiency; a fit pushed onto a bound is
// reported as such and its verdict is never "ok"; label priors anchor KE.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/calibrate.h"
#include "calibration/synthetic_log.h"
#include "common/error.h"
#include "diagnosis/diagnose.h"
#include "identification/parameters.h"
#include "model/physics.h"

namespace dynosize::calibration {
namespace {

using testing_util::DefaultSpec;
using testing_util::MakeSyntheticLog;
using testing_util::SyntheticSpec;
using testing_util::ThrottleOffsetSpec;

// Data made by an ESC that creates energy (c1 + c0 = 0.53, the sjkim AT2814 fit),
// and by ideal / lossy ESCs with noise, over several seeds: the fitted ESC never has PESC < 0.
TEST(CalibratePhysics, NoFittedEscCreatesEnergy) {
  struct Case {
    double c1, c0;
    bool ac;
  };
  const Case cases[] = {{0.30, 0.23, true}, {0.30, 0.23, false}, {1.1095, 0.0, true},
                        {1.1095, 0.0, false}, {1.12, 0.04, false}};
  for (const Case& c : cases) {
    for (unsigned seed : {1u, 2u, 3u}) {
      SyntheticSpec s = DefaultSpec();
      s.esc.c1 = c.c1;
      s.esc.c0 = c.c0;
      s.ac = c.ac;
      s.seed = seed;
      s.noise_rel = 0.01;
      const CalibrationResult r = Calibrate(MakeSyntheticLog(s));
      EXPECT_GE(EscEnergyMargin(r.esc), -1e-9)
          << "c1 " << r.esc.c1 << " c0 " << r.esc.c0 << " (data " << c.c1 << ", " << c.c0 << ", seed " << seed << ")";
      EXPECT_EQ(MotorEnergyViolation(r.motor), "");
      EXPECT_GE(r.esc.c0, 0.0);
    }
  }
}

// An energy-creating ESC in the data puts the fit on the ideal-ESC bound: reported, and the
// verdict refuses it.
TEST(CalibratePhysics, BoundActiveIsReportedAndNotOk) {
  SyntheticSpec s = DefaultSpec();
  s.esc.c1 = 0.30;
  s.esc.c0 = 0.23;
  s.noise_rel = 0.003;
  const auto t = MakeSyntheticLog(s);
  const CalibrationResult r = Calibrate(t);
  EXPECT_TRUE(r.param(Param::kC1).at_bound || r.param(Param::kC0).at_bound) << r.FullReport();
  const identification::Verdict v = JudgeCalibration(r, t, {}, nullptr);
  EXPECT_NE(v.status, identification::Status::kOk) << v.summary;
}

// KE on its bound means status not ok, whatever else passes.
TEST(CalibratePhysics, KeOnBoundIsNotOk) {
  SyntheticSpec s = DefaultSpec();
  s.noise_rel = 0.003;
  const auto t = MakeSyntheticLog(s);
  CalibrationResult r = Calibrate(t);
  ASSERT_EQ(JudgeCalibration(r, t, {}, nullptr).status, identification::Status::kOk)
      << JudgeCalibration(r, t, {}, nullptr).summary;
  r.params[static_cast<int>(Param::kKe)].at_bound = true;
  const identification::Verdict v = JudgeCalibration(r, t, {}, nullptr);
  EXPECT_NE(v.status, identification::Status::kOk);
  EXPECT_NE(v.summary.find("no_parameter_on_bound"), std::string::npos) << v.summary;
}

// A clean physical log passes every check, including the held-out error.
TEST(CalibratePhysics, CleanLogIsOkWithHeldOutCheck) {
  SyntheticSpec s = DefaultSpec();
  s.noise_rel = 0.003;
  const auto t = MakeSyntheticLog(s);
  CalibrationOptions o;
  o.labels.kv_rpm_per_v = 900.0;
  const CalibrationResult r = Calibrate(t, o);
  const CrossValidation cv = CrossValidateForVerdict(t, o);
  EXPECT_TRUE(cv.leave_one_out);  // 15 throttle levels: each left out in turn
  const identification::Verdict v = JudgeCalibration(r, t, o, &cv);
  EXPECT_EQ(v.status, identification::Status::kOk) << v.summary;
}

// The label prior: without torque, AC columns or no-load rows at one throttle level KE and R
// trade off; the --kv-label prior holds KE near the label and its standard error reflects it.
TEST(CalibratePhysics, KvLabelPriorAnchorsKe) {
  SyntheticSpec s = DefaultSpec();
  s.ac = false;
  s.torque = false;
  s.esc = EscParams{};
  s.noise_rel = 0.005;
  const auto t = MakeSyntheticLog(s);
  CalibrationOptions o;
  o.labels.kv_rpm_per_v = 900.0;
  const CalibrationResult r = Calibrate(t, o);
  const double kv = identification::KvFromKe(r.motor.ke_v_s_per_rad);
  EXPECT_NEAR(kv, 900.0, 0.05 * 900.0) << r.FullReport();
  // A standard error no larger than the prior's 10 % (the data add information, never remove it).
  EXPECT_LE(r.param(Param::kKe).standard_error, 0.10 * r.motor.ke_v_s_per_rad * 1.0001);
}

// Outliers: never more than 10 % of the rows, each listed with its reason.
TEST(CalibratePhysics, OutlierPassIsCappedAndListed) {
  SyntheticSpec s = DefaultSpec();
  s.noise_rel = 0.003;
  s.outliers = 9;  // 9 rows of 60 with idc * 1.25: more than the 10 % cap
  const auto t = MakeSyntheticLog(s);
  const CalibrationResult r = Calibrate(t);
  std::size_t outliers = 0;
  for (const auto& d : r.dropped_rows) {
    if (d.reason.rfind("outlier", 0) == 0) {
      ++outliers;
      EXPECT_GT(d.source_line, 0u);
    }
  }
  EXPECT_GT(outliers, 0u) << r.FullReport();
  EXPECT_LE(outliers, t.rows() / 10);
}

// A throttle offset (negative dead band, docs/model.md section 9) in the data is found and fitted.
TEST(CalibratePhysics, ThrottleOffsetIsFitted) {
  SyntheticSpec s = ThrottleOffsetSpec();
  s.noise_rel = 0.003;
  const CalibrationResult r = Calibrate(MakeSyntheticLog(s));
  ASSERT_TRUE(r.param(Param::kDeadband).fitted) << r.FullReport();
  const auto& e = r.param(Param::kDeadband);
  EXPECT_NEAR(e.value, -0.08, 5.0 * e.standard_error + 0.005);
}

// A table so small that no fold can be fitted: every fold is reported as failed and the verdict
// is never "ok" ("too few points to cross-validate").
TEST(CalibratePhysics, FoldsThatCannotBeFittedMakeTheStatusNotOk) {
  SyntheticSpec s = DefaultSpec();
  s.ac = false;  // DC with torque: 2 measured values per row, 5 free parameters
  s.vdc_v = {14.8};
  s.prop_c = {2.0e-7};
  s.throttles = {0.5, 0.7, 0.9};
  s.noise_rel = 0.002;
  const auto t = MakeSyntheticLog(s);
  ASSERT_EQ(t.rows(), 3u);
  CalibrationResult r;
  try {
    r = Calibrate(t);
  } catch (const DataError& e) {
    GTEST_SKIP() << "the full table cannot be fitted either: " << e.what();
  }
  const CrossValidation cv = CrossValidateForVerdict(t, {});
  EXPECT_EQ(cv.folds, 3u);
  EXPECT_EQ(cv.failed_folds, 3u);
  const identification::Verdict v = JudgeCalibration(r, t, {}, &cv);
  EXPECT_NE(v.status, identification::Status::kOk);
  bool reported = false;
  for (const auto& c : v.checks) {
    if (c.name == "cross_validation_folds") {
      reported = !c.passed && c.detail.find("could not be fitted") != std::string::npos;
    }
  }
  EXPECT_TRUE(reported) << v.summary;
}

// One engine: calibrate and diagnose fit the same base model to the same log; on a clean log
// they agree on the base parameters within the fit's own errors.
TEST(CalibratePhysics, CalibrateAndDiagnoseAgreeOnBaseParameters) {
  SyntheticSpec s = DefaultSpec();
  s.esc.tr_sat = 1.0;  // no extension in the data: both describe it with the base model
  s.esc.sat_slope = 1.0;
  s.noise_rel = 0.002;
  const auto t = MakeSyntheticLog(s);
  const CalibrationResult c = Calibrate(t);
  const diagnosis::DiagnoseResult d = diagnosis::Diagnose(t);
  ASSERT_TRUE(d.findings.empty()) << d.FullReport();
  auto near = [](double a, double b, double se, double rel) { return std::fabs(a - b) <= 5.0 * se + rel * std::fabs(b); };
  const auto& ke = c.param(Param::kKe);
  EXPECT_TRUE(near(d.base_motor.ke_v_s_per_rad, c.motor.ke_v_s_per_rad, ke.standard_error, 0.002))
      << d.base_motor.ke_v_s_per_rad << " vs " << c.motor.ke_v_s_per_rad;
  EXPECT_TRUE(near(d.base_motor.kt_nm_per_a, c.motor.kt_nm_per_a, c.param(Param::kKt).standard_error, 0.005));
  EXPECT_TRUE(near(d.base_motor.rm_ohm, c.motor.rm_ohm, c.param(Param::kRm).standard_error, 0.03));
  EXPECT_TRUE(near(d.base_motor.io_a, c.motor.io_a, c.param(Param::kIo).standard_error, 0.03));
  EXPECT_TRUE(near(d.base_esc.c1, c.esc.c1, c.param(Param::kC1).standard_error, 0.01));
  EXPECT_GE(EscEnergyMargin(d.base_esc), -1e-9);
}

}  // namespace
}  // namespace dynosize::calibration
