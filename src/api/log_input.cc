#include "api/log_input.h"

#include "common/error.h"
#include "logs/steady_table.h"

namespace dynosize::api {

logs::LogReadOptions ToLogReadOptions(const LogInputOptions& in) {
  logs::LogReadOptions ro;
  ro.format = logs::LogFormatFromName(in.format);
  ro.column_map = in.column_map;
  ro.mapped_drop_rows_with_empty_cells = in.drop_incomplete_rows;
  ro.decimal_comma = in.decimal_comma;
  ro.row_filter = in.where;
  ro.esc_min_us = in.esc_min_us;
  ro.esc_max_us = in.esc_max_us;
  if (std::string why; !ro.IsValid(&why)) throw UsageError(why);
  return ro;
}

std::string MissingThrottleLine(const logs::SteadyTable& table) {
  if (table.Has(logs::Column::kThrottle) || table.format == logs::LogFormat::kDriveCalc) return "";
  const std::string& note = table.info[static_cast<int>(logs::Column::kThrottle)].note;
  const bool says_so = note.rfind("no throttle", 0) == 0;
  return table.file + ": " + (says_so ? note : "no throttle column: " + note) +
         " (every point is then taken at full throttle)";
}

}  // namespace dynosize::api
