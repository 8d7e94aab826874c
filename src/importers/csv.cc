#include "importers/csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "common/error.h"
#include "common/text_encoding.h"
#include "common/text_file.h"

namespace dynosize {

std::string Trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  auto space_at_front = [&](std::size_t i) {
    if (s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == '\n') return std::size_t{1};
    if (i + 1 < s.size() && static_cast<unsigned char>(s[i]) == 0xC2 &&
        static_cast<unsigned char>(s[i + 1]) == 0xA0) {
      return std::size_t{2};  // U+00A0 no-break space
    }
    return std::size_t{0};
  };
  while (b < e) {
    const std::size_t k = space_at_front(b);
    if (k == 0) break;
    b += k;
  }
  while (e > b) {
    const char c = s[e - 1];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
      --e;
    } else if (e - b >= 2 && static_cast<unsigned char>(s[e - 2]) == 0xC2 &&
               static_cast<unsigned char>(s[e - 1]) == 0xA0) {
      e -= 2;
    } else {
      break;
    }
  }
  return s.substr(b, e - b);
}

std::optional<double> ParseNumber(const std::string& field) {
  std::string s = Trim(field);
  if (!s.empty() && s.back() == '%') s = Trim(s.substr(0, s.size() - 1));
  if (s.empty()) return std::nullopt;
  if (s.find('.') == std::string::npos) std::replace(s.begin(), s.end(), ',', '.');
  if (s[0] == '+') s.erase(0, 1);
  double v = 0.0;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (ec != std::errc() || ptr != last || !std::isfinite(v)) return std::nullopt;
  return v;
}

namespace {

// Splits records, honouring quotes (a quoted field may hold separators and line ends).
void SplitRecords(const std::string& text, char sep, std::size_t start, const std::string& name,
                  std::vector<CsvRow>* rows) {
  std::size_t line = 1;
  for (std::size_t i = 0; i < start; ++i) {
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 >= text.size() || text[i + 1] != '\n'))) {
      ++line;
    }
  }
  CsvRow row;
  row.line = line;
  std::string field;
  bool in_quotes = false, any = false;
  const std::size_t n = text.size();
  auto end_record = [&]() {
    row.fields.push_back(field);
    field.clear();
    const bool blank = std::all_of(row.fields.begin(), row.fields.end(),
                                   [](const std::string& f) { return Trim(f).empty(); });
    if (!blank || row.fields.size() > 1) {
      if (!(row.fields.size() == 1 && Trim(row.fields[0]).empty())) rows->push_back(row);
    }
    row.fields.clear();
    any = false;
  };
  std::size_t quote_line = 0;
  for (std::size_t i = start; i < n; ++i) {
    const char c = text[i];
    if (in_quotes) {
      if (c == '"') {
        if (i + 1 < n && text[i + 1] == '"') {
          field.push_back('"');
          ++i;
        } else {
          in_quotes = false;
        }
      } else {
        if (c == '\n' || (c == '\r' && (i + 1 >= n || text[i + 1] != '\n'))) ++line;
        field.push_back(c);
      }
      continue;
    }
    if (c == '"' && Trim(field).empty()) {
      field.clear();
      in_quotes = true;
      quote_line = line;
      any = true;
    } else if (c == sep) {
      row.fields.push_back(field);
      field.clear();
      any = true;
    } else if (c == '\r' || c == '\n') {
      if (c == '\r' && i + 1 < n && text[i + 1] == '\n') ++i;
      end_record();
      ++line;
      row.line = line;
    } else {
      field.push_back(c);
      any = true;
    }
  }
  if (in_quotes) {
    throw DataError(name + ":" + std::to_string(quote_line) +
                    ": unterminated quoted field (a '\"' opens a field that never closes)");
  }
  if (any || !field.empty()) end_record();
}

}  // namespace

CsvTable ParseCsv(const std::string& raw, const std::string& name, const CsvOptions& options) {
  CsvTable table;
  table.path = name;
  std::string text = raw;
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) {
    text.erase(0, 3);
    table.had_bom = true;
  }
  text = ToUtf8(text, &table.was_latin1);
  // Skip preamble lines.
  std::size_t pos = 0;
  for (std::size_t k = 0; k < options.skip_lines && pos < text.size(); ++k) {
    while (pos < text.size() && text[pos] != '\n' && text[pos] != '\r') ++pos;
    if (pos < text.size() && text[pos] == '\r' && pos + 1 < text.size() && text[pos + 1] == '\n') ++pos;
    if (pos < text.size()) ++pos;
  }
  char sep = options.separator;
  if (sep == 0) {
    std::size_t semis = 0, commas = 0;
    bool q = false;
    for (std::size_t i = pos; i < text.size() && (q || (text[i] != '\n' && text[i] != '\r')); ++i) {
      if (text[i] == '"') q = !q;
      else if (!q && text[i] == ';') ++semis;
      else if (!q && text[i] == ',') ++commas;
    }
    sep = semis > commas ? ';' : ',';
  }
  table.separator = sep;
  std::vector<CsvRow> rows;
  SplitRecords(text, sep, pos, name, &rows);
  if (rows.empty()) throw DataError(name + ": no header line (the file is empty)");
  for (const auto& h : rows.front().fields) table.header.push_back(Trim(h));
  rows.erase(rows.begin());
  table.rows = std::move(rows);
  return table;
}

CsvTable ReadCsv(const std::string& path, const CsvOptions& options) {
  return ParseCsv(ReadTextFile(path, options.max_bytes), path, options);
}

std::optional<std::size_t> CsvTable::FindColumn(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return i;
  }
  return std::nullopt;
}

std::size_t CsvTable::Column(const std::string& name) const {
  if (auto c = FindColumn(name)) return *c;
  std::string cols;
  for (std::size_t i = 0; i < header.size(); ++i) cols += (i ? ", " : "") + header[i];
  throw DataError(path + ": no column '" + name + "' (columns: " + cols + ")");
}

std::string CsvTable::Field(const CsvRow& row, std::size_t col) const {
  return col < row.fields.size() ? Trim(row.fields[col]) : std::string();
}

std::string CsvTable::Where(const CsvRow& row) const {
  return path + ":" + std::to_string(row.line);
}

std::optional<double> CsvCells::Num(const char* col) const { return ParseNumber(Str(col)); }

std::optional<double> CsvCells::Pos(const char* col) const {
  const auto v = Num(col);
  return v && *v > 0 ? v : std::nullopt;
}

}  // namespace dynosize
