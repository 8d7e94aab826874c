// The log-reading options that calibrate, diagnose and validate-stand share, converted once.
#pragma once

#include "commands.h"
#include "logs/log_reader.h"

namespace dynosize::cli {

// The reader options of a command's log input (LogInputOptions, set by the flags --format, --map,
// --drop-incomplete-rows, --decimal-comma, --where, --esc-min-us, --esc-max-us). Throws
// UsageError naming the flag when they contradict each other (logs::LogReadOptions::Validate).
logs::LogReadOptions ToLogReadOptions(const LogInputOptions& in);

}  // namespace dynosize::cli
