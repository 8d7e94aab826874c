// Reading a log, step 1: the header line, the canonical column names and the format detection
// (log_reader.h, docs/log-formats.md).
#include "logs/log_read_steps.h"

#include <algorithm>
#include <string>
#include <vector>

#include "common/error.h"
#include "logs/csv_scan.h"
#include "logs/log_reader.h"
#include "logs/header_synonyms.h"
#include "logs/log_units.h"
#include "logs/thrustapp.h"

namespace dynosize::logs::read_internal {

namespace {

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

}  // namespace

std::string JoinSorted(std::vector<std::string> v) {
  std::sort(v.begin(), v.end());
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + v[i];
  return out;
}

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

Header ParseHeader(std::string_view line) {
  Header h;
  h.delim = DetectDelimiter(line);
  h.raw_line_utf8 = ToUtf8(line, &h.latin1);
  std::vector<std::string_view> f;
  SplitFields(h.raw_line_utf8, h.delim, &f);
  for (auto v : f) h.cells.emplace_back(Trim(v));
  return h;
}

namespace {

bool HasCell(const Header& h, const char* name) {
  for (const auto& c : h.cells) {
    if (c == name) return true;
  }
  return false;
}

}  // namespace

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

namespace {

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

}  // namespace

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

namespace {

// The columns the synonym table names without a unit that reads ("\"Thrust\", \"Current\"").
std::string UnitlessColumns(const Header& h) {
  std::string out;
  for (const Matched& m : MatchAll(h)) {
    if (UnitReads(m.match)) continue;
    out += (out.empty() ? "\"" : ", \"") + h.cells[m.field] + "\"";
  }
  return out;
}

}  // namespace

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

bool LooksNumeric(const Header& h) {
  if (h.cells.empty()) return false;
  for (const auto& c : h.cells) {
    double v;
    if (!c.empty() && !ParseDouble(c, &v)) return false;
  }
  return true;
}

}  // namespace dynosize::logs::read_internal
