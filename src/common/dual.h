// Forward-mode automatic differentiation: a dual number a + sum_i v_i * eps_i with eps_i^2 = 0.
//
// Evaluating f on Dual arguments seeded with unit tangents (Dual<N>::Variable(x, i)) yields f(x)
// in .value and the exact gradient df/dx in .derivative, to rounding, with no step size to pick
// (unlike finite differences, which lose about half the digits). Used for Jacobians in src/fit/
// and gradients in solvers/ by callers who would rather not differentiate by hand.
//
// N is the number of tangent directions: a compile-time constant for small fixed problems (no
// heap allocation: a 4-parameter fit runs several times faster this way), or Eigen::Dynamic.
// Every function here follows the chain rule d f(u) = f'(u) du; where f'(u) is infinite (sqrt
// at 0, pow with a zero base) the derivative is inf/NaN as it mathematically is, and callers see
// it.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <ostream>

namespace dynosize {

template <int N = Eigen::Dynamic>
struct Dual {
  using Tangent = Eigen::Matrix<double, N, 1>;

  double value = 0.0;
  Tangent derivative;

  Dual() : derivative(Tangent::Zero(N == Eigen::Dynamic ? 0 : N)) {}
  // A constant (zero derivative). For N = Eigen::Dynamic a constant has an empty tangent that
  // behaves as zero in every operation below; this avoids knowing the size at construction.
  Dual(double v) : value(v), derivative(Tangent::Zero(N == Eigen::Dynamic ? 0 : N)) {}  // NOLINT
  Dual(double v, const Tangent& d) : value(v), derivative(d) {}

  // The independent variable number `index` of `size` (size is N unless N is dynamic).
  static Dual Variable(double v, int index, int size = N) {
    Dual d(v, Tangent::Zero(size));
    d.derivative[index] = 1.0;
    return d;
  }

  Dual& operator+=(const Dual& o) { return *this = *this + o; }
  Dual& operator-=(const Dual& o) { return *this = *this - o; }
  Dual& operator*=(const Dual& o) { return *this = *this * o; }
  Dual& operator/=(const Dual& o) { return *this = *this / o; }
};

namespace dual_internal {
// a*da + b*db where either tangent may be empty (a dynamic-size constant).
template <int N>
typename Dual<N>::Tangent Combine(double a, const typename Dual<N>::Tangent& da, double b,
                                  const typename Dual<N>::Tangent& db) {
  if (da.size() == 0) return b * db;
  if (db.size() == 0) return a * da;
  return a * da + b * db;
}
}  // namespace dual_internal

// Arithmetic.
template <int N> Dual<N> operator+(const Dual<N>& a) { return a; }
template <int N> Dual<N> operator-(const Dual<N>& a) { return Dual<N>(-a.value, -a.derivative); }
template <int N> Dual<N> operator+(const Dual<N>& a, const Dual<N>& b) {
  return Dual<N>(a.value + b.value, dual_internal::Combine<N>(1.0, a.derivative, 1.0, b.derivative));
}
template <int N> Dual<N> operator-(const Dual<N>& a, const Dual<N>& b) {
  return Dual<N>(a.value - b.value, dual_internal::Combine<N>(1.0, a.derivative, -1.0, b.derivative));
}
template <int N> Dual<N> operator*(const Dual<N>& a, const Dual<N>& b) {
  return Dual<N>(a.value * b.value,
                 dual_internal::Combine<N>(b.value, a.derivative, a.value, b.derivative));
}
template <int N> Dual<N> operator/(const Dual<N>& a, const Dual<N>& b) {
  const double inv = 1.0 / b.value;
  const double q = a.value * inv;
  return Dual<N>(q, dual_internal::Combine<N>(inv, a.derivative, -q * inv, b.derivative));
}
template <int N> Dual<N> operator+(const Dual<N>& a, double b) { return Dual<N>(a.value + b, a.derivative); }
template <int N> Dual<N> operator+(double a, const Dual<N>& b) { return Dual<N>(a + b.value, b.derivative); }
template <int N> Dual<N> operator-(const Dual<N>& a, double b) { return Dual<N>(a.value - b, a.derivative); }
template <int N> Dual<N> operator-(double a, const Dual<N>& b) { return Dual<N>(a - b.value, -b.derivative); }
template <int N> Dual<N> operator*(const Dual<N>& a, double b) { return Dual<N>(a.value * b, a.derivative * b); }
template <int N> Dual<N> operator*(double a, const Dual<N>& b) { return Dual<N>(a * b.value, a * b.derivative); }
template <int N> Dual<N> operator/(const Dual<N>& a, double b) { return Dual<N>(a.value / b, a.derivative / b); }
template <int N> Dual<N> operator/(double a, const Dual<N>& b) {
  const double q = a / b.value;
  return Dual<N>(q, (-q / b.value) * b.derivative);
}

// Comparisons look at the value only (branches in user code select a piece of a piecewise
// function; the derivative is that piece's).
template <int N> bool operator<(const Dual<N>& a, const Dual<N>& b) { return a.value < b.value; }
template <int N> bool operator>(const Dual<N>& a, const Dual<N>& b) { return a.value > b.value; }
template <int N> bool operator<=(const Dual<N>& a, const Dual<N>& b) { return a.value <= b.value; }
template <int N> bool operator>=(const Dual<N>& a, const Dual<N>& b) { return a.value >= b.value; }
template <int N> bool operator<(const Dual<N>& a, double b) { return a.value < b; }
template <int N> bool operator>(const Dual<N>& a, double b) { return a.value > b; }
template <int N> bool operator<=(const Dual<N>& a, double b) { return a.value <= b; }
template <int N> bool operator>=(const Dual<N>& a, double b) { return a.value >= b; }
template <int N> bool operator<(double a, const Dual<N>& b) { return a < b.value; }
template <int N> bool operator>(double a, const Dual<N>& b) { return a > b.value; }

// Elementary functions: f(u) with derivative f'(u) * du.
template <int N> Dual<N> Chain(const Dual<N>& u, double f, double df) {
  return Dual<N>(f, df * u.derivative);
}
template <int N> Dual<N> exp(const Dual<N>& u) { const double e = std::exp(u.value); return Chain(u, e, e); }
template <int N> Dual<N> log(const Dual<N>& u) { return Chain(u, std::log(u.value), 1.0 / u.value); }
template <int N> Dual<N> sqrt(const Dual<N>& u) {
  const double s = std::sqrt(u.value);
  return Chain(u, s, 0.5 / s);
}
template <int N> Dual<N> sin(const Dual<N>& u) { return Chain(u, std::sin(u.value), std::cos(u.value)); }
template <int N> Dual<N> cos(const Dual<N>& u) { return Chain(u, std::cos(u.value), -std::sin(u.value)); }
template <int N> Dual<N> tan(const Dual<N>& u) {
  const double t = std::tan(u.value);
  return Chain(u, t, 1.0 + t * t);
}
template <int N> Dual<N> atan(const Dual<N>& u) { return Chain(u, std::atan(u.value), 1.0 / (1.0 + u.value * u.value)); }
template <int N> Dual<N> tanh(const Dual<N>& u) {
  const double t = std::tanh(u.value);
  return Chain(u, t, 1.0 - t * t);
}
// |u| has derivative sign(u) du; at u = 0 we take +du (a subgradient) rather than NaN.
template <int N> Dual<N> abs(const Dual<N>& u) { return u.value < 0.0 ? -u : u; }
template <int N> Dual<N> fabs(const Dual<N>& u) { return abs(u); }
// u^p for a constant exponent: p*u^(p-1) du (finite at u = 0 for p >= 1, unlike the exp/log form).
template <int N> Dual<N> pow(const Dual<N>& u, double p) {
  const double f = std::pow(u.value, p);
  return Chain(u, f, p == 0.0 ? 0.0 : p * std::pow(u.value, p - 1.0));
}
// a^v for a constant base: a^v log(a) dv.
template <int N> Dual<N> pow(double a, const Dual<N>& v) {
  const double f = std::pow(a, v.value);
  return Chain(v, f, f * std::log(a));
}
// u^v = exp(v log u): d = u^v (v/u du + log(u) dv); requires u > 0 unless dv = 0.
template <int N> Dual<N> pow(const Dual<N>& u, const Dual<N>& v) {
  const double f = std::pow(u.value, v.value);
  return Dual<N>(f, dual_internal::Combine<N>(v.value * std::pow(u.value, v.value - 1.0), u.derivative,
                                              f * std::log(u.value), v.derivative));
}
template <int N> Dual<N> atan2(const Dual<N>& y, const Dual<N>& x) {
  const double r2 = x.value * x.value + y.value * y.value;
  return Dual<N>(std::atan2(y.value, x.value),
                 dual_internal::Combine<N>(x.value / r2, y.derivative, -y.value / r2, x.derivative));
}
template <int N> bool isfinite(const Dual<N>& u) { return std::isfinite(u.value) && u.derivative.allFinite(); }

template <int N> std::ostream& operator<<(std::ostream& os, const Dual<N>& u) {
  return os << u.value << " + [" << u.derivative.transpose() << "]eps";
}

// Value of a double or a Dual, so that templated user code can branch or print uniformly.
inline double ValueOf(double x) { return x; }
template <int N> double ValueOf(const Dual<N>& x) { return x.value; }

}  // namespace dynosize
