// Fuzz target: logs::ReadLog on ThrustApp reports (LaTeX filecontents tables and text exports
// with bracketed standard deviations), by detection and with --format thrustapp.
#include "fuzz_reader.h"
#include "log_checks.h"
#include "logs/log_reader.h"

DYNOSIZE_FUZZ_READER(".tex", {
  dynosize::logs::LogReadOptions o;
  o.max_line_bytes = 1 << 16;
  o.format = dynosize::logs::LogFormat::kThrustApp;
  dynosize::fuzz::CheckTable(dynosize::logs::ReadLog(path, o));
})
