// Figures of stand-table work (PNG + gnuplot script each, report/gnuplot.h):
//   thrust_current_vs_throttle.png  `simulate --prop P --vdc V --plot DIR`: thrust and DC current
//                                   vs throttle of the manufacturer-style table (stand/throttle_table.h)
//   stand_measured_vs_predicted.png `validate-stand --plot DIR`: measured vs predicted per column
//                                   (current and thrust at the measured rpm, rpm and current from
//                                   the throttle), dynosize and the plain DC model side by side,
//                                   with the 1:1 line and +-10 % lines
#pragma once

#include <string>
#include <vector>

#include "stand/stand.h"
#include "stand/throttle_table.h"

namespace dynosize {

// Writes DIR/thrust_current_vs_throttle.png (DIR created); returns its path.
std::string WriteThrottleTableFigure(const std::vector<ThrottleTableRow>& rows, const std::string& title,
                                     const std::string& dir);

// Writes DIR/stand_measured_vs_predicted.png (DIR created); returns its path, or "" when no
// column has both a measurement and predictions.
std::string WriteStandFigure(const stand::StandTable& table, const stand::StandResult& result,
                             const std::string& title, const std::string& dir);

}  // namespace dynosize
