#include "identification/fit_rows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <Eigen/Dense>

#include "common/numbers.h"
#include "common/units.h"
#include "fit/linear_least_squares.h"
#include "fit/statistics.h"
#include "model/dc_motor.h"

namespace dynosize::identification {

const char* RowRejection(double omega_rad_s, double omega_max_rad_s, double min_speed_fraction,
                         bool has_throttle, double throttle, double min_throttle, double vdc_v,
                         bool speed_unknown) {
  // Written as !(a > b) so that a NaN reading is rejected, not used.
  if (!speed_unknown && !(omega_rad_s > min_speed_fraction * omega_max_rad_s)) {
    return "speed below min_speed_fraction of the largest";
  }
  if (has_throttle && throttle < min_throttle) return "throttle below min_throttle";
  if (!(vdc_v > 0.0)) return "vdc_v not positive";
  return nullptr;
}

std::vector<SpuriousSpeed> FindSpuriousSpeeds(const logs::SteadyTable& t, const std::vector<std::size_t>& rows,
                                              double assumed_throttle) {
  using logs::Column;
  std::vector<SpuriousSpeed> out;
  if (!t.Has(Column::kOmegaRadS) || !t.Has(Column::kVdcV) || !t.Has(Column::kIdcA)) return out;
  const bool thr = t.Has(Column::kThrottle);
  struct R {
    std::size_t row;
    double x1, x2, x3, w;
  };
  std::vector<R> d;
  for (std::size_t i : rows) {
    const double tr = thr ? t.Get(Column::kThrottle)[i] : assumed_throttle;
    const double v = t.Get(Column::kVdcV)[i], w = t.Get(Column::kOmegaRadS)[i], idc = t.Get(Column::kIdcA)[i];
    if (!(tr > 0.0) || !(v > 0.0) || !(w > 0.0) || !std::isfinite(idc)) continue;
    d.push_back({i, v * tr, idc / tr, v, w});
  }
  const std::size_t n = d.size();
  if (n < 8) return out;
  std::vector<double> wabs;
  for (const R& r : d) wabs.push_back(r.w);
  const double wfloor = 0.05 * fit::Median(wabs);
  auto rel = [&](const Eigen::Vector3d& c, const R& r) {
    const double pred = c[0] * r.x1 + c[1] * r.x2 + c[2] * r.x3;
    return (r.w - pred) / std::max(std::fabs(pred), wfloor);
  };
  auto med_sq = [&](const Eigen::Vector3d& c) {
    std::vector<double> r2;
    for (const R& r : d) r2.push_back(rel(c, r) * rel(c, r));
    return fit::Median(std::move(r2));
  };
  // Deterministic triples: all of them up to 2000, else a fixed linear congruential sequence.
  const std::size_t total = n * (n - 1) * (n - 2) / 6;
  const std::size_t trials = std::min<std::size_t>(total, 2000);
  unsigned long long state = 88172645463325252ULL;
  auto next = [&]() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return static_cast<std::size_t>(state % n);
  };
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  double best_med = std::numeric_limits<double>::infinity();
  std::size_t a = 0, b = 1, c = 2;
  for (std::size_t k = 0; k < trials; ++k) {
    if (total <= 2000) {
      if (k > 0 && ++c == n) {
        if (++b == n - 1) b = ++a + 1;
        c = b + 1;
      }
    } else {
      a = next();
      b = next();
      c = next();
      if (a == b || b == c || a == c) continue;
    }
    Eigen::Matrix3d m;
    Eigen::Vector3d y;
    for (int q = 0; q < 3; ++q) {
      const R& r = d[q == 0 ? a : q == 1 ? b : c];
      m.row(q) << r.x1, r.x2, r.x3;
      y[q] = r.w;
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
    if (!lu.isInvertible()) continue;
    const Eigen::Vector3d coef = lu.solve(y);
    if (!(coef[0] > 0.0)) continue;  // speed rises with the voltage (eq 48)
    const double md = med_sq(coef);
    if (md < best_med) {
      best_med = md;
      best = coef;
    }
  }
  if (!std::isfinite(best_med)) return out;
  const double s = 1.4826 * (1.0 + 5.0 / static_cast<double>(n - 3)) * std::sqrt(best_med);
  const double limit = std::max(kSpuriousSpeedSigmas * s, kSpuriousSpeedMinRel);
  // Only rows at or above the median command: below it an ESC's output is often not proportional
  // to the command (jmajew: 48 % of the full speed at a 20 % command), and a high reading there
  // cannot be told from the ESC's curve.
  std::vector<double> trs;
  for (const R& q : d) trs.push_back(q.x1 / q.x3);
  const double tr_median = fit::Median(trs);
  std::vector<std::pair<double, std::size_t>> bad;
  for (std::size_t k = 0; k < n; ++k) {
    if (d[k].x1 / d[k].x3 < tr_median) continue;
    // Only readings above the circuit's speed: eq 48 caps the speed at a given voltage, throttle
    // and current; a low reading can be a load or ESC effect (the fit's outlier screen sees it).
    const double r = rel(best, d[k]);
    if (r > limit) bad.push_back({r, k});
  }
  std::sort(bad.begin(), bad.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  bad.resize(std::min(bad.size(), n / 4));
  for (const auto& [r, k] : bad) {
    const R& q = d[k];
    out.push_back({q.row, q.w, best[0] * q.x1 + best[1] * q.x2 + best[2] * q.x3});
  }
  std::sort(out.begin(), out.end(), [](const SpuriousSpeed& x, const SpuriousSpeed& y) { return x.row < y.row; });
  return out;
}

std::string SpuriousSpeedText(const logs::SteadyTable& t, const SpuriousSpeed& s) {
  const std::size_t line = s.row < t.source_line.size() ? t.source_line[s.row] : 0;
  return (line > 0 ? "line " + std::to_string(line) : "row " + std::to_string(s.row)) + ": " +
         std::to_string(static_cast<long long>(std::llround(s.omega_rad_s / kRadPerSecPerRpm))) + " rpm (expected about " +
         std::to_string(static_cast<long long>(std::llround(s.expected_omega_rad_s / kRadPerSecPerRpm))) + " rpm)";
}

std::vector<double> ThrottleLevels(const std::vector<double>& throttle) {
  std::vector<double> lv;
  lv.reserve(throttle.size());
  for (double v : throttle) lv.push_back(std::round(v * 1000.0) / 1000.0);
  std::sort(lv.begin(), lv.end());
  lv.erase(std::unique(lv.begin(), lv.end()), lv.end());
  return lv;
}

double MedianMagnitude(const std::vector<double>& column, const std::vector<std::size_t>& rows) {
  std::vector<double> mag;
  mag.reserve(rows.size());
  for (std::size_t i : rows) mag.push_back(std::fabs(column[i]));
  return fit::Median(std::move(mag));
}

std::array<double, kMeasCount> MedianPercentScales(const logs::SteadyTable& t, const std::vector<std::size_t>& rows,
                                                   std::array<bool, kMeasCount>* measured) {
  std::array<double, kMeasCount> inv_scale{};
  for (int m = 0; m < kMeasCount; ++m) {
    if (!(*measured)[m]) continue;
    const double med = MedianMagnitude(t.Get(kMeasColumn[m]), rows);
    inv_scale[m] = med > 0.0 ? 100.0 / med : 0.0;
    if (!(med > 0.0)) (*measured)[m] = false;
  }
  return inv_scale;
}

OutlierSelection SelectOutlierRows(const std::vector<double>& rmax, const std::vector<double>& throttle,
                                   bool has_throttle, double threshold, double max_fraction,
                                   std::size_t min_kept) {
  const std::size_t n = rmax.size();
  std::vector<std::size_t> cand;
  for (std::size_t k = 0; k < n; ++k) {
    if (rmax[k] > threshold) cand.push_back(k);
  }
  std::sort(cand.begin(), cand.end(), [&](std::size_t a, std::size_t b) { return rmax[a] > rmax[b]; });
  OutlierSelection sel;
  sel.cap = static_cast<std::size_t>(std::floor(max_fraction * static_cast<double>(n)));
  std::map<long long, std::size_t> per_level;
  for (double tr : throttle) ++per_level[std::llround(tr * 1000.0)];
  for (std::size_t k : cand) {
    std::size_t& left = per_level[std::llround(throttle[k] * 1000.0)];
    if (sel.dropped.size() >= sel.cap || n - sel.dropped.size() < min_kept || (has_throttle && left <= 1)) {
      ++sel.spared;
      continue;
    }
    --left;
    sel.dropped.push_back(k);
  }
  return sel;
}

CircuitStart LinearCircuitStart(const std::vector<double>& current_a, const std::vector<double>& omega_rad_s,
                                const std::vector<double>& u_v) {
  const Eigen::Index n = static_cast<Eigen::Index>(u_v.size());
  Eigen::MatrixXd a(n, 2);
  Eigen::VectorXd b(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    a(k, 0) = current_a[static_cast<std::size_t>(k)];
    a(k, 1) = omega_rad_s[static_cast<std::size_t>(k)];
    b[k] = u_v[static_cast<std::size_t>(k)];
  }
  CircuitStart out;
  if (n == 0) return out;
  const LinearLeastSquaresResult sol = SolveLinearLeastSquares(a, b);
  out.r_total_ohm = sol.coefficients[0];
  out.ke_v_s_per_rad = sol.coefficients[1];
  if (!(out.ke_v_s_per_rad > 0.0)) out.ke_v_s_per_rad = b.cwiseQuotient(a.col(1)).maxCoeff();
  return out;
}

double ResistanceWithKeHeld(const std::vector<double>& current_a, const std::vector<double>& omega_rad_s,
                            const std::vector<double>& u_v, double ke_v_s_per_rad) {
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < u_v.size(); ++k) {
    num += current_a[k] * (u_v[k] - ke_v_s_per_rad * omega_rad_s[k]);
    den += current_a[k] * current_a[k];
  }
  return den > 0.0 ? num / den : 0.0;
}

double TorquePerAmpereVsLabel(const logs::SteadyTable& t, double kv_label_rpm_per_v) {
  using logs::Column;
  if (!t.Has(Column::kTorqueNm) || !t.Has(Column::kIdcA) || !t.Has(Column::kThrottle) || !(kv_label_rpm_per_v > 0.0)) {
    return kNaN;
  }
  const auto& tr = t.Get(Column::kThrottle);
  const auto& q = t.Get(Column::kTorqueNm);
  const auto& idc = t.Get(Column::kIdcA);
  double top = 0.0;
  for (double x : tr) top = std::max(top, x);
  if (!(top >= 0.95)) return kNaN;
  DcMotor label;
  label.kv_rpm_per_v = kv_label_rpm_per_v;
  const double kt_dc = label.kt_nm_per_a();  // 60/(2*pi*Kv)
  std::vector<double> ratio;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (std::fabs(tr[i] - top) > 1e-3 || !(q[i] > 0.0) || !(idc[i] > 0.0)) continue;
    ratio.push_back(q[i] / (kt_dc * idc[i]));
  }
  return ratio.empty() ? kNaN : fit::Median(std::move(ratio));
}

}  // namespace dynosize::identification
