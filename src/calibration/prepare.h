// What calibrate fits, before any solve: the rows it uses (every dropped row with its reason),
// their residual terms, which parameters the log frees (identification::FreeBaseParams) with a
// note for each it cannot identify, and the starting values (starting_values.h). Internal to
// src/calibration.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "calibration/forward_model.h"
#include "logs/steady_table.h"

namespace dynosize::calibration::internal {

struct Prepared {
  FitData data;
  Layout layout;
  std::array<double, kBaseParamCount> start{};
  std::array<std::string, kBaseParamCount> notes;
  std::string mode;
  bool has_throttle = false;
  std::vector<double> levels;
  std::vector<logs::DropCount> dropped;
  std::vector<DroppedRow> dropped_rows;
  std::vector<std::string> warnings;
  double offset_upper = 0.5;  // upper bound of the dead band: below the lowest throttle level
};

// Which columns the log has, beyond those Prepared records (the stages of Prepare share it).
struct LogColumns {
  bool has_q = false;   // torque
  bool has_nl = false;  // no-load flag
  bool ac = false;      // vll_rms_v and irms_a
};

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
