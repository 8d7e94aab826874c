// Fuzz target: logs::ReadLog with format detection (what `dynosize calibrate LOG` does).
#include "fuzz_reader.h"
#include "log_checks.h"
#include "logs/log_reader.h"

DYNOSIZE_FUZZ_READER(".csv", {
  dynosize::logs::LogReadOptions o;
  o.max_line_bytes = 1 << 16;
  dynosize::fuzz::CheckTable(dynosize::logs::ReadLog(path, o));
})
