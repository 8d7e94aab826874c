// Reading a log, step 2: the plan of each format, which header cell feeds which column in which
// unit (canonical, stand export, synonym table, --map, DriveCalc, ThrustApp), and the --where
// filters.
#include "logs/log_read_steps.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "logs/csv_scan.h"
#include "logs/log_reader.h"
#include "logs/header_synonyms.h"
#include "logs/log_units.h"
#include "logs/thrustapp.h"

namespace dynosize::logs::read_internal {

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

namespace {

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
// throttle, the optical one is used whenever it saw anything.
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

}  // namespace

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

namespace {

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

}  // namespace

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

}  // namespace dynosize::logs::read_internal
