// The log-reading options that calibrate, diagnose and validate-stand share, converted once.
#pragma once

#include "commands.h"
#include "logs/log_reader.h"

namespace dynosize::cli {

// The reader options of a command's log input (LogInputOptions, set by the flags --format, --map,
// --drop-incomplete-rows, --decimal-comma, --where, --esc-min-us, --esc-max-us). Throws
// UsageError naming the flag when they contradict each other (logs::LogReadOptions::Validate).
logs::LogReadOptions ToLogReadOptions(const LogInputOptions& in);

// For a log read without a throttle column (DriveCalc's tables have none by design): one line
// naming the file, the header cells that look like a throttle and the arguments that read them
// (logs::ReadLog's note), printed before any fit result or advice. "" when there is a throttle.
std::string MissingThrottleLine(const logs::SteadyTable& table);

}  // namespace dynosize::cli
