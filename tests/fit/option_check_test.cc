// Options are checked the Ceres way: IsValid(std::string*) names the first violated rule as
// "Owner.field = value rule", the same form in every options struct of the identification code.
#include <gtest/gtest.h>

#include <string>

#include "calibration/calibrate.h"
#include "diagnosis/diagnose.h"
#include "fit/nonlinear_least_squares.h"
#include "fit/option_check.h"

namespace dynosize {
namespace {

TEST(OptionCheck, WritesOwnerFieldValueAndRule) {
  std::string e;
  EXPECT_FALSE(fit::OptionCheck("Foo", &e).Fail("bar", 0.5, "must be > 1"));
  EXPECT_EQ(e, "Foo.bar = 0.5 must be > 1");
  EXPECT_FALSE(fit::OptionCheck("Foo", &e).Fail("labels", "--kv-label: must be > 0"));
  EXPECT_EQ(e, "Foo.labels --kv-label: must be > 0");
  EXPECT_FALSE(fit::OptionCheck("Foo", nullptr).Fail("bar", 1.0, "x"));  // no error string: no crash
}

TEST(OptionCheck, EveryOptionsStructUsesTheSameForm) {
  std::string e;
  diagnosis::DiagnoseOptions d;
  EXPECT_TRUE(d.IsValid(&e)) << e;
  d.folds = 1;
  EXPECT_FALSE(d.IsValid(&e));
  EXPECT_EQ(e, "DiagnoseOptions.folds = 1 must be >= 2");

  calibration::CalibrationOptions c;
  EXPECT_TRUE(c.IsValid(&e)) << e;
  c.knee_step = 0.0;
  EXPECT_FALSE(c.IsValid(&e));
  EXPECT_EQ(e, "CalibrationOptions.knee_step = 0 must be in (0, 0.5]");
  c = calibration::CalibrationOptions{};
  c.solver.function_tolerance = -1.0;
  EXPECT_FALSE(c.IsValid(&e));
  EXPECT_EQ(e, "LevenbergMarquardtOptions.function_tolerance = -1 must be >= 0");
  c = calibration::CalibrationOptions{};
  c.labels.kv_rpm_per_v = -5.0;
  EXPECT_FALSE(c.IsValid(&e));
  EXPECT_EQ(e.rfind("CalibrationOptions.labels --kv-label", 0), 0u) << e;
}

}  // namespace
}  // namespace dynosize
