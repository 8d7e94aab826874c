// What calibrate fits, before any solve (Prepared, prepared_fit.h): the rows it uses (every
// dropped row with its reason), their residual terms, which parameters the log frees
// (identification::FreeBaseParams) with a note for each it cannot identify, and the starting
// values (starting_values.h). Internal to src/calibration.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "calibration/forward_model.h"
#include "calibration/prepared_fit.h"
#include "logs/steady_table.h"

namespace dynosize::calibration::internal {

// The speed readings of the rows a fit may use (not excluded, not no-load, passing RowRejection)
// that the circuit cannot produce (identification::FindSpuriousSpeeds).
std::vector<identification::SpuriousSpeed> SpuriousSpeedRows(const logs::SteadyTable& t, const CalibrationOptions& o,
                                                             const std::vector<char>* excluded);
// "log" or the table's file name.
std::string FileTag(const logs::SteadyTable& t);
// Drops table row i from the fit with its reason.
void DropRow(Prepared* pr, const logs::SteadyTable& t, std::size_t i, const std::string& reason);
// Selects the rows, decides what is free, and finds starting values by linear least squares.
Prepared Prepare(const logs::SteadyTable& t, const CalibrationOptions& o, const std::vector<char>* excluded);

}  // namespace dynosize::calibration::internal
