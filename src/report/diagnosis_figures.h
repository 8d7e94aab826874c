// Figures of `dynosize diagnose` (src/diagnosis): cross-validated residuals of the first-order
// and the extended model against each logged variable, measured vs predicted, and paper-style
// curves (each measured column against throttle or speed, one series per supply voltage) with
// the points the first-order model misses marked. PNGs via gnuplot (report/gnuplot.h), written
// atomically.
#pragma once

#include <string>
#include <vector>

#include "diagnosis/diagnose.h"
#include "logs/steady_table.h"

namespace dynosize {

// Writes the figures into `dir` (created if missing); returns the paths written.
std::vector<std::string> WriteDiagnosisFigures(const std::string& dir, const logs::SteadyTable& table,
                                               const diagnosis::DiagnoseResult& result);

}  // namespace dynosize
