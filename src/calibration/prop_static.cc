#include "calibration/prop_static.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "common/error.h"
#include "common/units.h"
#include "model/physics.h"

namespace dynosize::calibration {

using logs::Column;

PropStaticTable FitPropStatic(const logs::SteadyTable& t, const PropStaticOptions& o) {
  const std::string file = t.file.empty() ? std::string("log") : t.file;
  if (!(o.diameter_m > 0.0)) throw UsageError("--prop-diameter-in: must be > 0");
  for (Column c : {Column::kThrustN, Column::kTorqueNm, Column::kOmegaRadS}) {
    if (!t.Has(c)) {
      throw DataError(file + ": column " + std::string(logs::ColumnName(c)) +
                      " is absent: a static propeller entry needs thrust, torque and speed");
    }
  }
  const auto& w = t.Get(Column::kOmegaRadS);
  const auto& thrust = t.Get(Column::kThrustN);
  const auto& q = t.Get(Column::kTorqueNm);
  double wmax = 0.0;
  for (double x : w) wmax = std::max(wmax, x);
  std::vector<std::size_t> rows;
  PropStaticTable out;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (w[i] > o.min_speed_fraction * wmax && thrust[i] > 0.0 && q[i] > 0.0) {
      rows.push_back(i);
    } else {
      ++out.rows_dropped;
    }
  }
  std::sort(rows.begin(), rows.end(), [&](std::size_t a, std::size_t b) { return w[a] < w[b]; });
  const double d = o.diameter_m;
  std::size_t k = 0;
  while (k < rows.size()) {
    // Rows within 1 % of the group's first speed form one table point (mean of each coefficient).
    std::size_t j = k;
    double sw = 0.0, sct = 0.0, scp = 0.0;
    while (j < rows.size() && w[rows[j]] <= w[rows[k]] * 1.01) {
      const std::size_t i = rows[j];
      const double n = w[i] / (2.0 * kPi);  // rev/s
      const double p_w = q[i] * w[i];
      const double fm = FigureOfMerit(thrust[i], p_w, d, o.rho_kg_m3);
      if (fm > 1.0) {
        std::ostringstream m;
        m.precision(3);
        m << file << ": line " << (i < t.source_line.size() ? t.source_line[i] : 0) << ": thrust " << thrust[i]
          << " N at " << p_w << " W shaft power gives a figure of merit " << fm
          << " > 1 (momentum theory, model.md section 10): check the thrust/torque calibration or --prop-diameter-in";
        throw DataError(m.str());
      }
      out.max_figure_of_merit = std::max(out.max_figure_of_merit, fm);
      sw += RadPerSecToRpm(w[i]);
      sct += thrust[i] / (o.rho_kg_m3 * n * n * std::pow(d, 4));
      scp += p_w / (o.rho_kg_m3 * n * n * n * std::pow(d, 5));
      ++j;
    }
    const double c = static_cast<double>(j - k);
    out.rpm.push_back(sw / c);
    out.ct.push_back(sct / c);
    out.cp.push_back(scp / c);
    out.rows_used += j - k;
    k = j;
  }
  if (out.rpm.size() < 3) {
    throw DataError(file + ": " + std::to_string(out.rpm.size()) +
                    " speed point(s) with positive thrust and torque: a static propeller table needs at least 3");
  }
  return out;
}

}  // namespace dynosize::calibration
