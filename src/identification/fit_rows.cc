#include "identification/fit_rows.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "fit/statistics.h"

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

}  // namespace dynosize::identification
