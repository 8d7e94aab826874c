// Fuzz target: logs::ReadLog through a column map (kMapped), once by header names with units
// and once by column numbers of a headerless table.
#include "fuzz_reader.h"
#include "log_checks.h"
#include "logs/log_reader.h"

DYNOSIZE_FUZZ_READER(".csv", {
  dynosize::logs::LogReadOptions o;
  o.max_line_bytes = 1 << 16;
  o.column_map = {"vdc_v=Voltage (V)", "idc_a=Current (A)", "rpm=Rpm", "thrust_n=Thrust [g]",
                  "throttle=Throttle"};
  o.mapped_drop_rows_with_empty_cells = true;
  try {
    dynosize::fuzz::CheckTable(dynosize::logs::ReadLog(path, o));
  } catch (const dynosize::Error&) {
    // the second map below still runs
  }
  o.column_map = {"vdc_v=#1", "idc_a=#2", "rpm=#3", "throttle=#4"};
  o.mapped_drop_rows_with_empty_cells = false;
  dynosize::fuzz::CheckTable(dynosize::logs::ReadLog(path, o));
})
