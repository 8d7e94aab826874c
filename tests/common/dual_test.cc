#include "common/dual.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dynosize {
namespace {

// Forward-mode derivatives are exact up to rounding of the elementary operations: a few ulps of
// the largest intermediate, hence 1e-13 relative.
constexpr double kRel = 1e-13;

template <class T>
T F(const T& x, const T& y) {
  using std::atan;
  using std::cos;
  using std::exp;
  using std::log;
  using std::pow;
  using std::sin;
  using std::sqrt;
  return x * y + sin(x) / y - exp(0.5 * x) * log(y) + sqrt(x * x + y) + pow(x, 3.0) +
         pow(y, x) + atan(x - y) + cos(y) / 2.0 - 3.0 / (1.0 + x);
}

TEST(Dual, GradientMatchesHandDerivatives) {
  const double x = 0.7, y = 1.9;
  using D = Dual<2>;
  const D r = F(D::Variable(x, 0), D::Variable(y, 1));
  const double dfdx = y + std::cos(x) / y - 0.5 * std::exp(0.5 * x) * std::log(y) +
                      x / std::sqrt(x * x + y) + 3 * x * x + std::pow(y, x) * std::log(y) +
                      1.0 / (1.0 + (x - y) * (x - y)) + 3.0 / ((1.0 + x) * (1.0 + x));
  const double dfdy = x - std::sin(x) / (y * y) - std::exp(0.5 * x) / y +
                      0.5 / std::sqrt(x * x + y) + x * std::pow(y, x - 1.0) -
                      1.0 / (1.0 + (x - y) * (x - y)) - std::sin(y) / 2.0;
  EXPECT_NEAR(r.value, F(x, y), kRel * std::abs(F(x, y)));
  EXPECT_NEAR(r.derivative[0], dfdx, kRel * std::abs(dfdx));
  EXPECT_NEAR(r.derivative[1], dfdy, kRel * std::abs(dfdy));
}

TEST(Dual, DynamicSizeAgreesWithFixedSize) {
  using DD = Dual<Eigen::Dynamic>;
  using DF = Dual<2>;
  const DD rd = F(DD::Variable(0.3, 0, 2), DD::Variable(2.5, 1, 2));
  const DF rf = F(DF::Variable(0.3, 0), DF::Variable(2.5, 1));
  EXPECT_EQ(rd.value, rf.value);
  EXPECT_EQ(rd.derivative[0], rf.derivative[0]);
  EXPECT_EQ(rd.derivative[1], rf.derivative[1]);
}

TEST(Dual, ConstantsMixWithDynamicVariables) {
  using D = Dual<Eigen::Dynamic>;
  const D c(4.0);  // an empty-tangent constant
  const D x = D::Variable(3.0, 0, 1);
  const D r = c * x + c / x - c + (c - x);
  EXPECT_DOUBLE_EQ(r.value, 12.0 + 4.0 / 3.0 - 4.0 + 1.0);
  EXPECT_DOUBLE_EQ(r.derivative[0], 4.0 - 4.0 / 9.0 - 1.0);
}

TEST(Dual, AgreesWithCentralDifference) {
  // Independent check of the chain rule through a long expression: central difference with
  // h = 1e-5 has truncation error ~h^2 * f''' ~ 1e-10 relative.
  const double x = 1.3, y = 0.4, h = 1e-5;
  using D = Dual<2>;
  const D r = F(D::Variable(x, 0), D::Variable(y, 1));
  const double fd = (F(x + h, y) - F(x - h, y)) / (2 * h);
  EXPECT_NEAR(r.derivative[0], fd, 1e-8 * std::abs(fd));
}

}  // namespace
}  // namespace dynosize
