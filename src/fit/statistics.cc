#include "fit/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

namespace dynosize::fit {

namespace {

// ---------------------------------------------------------------------------------------------
// Regularized incomplete beta by Lentz's continued fraction (Numerical Recipes 6.4).
double BetaContinuedFraction(double a, double b, double x) {
  const double tiny = 1e-300;
  double c = 1.0, dd = 1.0 - (a + b) * x / (a + 1.0);
  if (std::fabs(dd) < tiny) dd = tiny;
  dd = 1.0 / dd;
  double h = dd;
  for (int m = 1; m <= 300; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    dd = 1.0 + aa * dd;
    if (std::fabs(dd) < tiny) dd = tiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < tiny) c = tiny;
    dd = 1.0 / dd;
    h *= dd * c;
    aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    dd = 1.0 + aa * dd;
    if (std::fabs(dd) < tiny) dd = tiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < tiny) c = tiny;
    dd = 1.0 / dd;
    const double del = dd * c;
    h *= del;
    if (std::fabs(del - 1.0) < 1e-14) break;
  }
  return h;
}

double RegularizedBeta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double lbt = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) +
                     b * std::log1p(-x);
  if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(lbt) * BetaContinuedFraction(a, b, x) / a;
  return 1.0 - std::exp(lbt) * BetaContinuedFraction(b, a, 1.0 - x) / b;
}


}  // namespace

double Median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h), v.end());
  double m = v[h];
  if (v.size() % 2 == 0) {
    m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h)));
  }
  return m;
}

double MedianAbs(std::vector<double> v) {
  for (double& x : v) x = std::fabs(x);
  return Median(std::move(v));
}

double Quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return SortedQuantile(v, q);
}

double SortedQuantile(const std::vector<double>& v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double pos = std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

double Aicc(double sse, int n, int p) {
  const double nn = n, pp = p;
  const double base = nn * std::log(std::max(sse, 1e-300) / nn) + 2.0 * pp;
  return n - p - 1 > 0 ? base + 2.0 * pp * (pp + 1.0) / (nn - pp - 1.0)
                       : std::numeric_limits<double>::infinity();
}

double FDistributionUpperTail(double f, double d1, double d2) {
  if (!(f > 0.0)) return 1.0;
  if (!std::isfinite(f)) return 0.0;
  return RegularizedBeta(0.5 * d2, 0.5 * d1, d2 / (d2 + d1 * f));
}

}  // namespace dynosize::fit
