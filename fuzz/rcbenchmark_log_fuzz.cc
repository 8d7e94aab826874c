// Fuzz target: logs::ReadLog with the rcbenchmark format forced (src/logs/log_reader.h).
#include "fuzz_reader.h"
#include "log_checks.h"
#include "logs/log_reader.h"

DYNOSIZE_FUZZ_READER(".csv", {
  dynosize::logs::LogReadOptions o;
  o.format = dynosize::logs::LogFormat::kRcbenchmark;
  o.max_line_bytes = 1 << 16;
  dynosize::fuzz::CheckTable(dynosize::logs::ReadLog(path, o));
})
