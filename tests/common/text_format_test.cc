// The one number formatter (common/text_format.h) writes what printf writes: the private
// formatters it replaced were ostream and snprintf formatters, and every report, figure and
// message must stay byte-identical.
#include "common/text_format.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "common/numbers.h"

namespace dynosize {
namespace {

std::string Printf(const char* format, int digits, double x) {
  char buf[512];
  std::snprintf(buf, sizeof buf, format, digits, x);
  return buf;
}

// Values where the two notations and the rounding differ: exact halves, powers of ten at the
// switch between fixed and exponent notation, signed zero, tiny and huge magnitudes, and
// seeded random values over 24 decades.
std::vector<double> Values() {
  std::vector<double> v = {0.0, -0.0, 1.0, -1.0, 0.5, 0.125, 2.5, 1e-5, 1e-4, 9.99995e-5, 123456.5,
                           999999.5, 1e6, 1e15, -3.14159265358979, 24.355, 0.1 + 0.2, 1e-300,
                           std::numeric_limits<double>::max()};
  std::mt19937 rng(27);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0), decade(-12.0, 12.0);
  for (int i = 0; i < 500; ++i) v.push_back(mantissa(rng) * std::pow(10.0, decade(rng)));
  return v;
}

TEST(TextFormat, FixedTextIsPrintfF) {
  for (const double x : Values()) {
    if (std::fabs(x) > 1e30) continue;  // %f of 1e308 is 309 digits: not a report's number
    for (const int d : {0, 1, 2, 3, 4, 6}) EXPECT_EQ(FixedText(x, d), Printf("%.*f", d, x)) << x;
  }
}

TEST(TextFormat, SignificantTextIsPrintfG) {
  for (const double x : Values()) {
    for (const int d : {1, 3, 4, 6, 17}) EXPECT_EQ(SignificantText(x, d), Printf("%.*g", d, x)) << x;
    EXPECT_EQ(SignificantText(x), Printf("%.*g", 6, x)) << x;
  }
}

TEST(TextFormat, NoValueIsNeverPrintedAsNan) {
  EXPECT_EQ(SignificantTextOr(kNaN, "-", 3), "-");
  EXPECT_EQ(SignificantTextOr(std::numeric_limits<double>::infinity(), ""), "");
  EXPECT_EQ(SignificantTextOr(0.0123456, "-", 3), "0.0123");
  EXPECT_TRUE(std::isnan(kNaN));
}

TEST(TextFormat, PercentTextIsAFractionInPercent) {
  EXPECT_EQ(PercentText(0.125), "12.5 %");
  EXPECT_EQ(PercentText(-0.0304), "-3.0 %");
  EXPECT_EQ(PercentText(0.5, 0), "50 %");
  for (const double x : Values()) {
    if (std::fabs(x) > 1e30) continue;
    EXPECT_EQ(PercentText(x), Printf("%.*f", 1, 100.0 * x) + " %") << x;
  }
}

}  // namespace
}  // namespace dynosize
