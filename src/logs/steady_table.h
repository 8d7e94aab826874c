// The steady-state table: every log format dynosize reads ends up here, one row per steady
// operating point, SI units, no NaN.
//
// Storage is one std::vector<double> per column (structure of arrays). A column the log does
// not have is *absent* (Has() is false, its vector empty, info[c].note says why), never filled
// with NaN or zeros: the calibration code asks Has() to know what it can identify (no throttle
// => no ESC model; no torque => no KT; no voltage => no back-EMF from the supply).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace dynosize::logs {

enum class Column : int {
  kTimeS = 0,    // time_s: time of the point (plateau: mean time of its averaged samples)
  kVdcV,         // vdc_v: DC supply voltage at the ESC
  kThrottle,     // throttle: command, fraction 0..1
  kOmegaRadS,    // omega_rad_s: shaft speed (logs in rpm are converted)
  kTorqueNm,     // torque_nm: shaft torque
  kIdcA,         // idc_a: DC supply current
  kVllRmsV,      // vll_rms_v: line-line rms voltage (eq 33)
  kIrmsA,        // irms_a: rms phase current (eq 34)
  kPacW,         // pac_w: AC electrical power into the motor (two-wattmeter, eqs 28-32)
  kTempC,        // temp_c: a temperature (motor or probe), degrees Celsius
  kThrustN,      // thrust_n: propeller thrust
  kNoLoad,       // no_load: 1 for a no-load point, 0 loaded (DriveCalc MData)
  kMotorId,      // motor_id: DriveCalc motor id (when several motors are read at once)
};
inline constexpr int kColumnCount = 13;

// The canonical CSV name of a column ("time_s", "omega_rad_s", ...).
const char* ColumnName(Column c);

enum class LogFormat { kAuto, kCanonical, kRcbenchmark, kMapped, kDriveCalc, kThrustApp };
// "auto", "canonical", "rcbenchmark", "mapped", "drivecalc", "thrustapp"
const char* LogFormatName(LogFormat f);
// The inverse of LogFormatName; UsageError ("--format 'x': valid are ...") for any other name.
LogFormat LogFormatFromName(const std::string& name);
// Every format, kAuto first: the one list the commands' --format flags offer.
const std::vector<LogFormat>& AllLogFormats();
std::vector<std::string> LogFormatNames();
// "auto (detected from the file), canonical (dynosize's CSV), ...": the --format help.
std::string LogFormatHelp();

// Where a column came from.
struct ColumnInfo {
  bool present = false;
  std::string source_header;  // the header cell as written (UTF-8), "" when absent
  std::string source_unit;    // the unit as written in the header or the mapping, "" if none
  std::string note;           // why it is absent, or a remark (sign flipped, source chosen)
};

// Rows (or plateaus) left out, per reason.
struct DropCount {
  std::string reason;
  std::size_t count = 0;
};

struct SteadyTable {
  // --- data ---
  std::array<std::vector<double>, kColumnCount> columns;
  // For each row: the 1-based line number in the file of its first averaged sample.
  std::vector<std::size_t> source_line;
  // For each row: how many samples were averaged into it (1 for one-row-per-point logs).
  std::vector<std::size_t> samples;

  // --- metadata ---
  std::string file;
  LogFormat format = LogFormat::kAuto;  // the format read (never kAuto after ReadLog)
  std::array<ColumnInfo, kColumnCount> info;
  std::string line_ends;            // "LF", "CRLF", "CR" or a '+' mix
  bool had_bom = false;
  bool header_latin1 = false;       // header decoded as Latin-1 (spreadsheet re-save)
  char delimiter = ',';
  std::size_t lines_read = 0;       // physical lines, header included
  std::size_t data_rows_read = 0;   // lines holding data (not header, blank or comment)
  std::size_t blank_or_comment_lines = 0;
  std::size_t rows_with_extra_cells = 0;  // cells beyond the header, ignored (see reader)
  bool time_series = false;         // samples were cut into plateaus and averaged
  std::size_t plateaus_found = 0;   // steady plateaus kept (== rows() for time series)
  std::size_t transient_samples = 0;  // samples dropped as transients after a step
  std::size_t outlier_samples = 0;    // samples rejected by the MAD test inside plateaus
  std::vector<DropCount> dropped;     // rows / plateaus left out, per reason
  std::vector<std::string> notes;     // anything the fit should know (absent throttle, ...)
  // The throttle came from ESC pulse widths: the end points used (--esc-min-us/--esc-max-us),
  // throttle = (us - min)/(max - min); both 0 otherwise. Refusal advice names pulse widths.
  double throttle_pulse_min_us = 0.0;
  double throttle_pulse_max_us = 0.0;

  std::size_t rows() const { return source_line.size(); }
  bool Has(Column c) const { return info[static_cast<int>(c)].present; }
  // The column's values; throws InternalError when the column is absent (ask Has() first).
  const std::vector<double>& Get(Column c) const;
  std::vector<double>& Mutable(Column c) { return columns[static_cast<int>(c)]; }
  std::size_t DroppedTotal() const;

  // One line: "file: rcbenchmark, 4814 rows read, 20 plateaus, dropped 12 (...); columns:
  // throttle vdc_v idc_a omega_rad_s thrust_n; absent: torque_nm vll_rms_v irms_a pac_w".
  std::string BriefReport() const;
  // A table of columns (source header, unit, present/absent and why) and the drop counts.
  std::string FullReport() const;
};

// Adds `n` to the count of `reason` (creating it).
void AddDrop(SteadyTable* table, const std::string& reason, std::size_t n = 1);

}  // namespace dynosize::logs
