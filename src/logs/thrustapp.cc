#include "logs/thrustapp.h"

#include <vector>

#include "common/error.h"

namespace dynosize::logs {

namespace {

bool StartsWith(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

// A cell as the mapped reader should see it: trimmed, "nan" (telemetry dropout) empty.
std::string_view CleanCell(std::string_view cell) {
  cell = Trim(cell);
  if (cell == "nan" || cell == "-nan") return std::string_view();
  return cell;
}

}  // namespace

bool IsThrustAppStart(std::string_view first_line) {
  first_line = Trim(first_line);
  return StartsWith(first_line, "\\documentclass") || StartsWith(first_line, "## Tool info");
}

void ThrustAppLines::TakeMetadata(std::string_view line) {
  const std::size_t colon = line.find(':');
  if (colon == std::string_view::npos) return;
  const std::string_view key = Trim(line.substr(0, colon));
  std::string_view value = line.substr(colon + 1);
  const std::size_t amp = value.find('&');  // LaTeX tabular: "Motor: & T-Motor MN2206-13\\"
  if (amp != std::string_view::npos) value = value.substr(amp + 1);
  value = Trim(value);
  while (!value.empty() && (value.back() == '\\' || value.back() == ' ')) value.remove_suffix(1);
  std::string* to = key == "Motor" ? &motor_ : key == "KV" ? &kv_
                  : (key == "Propeler" || key == "Propeller") ? &prop_ : nullptr;
  if (to != nullptr && to->empty()) *to = std::string(value);
}

bool ThrustAppLines::TakeRow(std::string_view line, bool bracketed_std) {
  std::vector<std::string_view> cells;
  if (bracketed_std) {
    // "20   24.53 [1.701]   48.08 [2.579] ...": means, each followed by its std in brackets.
    std::vector<std::string_view> tokens;
    SplitFields(line, ' ', &tokens);
    for (const auto t : tokens) {
      if (!t.empty() && t.front() != '[') cells.push_back(t);
    }
    cells.resize(6);  // level, thrust, torque, rpm, volt, curr (Pin, Eff follow)
  } else {
    std::vector<std::string_view> fields;
    SplitFields(line, ',', &fields);
    for (const std::size_t c : col_) {
      cells.push_back(c != kNoColumn && c < fields.size() ? fields[c] : std::string_view());
    }
  }
  row_.clear();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) row_ += ',';
    row_ += CleanCell(cells[i]);
  }
  return true;
}

bool ThrustAppLines::Next(std::string_view* out) {
  std::string_view line;
  while (reader_->Next(&line)) {
    const std::string_view t = Trim(line);
    if (!t.empty() && t.front() == '%') continue;  // commented out in the report
    if (StartsWith(t, "\\begin{filecontents*}")) {
      in_tex_table_ = expect_tex_header_ = true;
      ++tables_;
      continue;
    }
    if (StartsWith(t, "\\end{filecontents*}")) {
      in_tex_table_ = false;
      continue;
    }
    if (in_tex_table_ && expect_tex_header_) {
      expect_tex_header_ = false;
      std::vector<std::string_view> names;
      SplitFields(t, ',', &names);
      const char* want[6] = {"out", "th", "tq", "rpm", "v", "a"};
      for (int k = 0; k < 6; ++k) {
        std::size_t found = names.size();
        for (std::size_t i = 0; i < names.size(); ++i) {
          if (Trim(names[i]) == want[k]) found = i;
        }
        // Thrust and torque are optional (an empty column: absent from the table, said so).
        if (found == names.size() && (k == 1 || k == 2)) found = kNoColumn;
        if (found == names.size()) {
          throw DataError(reader_->path() + ": line " + std::to_string(reader_->line_number()) +
                          ": ThrustApp table header " + QuoteCell(t) + " has no column \"" +
                          want[k] + "\" (expected out, rpm, v, a; th and tq if measured)");
        }
        col_[k] = found;
      }
      continue;
    }
    if (in_tex_table_) {
      if (t.empty()) continue;
      TakeRow(t, false);
      *out = row_;
      return true;
    }
    if (StartsWith(t, "level [%]")) {
      // A summary table has "Pin [W]"; the raw-sample blocks that follow the summaries do not.
      in_txt_table_ = t.find("Pin [W]") != std::string_view::npos;
      tables_ += in_txt_table_ ? 1 : 0;
      continue;
    }
    if (in_txt_table_) {
      if (t.empty() || t.front() == '#') {
        in_txt_table_ = false;
        continue;
      }
      TakeRow(t, true);
      *out = row_;
      return true;
    }
    TakeMetadata(t);
  }
  return false;
}

std::string ThrustAppLines::Summary() const {
  std::string s = "ThrustApp report: motor \"" + motor_ + "\", KV label " +
                  (kv_.empty() ? std::string("?") : kv_) + ", propeller \"" + prop_ + "\"; " +
                  std::to_string(tables_) + " run" + (tables_ == 1 ? "" : "s") +
                  " (step tables) read as one table";
  return s;
}

}  // namespace dynosize::logs
