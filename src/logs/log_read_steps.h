// The steps of ReadLog (log_reader.h), shared by the files that implement them: the header and
// the format (log_detect.cc), the plan of each format (log_plans.cc), the rows (log_rows.cc) and
// the steady table (log_table.cc). Internal to src/logs: not part of the library's interface.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "logs/header_synonyms.h"
#include "logs/log_units.h"
#include "logs/plateau.h"
#include "logs/steady_table.h"

namespace dynosize::logs {
struct LogReadOptions;  // log_reader.h: its module includes this header, so this header may not include it
}  // namespace dynosize::logs

namespace dynosize::logs::read_internal {

// One source column being read.
struct Slot {
  Column target = Column::kTimeS;
  Quantity quantity = Quantity::kTime;
  std::size_t field = 0;  // 0-based cell index
  std::string header;     // as written (UTF-8)
  std::string unit;       // as written
  UnitConversion conv;
  double pulse_min = 0.0, pulse_max = 0.0;  // throttle from a pulse width / command units
  bool pulse = false;
  bool pulse_us = false;  // the throttle is a pulse width in us (pulse_min/max: --esc-min-us/--esc-max-us)
  // A command column without a unit: values kept raw, scaled after reading (ScaleUnitlessCommand).
  bool scale_from_values = false;
  std::vector<double> values;  // SI, NaN for an empty cell (lenient formats only)
  bool active = true;
};

struct Plan {
  LogFormat format = LogFormat::kAuto;
  std::vector<Slot> slots;
  bool lenient = false;        // RCbenchmark: empty cells allowed, extra cells ignored
  bool empty_cells_ok = false; // empty cells become NaN and drop their row (counted)
  bool has_header = true;
  std::size_t header_cells = 0;
  std::vector<std::string> header_for_errors;  // header cell per field (UTF-8)
  // --where: keep rows whose cell `field` reads `value`.
  struct RowFilter {
    std::size_t field = 0;
    std::string header, value;
  };
  std::vector<RowFilter> filters;
  // A table named by the synonym table, without --where: columns naming the motor ("motor",
  // "source_file"); rows of a second motor are a DataError (pick one with --where). Several
  // propellers on one motor stay one read: the torque column makes each row a load point.
  std::vector<std::size_t> setup_fields;
  std::vector<std::string> setup_headers;
};

// Canonical column names accepted in the canonical CSV and in column maps.
struct CanonicalName {
  const char* name;
  Column column;
  Quantity quantity;
  const char* default_unit;
};

struct Header {
  std::string raw_line_utf8;
  std::vector<std::string> cells;  // trimmed UTF-8
  bool latin1 = false;
  char delim = ',';
};

// Every header cell the synonym table names (header_synonyms.h), in header order.
struct Matched {
  std::size_t field;
  HeaderMatch match;
};

struct RawRows {
  std::vector<std::size_t> line;
  std::vector<char> esc_outside;  // per row: ESC signal outside the end points (lenient only)
  std::string esc_reason;
};

// ---- log_detect.cc
std::string JoinSorted(std::vector<std::string> v);
const CanonicalName* FindCanonical(std::string_view name);
std::string CanonicalNameList();
Header ParseHeader(std::string_view line);
std::vector<Matched> MatchAll(const Header& h);
bool UnitReads(const HeaderMatch& m);
std::string ReadyMapLine(const Header& h, const std::vector<Column>& missing);
std::string UnitChoicesFor(const std::string& map_line);
LogFormat Detect(const Header& h, const LogReadOptions& o, const std::string& path);
bool LooksNumeric(const Header& h);

// ---- log_plans.cc
Plan PlanCanonical(const Header& h, const std::string& path);
Plan PlanBySynonyms(const Header& h, bool stand, const LogReadOptions& o, const std::string& path,
                    SteadyTable* t);
Plan PlanDriveCalc(const Header& h, const std::string& path);
Plan PlanMapped(const Header& h, bool header_is_data, const LogReadOptions& o,
                const std::string& path);
Plan PlanThrustApp(const LogReadOptions& o, const std::string& path, SteadyTable* t);
void ResolveFilters(const Header& h, bool header_is_data, const LogReadOptions& o,
                    const std::string& path, Plan* plan);

// ---- log_rows.cc
[[noreturn]] void CellError(const std::string& path, std::size_t line, const std::string& column,
                            std::string_view cell, const std::string& rule);
void ScaleUnitlessCommand(Plan* plan, RawRows* rows, SteadyTable* t, const LogReadOptions& o);
// `Lines`: LineReader, or ThrustAppLines (a report's step tables as rows).
template <class Lines>
void ReadRows(Lines* lr, Plan* plan, const std::string& path, SteadyTable* t, RawRows* rows,
              std::string_view first_data_line, const LogReadOptions& o);

// ---- log_table.cc
std::vector<Slot*> ResolveColumns(Plan* plan, SteadyTable* t);
void BuildPerRow(SteadyTable* t, const std::vector<Slot*>& chosen, const RawRows& rows,
                 bool zero_is_dropout);
void BuildPlateaus(SteadyTable* t, const std::vector<Slot*>& chosen, const RawRows& rows,
                   const PlateauOptions& po);
double MedianInterval(const std::vector<double>& t);
void NormalizeSigns(SteadyTable* t);
void CheckCanonicalRanges(const SteadyTable& t, const std::string& path);
void CheckTable(const SteadyTable& t, const std::string& path);
void DropDriveCalcWithoutSpeed(SteadyTable* t, const LogReadOptions& options);

}  // namespace dynosize::logs::read_internal
