// A static propeller entry (catalog "static_table": CT, CP vs rpm, J = 0) from the steady rows of
// a thrust-stand log that measured thrust and torque.
//
//   CT = T / (rho * n^2 * D^4),   CP = P / (rho * n^3 * D^5),   P = Q * omega,  n = rpm/60
// (UIUC definitions, as src/prop/prop_model.h and catalog/README.md use them). Rows within 1 % of
// each other in speed are averaged into one table point so that the rpm column increases strictly.
// Every point must satisfy momentum theory: FM = T^1.5/(P*sqrt(2*rho*A)) <= 1 (docs/model.md section
// 10, model/physics.h FigureOfMerit); a point that beats it means a thrust or torque calibration
// error and the table is refused.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "logs/steady_table.h"

namespace dynosize::calibration {

struct PropStaticOptions {
  double diameter_m = 0.0;  // > 0
  double pitch_m = 0.0;     // 0: not stated
  // Air density of the test. Stand logs rarely record it: ISA sea level (15 C) is assumed and
  // the entry's provenance says so. CT and CP scale with 1/rho.
  double rho_kg_m3 = 1.225;
  double min_speed_fraction = 0.05;  // rows below this fraction of the top speed are left out
};

struct PropStaticTable {
  std::vector<double> rpm, ct, cp;  // rpm strictly increasing
  std::size_t rows_used = 0;
  std::size_t rows_dropped = 0;  // no speed, thrust or torque <= 0, or below min_speed_fraction
  double max_figure_of_merit = 0.0;
};

// Throws DataError naming the file when the log has no thrust_n or torque_nm column, when fewer
// than 3 table points remain, or when a point has FM > 1 (row and value in the message).
PropStaticTable FitPropStatic(const logs::SteadyTable& table, const PropStaticOptions& options);

}  // namespace dynosize::calibration
