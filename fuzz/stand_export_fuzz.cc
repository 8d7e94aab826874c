// Fuzz target: logs::ReadLog on stand exports with the options: format
// detection with --drop-incomplete-rows (Tyto quoted cells, unitless ESC commands, trailer
// rows), --decimal-comma, and a mapped table filtered by --where.
#include "fuzz_reader.h"
#include "log_checks.h"
#include "logs/log_reader.h"

DYNOSIZE_FUZZ_READER(".csv", {
  dynosize::logs::LogReadOptions o;
  o.max_line_bytes = 1 << 16;
  o.mapped_drop_rows_with_empty_cells = true;
  try {
    dynosize::fuzz::CheckTable(dynosize::logs::ReadLog(path, o));
  } catch (const dynosize::Error&) {
    // the readings below still run
  }
  o.decimal_comma = true;
  try {
    dynosize::fuzz::CheckTable(dynosize::logs::ReadLog(path, o));
  } catch (const dynosize::Error&) {
  }
  o.decimal_comma = false;
  o.column_map = {"throttle=#2 [%]", "idc_a=#3", "vdc_v=#4"};
  o.row_filter = {"#1=A"};
  dynosize::fuzz::CheckTable(dynosize::logs::ReadLog(path, o));
})
