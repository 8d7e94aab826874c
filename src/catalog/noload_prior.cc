#include "catalog/noload_prior.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include "common/error.h"
#include "common/numbers.h"

namespace dynosize {

namespace {

struct Sample {
  double log_imax, log_n0, log_io;
};

std::vector<Sample> Samples(const std::vector<MotorEntry>& motors) {
  std::vector<Sample> s;
  for (const auto& m : motors) {
    const double io = m.params.io_a;
    const double imax = m.params.max_current_a;
    const double kv = m.kv_rpm_per_v.value_or(0.0);
    const auto v = m.json.find("io_test_voltage_v");
    const double vt = v != m.json.end() && v->is_number() ? v->get<double>() : 0.0;
    if (!(io > 0.0) || !(vt > 0.0) || !(kv > 0.0) || !(imax > 0.0) || !std::isfinite(imax)) continue;
    // A law's estimate (catalog/motor_estimate.h) is no observation of a motor.
    if (ValueTier(m, "io_a") == DataTier::kEstimated) continue;
    s.push_back({std::log10(imax), std::log10(kv * vt), std::log10(io)});
  }
  return s;
}

double Quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

}  // namespace

NoLoadLaw FitNoLoadLaw(const std::vector<MotorEntry>& motors) {
  const std::vector<Sample> s = Samples(motors);
  if (s.size() < 10) {
    throw DataError("no-load prior: " + std::to_string(s.size()) +
                    " motor entries state io_a, io_test_voltage_v, kv_rpm_per_v and max_current_a: the fit needs 10");
  }
  const auto n = static_cast<Eigen::Index>(s.size());
  Eigen::MatrixXd a(n, 3);
  Eigen::VectorXd y(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    a(k, 0) = 1.0;
    a(k, 1) = s[k].log_imax;
    a(k, 2) = s[k].log_n0;
    y[k] = s[k].log_io;
  }
  const Eigen::VectorXd x = a.colPivHouseholderQr().solve(y);
  const Eigen::VectorXd r = y - a * x;
  NoLoadLaw law;
  law.a = x[0];
  law.b_imax = x[1];
  law.c_speed = x[2];
  law.motors = s.size();
  law.log10_sd = std::sqrt(r.squaredNorm() / static_cast<double>(n - 3));
  std::vector<double> res(r.data(), r.data() + n);
  law.p10_factor = std::pow(10.0, Quantile(res, 0.10));
  law.p90_factor = std::pow(10.0, Quantile(res, 0.90));
  return law;
}

double NoLoadPriorIoA(double max_current_a, double no_load_speed_rpm, const NoLoadLaw& law) {
  if (!(max_current_a > 0.0) || !(no_load_speed_rpm > 0.0) || !std::isfinite(max_current_a) ||
      !std::isfinite(no_load_speed_rpm)) {
    return kNaN;
  }
  return std::pow(10.0, law.a + law.b_imax * std::log10(max_current_a) + law.c_speed * std::log10(no_load_speed_rpm));
}

std::string NoLoadLawText(const NoLoadLaw& law) {
  std::ostringstream s;
  s.precision(4);
  s << "log10(Io) = " << law.a << " + " << law.b_imax << "*log10(Imax) + " << law.c_speed
    << "*log10(Kv*V) (docs/noload-prior.md; " << law.motors << " catalog motors, scatter x" << law.p10_factor
    << "..x" << law.p90_factor << " p10..p90)";
  return s.str();
}

}  // namespace dynosize
