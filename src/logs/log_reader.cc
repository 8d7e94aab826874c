#include "logs/log_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/numbers.h"
#include "common/units.h"
#include "common/text_format.h"
#include "logs/csv_scan.h"
#include "logs/header_synonyms.h"
#include "logs/log_units.h"
#include "logs/thrustapp.h"

namespace dynosize::logs {

namespace {

// Throttle computed from a pulse width may exceed 0..1 by rounding only.
constexpr double kThrottleRoundingSlack = 1e-9;
// Largest magnitude of a value in SI units (after unit conversion). Far beyond any measurement
// (1e12 A, V, rad/s; time stamps in Unix seconds are 1.7e9), it keeps squares and products
// the fit forms finite over millions of rows (1e24 * 1e6 << 1.8e308). Beyond it (1e308 in a
// cell, or kgf * 9.81 overflowing) the cell is a DataError in every format.
constexpr double kMaxAbsSiValue = 1e12;

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

[[noreturn]] void CellError(const std::string& path, std::size_t line, const std::string& column,
                            std::string_view cell, const std::string& rule) {
  throw DataError(path + ": line " + std::to_string(line) + ", column \"" + column + "\": " +
                  QuoteCell(cell) + ": " + rule);
}

std::string JoinSorted(std::vector<std::string> v) {
  std::sort(v.begin(), v.end());
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + v[i];
  return out;
}

// Canonical column names accepted in the canonical CSV and in column maps.
struct CanonicalName {
  const char* name;
  Column column;
  Quantity quantity;
  const char* default_unit;
};
const CanonicalName kCanonicalNames[] = {
    {"time_s", Column::kTimeS, Quantity::kTime, "s"},
    {"vdc_v", Column::kVdcV, Quantity::kVoltage, "V"},
    {"throttle", Column::kThrottle, Quantity::kThrottle, ""},
    {"rpm", Column::kOmegaRadS, Quantity::kSpeed, "rpm"},
    {"omega_rad_s", Column::kOmegaRadS, Quantity::kSpeed, "rad/s"},
    {"torque_nm", Column::kTorqueNm, Quantity::kTorque, "N*m"},
    {"idc_a", Column::kIdcA, Quantity::kCurrent, "A"},
    {"vll_rms_v", Column::kVllRmsV, Quantity::kVoltage, "V"},
    {"irms_a", Column::kIrmsA, Quantity::kCurrent, "A"},
    {"pac_w", Column::kPacW, Quantity::kPower, "W"},
    {"temp_c", Column::kTempC, Quantity::kTemperature, "C"},
    {"thrust_n", Column::kThrustN, Quantity::kForce, "N"},
};

const CanonicalName* FindCanonical(std::string_view name) {
  for (const auto& c : kCanonicalNames) {
    if (name == c.name) return &c;
  }
  return nullptr;
}

std::string CanonicalNameList() {
  std::string out;
  for (const auto& c : kCanonicalNames) out += std::string(out.empty() ? "" : ", ") + c.name;
  return out;
}

double ToSi(const Slot& s, double raw) {
  if (s.pulse) return (raw - s.pulse_min) / (s.pulse_max - s.pulse_min);
  return raw * s.conv.scale + s.conv.offset;
}

// ---------------------------------------------------------------- header and detection

struct Header {
  std::string raw_line_utf8;
  std::vector<std::string> cells;  // trimmed UTF-8
  bool latin1 = false;
  char delim = ',';
};

Header ParseHeader(std::string_view line) {
  Header h;
  h.delim = DetectDelimiter(line);
  h.raw_line_utf8 = ToUtf8(line, &h.latin1);
  std::vector<std::string_view> f;
  SplitFields(h.raw_line_utf8, h.delim, &f);
  for (auto v : f) h.cells.emplace_back(Trim(v));
  return h;
}

bool HasCell(const Header& h, const char* name) {
  for (const auto& c : h.cells) {
    if (c == name) return true;
  }
  return false;
}

// Every header cell the synonym table names (header_synonyms.h), in header order.
struct Matched {
  std::size_t field;
  HeaderMatch match;
};
std::vector<Matched> MatchAll(const Header& h) {
  std::vector<Matched> out;
  for (std::size_t i = 0; i < h.cells.size(); ++i) {
    if (auto m = MatchHeader(h.cells[i])) out.push_back({i, *m});
  }
  return out;
}

// A unit that reads for the column: written or implied, valid for its quantity (throttle may
// have none: a fraction, or a command scaled from its values in a stand export).
bool UnitReads(const HeaderMatch& m) {
  if (m.unit.empty()) return m.column == Column::kThrottle;
  return ParseUnit(m.quantity, m.unit).has_value();
}

// A stand export's command or speed column ("ESC signal (µs)", "Rotation speed (rpm)"); a bare
// "Throttle" is also a manufacturer table's column, so it counts only with a unit.
bool IsStandColumn(const Header& h, const Matched& m) {
  if (!m.match.stand) return false;
  if (m.match.column != Column::kThrottle && m.match.column != Column::kOmegaRadS) return false;
  const HeaderCell hc = SplitHeaderCell(h.cells[m.field]);
  return NormaliseHeaderName(hc.name) != "throttle" || (m.match.unit_written && UnitReads(m.match));
}

bool AllCanonicalNames(const Header& h) {
  for (const auto& c : h.cells) {
    if (FindCanonical(c) == nullptr) return false;
  }
  return !h.cells.empty();
}

// The --map arguments that read `h` as a mapped table: the first cell of each column the synonym
// table names, then, for `missing` columns, the cells that look like them.
std::string ReadyMapLine(const Header& h, const std::vector<Column>& missing) {
  std::string line;
  std::vector<char> done(kColumnCount, 0);
  std::vector<std::size_t> used;
  for (const Matched& m : MatchAll(h)) {
    const int c = static_cast<int>(m.match.column);
    if (done[c]) continue;
    done[c] = 1;
    used.push_back(m.field);
    line += (line.empty() ? "" : " ") + MapArgument(m.match.column, h.cells[m.field]);
  }
  for (const Column c : missing) {
    if (done[static_cast<int>(c)]) continue;
    const auto look = LookalikeColumns(c, h.cells, used);
    if (look.empty()) continue;
    used.push_back(look[0]);
    line += (line.empty() ? "" : " ") + MapArgument(c, h.cells[look[0]]);
  }
  return line;
}

// The columns the synonym table names without a unit that reads ("\"Thrust\", \"Current\"").
std::string UnitlessColumns(const Header& h) {
  std::string out;
  for (const Matched& m : MatchAll(h)) {
    if (UnitReads(m.match)) continue;
    out += (out.empty() ? "\"" : ", \"") + h.cells[m.field] + "\"";
  }
  return out;
}

// " (UNIT: thrust_n: n, gf, ...; ...)" for the --map arguments of `map_line` asking for a unit.
std::string UnitChoicesFor(const std::string& map_line) {
  std::string out;
  for (const CanonicalName& cn : kCanonicalNames) {
    if (cn.column == Column::kOmegaRadS && std::string(cn.name) == "rpm") continue;
    const std::size_t at = map_line.find(std::string("\"") + cn.name + "=");
    if (at == std::string::npos) continue;
    const std::size_t end = map_line.find('"', at + 1);
    if (map_line.substr(at, end - at).find("[UNIT]") == std::string::npos) continue;
    out += (out.empty() ? "" : "; ") + UnitChoices(cn.column);
  }
  return out.empty() ? out : " (UNIT: " + out + ")";
}

LogFormat Detect(const Header& h, const LogReadOptions& o, const std::string& path) {
  if (IsThrustAppStart(h.raw_line_utf8)) return LogFormat::kThrustApp;
  if (!o.column_map.empty()) return LogFormat::kMapped;
  // Canonical: time_s and idc_a, or nothing but canonical names (a steady table).
  if ((HasCell(h, "time_s") && HasCell(h, "idc_a")) || (AllCanonicalNames(h) && HasCell(h, "idc_a"))) {
    return LogFormat::kCanonical;
  }
  if (HasCell(h, "motor_id") && HasCell(h, "U") && HasCell(h, "n") && HasCell(h, "I") &&
      HasCell(h, "IsNoLoad")) {
    return LogFormat::kDriveCalc;
  }
  // A stand export names its command or speed column and writes units in the header; a
  // hand-made table that happens to have "ESC throttle (us)" but a bare "Current" (sjkim's
  // A4220) is not one: its other columns have no units to read.
  const std::vector<Matched> matched = MatchAll(h);
  bool stand_column = false, current_reads = false, command_or_speed = false, bare_current = false;
  for (const Matched& m : matched) {
    stand_column = stand_column || IsStandColumn(h, m);
    const Column c = m.match.column;
    if (c == Column::kIdcA && UnitReads(m.match)) current_reads = true;
    if (c == Column::kIdcA && m.match.unit.empty()) bare_current = true;
    if ((c == Column::kThrottle || c == Column::kOmegaRadS) && UnitReads(m.match)) command_or_speed = true;
  }
  if (stand_column && !bare_current) return LogFormat::kRcbenchmark;
  // Any other table whose current and command or speed columns are named by the synonym table
  // with units that read ("voltage_V", "thrust_g", "Amps"): a mapped table, map made here.
  if (current_reads && command_or_speed && UnitlessColumns(h).empty()) return LogFormat::kMapped;
  const std::string map_line =
      ReadyMapLine(h, {Column::kThrottle, Column::kVdcV, Column::kIdcA, Column::kOmegaRadS});
  std::string why;
  const std::string unitless = UnitlessColumns(h);
  if (!unitless.empty()) {
    why = "column(s) " + unitless + " name no unit (or none dynosize reads)";
  } else if (!current_reads) {
    why = "no current column (\"Current (A)\", \"current_A\", \"Amps\", ...)";
  } else {
    why = "no throttle or speed column (\"ESC signal (µs)\", \"throttle\", \"rpm\", ...)";
  }
  throw DataError(path + ": line 1: cannot tell the log format from the header " +
                  QuoteCell(h.raw_line_utf8) + ": " + why +
                  " (docs/log-formats.md lists the header names read). " +
                  (map_line.empty()
                       ? std::string("Read the table with --format mapped --map canonical=Header [unit], one "
                                     "per column, e.g. --map \"idc_a=Current [A]\" --map rpm=RPM")
                       : "Read it with: --format mapped " + map_line + UnitChoicesFor(map_line)));
}

// ---------------------------------------------------------------- plans per format

Plan PlanCanonical(const Header& h, const std::string& path) {
  Plan p;
  p.format = LogFormat::kCanonical;
  p.header_cells = h.cells.size();
  std::vector<std::string> unknown;
  std::vector<int> seen(kColumnCount, -1);
  for (std::size_t i = 0; i < h.cells.size(); ++i) {
    const std::string& name = h.cells[i];
    const CanonicalName* cn = FindCanonical(name);
    if (cn == nullptr) {
      unknown.push_back(name.empty() ? "(empty: trailing delimiter?)" : "\"" + name + "\"");
      continue;
    }
    const int col = static_cast<int>(cn->column);
    if (seen[col] >= 0) {
      throw DataError(path + ": line 1: column \"" + name + "\" given twice (as \"" +
                      h.cells[static_cast<std::size_t>(seen[col])] + "\" in column " +
                      std::to_string(seen[col] + 1) + " and in column " + std::to_string(i + 1) +
                      "): each canonical column at most once");
    }
    seen[col] = static_cast<int>(i);
    Slot s;
    s.target = cn->column;
    s.quantity = cn->quantity;
    s.field = i;
    s.header = name;
    s.unit = cn->default_unit;
    s.conv = *ParseUnit(cn->quantity, cn->default_unit);
    p.slots.push_back(std::move(s));
  }
  if (!unknown.empty()) {
    throw DataError(path + ": line 1: unknown column(s) " + JoinSorted(unknown) +
                    " in the canonical format; valid names: " + CanonicalNameList());
  }
  std::vector<std::string> missing;
  // time_s is optional (a steady table has one row per operating point, no time), and so is
  // torque_nm, as in every format.
  for (const Column c : {Column::kVdcV, Column::kThrottle, Column::kOmegaRadS, Column::kIdcA}) {
    if (seen[static_cast<int>(c)] < 0) {
      missing.push_back(c == Column::kOmegaRadS ? "rpm (or omega_rad_s)" : ColumnName(c));
    }
  }
  if (!missing.empty()) {
    throw DataError(path + ": line 1: missing required column(s) " + JoinSorted(missing) +
                    " of the canonical format (required: vdc_v, throttle, rpm or omega_rad_s, idc_a; "
                    "optional: time_s, torque_nm, vll_rms_v, irms_a, pac_w, temp_c, thrust_n)");
  }
  return p;
}

// A slot reading the header cell the synonym table matched. A command without a unit is a
// fraction, or in a stand export (`stand`) a command scaled from its values (log_reader.h); any
// other column must name a unit that reads (written or implied), else a DataError.
Slot SynonymSlot(const Header& h, const Matched& m, bool stand, const LogReadOptions& o,
                 const std::string& path, SteadyTable* t) {
  Slot s;
  s.field = m.field;
  s.header = h.cells[m.field];
  s.unit = m.match.unit;
  s.target = m.match.column;
  s.quantity = m.match.quantity;
  if (s.target == Column::kThrottle && s.unit.empty() && stand) {
    if (o.esc_unitless_max > o.esc_unitless_min) {
      s.pulse = true, s.pulse_min = o.esc_unitless_min, s.pulse_max = o.esc_unitless_max;
      std::ostringstream note;
      note << "no unit: read as command units " << o.esc_unitless_min << ".." << o.esc_unitless_max
           << " as configured";
      t->info[static_cast<int>(Column::kThrottle)].note = note.str();
    } else {
      s.scale_from_values = true;  // decided from the values once read
    }
    return s;
  }
  const auto u = ParseUnit(s.quantity, s.unit);
  if (!u) {
    throw DataError(path + ": line 1, column " + std::to_string(m.field + 1) + " \"" + s.header +
                    "\": " + (s.unit.empty() ? std::string("no unit") : "unit " + QuoteCell(s.unit)) +
                    " is not a unit of " +
                    (s.quantity == Quantity::kThrottle ? "an ESC signal" : SiUnit(s.quantity)) +
                    "; valid: " + ValidUnits(s.quantity) + " (write it in the header, \"Name (unit)\", or " +
                    MapArgument(s.target, s.header) + " with --format " +
                    (stand ? "rcbenchmark" : "mapped") + ")");
  }
  s.conv = *u;
  if (u->pulse_width_us) {
    s.pulse = true, s.pulse_us = true, s.pulse_min = o.esc_min_us, s.pulse_max = o.esc_max_us;
  }
  return s;
}

// The names RCbenchmark / Tyto exports write for their measured columns (their units are
// checked: a "Torque" without one is an error, as it always was).
bool IsExportName(const std::string& cell) {
  const std::string name = NormaliseHeaderName(SplitHeaderCell(cell).name);
  return name == "time" || name == "torque" || name == "thrust" || name == "voltage" || name == "current";
}

// Optical speed before electrical: the electrical probe reads spurious values at low
// throttle (ecosystem-notes.md), the optical one is used whenever it saw anything.
void SortByRank(std::vector<Slot>* slots, const std::vector<int>& rank) {
  std::vector<std::size_t> order(slots->size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
  std::vector<Slot> sorted;
  for (const std::size_t i : order) sorted.push_back(std::move((*slots)[i]));
  *slots = std::move(sorted);
}

Slot MappedSlot(const std::string& entry, const Header& h, bool header_is_data, const LogReadOptions& o,
                const std::string& path, std::vector<int>* seen_columns);

// The columns of a stand export (RCbenchmark / Tyto) or of a table named by the synonym table:
// every cell the table names (the first temperature only). `stand`: lenient cells, unitless
// command scaled from its values.
Plan PlanBySynonyms(const Header& h, bool stand, const LogReadOptions& o, const std::string& path,
                    SteadyTable* t) {
  Plan p;
  p.format = stand ? LogFormat::kRcbenchmark : LogFormat::kMapped;
  p.lenient = stand;
  p.header_cells = h.cells.size();
  // A trailing delimiter leaves an empty last header cell: not a column.
  while (stand && p.header_cells > 0 && h.cells[p.header_cells - 1].empty()) --p.header_cells;
  bool have_temp = false;
  std::vector<int> rank;
  for (const Matched& m : MatchAll(h)) {
    if (m.field >= p.header_cells) continue;
    // In a stand export, a column named by a table row other than the export's own names
    // ("Speed (km/h)" beside "Motor Optical Speed (RPM)") is left out when its unit does not
    // read, as the exports' other columns are; the export's own names keep their unit check.
    if (stand && !m.match.stand && !UnitReads(m.match) && !IsExportName(h.cells[m.field])) {
      t->notes.push_back("column \"" + h.cells[m.field] + "\" not read: its unit is not one of " +
                         ColumnName(m.match.column));
      continue;
    }
    if (m.match.column == Column::kTempC) {
      if (have_temp) continue;
      have_temp = true;
    }
    p.slots.push_back(SynonymSlot(h, m, stand, o, path, t));
    rank.push_back(m.match.column == Column::kOmegaRadS ? 1 + m.match.rank : 0);
  }
  SortByRank(&p.slots, rank);
  // --format rcbenchmark with --map: the map names columns the table does not know (or reads
  // a column from another cell); the others stay as detected.
  std::vector<int> seen(kColumnCount, -1);
  for (const std::string& entry : o.column_map) {
    Slot s = MappedSlot(entry, h, false, o, path, &seen);
    p.slots.erase(std::remove_if(p.slots.begin(), p.slots.end(),
                                 [&](const Slot& x) { return x.target == s.target || x.field == s.field; }),
                  p.slots.end());
    p.slots.push_back(std::move(s));
  }
  if (!stand) {
    t->notes.push_back("columns named by the header synonym table (docs/log-formats.md), no --map given");
    for (std::size_t i = 0; i < h.cells.size() && o.row_filter.empty(); ++i) {
      const std::string name = NormaliseHeaderName(h.cells[i]);
      for (const char* id : {"motor", "motor name", "source file", "brand"}) {
        if (name == id) p.setup_fields.push_back(i), p.setup_headers.push_back(h.cells[i]);
      }
    }
  }
  return p;
}

// motor_id is always read (the filter needs it); with a filter it is dropped from the table.
Plan PlanDriveCalc(const Header& h, const std::string& path) {
  Plan p;
  p.format = LogFormat::kDriveCalc;
  p.header_cells = h.cells.size();
  struct Want {
    const char* name;
    Column column;
    Quantity quantity;
    const char* unit;
    bool required;
  };
  const Want wants[] = {
      {"motor_id", Column::kMotorId, Quantity::kId, "", true},
      {"U", Column::kVdcV, Quantity::kVoltage, "V", true},
      {"n", Column::kOmegaRadS, Quantity::kSpeed, "rpm", true},
      {"I", Column::kIdcA, Quantity::kCurrent, "A", true},
      {"IsNoLoad", Column::kNoLoad, Quantity::kFlag, "", true},
      {"Temp", Column::kTempC, Quantity::kTemperature, "C", false},
  };
  for (const Want& w : wants) {
    std::size_t idx = h.cells.size();
    for (std::size_t i = 0; i < h.cells.size(); ++i) {
      if (h.cells[i] == w.name) idx = i;
    }
    if (idx == h.cells.size()) {
      if (w.required) {
        throw DataError(path + ": line 1: DriveCalc MData column \"" + w.name +
                        "\" missing (required: motor_id, U, n, I, IsNoLoad)");
      }
      continue;
    }
    Slot s;
    s.target = w.column;
    s.quantity = w.quantity;
    s.field = idx;
    s.header = w.name;
    s.unit = w.unit;
    s.conv = *ParseUnit(w.quantity, w.unit);
    p.slots.push_back(std::move(s));
  }
  return p;
}

// One --map entry ("canonical_name=Source Header [unit]") as a slot; `seen` (per column: the
// field mapped, or -1) refuses a column mapped twice.
Slot MappedSlot(const std::string& entry, const Header& h, bool header_is_data, const LogReadOptions& o,
                const std::string& path, std::vector<int>* seen_columns) {
  std::vector<int>& seen = *seen_columns;
  const std::size_t eq = entry.find('=');
  if (eq == std::string::npos) {
    throw UsageError("column map entry \"" + entry +
                     "\": expected canonical_name=Source Header [unit]");
  }
  const std::string key(Trim(std::string_view(entry).substr(0, eq)));
  std::string source(Trim(std::string_view(entry).substr(eq + 1)));
  const CanonicalName* cn = FindCanonical(key);
  if (cn == nullptr) {
    throw UsageError("column map entry \"" + entry + "\": unknown canonical name \"" + key +
                     "\"; valid: " + CanonicalNameList());
  }
  const int col = static_cast<int>(cn->column);
  if (seen[col] >= 0) {
    throw UsageError("column map entry \"" + entry + "\": " + ColumnName(cn->column) +
                     " is mapped twice");
  }
  // Locate the source: whole header cell first, then "name [unit]" split.
  std::size_t idx = h.cells.size();
  std::string unit;
  bool unit_from_map = false;
  if (!source.empty() && source[0] == '#') {
    const HeaderCell hc = SplitHeaderCell(source);
    double k = 0;
    if (!ParseDouble(std::string_view(hc.name).substr(1), &k) || k < 1 || k != std::floor(k)) {
      throw UsageError("column map entry \"" + entry + "\": \"#k\" needs a column number >= 1");
    }
    if (!hc.unit.empty()) unit = hc.unit, unit_from_map = true;
    idx = static_cast<std::size_t>(k) - 1;
  } else {
    for (std::size_t i = 0; i < h.cells.size() && !header_is_data; ++i) {
      if (h.cells[i] == source) idx = i;
    }
    if (idx < h.cells.size()) {
      unit = SplitHeaderCell(h.cells[idx]).unit;  // the header's own unit, if any
      if (!unit.empty() && !ParseUnit(cn->quantity, unit)) unit.clear();
    } else {
      const HeaderCell want = SplitHeaderCell(source);
      for (std::size_t i = 0; i < h.cells.size() && !header_is_data; ++i) {
        if (h.cells[i] == want.name || SplitHeaderCell(h.cells[i]).name == want.name) idx = i;
      }
      if (idx < h.cells.size()) {
        unit = want.unit.empty() ? SplitHeaderCell(h.cells[idx]).unit : want.unit;
        unit_from_map = !want.unit.empty();
      }
    }
    if (idx >= h.cells.size()) {
      std::vector<std::string> have;
      for (const auto& c : h.cells) have.push_back("\"" + c + "\"");
      throw DataError(path + ": line 1: column map entry \"" + entry + "\": no column \"" +
                      source + "\" in the header; columns: " +
                      (header_is_data ? std::string("(no header: use #k)") : JoinSorted(have)));
    }
  }
  if (unit.empty()) unit = cn->default_unit;
  const auto u = ParseUnit(cn->quantity, unit);
  if (!u) {
    throw UsageError("column map entry \"" + entry + "\": unit " + QuoteCell(unit) +
                     (unit_from_map ? "" : " (from the header)") + " is not valid for " +
                     key + "; valid: " + ValidUnits(cn->quantity));
  }
  seen[col] = static_cast<int>(idx);
  Slot s;
  s.target = cn->column;
  s.quantity = cn->quantity;
  s.field = idx;
  s.header = idx < h.cells.size() && !header_is_data ? h.cells[idx] : "#" + std::to_string(idx + 1);
  s.unit = unit;
  s.conv = *u;
  if (u->pulse_width_us) s.pulse = true, s.pulse_us = true, s.pulse_min = o.esc_min_us, s.pulse_max = o.esc_max_us;
  return s;
}

Plan PlanMapped(const Header& h, bool header_is_data, const LogReadOptions& o,
                const std::string& path) {
  Plan p;
  p.format = LogFormat::kMapped;
  p.has_header = !header_is_data;
  p.header_cells = h.cells.size();
  std::vector<int> seen(kColumnCount, -1);
  for (const std::string& entry : o.column_map) {
    p.slots.push_back(MappedSlot(entry, h, header_is_data, o, path, &seen));
  }
  if (seen[static_cast<int>(Column::kIdcA)] < 0) {
    throw UsageError("column map: idc_a must be mapped (every calibration needs the DC current)");
  }
  return p;
}

// ThrustApp reports (thrustapp.h): the step tables, in the units of the data set's README.
Plan PlanThrustApp(const LogReadOptions& o, const std::string& path, SteadyTable* t) {
  if (!o.column_map.empty()) {
    throw UsageError("--map is given for a ThrustApp report: its columns are fixed (out %, thrust "
                     "g, torque g*cm, rpm, V, A); drop --map");
  }
  LogReadOptions fixed;
  fixed.column_map = {"throttle=out [%]", "thrust_n=th [g]", "torque_nm=tq [G cm]", "rpm=rpm",
                      "vdc_v=v [V]", "idc_a=a [A]"};
  Plan p = PlanMapped(ParseHeader(ThrustAppLines::kHeader), false, fixed, path);
  p.format = LogFormat::kThrustApp;
  p.empty_cells_ok = true;  // "nan" rpm (telemetry dropout): the step is dropped and counted
  t->delimiter = ',';
  return p;
}

// ---------------------------------------------------------------- row reading

struct RawRows {
  std::vector<std::size_t> line;
  std::vector<char> esc_outside;  // per row: ESC signal outside the end points (lenient only)
  std::string esc_reason;
};

// A cell that does not begin like a number (digit, sign, '.'): an annotation such as "PEAK
// THRUST" or "n/a", which --drop-incomplete-rows drops. "1.2.3" begins like one: an error.
bool IsTextCell(std::string_view cell) {
  cell = Trim(cell);
  if (cell.empty()) return false;
  const char c = cell.front();
  return !((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == ',');
}

// The rule named when a cell is not a number, with the likely fix.
std::string NotANumberRule(std::string_view cell, bool decimal_comma) {
  double v = 0.0;
  if (decimal_comma) {
    if (cell.find('.') != std::string_view::npos && ParseDouble(cell, &v)) {
      return "not a number with --decimal-comma (a '.' reads as a thousands separator: drop "
             "--decimal-comma if the file uses decimal points)";
    }
    return "not a number (rule: a finite decimal number with ',' as decimal point, "
           "--decimal-comma)";
  }
  if (cell.find(',') != std::string_view::npos && ParseDoubleDecimalComma(cell, &v)) {
    return "not a number (rule: '.' as decimal point; a decimal comma? read the file with "
           "--decimal-comma)";
  }
  return "not a number (rule: a finite decimal number with '.' as decimal point)";
}

// A line written with decimal commas read without --decimal-comma: most of its cells hold a
// comma between digits ("12,5" quoted, or after ';' or tabs), or, split at ',', the line has
// half again as many cells as the header (every "12,5" became two cells). Checked only when a
// cell failed, to add the hint to its error. Returns what was seen, or "".
std::string LooksDecimalComma(std::string_view line, std::size_t header_cells, char delim) {
  std::vector<std::string_view> cells;
  SplitFields(line, delim, &cells);
  if (delim == ',' && header_cells > 0 && 2 * cells.size() >= 3 * header_cells) {
    return "the line has " + std::to_string(cells.size()) + " cells for " + std::to_string(header_cells) +
           " header columns";
  }
  std::size_t with_comma = 0, nonempty = 0;
  for (const std::string_view c : cells) {
    const std::string_view v = Trim(c);
    if (v.empty()) continue;
    ++nonempty;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
      const auto digit = [](char x) { return x >= '0' && x <= '9'; };
      if (v[i] == ',' && digit(v[i - 1]) && digit(v[i + 1])) {
        ++with_comma;
        break;
      }
    }
  }
  if (nonempty == 0 || 2 * with_comma <= nonempty) return "";
  return std::to_string(with_comma) + " of the line's " + std::to_string(nonempty) +
         " cells hold a comma inside a number";
}

// Counts of rows left out while reading, reported once at the end.
struct ReadCounts {
  std::size_t other_motor_rows = 0, short_rows = 0, esc_outside = 0, filtered = 0, text_rows = 0;
  std::string first_text;                 // "line 13, column "X": "PEAK THRUST""
  std::vector<std::string> filter_seen;   // distinct values of the --where columns (first 8)
};

// --where: true when the row is kept.
bool RowSelected(const Plan& plan, const std::vector<std::string_view>& fields, ReadCounts* n) {
  for (const Plan::RowFilter& f : plan.filters) {
    const std::string_view cell = f.field < fields.size() ? Trim(fields[f.field]) : std::string_view();
    if (cell != f.value) {
      if (n->filter_seen.size() < 8 &&
          std::find(n->filter_seen.begin(), n->filter_seen.end(), cell) == n->filter_seen.end()) {
        n->filter_seen.emplace_back(cell);
      }
      ++n->filtered;
      return false;
    }
  }
  return true;
}

// A table of several motors read without --where: the first row's motor cells (`first`) must
// hold in every row.
void CheckOneSetup(const Plan& plan, const std::vector<std::string_view>& fields, std::size_t line_no,
                   const std::string& path, std::vector<std::string>* first) {
  if (plan.setup_fields.empty()) return;
  if (first->empty()) {
    for (const std::size_t f : plan.setup_fields) first->emplace_back(f < fields.size() ? Trim(fields[f]) : "");
    return;
  }
  for (std::size_t k = 0; k < plan.setup_fields.size(); ++k) {
    const std::size_t f = plan.setup_fields[k];
    const std::string_view cell = f < fields.size() ? Trim(fields[f]) : std::string_view();
    if (cell == (*first)[k]) continue;
    const std::string& header = plan.setup_headers[k];
    throw DataError(path + ": line " + std::to_string(line_no) + ", column \"" + header + "\": " +
                    QuoteCell(cell) + " after " + QuoteCell((*first)[k]) +
                    ": the table holds several motors or reports (rule: one motor per read); "
                    "keep one with --where \"" + header + "=" + (*first)[k] + "\"");
  }
}

// --drop-incomplete-rows: true when a used cell holds text (the row is dropped and counted).
bool RowHasText(const Plan& plan, const std::vector<std::string_view>& fields, std::size_t line_no,
                ReadCounts* n) {
  for (const Slot& s : plan.slots) {
    if (s.field < fields.size() && IsTextCell(fields[s.field])) {
      if (n->text_rows++ == 0) {
        n->first_text = "line " + std::to_string(line_no) + ", column \"" + s.header + "\": " +
                        QuoteCell(Trim(fields[s.field]));
      }
      return true;
    }
  }
  return false;
}

// Parses one used cell into its slot (SI value, NaN for an allowed empty cell); returns true
// when a lenient format's throttle lies outside the end points (the row is then dropped).
inline bool ReadCell(Slot& s, std::string_view cell, const Plan& plan, const LogReadOptions& o,
              const std::string& path, std::size_t line_no) {
  double v = 0.0;
  std::string_view number = Trim(cell);
  if (number.empty()) {
    if (!plan.lenient && !plan.empty_cells_ok) {
      CellError(path, line_no, s.header, cell,
                std::string("empty cell (rule: the ") + LogFormatName(plan.format) +
                    " format has no optional cells" +
                    (plan.format == LogFormat::kMapped ? "; --drop-incomplete-rows drops such rows)"
                                                       : ")"));
    }
    s.values.push_back(kNaN);
    return false;
  }
  // Manufacturer tables write throttle as "40.00%" (dronebuildcalc): a percent sign on a
  // throttle cell means percent, whatever the column's unit (a pulse width excepted).
  const bool percent = s.target == Column::kThrottle && !s.pulse && !s.scale_from_values &&
                       number.size() > 1 && number.back() == '%';
  if (percent) number.remove_suffix(1);
  const bool ok = o.decimal_comma ? ParseDoubleDecimalComma(number, &v) : ParseDouble(number, &v);
  if (!ok) CellError(path, line_no, s.header, cell, NotANumberRule(cell, o.decimal_comma));
  const double si = percent ? v * 0.01 : ToSi(s, v);
  if (!(std::fabs(si) <= kMaxAbsSiValue)) {
    std::ostringstream rule;
    rule << "out of range: " << si << " " << SiUnit(s.quantity)
         << " after conversion (rule: magnitude at most " << kMaxAbsSiValue << " in SI units)";
    CellError(path, line_no, s.header, cell, rule.str());
  }
  if (s.target == Column::kThrottle && !s.scale_from_values &&
      (si < -kThrottleRoundingSlack || si > 1.0 + kThrottleRoundingSlack)) {
    if (plan.lenient) {
      // Stand scripts send e.g. 980 us (arming, motor off) or 2100 us: no throttle point.
      s.values.push_back(kNaN);
      return true;
    }
    if (s.pulse) {
      std::ostringstream rule;
      rule << "outside the ESC end points " << s.pulse_min << " .. " << s.pulse_max
           << " us (set --esc-min-us/--esc-max-us to the end points the ESC was calibrated to)";
      CellError(path, line_no, s.header, cell, rule.str());
    }
    CellError(path, line_no, s.header, cell, "throttle outside 0..1");
  }
  s.values.push_back(si);
  return false;
}

// Checks the cell count of a row; false when the row is skipped (counted).
bool RowShapeOk(const Plan& plan, const std::vector<std::string_view>& fields, std::size_t max_field,
                const std::string& path, std::size_t line_no, const LogReadOptions& o,
                bool line_has_comma, SteadyTable* t, ReadCounts* n) {
  if (plan.lenient || (plan.empty_cells_ok && fields.size() <= max_field)) {
    if (fields.size() <= max_field) {
      ++n->short_rows;
      return false;
    }
    // A trailing delimiter gives one empty extra cell: that is the format, not an extra.
    std::size_t cells = fields.size();
    if (cells > plan.header_cells && Trim(fields[cells - 1]).empty()) --cells;
    if (plan.lenient && cells > plan.header_cells) ++t->rows_with_extra_cells;
    if (plan.lenient) return true;
  }
  if (plan.has_header && fields.size() != plan.header_cells) {
    throw DataError(path + ": line " + std::to_string(line_no) + ": " + std::to_string(fields.size()) +
                    " cells, the header has " + std::to_string(plan.header_cells) +
                    " (rule: one cell per header column in every row" +
                    (!o.decimal_comma && fields.size() > plan.header_cells && line_has_comma
                         ? "; decimal commas? save with ';' between cells and use --decimal-comma"
                         : "") +
                    ")");
  }
  if (fields.size() <= max_field) {
    throw DataError(path + ": line " + std::to_string(line_no) + ": " + std::to_string(fields.size()) +
                    " cells, column " + std::to_string(max_field + 1) +
                    " is mapped (rule: every row has it)");
  }
  return true;
}

void ReportReadCounts(const ReadCounts& n, const Plan& plan, const std::string& path,
                      const LogReadOptions& o, SteadyTable* t, RawRows* rows) {
  AddDrop(t, "rows shorter than the header", n.short_rows);
  if (n.text_rows > 0) {
    AddDrop(t, "rows with text where a number belongs (--drop-incomplete-rows; first: " +
                   n.first_text + ")",
            n.text_rows);
  }
  {
    std::ostringstream s;
    s << "rows with the ESC signal outside the end points " << o.esc_min_us << "-"
      << o.esc_max_us << " us (arming / beyond full throttle; --esc-min-us/--esc-max-us)";
    rows->esc_reason = s.str();
  }
  if (!plan.filters.empty()) {
    std::string what;
    for (const auto& f : plan.filters) what += (what.empty() ? "" : ", ") + f.header + "=" + f.value;
    if (rows->line.empty()) {
      std::string seen;
      for (const auto& v : n.filter_seen) seen += (seen.empty() ? "\"" : ", \"") + v + "\"";
      throw DataError(path + ": no row has " + what + " (--where; " + std::to_string(n.filtered) +
                      " rows of other values" + (seen.empty() ? "" : ", e.g. " + seen) + ")");
    }
    t->notes.push_back(std::to_string(n.filtered) + " rows of other values skipped (--where " +
                       what + ")");
  }
  if (plan.format == LogFormat::kDriveCalc && o.drivecalc_motor_id >= 0) {
    if (rows->line.empty()) {
      throw DataError(path + ": no MData row has motor_id " + std::to_string(o.drivecalc_motor_id) +
                      " (" + std::to_string(n.other_motor_rows) + " rows of other motors)");
    }
    t->notes.push_back(std::to_string(n.other_motor_rows) +
                       " rows of other motors skipped (--drivecalc-motor " +
                       std::to_string(o.drivecalc_motor_id) + ")");
  }
}

// `Lines`: LineReader, or ThrustAppLines (a report's step tables as rows).
template <class Lines>
void ReadRows(Lines* lr, Plan* plan, const std::string& path, SteadyTable* t,
              RawRows* rows, std::string_view first_data_line, const LogReadOptions& o) {
  std::vector<std::string_view> fields;
  fields.reserve(64);
  std::size_t max_field = 0;
  for (const Slot& s : plan->slots) max_field = std::max(max_field, s.field);
  const bool drivecalc_filter = plan->format == LogFormat::kDriveCalc && o.drivecalc_motor_id >= 0;
  std::size_t motor_slot = plan->slots.size();
  for (std::size_t k = 0; k < plan->slots.size(); ++k) {
    if (plan->slots[k].target == Column::kMotorId) motor_slot = k;
  }
  ReadCounts counts;
  std::vector<std::string> first_setup;
  const bool comma_split_risk = o.decimal_comma && t->delimiter == ',';

  auto process = [&](std::string_view line, std::size_t line_no) {
    if (Trim(line).empty() || Trim(line).front() == '#') {
      ++t->blank_or_comment_lines;
      return;
    }
    SplitFields(line, t->delimiter, &fields);
    if (!plan->filters.empty() && !RowSelected(*plan, fields, &counts)) return;
    if (!plan->setup_fields.empty()) CheckOneSetup(*plan, fields, line_no, path, &first_setup);
    ++t->data_rows_read;
    if (comma_split_risk && line.find('"') == std::string_view::npos) {
      throw DataError(path + ": line " + std::to_string(line_no) +
                      ": --decimal-comma, but cells are separated by ',' and this row is not "
                      "quoted: every decimal comma would split a number (quote the cells, or "
                      "save the file with ';' between cells)");
    }
    if (!RowShapeOk(*plan, fields, max_field, path, line_no, o, t->delimiter == ',', t, &counts)) {
      return;
    }
    if (drivecalc_filter) {
      double id = 0;
      const std::string_view cell = fields[plan->slots[motor_slot].field];
      if (!ParseDouble(cell, &id)) {
        CellError(path, line_no, "motor_id", cell, "not a number");
      }
      if (static_cast<long long>(id) != o.drivecalc_motor_id) {
        ++counts.other_motor_rows;
        --t->data_rows_read;
        return;
      }
    }
    if (o.mapped_drop_rows_with_empty_cells && RowHasText(*plan, fields, line_no, &counts)) return;
    char row_outside = 0;
    for (Slot& s : plan->slots) {
      if (ReadCell(s, fields[s.field], *plan, o, path, line_no)) {
        row_outside = 1;
        ++counts.esc_outside;
      }
    }
    rows->line.push_back(line_no);
    rows->esc_outside.push_back(row_outside);
  };

  // A cell refused on a line written with decimal commas gets the --decimal-comma hint (the
  // line's view stays valid here: nothing is read after the throw).
  std::string_view line = first_data_line;
  try {
    if (!plan->has_header) process(first_data_line, 1);
    while (lr->Next(&line)) {
      ++t->lines_read;
      process(line, lr->line_number());
    }
  } catch (const DataError& e) {
    const std::string what = e.what();
    if (o.decimal_comma || what.find("--decimal-comma") != std::string::npos) throw;
    const std::string seen = LooksDecimalComma(line, plan->header_cells, t->delimiter);
    if (seen.empty()) throw;
    throw DataError(what + " (" + seen + ": decimal commas? read the file with --decimal-comma)");
  }
  ReportReadCounts(counts, *plan, path, o, t, rows);
  if (drivecalc_filter) {
    for (Slot& s : plan->slots) {
      if (s.target == Column::kMotorId) s.active = false;
    }
  }
}

// A command column without a unit: the scale is read from its values (log_reader.h). Values
// outside 0..1 after scaling drop their rows as the end points do (lenient formats only).
void ScaleUnitlessCommand(Plan* plan, RawRows* rows, SteadyTable* t, const LogReadOptions& o) {
  for (Slot& s : plan->slots) {
    if (!s.scale_from_values) continue;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const double v : s.values) {
      if (!std::isnan(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
    ColumnInfo& ci = t->info[static_cast<int>(Column::kThrottle)];
    if (!(hi >= lo)) continue;  // empty in every row: ResolveColumns says so
    constexpr double kPulseLowUs = 800.0, kPulseHighUs = 2200.0, kCommandMax = 2000.0;
    double offset = 0.0, span = 1.0;
    std::ostringstream note;
    note << "\"" << s.header << "\" has no unit; values " << lo << ".." << hi;
    if (lo >= 0.0 && hi <= 1.0) {
      note << " read as a fraction 0..1";
    } else if (lo >= kPulseLowUs && hi <= kPulseHighUs) {
      offset = o.esc_min_us;
      span = o.esc_max_us - o.esc_min_us;
      s.pulse_us = true, s.pulse_min = o.esc_min_us, s.pulse_max = o.esc_max_us;
      note << " read as a pulse width in us (" << offset << ".." << offset + span
           << ", --esc-min-us/--esc-max-us)";
    } else if (lo >= 0.0 && hi <= kCommandMax) {
      span = kCommandMax;
      note << " read as command units 0..2000 (RCbenchmark scripts' unitless ESC command)";
    } else {
      note << ": not a fraction, a pulse width or 0..2000 command units";
      ci.note = note.str();
      t->notes.push_back("throttle absent: " + ci.note);
      s.active = false;
      continue;
    }
    ci.note = note.str();
    t->notes.push_back("throttle: " + ci.note);
    for (std::size_t r = 0; r < s.values.size(); ++r) {
      double& v = s.values[r];
      if (std::isnan(v)) continue;
      v = (v - offset) / span;
      if (v < -kThrottleRoundingSlack || v > 1.0 + kThrottleRoundingSlack) {
        v = kNaN;
        rows->esc_outside[r] = 1;
      }
    }
  }
}

// ---------------------------------------------------------------- building the table

bool AllNaN(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isnan(x); });
}
bool AllZeroOrNaN(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isnan(x) || x == 0.0; });
}

// Decides which slots make columns; fills info.
std::vector<Slot*> ResolveColumns(Plan* plan, SteadyTable* t) {
  std::vector<Slot*> chosen(kColumnCount, nullptr);
  for (Slot& s : plan->slots) {
    if (!s.active) continue;
    ColumnInfo& ci = t->info[static_cast<int>(s.target)];
    if (AllNaN(s.values)) {
      if (chosen[static_cast<int>(s.target)] == nullptr) {
        ci.note = "\"" + s.header + "\" is empty in every row";
      }
      continue;
    }
    if (s.target == Column::kOmegaRadS && AllZeroOrNaN(s.values)) {
      if (chosen[static_cast<int>(s.target)] == nullptr) {
        ci.note += std::string(ci.note.empty() ? "" : "; ") + "\"" + s.header +
                   "\" is zero in every row (no speed sensor)";
      }
      continue;
    }
    if (chosen[static_cast<int>(s.target)] != nullptr) {
      ci.note += std::string(ci.note.empty() ? "" : "; ") + "\"" + s.header + "\" not used";
      continue;
    }
    chosen[static_cast<int>(s.target)] = &s;
    if (s.target == Column::kThrottle && s.pulse_us) {
      t->throttle_pulse_min_us = s.pulse_min;
      t->throttle_pulse_max_us = s.pulse_max;
    }
    ci.present = true;
    ci.source_header = s.header;
    ci.source_unit = s.unit;
  }
  return chosen;
}

void AppendRow(SteadyTable* t, const std::vector<Slot*>& chosen, std::size_t line,
               std::size_t samples, const double* values) {
  for (int c = 0; c < kColumnCount; ++c) {
    if (chosen[c] != nullptr) t->columns[c].push_back(values[c]);
  }
  t->source_line.push_back(line);
  t->samples.push_back(samples);
}

void BuildPerRow(SteadyTable* t, const std::vector<Slot*>& chosen, const RawRows& rows,
                 bool zero_is_dropout) {
  double vals[kColumnCount];
  const std::size_t n = rows.line.size();
  // At most n rows: no growth by doubling on the way (peak memory of a million-row log).
  for (int c = 0; c < kColumnCount; ++c) {
    if (chosen[c] != nullptr) t->columns[c].reserve(n);
  }
  t->source_line.reserve(n);
  t->samples.reserve(n);
  for (std::size_t r = 0; r < n; ++r) {
    if (rows.esc_outside[r]) {
      AddDrop(t, rows.esc_reason);
      continue;
    }
    bool ok = true;
    for (int c = 0; c < kColumnCount && ok; ++c) {
      if (chosen[c] == nullptr) continue;
      vals[c] = chosen[c]->values[r];
      if (std::isnan(vals[c])) {
        AddDrop(t, "rows with an empty " +
                       std::string(zero_is_dropout && c == static_cast<int>(Column::kOmegaRadS)
                                       ? "or zero (probe dropout / motor not started) "
                                       : "") +
                       "\"" + chosen[c]->header + "\" cell");
        ok = false;
      }
    }
    if (ok) AppendRow(t, chosen, rows.line[r], 1, vals);
  }
}

void BuildPlateaus(SteadyTable* t, const std::vector<Slot*>& chosen, const RawRows& rows,
                   const PlateauOptions& po) {
  const std::size_t n = rows.line.size();
  const Slot* time = chosen[static_cast<int>(Column::kTimeS)];
  const Slot* cmd = chosen[static_cast<int>(Column::kThrottle)];
  const Slot* sig = chosen[static_cast<int>(Column::kOmegaRadS)];
  if (sig == nullptr) sig = chosen[static_cast<int>(Column::kIdcA)];
  // Rows without time or command cannot be placed in a step.
  std::vector<std::size_t> keep;
  keep.reserve(n);
  for (std::size_t r = 0; r < n; ++r) {
    if (rows.esc_outside[r]) {
      AddDrop(t, rows.esc_reason);
      continue;
    }
    if (time != nullptr && std::isnan(time->values[r])) {
      AddDrop(t, "samples with an empty \"" + time->header + "\" cell");
      continue;
    }
    if (cmd != nullptr && std::isnan(cmd->values[r])) {
      AddDrop(t, "samples with an empty \"" + cmd->header + "\" cell");
      continue;
    }
    keep.push_back(r);
  }
  // Gather compact copies (contiguous arrays for the search).
  std::vector<std::vector<double>> col(kColumnCount);
  for (int c = 0; c < kColumnCount; ++c) {
    if (chosen[c] == nullptr) continue;
    col[c].reserve(keep.size());
    for (const std::size_t r : keep) col[c].push_back(chosen[c]->values[r]);
  }
  const int sig_col = sig == nullptr ? -1 : static_cast<int>(sig->target);
  std::vector<const double*> measured;
  for (int c = 0; c < kColumnCount; ++c) {
    if (chosen[c] == nullptr || c == static_cast<int>(Column::kTimeS) ||
        c == static_cast<int>(Column::kThrottle)) {
      continue;
    }
    measured.push_back(col[c].data());
  }
  // Independent runs where time goes backwards (appended recordings, out-of-order rows).
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  std::size_t run_start = 0;
  const std::size_t m = keep.size();
  // Asynchronous sampling makes time jitter backwards by a few ms; only a jump back by more
  // than summary_min_interval_s is a new recording appended to the file.
  for (std::size_t i = 1; i <= m; ++i) {
    if (i == m || (time != nullptr && col[0][i] < col[0][i - 1] - po.summary_min_interval_s)) {
      runs.emplace_back(run_start, i);
      run_start = i;
    }
  }
  if (runs.size() > 1) {
    t->notes.push_back("time goes backwards " + std::to_string(runs.size() - 1) +
                       " time(s): the log was searched as " + std::to_string(runs.size()) +
                       " separate runs");
  }
  std::vector<char> mask;
  std::size_t short_plateaus = 0, short_samples = 0, unsteady = 0;
  std::vector<std::size_t> by_method(4, 0);
  double vals[kColumnCount];
  for (const auto& [rb, re] : runs) {
    const std::size_t len = re - rb;
    const double* tp = time != nullptr ? col[0].data() + rb : nullptr;
    const double* cp = cmd != nullptr ? col[static_cast<int>(Column::kThrottle)].data() + rb : nullptr;
    const double* sp = sig_col >= 0 ? col[sig_col].data() + rb : nullptr;
    const PlateauSearch ps = FindPlateaus(tp, cp, sp, len, po);
    by_method[static_cast<std::size_t>(ps.method)] += 1;
    t->transient_samples += ps.transient_samples;
    short_plateaus += ps.short_plateaus;
    short_samples += ps.short_plateau_samples;
    unsteady += ps.unsteady_samples;
    for (const Plateau& pl : ps.plateaus) {
      std::vector<const double*> cols;
      for (const double* x : measured) cols.push_back(x + rb);
      t->outlier_samples += MarkOutliers(cols, pl.begin, pl.end, po, &mask);
      bool ok = true;
      std::size_t used_max = 0;
      std::size_t first_line = 0;
      for (int c = 0; c < kColumnCount && ok; ++c) {
        if (chosen[c] == nullptr) continue;
        const double* x = col[c].data() + rb;
        double sum = 0.0;
        std::size_t cnt = 0;
        for (std::size_t i = pl.begin; i < pl.end; ++i) {
          if (mask[i - pl.begin] || std::isnan(x[i])) continue;
          if (first_line == 0) first_line = rows.line[keep[rb + i]];
          sum += x[i];
          ++cnt;
        }
        if (cnt == 0) {
          AddDrop(t, "plateaus without a \"" + chosen[c]->header + "\" sample");
          ok = false;
          break;
        }
        vals[c] = sum / static_cast<double>(cnt);
        used_max = std::max(used_max, cnt);
      }
      if (ok) {
        AppendRow(t, chosen, first_line, used_max, vals);
        ++t->plateaus_found;
      }
    }
  }
  AddDrop(t, "samples in steps too short to average after the transient (plateau minimum sample count)", short_samples);
  AddDrop(t, "samples not steady (signal search)", unsteady);
  if (short_plateaus > 0) {
    t->notes.push_back(std::to_string(short_plateaus) + " steps/runs too short to be plateaus");
  }
  std::string how;
  for (std::size_t k = 0; k < by_method.size(); ++k) {
    if (by_method[k] == 0) continue;
    how += std::string(how.empty() ? "" : ", ") + PlateauMethodName(static_cast<PlateauMethod>(k));
    if (runs.size() > 1) how += " (" + std::to_string(by_method[k]) + " runs)";
  }
  t->notes.push_back("plateaus found by " + how);
}

double MedianInterval(const std::vector<double>& t) {
  std::vector<double> d;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (!std::isnan(t[i]) && !std::isnan(t[i - 1])) d.push_back(std::fabs(t[i] - t[i - 1]));
  }
  return MedianOf(d.data(), 0, d.size());
}

void NormalizeSigns(SteadyTable* t) {
  for (const Column c : {Column::kTorqueNm, Column::kThrustN}) {
    if (!t->Has(c)) continue;
    std::vector<double>& v = t->Mutable(c);
    const double med = MedianOf(v.data(), 0, v.size());
    if (med < 0.0) {
      for (double& x : v) x = -x;
      ColumnInfo& ci = t->info[static_cast<int>(c)];
      ci.note += std::string(ci.note.empty() ? "" : "; ") +
                 "sign flipped (negative median: mounting direction)";
    }
  }
}

void CheckCanonicalRanges(const SteadyTable& t, const std::string& path) {
  const std::size_t n = t.rows();
  auto check = [&](Column c, bool (*ok)(double), const char* rule) {
    if (!t.Has(c)) return;
    const auto& v = t.Get(c);
    for (std::size_t r = 0; r < n; ++r) {
      if (!ok(v[r])) {
        std::ostringstream val;
        val.precision(17);
        val << v[r];
        CellError(path, t.source_line[r], ColumnName(c), val.str(), rule);
      }
    }
  };
  check(Column::kVdcV, [](double x) { return x > 0.0; }, "vdc_v must be > 0");
  check(Column::kVllRmsV, [](double x) { return x >= 0.0; }, "vll_rms_v must be >= 0");
  check(Column::kIrmsA, [](double x) { return x >= 0.0; }, "irms_a must be >= 0");
}

void CheckTable(const SteadyTable& t, const std::string& path) {
  const std::size_t n = t.rows();
  std::string why = t.DroppedTotal() > 0 ? " after dropping " + std::to_string(t.DroppedTotal()) +
                                               " rows/samples"
                                         : std::string();
  if (n < 2) {
    throw DataError(path + ": " + std::to_string(n) + " steady operating point" +
                    (n == 1 ? "" : "s") + why + " (" + std::to_string(t.data_rows_read) +
                    " data rows read): a calibration needs at least 2");
  }
  if (!t.Has(Column::kIdcA)) {
    throw DataError(path + ": no usable current column (" +
                    t.info[static_cast<int>(Column::kIdcA)].note +
                    "): every calibration needs the DC current");
  }
  bool all_same = true;
  for (int c = 0; c < kColumnCount && all_same; ++c) {
    if (!t.info[c].present || c == static_cast<int>(Column::kTimeS)) continue;
    const auto& v = t.columns[c];
    for (std::size_t r = 1; r < n && all_same; ++r) all_same = v[r] == v[0];
  }
  if (all_same) {
    throw DataError(path + ": all " + std::to_string(n) +
                    " operating points are identical (time aside): nothing to fit");
  }
  const auto& idc = t.Get(Column::kIdcA);
  if (std::all_of(idc.begin(), idc.end(), [](double x) { return x == 0.0; })) {
    throw DataError(path + ": column \"" + t.info[static_cast<int>(Column::kIdcA)].source_header +
                    "\" (idc_a) is zero in every point: current sensor not connected?");
  }
}

std::string LineEnds(const LineReader& lr) {
  std::string s;
  if (lr.saw_lf()) s += "LF";
  if (lr.saw_crlf()) s += std::string(s.empty() ? "" : "+") + "CRLF";
  if (lr.saw_cr()) s += std::string(s.empty() ? "" : "+") + "CR";
  return s;
}

bool LooksNumeric(const Header& h) {
  if (h.cells.empty()) return false;
  for (const auto& c : h.cells) {
    double v;
    if (!c.empty() && !ParseDouble(c, &v)) return false;
  }
  return true;
}

// DriveCalc: points whose speed was not measured (n = 0) are not operating points (see
// LogReadOptions::drivecalc_keep_no_load_without_speed for the no-load exception).
void DropDriveCalcWithoutSpeed(SteadyTable* t, const LogReadOptions& options) {
  std::size_t w = 0;
  const std::size_t n = t->rows();
  auto& om = t->columns[static_cast<int>(Column::kOmegaRadS)];
  std::vector<char> keep(n);
  const bool keep_nl = options.drivecalc_keep_no_load_without_speed && t->Has(Column::kNoLoad);
  std::size_t kept_without_speed = 0;
  for (std::size_t r = 0; r < n; ++r) {
    keep[r] = om[r] != 0.0;
    if (!keep[r] && keep_nl && t->columns[static_cast<int>(Column::kNoLoad)][r] != 0.0) {
      keep[r] = 1;
      ++kept_without_speed;
    }
  }
  if (kept_without_speed > 0) {
    t->notes.push_back(std::to_string(kept_without_speed) +
                      " no-load points without a speed reading (n = 0) kept: they give Io only");
  }
  for (int c = 0; c < kColumnCount; ++c) {
    if (!t->info[c].present) continue;
    auto& v = t->columns[c];
    w = 0;
    for (std::size_t r = 0; r < n; ++r) {
      if (keep[r]) v[w++] = v[r];
    }
    v.resize(w);
  }
  w = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (keep[r]) {
      t->source_line[w] = t->source_line[r];
      t->samples[w] = t->samples[r];
      ++w;
    }
  }
  AddDrop(t, keep_nl ? "loaded points with n = 0 (speed not measured)" : "points with n = 0 (speed not measured)",
          n - w);
  t->source_line.resize(w);
  t->samples.resize(w);
}

// --where: the columns named by LogReadOptions::row_filter.
void ResolveFilters(const Header& h, bool header_is_data, const LogReadOptions& o,
                    const std::string& path, Plan* plan) {
  for (const std::string& entry : o.row_filter) {
    const std::size_t eq = entry.find('=');
    const std::string key(Trim(std::string_view(entry).substr(0, eq)));
    Plan::RowFilter f;
    f.header = key;
    f.value = std::string(Trim(std::string_view(entry).substr(eq + 1)));
    f.field = h.cells.size();
    double k = 0;
    if (key.size() > 1 && key[0] == '#' && ParseDouble(key.substr(1), &k) && k >= 1 &&
        k == std::floor(k) && k <= 1e6) {
      f.field = static_cast<std::size_t>(k) - 1;
    } else {
      for (std::size_t i = 0; i < h.cells.size() && !header_is_data; ++i) {
        if (h.cells[i] == key || (f.field == h.cells.size() && SplitHeaderCell(h.cells[i]).name == key)) {
          f.field = i;
        }
      }
      if (f.field >= h.cells.size()) {
        std::vector<std::string> have;
        for (const auto& c : h.cells) have.push_back("\"" + c + "\"");
        throw DataError(path + ": line 1: --where \"" + entry + "\": no column \"" + key +
                        "\" in the header; columns: " +
                        (header_is_data ? std::string("(no header: use #k)") : JoinSorted(have)));
      }
    }
    plan->filters.push_back(std::move(f));
  }
}

// The arguments that read column `c` from header cell `field` in addition to what was read:
// the map of a mapped read (given, or the synonym table's) or --format rcbenchmark --map.
std::string ReadArguments(const Header& h, const Plan& plan, const LogReadOptions& o, Column c,
                          std::size_t field) {
  std::string line = plan.format == LogFormat::kRcbenchmark ? "--format rcbenchmark " : "";
  if (plan.format == LogFormat::kMapped && o.column_map.empty()) line = ReadyMapLine(h, {}) + " ";
  for (const std::string& e : o.column_map) line += "--map \"" + e + "\" ";
  const std::string arg = MapArgument(c, h.cells[field]);
  return line + arg + UnitChoicesFor(arg);
}

// An absent throttle, voltage, speed, torque or current column: the note names the header
// cells that look like it (header_synonyms.h) and the arguments that read the first of them.
void NoteAbsentColumns(const Header& h, const Plan& plan, const LogReadOptions& o, SteadyTable* t) {
  if (plan.format != LogFormat::kRcbenchmark && plan.format != LogFormat::kMapped) return;
  std::vector<std::size_t> used;
  for (const Slot& s : plan.slots) used.push_back(s.field);
  for (const Column c : {Column::kThrottle, Column::kIdcA, Column::kVdcV, Column::kOmegaRadS,
                         Column::kTorqueNm}) {
    ColumnInfo& ci = t->info[static_cast<int>(c)];
    if (t->Has(c) || !ci.note.empty()) continue;
    const std::string what = c == Column::kThrottle ? "throttle" : c == Column::kIdcA ? "current"
                           : c == Column::kVdcV     ? "voltage"
                           : c == Column::kOmegaRadS ? "speed" : "torque";
    const std::vector<std::size_t> look = LookalikeColumns(c, h.cells, used);
    if (look.empty()) continue;
    std::string names;
    for (const std::size_t i : look) names += (names.empty() ? "\"" : ", \"") + h.cells[i] + "\"";
    ci.note = "no " + what + " column found; " + names + (look.size() == 1 ? " looks" : " look") +
              " like one: to read it, " + ReadArguments(h, plan, o, c, look[0]);
  }
}

}  // namespace

bool LogReadOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(esc_max_us > esc_min_us) || !std::isfinite(esc_min_us) || !std::isfinite(esc_max_us)) {
    return fail("--esc-min-us " + SignificantText(esc_min_us) + " --esc-max-us " + SignificantText(esc_max_us) +
                ": need finite values with --esc-max-us > --esc-min-us");
  }
  if (esc_unitless_max != 0.0 || esc_unitless_min != 0.0) {
    if (!(esc_unitless_max > esc_unitless_min)) {
      return fail("unitless ESC command range " + SignificantText(esc_unitless_min) + ".." +
                  SignificantText(esc_unitless_max) + " (LogReadOptions esc_unitless_min/max): need max > min");
    }
  }
  if (!column_map.empty() && format != LogFormat::kAuto && format != LogFormat::kMapped &&
      format != LogFormat::kRcbenchmark) {
    return fail(std::string("--map is given with --format ") + LogFormatName(format) +
                ": a column map needs --format mapped, rcbenchmark (to add columns to the detected "
                "ones) or auto");
  }
  if (format == LogFormat::kMapped && column_map.empty()) {
    return fail("--format mapped without --map: name each column, e.g. --map idc_a=Current");
  }
  for (const std::string& f : row_filter) {
    const std::size_t eq = f.find('=');
    if (eq == std::string::npos || Trim(std::string_view(f).substr(0, eq)).empty()) {
      return fail("--where \"" + f + "\": expected Header=value, e.g. --where \"motor=T-Motor MN2206\"");
    }
  }
  if (max_line_bytes < 64) return fail("LogReadOptions.max_line_bytes must be >= 64");
  return plateau.IsValid(error);
}

SteadyTable ReadLog(const std::string& path, const LogReadOptions& options) {
  if (std::string why; !options.IsValid(&why)) throw UsageError(why);
  SteadyTable t;
  t.file = path;
  LineReader lr(path, options.max_line_bytes);
  std::string_view line;
  // The header: the first line that is not blank.
  bool got = false;
  while (lr.Next(&line)) {
    ++t.lines_read;
    if (!Trim(line).empty()) {
      got = true;
      break;
    }
    ++t.blank_or_comment_lines;
  }
  if (!got) throw DataError(path + ": empty file: no header line");
  const Header h = ParseHeader(line);
  t.header_latin1 = h.latin1;
  t.delimiter = h.delim;
  LogFormat fmt = options.format;
  if (fmt == LogFormat::kAuto) fmt = Detect(h, options, path);
  t.format = fmt;

  Plan plan;
  std::string first_data;  // a headerless mapped file's first line is data
  switch (fmt) {
    case LogFormat::kCanonical: plan = PlanCanonical(h, path); break;
    case LogFormat::kRcbenchmark: plan = PlanBySynonyms(h, true, options, path, &t); break;
    case LogFormat::kDriveCalc: plan = PlanDriveCalc(h, path); break;
    case LogFormat::kMapped: {
      if (options.column_map.empty()) {  // auto-detected: the synonym table names the columns
        plan = PlanBySynonyms(h, false, options, path, &t);
        break;
      }
      bool all_hash = true;
      for (const auto& e : options.column_map) {
        const std::size_t eq = e.find('=');
        all_hash = all_hash && eq != std::string::npos &&
                   Trim(std::string_view(e).substr(eq + 1)).substr(0, 1) == "#";
      }
      const bool header_is_data = all_hash && LooksNumeric(h);
      plan = PlanMapped(h, header_is_data, options, path);
      if (header_is_data) first_data = std::string(line);
      break;
    }
    case LogFormat::kThrustApp: plan = PlanThrustApp(options, path, &t); break;
    case LogFormat::kAuto: throw InternalError("ReadLog: format still auto");
  }
  if (options.mapped_drop_rows_with_empty_cells && fmt == LogFormat::kMapped) {
    plan.empty_cells_ok = true;
  }
  RawRows rows;
  if (fmt == LogFormat::kThrustApp) {
    if (!IsThrustAppStart(h.raw_line_utf8)) {
      throw DataError(path + ": line 1: " + QuoteCell(h.raw_line_utf8) +
                      ": not a ThrustApp report (--format thrustapp: a .tex report starts with "
                      "\\documentclass, a .txt export with \"## Tool info\")");
    }
    ResolveFilters(ParseHeader(ThrustAppLines::kHeader), false, options, path, &plan);
    ThrustAppLines tl(&lr);
    ReadRows(&tl, &plan, path, &t, &rows, first_data, options);
    t.notes.push_back(tl.Summary());
  } else {
    ResolveFilters(h, !first_data.empty(), options, path, &plan);
    ReadRows(&lr, &plan, path, &t, &rows, first_data, options);
  }
  ScaleUnitlessCommand(&plan, &rows, &t, options);
  t.line_ends = LineEnds(lr);
  t.had_bom = lr.had_bom();

  std::vector<Slot*> chosen = ResolveColumns(&plan, &t);
  // RCbenchmark speed probes read exactly 0 when they lose the target (optical dropouts,
  // electrical probe below its minimum speed): a 0 in a column that reads elsewhere is "no
  // reading", not a stopped motor.
  if (fmt == LogFormat::kRcbenchmark) {
    if (Slot* sp = chosen[static_cast<int>(Column::kOmegaRadS)]) {
      std::size_t zeros = 0;
      for (double& v : sp->values) {
        if (v == 0.0) v = kNaN, ++zeros;
      }
      if (zeros > 0) {
        t.info[static_cast<int>(Column::kOmegaRadS)].note +=
            std::string(t.info[static_cast<int>(Column::kOmegaRadS)].note.empty() ? "" : "; ") +
            std::to_string(zeros) + " cells reading 0 treated as dropouts";
      }
    }
  }
  bool plateaus = false;
  if (fmt == LogFormat::kRcbenchmark || options.time_series == TimeSeriesMode::kPlateaus) {
    plateaus = options.time_series != TimeSeriesMode::kPerRow;
    const Slot* time = chosen[static_cast<int>(Column::kTimeS)];
    if (plateaus && options.time_series == TimeSeriesMode::kAuto && time != nullptr) {
      const double dt = MedianInterval(time->values);
      if (!std::isnan(dt) && dt >= options.plateau.summary_min_interval_s) {
        plateaus = false;
        std::ostringstream s;
        s << "one steady point per row (median interval " << dt
          << " s, at least the plateau summary interval): no plateau search";
        t.notes.push_back(s.str());
      }
    }
  }
  t.time_series = plateaus;
  if (plateaus) {
    BuildPlateaus(&t, chosen, rows, options.plateau);
  } else {
    BuildPerRow(&t, chosen, rows, fmt == LogFormat::kRcbenchmark);
  }
  // DriveCalc: points whose speed was not measured (n = 0) are not operating points.
  if (fmt == LogFormat::kDriveCalc && t.Has(Column::kOmegaRadS)) DropDriveCalcWithoutSpeed(&t, options);
  if (fmt == LogFormat::kCanonical) CheckCanonicalRanges(t, path);
  if (options.normalize_signs && fmt != LogFormat::kCanonical) NormalizeSigns(&t);
  // What the fit can identify.
  NoteAbsentColumns(h, plan, options, &t);
  if (!t.Has(Column::kThrottle) && t.info[static_cast<int>(Column::kThrottle)].note.empty()) {
    t.info[static_cast<int>(Column::kThrottle)].note = "no throttle column in this log";
  }
  for (const Column c : {Column::kThrottle, Column::kVdcV, Column::kOmegaRadS, Column::kTorqueNm}) {
    if (!t.Has(c)) {
      const std::string& why = t.info[static_cast<int>(c)].note;
      t.notes.push_back(std::string(ColumnName(c)) + " absent" + (why.empty() ? "" : ": " + why));
    }
  }
  CheckTable(t, path);
  return t;
}

}  // namespace dynosize::logs
