// Reading measurement logs into one SteadyTable (steady_table.h).
//
// Formats (LogFormat; kAuto decides from the header line):
//  - kCanonical: dynosize's own CSV. Header names exactly from
//      vdc_v, throttle, rpm | omega_rad_s, idc_a                               (required)
//      time_s, torque_nm, vll_rms_v, irms_a, pac_w, temp_c, thrust_n           (optional)
//    one row per operating point, SI units (rpm is the one datasheet unit accepted); a steady
//    table (a manufacturer's or a stand's table of operating points) needs no time_s. Strict: an
//    unknown or repeated column, a row with a different cell count, an empty cell or text in a
//    number, throttle outside 0..1, vdc_v <= 0, negative vll_rms_v / irms_a are DataErrors
//    naming file, line, column, value and rule. Detected by a header holding time_s and idc_a,
//    or holding idc_a and nothing but canonical names.
//  - kRcbenchmark: RCbenchmark / Tyto Robotics exports (Series 1520/1580/1585/1780, and the
//    Tyto Flight Stand software in all its export variants, which quote every cell), and the
//    same files re-saved by a spreadsheet. Headers "Name (unit)", names from the header synonym
//    table (header_synonyms.h, docs/log-formats.md), units parsed (gf/kgf/N, RPM/rad/s,
//    N*m/N.m/N⋅m, ...). Throttle = (us - esc_min_us)/(esc_max_us - esc_min_us) for a
//    pulse width. A command without a unit (bhabas_sar_motor_sysid: "ESC signal", 0..2000
//    command units) is scaled from its values (see ReadLog's note): values within 0..1 are a
//    fraction, values within 800..2200 a pulse width in us, values within 0..2000 otherwise
//    command units of 0..2000; else throttle is absent, with a note. Optical speed before
//    electrical. Time series are cut into plateaus (plateau.h); logs already holding one
//    averaged row per step (median interval >= plateau.summary_min_interval_s) are read row by
//    row. Lenient where the real files demand it: empty cells (asynchronous sensors) are
//    skipped and counted; rows with more cells than the header (commas inside "App message",
//    script columns) keep their named cells; blank and '#' comment lines are skipped and
//    counted. Text in a number is still a DataError (unless mapped_drop_rows_with_empty_cells).
//    Detected by a command or speed column a stand export writes ("ESC signal", "PWM throttle
//    signal", "Throttle (µs)" with a unit, "Motor Optical Speed", "Rotation speed", ...), with
//    the current column (if any) carrying a unit ("Current (A)"). With --format rcbenchmark, a
//    column map adds (or replaces) columns the table does not name.
//  - kMapped: any table with a header (or none) through LogReadOptions::column_map. Without a
//    map, kAuto also picks it for a table whose current and throttle or speed columns the
//    synonym table names with units that read ("voltage_V", "current_A", "thrust_g", "Amps",
//    "rpm"): the map is made from the table, strict like a given one; a "motor" or
//    "source_file" column holding a second value is a DataError naming the --where that keeps
//    one motor.
//  - kDriveCalc: DriveCalc's MData table (motor_id, U, n, I, IsNoLoad, ...): U -> vdc_v,
//    n -> omega_rad_s, I -> idc_a, IsNoLoad -> no_load, Temp -> temp_c. Points with n = 0
//    (speed not measured) are dropped and counted. Detected by motor_id, U, n, I, IsNoLoad.
//  - kThrustApp: jmajew's ThrustApp reports (thrustapp.h), detected by their first line.
//
// A quantity the fit uses (throttle, current, voltage, speed, torque) that is absent gets a
// note (ColumnInfo::note) naming the header cells that look like it and the arguments that read
// them; when the format cannot be told, the DataError names what is missing and gives a ready
// --map line.
// Every format: a UTF-8 BOM, LF/CRLF/CR line ends, a Latin-1 header and quoted cells
// ("1.5", RFC 4180; csv_scan.h) are accepted, blank lines and lines starting with '#' are
// skipped (counted in blank_or_comment_lines); torque is optional everywhere (it identifies KT;
// without it the fit uses KT = sqrt(27/10)*KE and says so); the table
// must end with at least 2 rows, not all identical, idc_a present and not all zero - else a
// DataError. A missing file is a NoInputError; invalid options a UsageError.
// Memory: the file is read through a fixed buffer; only the parsed numbers are kept.
#pragma once

#include <string>
#include <vector>

#include "logs/plateau.h"
#include "logs/steady_table.h"

namespace dynosize::logs {

enum class TimeSeriesMode {
  kAuto,      // RCbenchmark: plateaus unless the log is a list of steady points
  kPerRow,    // every row is a steady point
  kPlateaus,  // always search plateaus (needs a time column or a stepped command)
};

struct LogReadOptions {
  LogFormat format = LogFormat::kAuto;

  // ESC pulse width end points: throttle = (us - esc_min_us) / (esc_max_us - esc_min_us).
  // A pulse width outside [esc_min_us, esc_max_us] is a DataError (set the end points your ESC
  // was calibrated to). Defaults: the usual 1000-2000 us.
  double esc_min_us = 1000.0;
  double esc_max_us = 2000.0;
  // An ESC command column without a unit (bhabas_sar_motor_sysid: "ESC signal", 0..2000
  // command units): when these are set (esc_unitless_max > esc_unitless_min), throttle =
  // (value - min)/(max - min); otherwise the scale is decided from the values (see kRcbenchmark).
  double esc_unitless_min = 0.0;
  double esc_unitless_max = 0.0;

  // kMapped (CLI --map): "canonical_name=Source Header [unit]" pairs, e.g. "thrust_n=Thrust [g]",
  // "rpm=Rpm", "torque_nm=#2 [N*m]". canonical_name is a canonical column name (rpm allowed
  // for omega). The source is a header cell (matched whole, or by its name without unit) or
  // "#k", the k-th column (1-based) of a file without header. The unit in brackets overrides
  // the header's; without either the canonical column's own unit is assumed. Giving a map
  // with format kAuto selects kMapped; with kRcbenchmark the map adds to the detected columns.
  std::vector<std::string> column_map;
  // CLI --drop-incomplete-rows. kMapped is strict like the canonical format, and kRcbenchmark
  // refuses text in a number. Hand-made tables carry annotation and trailer rows ("6s
  // Lipo,,PEAK THRUST,,," in sjkim's A4220 table): with this set, a row whose used cell is
  // empty or text (a cell that does not begin like a number: not a digit, sign or '.') is
  // dropped and counted, with the first such lines named. A malformed number ("1.2.3", "12 A")
  // stays an error: it is a broken value, not an annotation.
  bool mapped_drop_rows_with_empty_cells = false;

  // CLI --decimal-comma: numbers are written with a decimal comma ("1,5"), as Excel writes
  // them in many locales. The cells are then separated by ';' or tabs (the usual pairing); a
  // ','-separated file must quote every cell holding a comma, else the row is a DataError. A
  // cell holding '.' is refused in this mode (a thousands separator: ambiguous).
  bool decimal_comma = false;

  // CLI --where "Header=value" (repeatable, all must hold): keep only the rows whose cell in
  // that column reads exactly `value` (blanks trimmed; quotes removed). For tables of several
  // motors in one file (ctu_mrs_motor_tests: motor; dronebuildcalc: Motor; jmajew's
  // extracted_steady_points.csv: source_file). Rows of other values are counted in a note; no
  // row matching is a DataError naming the values seen.
  std::vector<std::string> row_filter;

  TimeSeriesMode time_series = TimeSeriesMode::kAuto;
  PlateauOptions plateau;

  // kDriveCalc: keep only this motor_id (negative: all motors, with a motor_id column).
  long long drivecalc_motor_id = -1;
  // kDriveCalc: a point with n = 0 had its speed not measured. Such points are dropped unless
  // this is set, in which case *no-load* points with n = 0 are kept with omega_rad_s = 0: they
  // still give the no-load current Io (the model's I at Q = 0 does not depend on the speed,
  // eq 42), and the calibration treats omega = 0 on a no-load row as "speed not measured".
  // Loaded points with n = 0 are always dropped.
  bool drivecalc_keep_no_load_without_speed = false;

  // Thrust-stand torque and thrust signs depend on how the motor is mounted: when the median is
  // negative, the column is negated (and a note says so).
  bool normalize_signs = true;

  // Longest line accepted (a longer one is a DataError: not a text log).
  std::size_t max_line_bytes = 1 << 20;

  // True when valid; else false, and *error (when not null) names the field, its value and the
  // rule.
  bool IsValid(std::string* error) const;
};

// Reads `path` into a steady table. Throws NoInputError, DataError or UsageError (see above).
SteadyTable ReadLog(const std::string& path, const LogReadOptions& options = LogReadOptions());

}  // namespace dynosize::logs
