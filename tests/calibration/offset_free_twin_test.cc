// calibration/calibrate.h: Calibrate with `without_offset` returns, beside the fit with the
// throttle offset tested, exactly what a separate Calibrate with fit_throttle_offset off returns
// (diagnose takes both from one run). Checked where the offset is kept (the two runs part after
// the first fit), where it is not (they share every stage), with outliers (the outlier pass is
// shared or run twice) and on a DC log whose ESC ratio is held at the prior (the third stage).
#include <gtest/gtest.h>

#include <string>

#include "calibration/calibrate.h"
#include "calibration/synthetic_log.h"

namespace dynosize::calibration {
namespace {

using testing_util::DefaultSpec;
using testing_util::MakeSyntheticLog;
using testing_util::SyntheticSpec;
using testing_util::ThrottleOffsetSpec;

// Bit for bit: the report prints every value, error, flag and note; the values are compared
// exactly too, beyond the report's digits.
void ExpectSameResult(const CalibrationResult& a, const CalibrationResult& b) {
  EXPECT_EQ(a.FullReport(), b.FullReport());
  EXPECT_EQ(a.converged, b.converged);
  EXPECT_EQ(a.points_used, b.points_used);
  EXPECT_EQ(a.dropped_rows.size(), b.dropped_rows.size());
  EXPECT_EQ(a.warnings, b.warnings);
  for (int k = 0; k < kBaseParamCount; ++k) {
    SCOPED_TRACE(ParamName(static_cast<Param>(k)));
    EXPECT_EQ(a.params[k].value, b.params[k].value);
    EXPECT_EQ(a.params[k].fitted, b.params[k].fitted);
    EXPECT_EQ(a.params[k].note, b.params[k].note);
    const double sa = a.params[k].standard_error, sb = b.params[k].standard_error;
    EXPECT_TRUE(sa == sb || (sa != sa && sb != sb)) << sa << " vs " << sb;
  }
  EXPECT_EQ(a.motor.ke_v_s_per_rad, b.motor.ke_v_s_per_rad);
  EXPECT_EQ(a.motor.rm_ohm, b.motor.rm_ohm);
  EXPECT_EQ(a.esc.c1, b.esc.c1);
}

// Both results of one run against two separate runs; returns whether the offset was kept.
bool CheckTwin(const logs::SteadyTable& t) {
  CalibrationOptions on;
  on.fit_throttle_offset = true;
  CalibrationOptions off = on;
  off.fit_throttle_offset = false;
  CalibrationResult without;
  const CalibrationResult with = Calibrate(t, on, &without);
  {
    SCOPED_TRACE("with the offset tested");
    ExpectSameResult(with, Calibrate(t, on));
  }
  {
    SCOPED_TRACE("without the offset");
    ExpectSameResult(without, Calibrate(t, off));
  }
  EXPECT_FALSE(without.param(Param::kDeadband).fitted);
  return with.param(Param::kDeadband).fitted;
}

TEST(CalibrateOffsetFreeTwin, OffsetKeptTheRunsPartAfterTheFirstFit) {
  SyntheticSpec s = ThrottleOffsetSpec();
  s.noise_rel = 0.003;
  EXPECT_TRUE(CheckTwin(MakeSyntheticLog(s)));
}

TEST(CalibrateOffsetFreeTwin, NoOffsetTheRunsShareEveryStage) {
  EXPECT_FALSE(CheckTwin(MakeSyntheticLog(DefaultSpec())));
}

TEST(CalibrateOffsetFreeTwin, OutlierPassWithAndWithoutOffset) {
  SyntheticSpec s = DefaultSpec();
  s.outliers = 3;
  CheckTwin(MakeSyntheticLog(s));
  SyntheticSpec offset = ThrottleOffsetSpec();
  offset.outliers = 3;
  EXPECT_TRUE(CheckTwin(MakeSyntheticLog(offset)));
}

TEST(CalibrateOffsetFreeTwin, DcLogWithTheEscHeld) {
  SyntheticSpec s = DefaultSpec();
  s.ac = false;  // DC with torque: C1, C0 free, and held at the prior when the log cannot fix them
  CheckTwin(MakeSyntheticLog(s));
  s.esc.deadband = -0.08;
  CheckTwin(MakeSyntheticLog(s));
}

}  // namespace
}  // namespace dynosize::calibration
