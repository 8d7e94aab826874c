// Low-level text scanning shared by the log readers: a streaming line reader with bounded
// memory, a field splitter, a locale-free number parser and header-text normalisation.
//
// Transport quirks handled here, for every format (they change no value):
//   - a UTF-8 byte-order mark at the start of the file;
//   - LF, CRLF and CR-only line ends (a spreadsheet re-save gives CR-only), mixed in one file;
//   - header text in Latin-1 instead of UTF-8 (converted to UTF-8 before any comparison).
// Everything else (empty cells, trailing commas, text in a number) is the readers' business.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "common/text_encoding.h"

namespace dynosize::logs {

// Reads a file line by line through a fixed buffer: memory stays bounded whatever the file
// size (a line longer than max_line_bytes is a DataError naming the file and line).
class LineReader {
 public:
  // Throws NoInputError when the file is missing, a folder or unreadable.
  explicit LineReader(const std::string& path, std::size_t max_line_bytes = 1 << 20);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The next line without its line end; false at the end of the file. The view is valid until
  // the next call. A leading UTF-8 BOM is removed from the first line.
  bool Next(std::string_view* line);
  // 1-based number of the line last returned.
  std::size_t line_number() const { return line_number_; }
  // Line ends seen so far, for the metadata ("LF", "CRLF", "CR", mixed).
  bool saw_lf() const { return saw_lf_; }
  bool saw_crlf() const { return saw_crlf_; }
  bool saw_cr() const { return saw_cr_; }
  bool had_bom() const { return had_bom_; }
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void TooLong() const;
  bool Fill();  // moves the unread tail to the front and reads more; false at EOF

  std::string path_;
  std::FILE* file_ = nullptr;
  std::size_t max_line_bytes_;
  std::vector<char> buf_;
  std::size_t begin_ = 0, end_ = 0;
  bool eof_ = false;
  bool encoding_checked_ = false;
  bool skip_lf_ = false;  // the previous line ended with CR at a buffer edge
  std::size_t line_number_ = 0;
  bool saw_lf_ = false, saw_crlf_ = false, saw_cr_ = false, had_bom_ = false;
};

// Splits `line` at `delim` into `fields` (reused: no allocation once it has grown). With
// delim == ' ' any run of spaces and tabs separates fields and leading/trailing blanks are
// ignored. Otherwise a field that starts with a double quote (after blanks) and ends with one
// (before blanks and the delimiter) is a quoted field, RFC 4180 style (Tyto Flight Stand
// exports quote every cell): the view is its content without the quotes, delimiters inside it
// do not split, and an escaped quote stays written as "" in the view (a quoted field never
// spans lines). A quote that does not close a field this way is ordinary text.
void SplitFields(std::string_view line, char delim, std::vector<std::string_view>* fields);

// Removes leading and trailing spaces and tabs.
std::string_view Trim(std::string_view s);

// Parses a whole cell as a finite double with std::from_chars (locale-free, no allocation).
// Leading/trailing blanks and a leading '+' are accepted; "nan", "inf", hex, a decimal comma or
// any other text make it return false.
bool ParseDouble(std::string_view cell, double* value);
// The same with a decimal comma (Excel exports in locales that write 1,5): exactly the cells
// ParseDouble accepts with their one ',' in place of '.'. A cell holding a '.' is refused: with
// decimal commas a '.' is a thousands separator ("1.234,5"), and "1.234" would be ambiguous.
bool ParseDoubleDecimalComma(std::string_view cell, double* value);

// IsValidUtf8 and ToUtf8 (Latin-1 fallback) come from common/text_encoding.h.

// Picks the field delimiter of a header line: ',' ';' or '\t' (the most frequent outside
// double quotes), else ' ' (whitespace-separated).
char DetectDelimiter(std::string_view header_line);

// A header cell split into name and unit. Recognised forms: "Name (unit)", "Name [unit]",
// "Name - unit" (unit after the last " - "), and "Name" (unit empty). Name and unit are
// trimmed.
struct HeaderCell {
  std::string name;
  std::string unit;
};
HeaderCell SplitHeaderCell(std::string_view cell);

// Lower-cases ASCII letters (units and names are compared case-insensitively where safe).
std::string AsciiLower(std::string_view s);

// Quotes a cell for an error message: at most 40 bytes, control characters and (when the cell
// is not valid UTF-8) bytes >= 0x80 escaped as \xNN.
std::string QuoteCell(std::string_view cell);

}  // namespace dynosize::logs
