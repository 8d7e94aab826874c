#include "diagnosis/baseline.h"

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/units.h"
#include "diagnosis/candidates.h"
#include "fit/statistics.h"

namespace dynosize::diagnosis::internal {

using logs::Column;
using logs::SteadyTable;
using fit::FDistributionUpperTail;

namespace {

// A quadratic trend of the held-out percent errors ys against the variable xs; nullopt when
// there are fewer than 6 points or xs does not vary. Structured: p < alpha and r2 >= 0.2.
std::optional<ResidualTrend> FitTrend(const std::vector<double>& xs, const std::vector<double>& ys, double alpha) {
  if (xs.size() < 6) return std::nullopt;
  const auto [lo_it, hi_it] = std::minmax_element(xs.begin(), xs.end());
  const double lo = *lo_it, span = *hi_it - *lo_it;
  if (!(span > 0.0)) return std::nullopt;
  const Eigen::Index nn = static_cast<Eigen::Index>(xs.size());
  Eigen::MatrixXd a(nn, 3);
  Eigen::VectorXd y(nn);
  for (Eigen::Index i = 0; i < nn; ++i) {
    const double u = (xs[static_cast<std::size_t>(i)] - lo) / span;
    a(i, 0) = 1.0;
    a(i, 1) = u;
    a(i, 2) = u * u;
    y[i] = ys[static_cast<std::size_t>(i)];
  }
  const Eigen::VectorXd c3 = a.colPivHouseholderQr().solve(y);
  const double mean = y.mean();
  const double sst = (y.array() - mean).square().sum();
  const double ssr = (a * c3 - y).squaredNorm();
  ResidualTrend tr;
  tr.r2 = sst > 0.0 ? 1.0 - ssr / sst : 0.0;
  const double df2 = static_cast<double>(nn) - 3.0;
  tr.p_value = tr.r2 < 1.0 ? FDistributionUpperTail((tr.r2 / 2.0) / ((1.0 - tr.r2) / df2), 2.0, df2) : 0.0;
  const Eigen::VectorXd c2 = a.leftCols(2).colPivHouseholderQr().solve(y);
  tr.slope_percent_per_range = c2[1];
  tr.structured = tr.p_value < alpha && tr.r2 >= 0.2;
  return tr;
}

}  // namespace

// Held-out predictions of cv as full table columns (NaN on rows not used).
void CvTable(const Data& d, std::size_t table_rows, const std::vector<std::size_t>& used, const CvOut& cv,
             std::map<Column, std::vector<double>>* out) {
  for (int m = 0; m < kMeasCount; ++m) {
    if (!d.measured[m]) continue;
    std::vector<double> col(table_rows, kNaN);
    for (std::size_t k : used) col[d.table_row[k]] = cv.pred[m][k];
    (*out)[kMeasColumn[m]] = col;
  }
}

// Stage 7: the first-order model fitted and cross-validated.
Step FitBaseline(const SteadyTable& t, const Data& d, const std::vector<std::size_t>& used, const Folds& folds,
                 const Model& base, const std::vector<double>& knees, DiagnoseResult* res) {
  Step cur;
  cur.model = base;
  cur.fit = FitModel(d, used, cur.model, LossType::kTrivial, 1.0);
  if (!cur.fit.ok) {
    throw DataError(res->file + ": the first-order model could not be fitted to the log (no finite "
                    "prediction at the start values): check the units of the columns");
  }
  cur.model.values = cur.fit.values;
  if (BaseAtBound(cur.model, cur.fit.values)) {
    std::string which;
    for (int s = 0; s < kSlotCount; ++s) {
      if (!id::IsFirstOrderParam(s) || !cur.model.free[s]) continue;
      if (SlotAtBound(cur.model, cur.fit.values, s)) which += (which.empty() ? "" : ", ") + std::string(SlotName(s));
    }
    res->warnings.push_back("first-order fit has " + which +
                            " on a physical bound: the first-order model cannot follow this log");
  }
  cur.cv = CrossValidate(d, used, folds.fold_of, folds.count, cur.model, cur.fit, knees);
  res->cv_folds = folds.count;
  res->leave_one_out = folds.count == static_cast<int>(d.rows());
  res->baseline_cv_failed_folds = cur.cv.failed_folds;
  ToParams(d, cur.fit.values, &res->base_motor, &res->base_esc);
  res->baseline_cv = ColumnErrors(d, used, cur.cv);
  res->baseline_cv_rms_percent = cur.cv.rms_percent;
  CvTable(d, t.rows(), used, cur.cv, &res->baseline_cv_prediction);
  return cur;
}

// Stage 8a: the 5 worst held-out points of the baseline.
std::vector<WorstPoint> WorstPoints(const SteadyTable& t, const Data& d, const std::vector<std::size_t>& used,
                                    const CvOut& cv) {
  std::vector<WorstPoint> all;
  for (std::size_t k : used) {
    for (int tt = d.term_begin[k]; tt < d.term_begin[k + 1]; ++tt) {
      const Term& term = d.terms[tt];
      const double p = cv.pred[term.meas][k];
      if (!std::isfinite(p) || term.value == 0.0) continue;
      WorstPoint w;
      w.row = d.table_row[k];
      w.source_line = t.source_line[w.row];
      w.column = kMeasColumn[term.meas];
      w.measured = term.value;
      w.predicted = p;
      w.error_percent = (p - term.value) / term.value * 100.0;
      all.push_back(w);
    }
  }
  std::sort(all.begin(), all.end(), [](const WorstPoint& a, const WorstPoint& b) {
    return std::fabs(a.error_percent) > std::fabs(b.error_percent);
  });
  if (all.size() > 5) all.resize(5);
  return all;
}

namespace {

// The held-out percent error of measured column m on the used rows that have one: the fit rows
// in rows, the errors in ys.
void HeldOutErrors(const Data& d, const std::vector<std::size_t>& used, const CvOut& cv, int m,
                   std::vector<std::size_t>* rows, std::vector<double>* ys) {
  for (std::size_t k : used) {
    const double pr = cv.pred[m][k];
    double meas = kNaN;
    for (int tt = d.term_begin[k]; tt < d.term_begin[k + 1]; ++tt) {
      if (d.terms[tt].meas == m) meas = d.terms[tt].value;
    }
    if (!std::isfinite(pr) || !std::isfinite(meas) || meas == 0.0) continue;
    rows->push_back(k);
    ys->push_back((pr - meas) / meas * 100.0);
  }
}

}  // namespace

// Stage 8b: residual structure of the baseline: the held-out percent error of every predicted
// column against each logged variable.
std::vector<ResidualTrend> ResidualTrends(const SteadyTable& t, const Prepared& p,
                                          const std::vector<std::size_t>& used, const CvOut& cv, double alpha) {
  const Data& d = p.d;
  struct Var {
    const char* name;
    Column col;
  };
  std::vector<Var> vars;
  if (p.has_tr) vars.push_back({"throttle", Column::kThrottle});
  vars.push_back({"rpm", Column::kOmegaRadS});
  if (d.measured[kMIrms]) vars.push_back({"current_a", Column::kIrmsA});
  else if (d.measured[kMIdc]) vars.push_back({"current_a", Column::kIdcA});
  vars.push_back({"vdc_v", Column::kVdcV});
  if (p.has_q) vars.push_back({"torque_nm", Column::kTorqueNm});
  if (t.Has(Column::kTimeS)) vars.push_back({"time_s", Column::kTimeS});
  if (t.Has(Column::kTempC)) vars.push_back({"temp_c", Column::kTempC});
  std::vector<ResidualTrend> trends;
  for (int m = 0; m < kMeasCount; ++m) {
    if (!d.measured[m]) continue;
    std::vector<std::size_t> rows;
    std::vector<double> ys;
    HeldOutErrors(d, used, cv, m, &rows, &ys);
    for (const Var& var : vars) {
      std::vector<double> xs;
      for (std::size_t k : rows) xs.push_back(t.Get(var.col)[d.table_row[k]]);
      std::optional<ResidualTrend> tr = FitTrend(xs, ys, alpha);
      if (!tr) continue;
      tr->variable = var.name;
      tr->column = kMeasColumn[m];
      trends.push_back(*tr);
    }
  }
  return trends;
}

std::vector<RemainingTrend> RemainingTrends(const SteadyTable& t, const Prepared& p,
                                            const std::vector<std::size_t>& used, const CvOut& cv, double alpha) {
  const Data& d = p.d;
  const Column current = d.measured[kMIrms] ? Column::kIrmsA : Column::kIdcA;
  if (!t.Has(current)) return {};
  std::vector<RemainingTrend> out;
  for (int m = 0; m < kMeasCount; ++m) {
    if (!d.measured[m]) continue;
    identification::TrendRows tr;
    for (std::size_t k : used) {
      const std::size_t row = d.table_row[k];
      const double meas = t.Get(kMeasColumn[m])[row];
      if (!std::isfinite(cv.pred[m][k]) || !std::isfinite(meas)) continue;
      tr.predicted.push_back(cv.pred[m][k]);
      tr.measured.push_back(meas);
      tr.omega_rad_s.push_back(t.Get(Column::kOmegaRadS)[row]);
      tr.current_a.push_back(t.Get(current)[row]);
      if (t.Has(Column::kTimeS)) tr.time_s.push_back(t.Get(Column::kTimeS)[row]);
      if (p.has_tr) tr.throttle.push_back(d.tr[k]);
    }
    RemainingTrend r;
    r.column = kMeasColumn[m];
    r.attribution = identification::AttributeTrend(tr, alpha);
    if (r.attribution.structured) out.push_back(std::move(r));
  }
  return out;
}

}  // namespace dynosize::diagnosis::internal
