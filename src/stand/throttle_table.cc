#include "stand/throttle_table.h"

#include "common/units.h"
#include "model/physics.h"

namespace dynosize {

double GramsPerWatt(double thrust_n, double pdc_w) {
  return pdc_w > 0.0 ? thrust_n / kNewtonPerGramForce / pdc_w : 0.0;
}

std::vector<ThrottleTableRow> PropThrottleTable(const Drive& drive, const PropModel& prop, double vdc_v,
                                                double rho_kg_m3, int steps) {
  std::vector<ThrottleTableRow> rows;
  rows.reserve(static_cast<std::size_t>(steps));
  for (int k = 1; k <= steps; ++k) {
    ThrottleTableRow r;
    r.throttle = static_cast<double>(k) / steps;
    r.point = SolveDriveWithProp(drive, prop, vdc_v, r.throttle, rho_kg_m3);
    r.thrust_n = r.point.prop.thrust_n;
    r.g_per_w = GramsPerWatt(r.thrust_n, r.point.drive.pdc_w);
    r.figure_of_merit = FigureOfMerit(r.thrust_n, r.point.prop.power_w, prop.diameter_m(), rho_kg_m3);
    rows.push_back(std::move(r));
  }
  return rows;
}

}  // namespace dynosize
