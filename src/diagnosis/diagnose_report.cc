// DiagnoseResult::FullReport: the readable report of a diagnosis.
#include <iomanip>
#include <sstream>

#include "diagnosis/diagnose.h"

namespace dynosize::diagnosis {

std::string DiagnoseResult::FullReport() const {
  std::ostringstream s;
  s << std::setprecision(4);
  s << "diagnose " << file << " (" << mode << "): " << points_used << " points";
  if (!outlier_rows.empty()) s << ", " << outlier_rows.size() << " outlier(s) left out";
  s << "\nbase model fitted on the log, free: ";
  for (std::size_t j = 0; j < base_free_parameters.size(); ++j) s << (j ? ", " : "") << base_free_parameters[j];
  s << "\n\nWhat the first-order model gets wrong (cross-validated, held-out rows):\n";
  for (const auto& c : baseline_cv) {
    s << "  " << std::left << std::setw(12) << logs::ColumnName(c.column) << std::right << " rmse "
      << c.rmse << " (" << c.rmse_percent << " %), " << c.points << " points\n";
  }
  s << "  all columns: " << baseline_cv_rms_percent << " % rms (percent of each measured value)\n";
  if (!worst_points.empty()) {
    s << "  worst points:\n";
    for (const auto& w : worst_points) {
      s << "    line " << w.source_line << " " << logs::ColumnName(w.column) << ": measured "
        << w.measured << ", predicted " << w.predicted << " (" << std::showpos << w.error_percent
        << std::noshowpos << " %)\n";
    }
  }
  bool any_trend = false;
  for (const auto& tr : residual_trends) {
    if (!tr.structured) continue;
    if (!any_trend) s << "  residual structure (quadratic trend of the error, R^2, p):\n";
    any_trend = true;
    s << "    " << logs::ColumnName(tr.column) << " error vs " << tr.variable << ": R^2 " << tr.r2
      << ", p " << tr.p_value << ", linear change " << std::showpos << tr.slope_percent_per_range
      << std::noshowpos << " % over the range\n";
  }
  if (!any_trend) s << "  no residual structure against the logged variables\n";
  s << "\nFindings:\n";
  if (findings.empty()) {
    if (any_trend) {
      s << "  none: the residuals have structure (above) that no candidate explains";
      std::string closest;
      for (const auto& c : last_step_scores) {
        if (c.p_value < 1e-3 && !c.note.empty()) closest += std::string(closest.empty() ? "" : "; ") + CauseId(c.cause) + " (" + c.note + ")";
      }
      if (!closest.empty()) s << "; rejected: " << closest;
      s << "\n";
    } else if (baseline_cv_rms_percent <= kNoiseLevelPercent && baseline_cv_failed_folds == 0) {
      s << "  none: nothing significant beyond noise\n";
    } else {
      s << "  none found, but the first-order model misses held-out rows by " << baseline_cv_rms_percent
        << " % rms" << (baseline_cv_failed_folds > 0 ? " (" + std::to_string(baseline_cv_failed_folds) +
                                                          " fold(s) could not be fitted)" : std::string())
        << ": this is not noise; the model does not follow this log\n";
    }
  }
  int k = 0;
  for (const auto& f : findings) {
    s << "  " << ++k << ". " << CauseId(f.cause) << ": " << f.description << "\n     ";
    for (const auto& [name, val] : f.parameters) {
      s << name << " = " << val;
      const auto e = f.stderrs.find(name);
      if (e != f.stderrs.end() && std::isfinite(e->second)) s << " +- " << e->second;
      s << "  ";
    }
    s << "\n     gain " << f.gain_percent << " % (CV rms), F " << f.f_statistic << ", p "
      << f.p_value << ", dAICc " << f.delta_aicc;
    if (f.max_abs_correlation > 0.0) {
      s << ", max |corr| " << f.max_abs_correlation << " with " << f.most_correlated_with;
    }
    s << "\n     after:";
    for (const auto& c : f.cv_after) s << " " << logs::ColumnName(c.column) << " " << c.rmse_percent << " %";
    s << "\n";
  }
  for (const auto& a : ambiguous) {
    s << "  ambiguous: " << a.reason << "\n    to separate them: " << a.measurement << "\n";
  }
  for (const auto& rt : remaining_trends) {
    s << "  remaining trend of the extended model (held out), " << logs::ColumnName(rt.column) << ": "
      << rt.attribution.text << "\n";
    if (!rt.attribution.measurement.empty()) s << "    to separate them: " << rt.attribution.measurement << "\n";
  }
  for (const auto& nt : not_testable) {
    s << "  not testable: " << CauseId(nt.cause) << " (" << nt.not_testable_reason << ")\n";
  }
  s << "\nExtended model (cross-validated):";
  for (const auto& c : extended_cv) s << " " << logs::ColumnName(c.column) << " " << c.rmse_percent << " %";
  s << "; all columns " << extended_cv_rms_percent << " % (baseline " << baseline_cv_rms_percent << " %)\n";
  for (const auto& r : outlier_reasons) s << "dropped " << r << "\n";
  for (const auto& w : warnings) s << "warning: " << w << "\n";
  s << verdict.summary << "\n";
  if (!verdict.advice.empty()) s << "next: " << verdict.advice << "\n";
  return s.str();
}

}  // namespace dynosize::diagnosis
