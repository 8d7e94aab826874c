// The state Prepare hands to the fit (prepare.h): the rows and residual terms, the layout of free
// parameters, the starting values (starting_values.h) with a note per parameter, and the log's
// columns. Below prepare and starting_values, which both fill it. Internal to src/calibration.
#pragma once

#include <array>
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

}  // namespace dynosize::calibration::internal
