// AttributeTrend: a residual made by one mechanism (seeded noise) is named where the sweep
// separates it from the others, and left unnamed, with the separating measurement, where the
// sweep runs one way.
#include "identification/trend_attribution.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace dynosize::identification {
namespace {

// The diagnosis's test level (DiagnoseOptions::alpha).
constexpr double kAlpha = 1e-3;
// Residual noise, percent: the held-out error of a good fit on a stand log.
constexpr double kNoisePercent = 0.5;

// A stand sweep of steps 5 s apart at speeds proportional to the command, current growing with
// the square of the speed (a propeller): `up_down` runs 16 steps up and then 16 down again;
// `two_props` alternates a second, lighter propeller (20 % faster at the same command).
TrendRows Sweep(bool up_down, bool two_props = false) {
  TrendRows r;
  const int n = 16;
  for (int k = 0; k < (up_down ? 2 * n : n); ++k) {
    const int level = k < n ? k : 2 * n - 1 - k;
    const double tr = 0.25 + 0.05 * level;
    const double prop = two_props && k % 2 == 1 ? 1.2 : 1.0;
    r.throttle.push_back(tr);
    r.omega_rad_s.push_back(1000.0 * tr * prop);
    r.current_a.push_back(30.0 * tr * tr / prop);
    r.time_s.push_back(5.0 * k);
  }
  return r;
}

// Heat accumulated with a 100 s time constant from a cold start (as the attribution computes
// it), scaled to an error of about `percent` at its largest.
std::vector<double> Heat(const TrendRows& r, double percent) {
  std::vector<double> h(r.time_s.size());
  double x = 0.0, hmax = 0.0;
  for (std::size_t k = 0; k < h.size(); ++k) {
    const double a = std::exp(-5.0 / 100.0);
    x = a * x + (1.0 - a) * r.current_a[k] * r.current_a[k];
    h[k] = x;
    hmax = std::max(hmax, x);
  }
  for (double& v : h) v *= percent / hmax;
  return h;
}

// A measured column of 100 and a prediction that misses it by `percent` at each row.
void SetResidual(const std::vector<double>& percent, TrendRows* r) {
  r->measured.assign(percent.size(), 100.0);
  r->predicted.clear();
  for (double e : percent) r->predicted.push_back(100.0 + e);
}

std::vector<double> Speed(const TrendRows& r, double percent_per_rad_s) {
  std::vector<double> y;
  for (double w : r.omega_rad_s) y.push_back(percent_per_rad_s * w);
  return y;
}

void AddNoise(unsigned seed, TrendRows* r) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> e(0.0, kNoisePercent);
  for (double& y : r->predicted) y += e(rng);
}

// The attribution of a sweep's residual (seeded noise added).
TrendAttribution Attribute(TrendRows r, const std::vector<double>& residual_percent, unsigned seed) {
  SetResidual(residual_percent, &r);
  AddNoise(seed, &r);
  return AttributeTrend(r, kAlpha);
}

TEST(TrendAttribution, HeatingInAnUpAndDownSweepIsNamed) {
  const TrendRows r = Sweep(true);
  const TrendAttribution a = Attribute(r, Heat(r, 8.0), 1);
  ASSERT_TRUE(a.structured);
  EXPECT_EQ(a.signatures.front().mechanism, "heating") << a.text;
  EXPECT_TRUE(a.separable) << a.text;
  EXPECT_TRUE(a.measurement.empty());
  EXPECT_NE(a.text.find("warming"), std::string::npos) << a.text;
}

TEST(TrendAttribution, SpeedLossWithTwoPropellersIsNamed) {
  const TrendRows r = Sweep(true, true);
  const TrendAttribution a = Attribute(r, Speed(r, -0.008), 2);
  ASSERT_TRUE(a.structured);
  EXPECT_EQ(a.signatures.front().mechanism, "speed") << a.text;
  EXPECT_TRUE(a.separable) << a.text;
  EXPECT_NE(a.text.find("grows with speed"), std::string::npos) << a.text;
}

TEST(TrendAttribution, SpeedLossWithOnePropellerIsNotToldFromTheCommand) {
  const TrendRows r = Sweep(true);
  const TrendAttribution a = Attribute(r, Speed(r, -0.008), 2);
  ASSERT_TRUE(a.structured);
  // One propeller: the speed is a function of the command, the two are one regressor.
  EXPECT_FALSE(a.separable) << a.text;
  EXPECT_NE(a.measurement.find("second propeller"), std::string::npos) << a.measurement;
}

TEST(TrendAttribution, HeatingInAOneWaySweepCannotBeTold) {
  const TrendRows r = Sweep(false);
  const TrendAttribution a = Attribute(r, Heat(r, 8.0), 3);
  ASSERT_TRUE(a.structured);
  EXPECT_FALSE(a.separable) << a.text;
  EXPECT_GE(a.rival_correlation, 0.9);  // a one-way sweep: heat and speed rise together
  EXPECT_NE(a.text.find("cannot tell"), std::string::npos) << a.text;
  EXPECT_FALSE(a.measurement.empty());
}

TEST(TrendAttribution, NoiseAloneIsNoTrend) {
  int structured = 0;
  for (unsigned seed = 10; seed < 60; ++seed) {
    TrendRows r = Sweep(seed % 2 == 0);
    SetResidual(std::vector<double>(r.time_s.size(), 0.0), &r);
    AddNoise(seed, &r);
    structured += AttributeTrend(r, kAlpha).structured;
  }
  // alpha = 0.001 with the Bonferroni correction: 50 draws of noise, none expected.
  EXPECT_EQ(structured, 0);
}

TEST(TrendAttribution, WithoutTimeOnlySpeedAndCommandAreTested) {
  TrendRows r = Sweep(true);
  SetResidual(Speed(r, 0.01), &r);
  r.time_s.clear();
  const TrendAttribution a = AttributeTrend(r, kAlpha);
  for (const auto& s : a.signatures) EXPECT_NE(s.mechanism, "heating");
  EXPECT_EQ(a.signatures.size(), 2u);
}

TEST(TrendAttribution, TooFewRowsSayNothing) {
  TrendRows r = Sweep(false);
  SetResidual(Heat(r, 8.0), &r);
  for (auto* v : {&r.measured, &r.predicted, &r.time_s, &r.omega_rad_s, &r.current_a, &r.throttle}) v->resize(5);
  const TrendAttribution a = AttributeTrend(r, kAlpha);
  EXPECT_FALSE(a.structured);
  EXPECT_TRUE(a.signatures.empty());
}

}  // namespace
}  // namespace dynosize::identification
