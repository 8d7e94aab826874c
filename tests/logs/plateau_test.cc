// Plateau detection on a synthetic step test with known plateaus, through the whole reader
// (an RCbenchmark-style time series written in the test) and through FindPlateaus directly.
#include "logs/plateau.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "common/units.h"
#include "logs/log_reader.h"
#include "logs/log_test_util.h"

namespace dynosize::logs {
namespace {

using testing_util::RelErr;
using testing_util::WriteTemp;

// Step test: throttle 0.2, 0.3, ..., 0.7, each held 5 s, sampled at 100 Hz. Speed follows the
// command with a first-order lag (tau = 0.15 s) to rpm = 20000*throttle; current to
// 20*throttle^2 A. Noise: Gaussian 0.3 % of the level (seed 7); 6 spikes of 3x the speed
// (electrical-probe glitches) at known samples inside the steady parts.
struct StepTest {
  std::vector<double> t, throttle, rpm, amps;
  std::vector<double> levels;
  std::vector<std::size_t> spikes;
};

StepTest MakeStepTest() {
  StepTest s;
  std::mt19937 rng(7);
  std::normal_distribution<double> n01(0.0, 1.0);
  const double dt = 0.01, tau = 0.15, hold = 5.0;
  double rpm = 0.0, amps = 0.0;
  for (int step = 0; step < 6; ++step) {
    const double tr = 0.2 + 0.1 * step;
    s.levels.push_back(tr);
    for (int k = 0; k < static_cast<int>(hold / dt); ++k) {
      const double target_rpm = 20000.0 * tr, target_a = 20.0 * tr * tr;
      rpm += (target_rpm - rpm) * (1.0 - std::exp(-dt / tau));
      amps += (target_a - amps) * (1.0 - std::exp(-dt / tau));
      s.t.push_back(static_cast<double>(s.t.size()) * dt);
      s.throttle.push_back(tr);
      double r = rpm * (1.0 + 0.003 * n01(rng));
      if (k == 300) {
        r *= 3.0;
        s.spikes.push_back(s.t.size() - 1);
      }
      s.rpm.push_back(r);
      s.amps.push_back(amps * (1.0 + 0.003 * n01(rng)));
    }
  }
  return s;
}

// Residual transient after settle_time_s (0.5 s = 3.3 tau): exp(-3.3) = 3.6 % of the step,
// then the 3 % settle band drops the samples still outside; what is left biases the plateau
// mean by < 0.05 % of the level; the mean of ~450 samples with 0.3 % noise has a standard
// error of 0.014 %. 0.2 % covers both with margin.
constexpr double kPlateauMeanRelTol = 2e-3;

TEST(Plateau, StepTestThroughTheReader) {
  const StepTest s = MakeStepTest();
  std::ostringstream csv;
  csv.precision(10);
  csv << "\xEF\xBB\xBFTime (s),ESC signal (\xC2\xB5s),Voltage (V),Current (A),Motor Electrical Speed (RPM),\n";
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    // Current sampled asynchronously: empty on every 4th row.
    csv << s.t[i] << "," << 1000.0 + 1000.0 * s.throttle[i] << ",16.0,";
    if (i % 4 != 3) csv << s.amps[i];
    csv << "," << s.rpm[i] << ",\n";
  }
  const SteadyTable t = ReadLog(WriteTemp("steps.csv", csv.str()));
  ASSERT_TRUE(t.time_series);
  ASSERT_EQ(t.plateaus_found, 6u) << t.FullReport();
  ASSERT_EQ(t.rows(), 6u);
  for (std::size_t p = 0; p < 6; ++p) {
    const double tr = s.levels[p];
    EXPECT_NEAR(t.Get(Column::kThrottle)[p], tr, 1e-12);
    EXPECT_LT(RelErr(t.Get(Column::kOmegaRadS)[p], RpmToRadPerSec(20000.0 * tr)), kPlateauMeanRelTol) << p;
    EXPECT_LT(RelErr(t.Get(Column::kIdcA)[p], 20.0 * tr * tr), kPlateauMeanRelTol) << p;
  }
  // Every step's first 0.5 s (50 samples) at least is transient.
  EXPECT_GE(t.transient_samples, 6u * 50u);
  EXPECT_LE(t.transient_samples, 6u * 80u);
  // The 6 spikes are rejected; 5-sigma MAD rejects essentially no Gaussian sample, but it also
  // trims the transient tail of the first step (from standstill, the 3 % settle band is wider
  // than 5 sigma of the 0.3 % noise): at most ~25 more.
  EXPECT_GE(t.outlier_samples, 6u);
  EXPECT_LE(t.outlier_samples, 6u + 25u);
  EXPECT_EQ(t.DroppedTotal(), 0u) << t.BriefReport();
}

TEST(Plateau, SignalSearchWithoutCommand) {
  const StepTest s = MakeStepTest();
  PlateauOptions o;
  const PlateauSearch ps = FindPlateaus(s.t.data(), nullptr, s.rpm.data(), s.t.size(), o);
  EXPECT_EQ(ps.method, PlateauMethod::kSignalSteadiness);
  ASSERT_EQ(ps.plateaus.size(), 6u);
  for (std::size_t p = 0; p < 6; ++p) {
    const double med = MedianOf(s.rpm.data(), ps.plateaus[p].begin, ps.plateaus[p].end);
    EXPECT_LT(RelErr(med, 20000.0 * s.levels[p]), kPlateauMeanRelTol) << p;
  }
}

TEST(Plateau, CommandClassification) {
  PlateauOptions o;
  std::vector<double> ramp, steps, pid;
  for (int i = 0; i < 200; ++i) {
    ramp.push_back(0.001 * i);
    steps.push_back(0.1 * (i / 20));
    pid.push_back(0.5 + 0.01 * ((i % 2) ? 1 : -1) * (1 + i % 3));
  }
  EXPECT_EQ(ClassifyCommand(ramp.data(), ramp.size(), o), CommandKind::kRamp);
  EXPECT_EQ(ClassifyCommand(steps.data(), steps.size(), o), CommandKind::kStepped);
  EXPECT_EQ(ClassifyCommand(pid.data(), pid.size(), o), CommandKind::kVarying);
  EXPECT_EQ(ClassifyCommand(nullptr, 0, o), CommandKind::kNone);
  // Ramp bins of 0.02: 200 samples over 0..0.199 -> 11 bins (rounded to the nearest bin).
  const PlateauSearch ps = FindPlateaus(nullptr, ramp.data(), nullptr, ramp.size(), o);
  EXPECT_EQ(ps.method, PlateauMethod::kRampBins);
  EXPECT_EQ(ps.plateaus.size(), 11u);
  PlateauOptions bad;
  bad.settle_band = -1;
  std::string why;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("PlateauOptions.settle_band"), std::string::npos);
}

TEST(Plateau, MadOutliersIgnoreNaNAndQuantisedSignals) {
  std::vector<double> x = {100, 100, 101, 100, 99, 100, NAN, 100, 400, 100};
  std::vector<char> mask;
  PlateauOptions o;
  EXPECT_EQ(MarkOutliers({x.data()}, 0, x.size(), o, &mask), 1u);
  EXPECT_EQ(mask[8], 1);
  // All equal but one count: sigma floored at 0.1 % of the median, so 101 is no outlier.
  std::vector<double> q = {1000, 1000, 1000, 1001, 1000};
  EXPECT_EQ(MarkOutliers({q.data()}, 0, q.size(), o, &mask), 0u);
}

}  // namespace
}  // namespace dynosize::logs
