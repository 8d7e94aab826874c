#include "logs/log_reader.h"

#include <cmath>
#include <sstream>

#include "common/error.h"
#include "common/numbers.h"
#include "common/text_format.h"
#include "logs/csv_scan.h"
#include "logs/header_synonyms.h"
#include "logs/log_read_steps.h"
#include "logs/thrustapp.h"

namespace dynosize::logs {

// ReadLog's steps (log_read_steps.h).
using namespace read_internal;

namespace {

std::string LineEnds(const LineReader& lr) {
  std::string s;
  if (lr.saw_lf()) s += "LF";
  if (lr.saw_crlf()) s += std::string(s.empty() ? "" : "+") + "CRLF";
  if (lr.saw_cr()) s += std::string(s.empty() ? "" : "+") + "CR";
  return s;
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
