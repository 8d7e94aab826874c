// Figures of a calibration (dynosize calibrate --plot DIR): for each measured column the fit
// compares, measured vs predicted (with the 1:1 line), and the residuals in percent against
// throttle (when the log has one) and against speed. PNG + gnuplot script each (gnuplot.h).
#pragma once

#include <string>
#include <vector>

#include "calibration/calibrate.h"
#include "logs/steady_table.h"

namespace dynosize {

// Writes the figures into `dir` (created); returns the PNG paths. CantCreateError on failure.
std::vector<std::string> WriteCalibrationFigures(const std::string& dir, const logs::SteadyTable& table,
                                                 const calibration::CalibrationResult& result);

}  // namespace dynosize
