// CalibrationResult::BriefReport and FullReport.
#include <cmath>
#include <iomanip>
#include <sstream>

#include "calibration/calibrate.h"
#include "common/text_format.h"

namespace dynosize::calibration {

namespace {

// A standard error for the table: "-" where there is none (held parameters, bounds).
std::string ErrText(double v) { return SignificantTextOr(v, "-", 3); }

}  // namespace

std::string CalibrationResult::BriefReport() const {
  if (!solve_called) return message;
  std::ostringstream s;
  s << std::setprecision(4) << "calibrate (" << mode << "): " << (converged ? "converged" : "NOT converged")
    << ", " << points_used << " points (" << points_dropped << " dropped), KE " << motor.ke_v_s_per_rad
    << " V*s/rad, R " << r_total_ohm << " ohm";
  for (const auto& f : fit) s << ", " << logs::ColumnName(f.column) << " rmse " << f.rmse_percent << " %";
  return s.str();
}

std::string CalibrationResult::FullReport() const {
  if (!solve_called) return message + "\n";
  std::ostringstream s;
  s << BriefReport() << "\n" << message << "\n\n";
  s << std::left << std::setw(16) << "parameter" << std::right << std::setw(14) << "value" << std::setw(14)
    << "std error" << "  fitted ident  note\n";
  for (int k = 0; k < kBaseParamCount; ++k) {
    const auto& e = params[k];
    s << std::left << std::setw(16) << ParamName(static_cast<Param>(k)) << std::right << std::setw(14)
      << std::setprecision(6) << e.value << std::setw(14) << ErrText(e.standard_error) << "  "
      << std::left << std::setw(7) << (e.fitted ? "yes" : "no") << std::setw(6)
      << (e.identifiable ? "yes" : "NO") << e.note << std::right << "\n";
  }
  s << std::left << std::setw(16) << "r_total_ohm" << std::right << std::setw(14) << std::setprecision(6)
    << r_total_ohm << std::setw(14) << ErrText(r_total_standard_error) << "\n";
  s << "condition (unit-scaled Jacobian): " << std::setprecision(3) << condition_number << "\n\n";
  for (const auto& f : fit) {
    s << "  " << std::left << std::setw(12) << logs::ColumnName(f.column) << std::right << " n " << f.points
      << "  rmse " << std::setprecision(4) << f.rmse << " (" << f.rmse_percent << " %), median |err| "
      << f.median_abs_percent << " %\n";
  }
  for (const auto& d : dropped) s << "  dropped " << d.count << ": " << d.reason << "\n";
  for (const auto& d : dropped_rows) s << "    line " << d.source_line << ": " << d.reason << "\n";
  for (const auto& u : unidentifiable_directions) s << "  unidentifiable: " << u << "\n";
  for (const auto& w : warnings) s << "  warning: " << w << "\n";
  return s.str();
}

}  // namespace dynosize::calibration
