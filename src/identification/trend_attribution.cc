#include "identification/trend_attribution.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "fit/statistics.h"

namespace dynosize::identification {
namespace {

// Thermal time constants tried for the heating signature: a small outrunner's winding (tens of
// seconds) to a large motor's stator (many minutes).
constexpr double kTauGridS[] = {10.0, 30.0, 100.0, 300.0, 1000.0};

double Correlation(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n;
  const double my = std::accumulate(y.begin(), y.end(), 0.0) / n;
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxx > 0.0 && syy > 0.0 ? sxy / std::sqrt(sxx * syy) : 0.0;
}

// The residual's linear trend against x: R^2, the uncorrected p value of the slope (F(1, n-2))
// and the change over x's range.
TrendSignature LinearTrend(const std::string& mechanism, const std::vector<double>& x, const std::vector<double>& y) {
  TrendSignature s;
  s.mechanism = mechanism;
  const double r = Correlation(x, y);
  s.r2 = r * r;
  const double df2 = static_cast<double>(x.size()) - 2.0;
  s.p_value = s.r2 < 1.0 ? fit::FDistributionUpperTail(s.r2 / (1.0 - s.r2) * df2, 1.0, df2) : 0.0;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  double sx = 0.0, sy = 0.0;
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
  const double my = std::accumulate(y.begin(), y.end(), 0.0) / static_cast<double>(y.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += (x[i] - mx) * (x[i] - mx);
    sy += (x[i] - mx) * (y[i] - my);
  }
  s.change_percent = sx > 0.0 ? sy / sx * (*hi - *lo) : 0.0;
  return s;
}

// p value of x1 beyond x2: the F test of y ~ 1 + x2 + x2^2 + x1 against y ~ 1 + x2 + x2^2 (what
// x1 explains that no smooth function of x2 can: a curvature alone - a loss growing with the
// square of the speed, heat lagging the current - is not told from the other mechanism).
double PartialPValue(const std::vector<double>& x1, const std::vector<double>& x2, const std::vector<double>& y) {
  const Eigen::Index n = static_cast<Eigen::Index>(y.size());
  if (n < 6) return 1.0;
  const auto [lo, hi] = std::minmax_element(x2.begin(), x2.end());
  const auto [lo1, hi1] = std::minmax_element(x1.begin(), x1.end());
  const double span = *hi - *lo, span1 = *hi1 - *lo1;
  if (!(span > 0.0) || !(span1 > 0.0)) return 1.0;
  Eigen::MatrixXd a(n, 4);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    const double u = (x2[k] - *lo) / span;
    a(i, 0) = 1.0;
    a(i, 1) = u;
    a(i, 2) = u * u;
    a(i, 3) = (x1[k] - *lo1) / span1;
    v[i] = y[k];
  }
  const auto sse = [&](Eigen::Index cols) {
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a.leftCols(cols));
    return std::pair<double, Eigen::Index>((a.leftCols(cols) * qr.solve(v) - v).squaredNorm(), qr.rank());
  };
  const auto [sse_r, rank_r] = sse(3);
  const auto [sse_f, rank_f] = sse(4);
  if (rank_f <= rank_r) return 1.0;  // x1 is a function of x2 here
  const double df2 = static_cast<double>(n - rank_f);
  if (!(df2 > 0.0)) return 1.0;
  if (!(sse_f > 0.0)) return 0.0;
  return fit::FDistributionUpperTail(std::max(sse_r - sse_f, 0.0) / (sse_f / df2), 1.0, df2);
}

// The copper loss the winding has accumulated at each row: I^2 through a first-order lag of time
// constant tau_s along the log's time, from a cold start. Each row is the end of a step run at
// its own current since the row before (the first step as long as the median step).
std::vector<double> AccumulatedHeat(const std::vector<double>& time_s, const std::vector<double>& current_a,
                                    double tau_s) {
  std::vector<std::size_t> order(time_s.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return time_s[a] < time_s[b]; });
  std::vector<double> steps;
  for (std::size_t j = 1; j < order.size(); ++j) steps.push_back(time_s[order[j]] - time_s[order[j - 1]]);
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  const double first_step = steps.empty() ? 0.0 : steps[steps.size() / 2];
  std::vector<double> heat(time_s.size(), 0.0);
  double h = 0.0;
  for (std::size_t j = 0; j < order.size(); ++j) {
    const std::size_t k = order[j];
    const double dt = j == 0 ? first_step : time_s[k] - time_s[order[j - 1]];
    const double a = std::exp(-std::max(dt, 0.0) / tau_s);
    h = a * h + (1.0 - a) * current_a[k] * current_a[k];
    heat[k] = h;
  }
  return heat;
}

const char* Cause(const std::string& mechanism) {
  if (mechanism == "speed") return "a loss that grows with speed beyond the model's (iron, eddy-current, windage)";
  if (mechanism == "heating") return "the winding warming over the run (Rm rising with the copper loss it has accumulated)";
  return "the ESC changing with the command (its DC/AC current ratio or voltage gain)";
}

const char* Follows(const std::string& mechanism) {
  if (mechanism == "speed") return "the shaft speed";
  if (mechanism == "heating") return "the copper loss accumulated over the run";
  return "the throttle command";
}

std::string Separation(const std::string& a, const std::string& b) {
  auto is = [&](const char* x, const char* y) { return (a == x && b == y) || (a == y && b == x); };
  if (is("speed", "heating")) {
    return "run the steps down after running them up (or in random order), or log the winding temperature "
           "(temp_c): accumulated heat follows the run's history, a speed loss only the speed";
  }
  if (is("speed", "command")) {
    return "repeat the throttle steps with a second propeller or at a second supply voltage: the speed "
           "changes at the same command";
  }
  return "repeat the sweep after a cool-down or run the steps in random order: accumulated heat follows the "
         "run's history, the ESC only the command";
}

}  // namespace

TrendAttribution AttributeTrend(const TrendRows& rows, double alpha) {
  TrendAttribution out;
  const std::size_t n = rows.measured.size();
  const bool has_time = rows.time_s.size() == n;
  const bool has_tr = rows.throttle.size() == n;
  std::vector<double> magnitudes;
  for (double m : rows.measured) {
    if (std::isfinite(m)) magnitudes.push_back(std::fabs(m));
  }
  if (magnitudes.empty()) return out;
  std::nth_element(magnitudes.begin(), magnitudes.begin() + static_cast<std::ptrdiff_t>(magnitudes.size() / 2),
                   magnitudes.end());
  const double floor = 0.05 * magnitudes[magnitudes.size() / 2];
  std::vector<double> y, w, i, t, tr;
  for (std::size_t k = 0; k < n; ++k) {
    const double den = std::max(std::fabs(rows.measured[k]), floor);
    const double e = (rows.predicted[k] - rows.measured[k]) / den * 100.0;
    const bool ok = std::isfinite(e) && den > 0.0 && std::isfinite(rows.omega_rad_s[k]) &&
                    std::isfinite(rows.current_a[k]) && (!has_time || std::isfinite(rows.time_s[k])) &&
                    (!has_tr || std::isfinite(rows.throttle[k]));
    if (!ok) continue;
    y.push_back(e);
    w.push_back(rows.omega_rad_s[k]);
    i.push_back(rows.current_a[k]);
    if (has_time) t.push_back(rows.time_s[k]);
    if (has_tr) tr.push_back(rows.throttle[k]);
  }
  if (y.size() < 6) return out;
  struct Candidate {
    TrendSignature sig;
    std::vector<double> x;
  };
  std::vector<Candidate> c;
  c.push_back({LinearTrend("speed", w, y), w});
  const bool tr_varies = has_tr && *std::max_element(tr.begin(), tr.end()) > *std::min_element(tr.begin(), tr.end());
  if (tr_varies) c.push_back({LinearTrend("command", tr, y), tr});
  int tests = static_cast<int>(c.size());
  if (has_time) {
    Candidate best;
    for (double tau : kTauGridS) {
      std::vector<double> h = AccumulatedHeat(t, i, tau);
      TrendSignature s = LinearTrend("heating", h, y);
      s.tau_s = tau;
      if (best.x.empty() || s.r2 > best.sig.r2) best = {s, std::move(h)};
      ++tests;
    }
    c.push_back(std::move(best));
  }
  for (Candidate& x : c) x.sig.p_value = std::min(1.0, x.sig.p_value * tests);
  std::sort(c.begin(), c.end(), [](const Candidate& a, const Candidate& b) { return a.sig.r2 > b.sig.r2; });
  for (const Candidate& x : c) out.signatures.push_back(x.sig);
  const TrendSignature& top = c.front().sig;
  out.structured = top.p_value < alpha && top.r2 >= 0.2 && std::fabs(top.change_percent) >= kMinTrendChangePercent;
  if (!out.structured) return out;
  // The rival: the other signature that leaves the least to the strongest (the largest p value of
  // the strongest beyond it). Named only when the strongest explains what every rival cannot.
  double worst_p = 0.0;
  for (std::size_t j = 1; j < c.size(); ++j) {
    const double p = std::min(1.0, PartialPValue(c.front().x, c[j].x, y) * tests);
    if (out.rival.empty() || p > worst_p) {
      worst_p = p;
      out.rival = c[j].sig.mechanism;
      out.rival_correlation = std::fabs(Correlation(c.front().x, c[j].x));
    }
  }
  out.separable = out.rival.empty() || worst_p < alpha;
  std::ostringstream s;
  s << std::setprecision(3) << "the residual follows " << Follows(top.mechanism) << " (R^2 " << top.r2 << ", "
    << std::showpos << top.change_percent << std::noshowpos << " % over its range";
  if (top.mechanism == "heating") s << ", time constant about " << top.tau_s << " s";
  s << ")";
  if (out.separable) {
    s << ": " << Cause(top.mechanism);
    if (!out.rival.empty()) {
      s << " (beyond " << Follows(out.rival) << ", |r| " << out.rival_correlation << " with it in this log)";
    }
  } else {
    s << ", but " << Follows(out.rival) << " explains it as well in this log (|r| " << out.rival_correlation
      << "): it cannot tell " << Cause(top.mechanism) << " from " << Cause(out.rival);
    out.measurement = Separation(top.mechanism, out.rival);
  }
  out.text = s.str();
  return out;
}

}  // namespace dynosize::identification
