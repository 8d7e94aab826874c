// The log-reading options that calibrate, diagnose and validate-stand share (the CLI's flags and
// the Python module's keyword arguments), converted once.
#pragma once

#include <string>
#include <vector>

#include "logs/log_reader.h"

namespace dynosize::api {

// How a measured log or stand table is read (apps/main.cc registers the flags once,
// AddLogInputOptions; ToLogReadOptions converts them).
struct LogInputOptions {
  std::string format = "auto";  // auto | canonical | rcbenchmark | mapped | drivecalc | thrustapp
  std::vector<std::string> column_map;  // mapped tables: canonical=Header [unit]
  bool drop_incomplete_rows = false;    // drop rows with an empty or text cell in a used column
  bool decimal_comma = false;           // numbers written 1,5 (logs::LogReadOptions::decimal_comma)
  std::vector<std::string> where;       // Header=value row filters (logs::LogReadOptions::row_filter)
  double esc_min_us = 1000.0, esc_max_us = 2000.0;
};

// The reader options of a command's log input (LogInputOptions, set by the flags --format, --map,
// --drop-incomplete-rows, --decimal-comma, --where, --esc-min-us, --esc-max-us). Throws
// UsageError naming the flag when they contradict each other (logs::LogReadOptions::Validate).
logs::LogReadOptions ToLogReadOptions(const LogInputOptions& in);

// For a log read without a throttle column (DriveCalc's tables have none by design): one line
// naming the file, the header cells that look like a throttle and the arguments that read them
// (logs::ReadLog's note), printed before any fit result or advice. "" when there is a throttle.
std::string MissingThrottleLine(const logs::SteadyTable& table);

}  // namespace dynosize::api
