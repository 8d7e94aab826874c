// A small CSV reader shared by the catalog importers.
//
// The public data sets in ../shared/data come in several dialects: ',' or ';' separated,
// double-quoted fields with "" escapes and embedded separators ("6pol 5x1,5x1"), a UTF-8
// byte-order mark, LF / CRLF / CR-only line ends, and text that is UTF-8 in one file and
// Latin-1 (German umlauts) in another. ReadCsv turns all of these into UTF-8 strings so that
// the catalog JSON written from them is valid UTF-8.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace dynosize {

struct CsvOptions {
  // Field separator; 0 = detect from the header line (the more frequent of ';' and ',' outside
  // quotes; ',' on a tie).
  char separator = 0;
  // Number of lines to skip before the header (e.g. units rows or a preamble).
  std::size_t skip_lines = 0;
  std::size_t max_bytes = 64u << 20;
};

struct CsvRow {
  std::size_t line = 0;  // 1-based line number in the file, for messages
  std::vector<std::string> fields;
};

struct CsvTable {
  std::string path;
  char separator = ',';
  bool had_bom = false;
  bool was_latin1 = false;  // the bytes were not valid UTF-8 and were decoded as Latin-1
  std::vector<std::string> header;  // trimmed
  std::vector<CsvRow> rows;         // blank lines are skipped

  // Index of the column named `name` (exact match after trimming). Throws DataError naming the
  // file, the missing column and the columns present.
  std::size_t Column(const std::string& name) const;
  std::optional<std::size_t> FindColumn(const std::string& name) const;

  // The field of `row` in column `col`, trimmed; "" when the row is short.
  std::string Field(const CsvRow& row, std::size_t col) const;

  // "path:line" for messages.
  std::string Where(const CsvRow& row) const;
};

// Reads and splits a CSV file. Throws NoInputError when missing, DataError on an unterminated
// quote (naming the line).
CsvTable ReadCsv(const std::string& path, const CsvOptions& options = {});

// Same for text in memory (`name` used in messages).
CsvTable ParseCsv(const std::string& text, const std::string& name, const CsvOptions& options = {});


// One row of a table read by column name (the importers' cells): the trimmed text, a number
// (nullopt when empty or malformed), or a number > 0 (nullopt otherwise). A missing column
// throws DataError naming it (CsvTable::Column).
struct CsvCells {
  const CsvTable* t;
  const CsvRow* r;
  std::string Str(const char* col) const { return t->Field(*r, t->Column(col)); }
  std::optional<double> Num(const char* col) const;
  std::optional<double> Pos(const char* col) const;
};

// Trims ASCII white space (and non-breaking spaces) at both ends.
std::string Trim(const std::string& s);

// Parses a whole field as a finite number with std::from_chars; accepts a decimal comma when
// the field has no '.', and a trailing '%'. nullopt for an empty or malformed field.
std::optional<double> ParseNumber(const std::string& field);

}  // namespace dynosize
