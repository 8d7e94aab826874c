// Table operations on steady logs (logs::SteadyTable) shared by calibration and diagnosis.
#pragma once

#include <cstddef>
#include <vector>

#include "logs/steady_table.h"

namespace dynosize::logs {

// Rows of several logs of one motor + ESC pair as one table: the columns present in every log
// (a column missing from one is absent, with a note), file = the names joined by ", ".
// Throws UsageError for an empty list.
SteadyTable MergeLogs(const std::vector<SteadyTable>& tables);

// The rows `keep` of `table` (every present column, source lines, samples; metadata kept).
SteadyTable SelectRows(const SteadyTable& table, const std::vector<std::size_t>& keep);

}  // namespace dynosize::logs
