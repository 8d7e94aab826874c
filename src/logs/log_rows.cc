// Reading a log, step 3: the data rows, cell by cell into SI values, with the row checks and
// the counts of rows left out.
#include "logs/log_read_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/numbers.h"
#include "logs/csv_scan.h"
#include "logs/log_reader.h"
#include "logs/log_units.h"
#include "logs/thrustapp.h"

namespace dynosize::logs::read_internal {

namespace {

// Throttle computed from a pulse width may exceed 0..1 by rounding only.
constexpr double kThrottleRoundingSlack = 1e-9;
// Largest magnitude of a value in SI units (after unit conversion). Far beyond any measurement
// (1e12 A, V, rad/s; time stamps in Unix seconds are 1.7e9), it keeps squares and products
// the fit forms finite over millions of rows (1e24 * 1e6 << 1.8e308). Beyond it (1e308 in a
// cell, or kgf * 9.81 overflowing) the cell is a DataError in every format.
constexpr double kMaxAbsSiValue = 1e12;

}  // namespace

[[noreturn]] void CellError(const std::string& path, std::size_t line, const std::string& column,
                            std::string_view cell, const std::string& rule) {
  throw DataError(path + ": line " + std::to_string(line) + ", column \"" + column + "\": " +
                  QuoteCell(cell) + ": " + rule);
}

namespace {

double ToSi(const Slot& s, double raw) {
  if (s.pulse) return (raw - s.pulse_min) / (s.pulse_max - s.pulse_min);
  return raw * s.conv.scale + s.conv.offset;
}

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

}  // namespace

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

// The two kinds of line source ReadRows reads.
template void ReadRows<LineReader>(LineReader* lr, Plan* plan, const std::string& path, SteadyTable* t,
                                   RawRows* rows, std::string_view first_data_line, const LogReadOptions& o);
template void ReadRows<ThrustAppLines>(ThrustAppLines* lr, Plan* plan, const std::string& path, SteadyTable* t,
                                       RawRows* rows, std::string_view first_data_line,
                                       const LogReadOptions& o);

}  // namespace dynosize::logs::read_internal
