#include "logs/csv_scan.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "common/error.h"

namespace dynosize::logs {

namespace {
constexpr std::size_t kChunkBytes = 1 << 20;  // one read(2) per MiB
}  // namespace

LineReader::LineReader(const std::string& path, std::size_t max_line_bytes)
    : path_(path), max_line_bytes_(max_line_bytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw NoInputError(path + ": no such file");
  if (std::filesystem::is_directory(status)) {
    throw NoInputError(path + ": is a folder, expected a file");
  }
  file_ = std::fopen(path.c_str(), "rb");
  if (file_ == nullptr) throw NoInputError(path + ": cannot open: " + std::strerror(errno));
  // A small file gets a small buffer (Fill grows it when a line needs more).
  const auto size = std::filesystem::file_size(path, ec);
  buf_.resize(ec ? kChunkBytes : std::clamp<std::size_t>(static_cast<std::size_t>(size) + 1, 64, kChunkBytes));
}

LineReader::~LineReader() {
  if (file_ != nullptr) std::fclose(file_);
}

void LineReader::TooLong() const {
  throw DataError(path_ + ": line " + std::to_string(line_number_) + ": longer than " +
                  std::to_string(max_line_bytes_) + " bytes: not a text log");
}

bool LineReader::Fill() {
  if (eof_) return false;
  if (begin_ > 0) {
    std::memmove(buf_.data(), buf_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (end_ == buf_.size()) {
    // A line longer than the buffer: grow, up to the limit.
    if (buf_.size() >= max_line_bytes_ + 2) {
      ++line_number_;
      TooLong();
    }
    buf_.resize(std::min(buf_.size() * 2, max_line_bytes_ + 2));
  }
  const std::size_t n = std::fread(buf_.data() + end_, 1, buf_.size() - end_, file_);
  if (n == 0) {
    if (std::ferror(file_)) throw NoInputError(path_ + ": read failed");
    eof_ = true;
    return false;
  }
  end_ += n;
  if (!encoding_checked_) {
    // Refused before any line is read: UTF-16 text would otherwise reach the header detection
    // as garbage with NULs. (The first read(2) of a file returns its start: 64 bytes suffice.)
    encoding_checked_ = true;
    const std::string enc = UnsupportedTextEncoding(std::string_view(buf_.data(), end_));
    if (!enc.empty()) {
      throw DataError(path_ + ": the file is " + enc + ": save it as UTF-8 (or Latin-1) text");
    }
  }
  return true;
}

bool LineReader::Next(std::string_view* line) {
  for (;;) {
    if (skip_lf_) {
      if (begin_ == end_ && !Fill()) return false;
      if (begin_ < end_) {
        if (buf_[begin_] == '\n') {
          ++begin_;
          saw_crlf_ = true;
        } else {
          saw_cr_ = true;
        }
        skip_lf_ = false;
      }
    }
    // Search a line end in the unread part.
    const char* base = buf_.data();
    std::size_t i = begin_;
    while (i < end_ && base[i] != '\n' && base[i] != '\r') ++i;
    if (i < end_) {
      std::size_t start = begin_;
      const std::size_t len = i - begin_;
      if (base[i] == '\n') {
        saw_lf_ = true;
        begin_ = i + 1;
      } else if (i + 1 < end_) {
        if (base[i + 1] == '\n') {
          saw_crlf_ = true;
          begin_ = i + 2;
        } else {
          saw_cr_ = true;
          begin_ = i + 1;
        }
      } else {
        begin_ = i + 1;
        skip_lf_ = true;  // CR at the buffer edge: decide CR vs CRLF on the next call
      }
      ++line_number_;
      if (len > max_line_bytes_) TooLong();
      std::string_view v(base + start, len);
      if (line_number_ == 1 && v.size() >= 3 && static_cast<unsigned char>(v[0]) == 0xEF &&
          static_cast<unsigned char>(v[1]) == 0xBB && static_cast<unsigned char>(v[2]) == 0xBF) {
        v.remove_prefix(3);
        had_bom_ = true;
      }
      *line = v;
      return true;
    }
    if (!Fill()) {
      if (begin_ == end_) return false;
      // Last line without a line end.
      ++line_number_;
      if (end_ - begin_ > max_line_bytes_) TooLong();
      std::string_view v(buf_.data() + begin_, end_ - begin_);
      begin_ = end_;
      if (line_number_ == 1 && v.size() >= 3 && static_cast<unsigned char>(v[0]) == 0xEF &&
          static_cast<unsigned char>(v[1]) == 0xBB && static_cast<unsigned char>(v[2]) == 0xBF) {
        v.remove_prefix(3);
        had_bom_ = true;
      }
      *line = v;
      return true;
    }
  }
}

void SplitFields(std::string_view line, char delim, std::vector<std::string_view>* fields) {
  fields->clear();
  if (delim == ' ') {
    std::size_t i = 0;
    const std::size_t n = line.size();
    while (i < n) {
      while (i < n && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= n) break;
      const std::size_t start = i;
      while (i < n && line[i] != ' ' && line[i] != '\t') ++i;
      fields->push_back(line.substr(start, i - start));
    }
    return;
  }
  const std::size_t n = line.size();
  std::size_t start = 0;
  for (;;) {
    // Only a field that begins with a quote or a blank can be quoted: one test per field.
    if (start < n && (line[start] == '"' || line[start] == ' ' || line[start] == '\t')) {
      std::size_t q = start;
      while (q < n && (line[q] == ' ' || line[q] == '\t')) ++q;
      if (q < n && line[q] == '"') {
        std::size_t i = q + 1;
        std::size_t close = std::string_view::npos;
        while (i < n) {
          if (line[i] == '"') {
            if (i + 1 < n && line[i + 1] == '"') {
              i += 2;  // an escaped quote inside the field
              continue;
            }
            close = i;
            break;
          }
          ++i;
        }
        if (close != std::string_view::npos) {
          std::size_t after = close + 1;
          while (after < n && (line[after] == ' ' || line[after] == '\t')) ++after;
          if (after == n || line[after] == delim) {
            fields->push_back(line.substr(q + 1, close - q - 1));
            if (after == n) return;
            start = after + 1;
            continue;
          }
        }
        // Not a well-formed quoted field: plain text up to the next delimiter.
      }
    }
    const std::size_t pos = line.find(delim, start);
    if (pos == std::string_view::npos) {
      fields->push_back(line.substr(start));
      return;
    }
    fields->push_back(line.substr(start, pos - start));
    start = pos + 1;
  }
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool ParseDouble(std::string_view cell, double* value) {
  cell = Trim(cell);
  if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
  if (cell.empty()) return false;
  const char c0 = cell.front();
  // from_chars accepts "nan"/"inf"; a log cell must be a finite decimal number.
  if (!((c0 >= '0' && c0 <= '9') || c0 == '-' || c0 == '.')) return false;
  const char* first = cell.data();
  const char* last = first + cell.size();
  const auto res = std::from_chars(first, last, *value, std::chars_format::general);
  if (res.ec != std::errc() || res.ptr != last) return false;
  return std::isfinite(*value);
}

bool ParseDoubleDecimalComma(std::string_view cell, double* value) {
  cell = Trim(cell);
  // A number is short: a longer cell is text (and would not fit the copy below).
  constexpr std::size_t kMaxNumberChars = 64;
  if (cell.size() > kMaxNumberChars) return false;
  char buf[kMaxNumberChars];
  std::size_t commas = 0;
  for (std::size_t i = 0; i < cell.size(); ++i) {
    const char c = cell[i];
    if (c == '.') return false;  // a thousands separator, or a decimal point: ambiguous here
    if (c == ',') ++commas;
    buf[i] = c == ',' ? '.' : c;
  }
  if (commas > 1) return false;
  return ParseDouble(std::string_view(buf, cell.size()), value);
}

char DetectDelimiter(std::string_view header_line) {
  std::size_t comma = 0, semi = 0, tab = 0;
  bool quoted = false;
  for (const char c : header_line) {
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    if (c == ',') ++comma;
    if (c == ';') ++semi;
    if (c == '\t') ++tab;
  }
  if (comma == 0 && semi == 0 && tab == 0) return ' ';
  if (comma >= semi && comma >= tab) return ',';
  return semi >= tab ? ';' : '\t';
}

HeaderCell SplitHeaderCell(std::string_view cell) {
  cell = Trim(cell);
  HeaderCell out;
  if (!cell.empty() && (cell.back() == ')' || cell.back() == ']')) {
    const char open = cell.back() == ')' ? '(' : '[';
    const std::size_t pos = cell.rfind(open);
    if (pos != std::string_view::npos && pos > 0) {
      out.name = std::string(Trim(cell.substr(0, pos)));
      out.unit = std::string(Trim(cell.substr(pos + 1, cell.size() - pos - 2)));
      return out;
    }
  }
  const std::size_t dash = cell.rfind(" - ");
  if (dash != std::string_view::npos && dash > 0) {
    out.name = std::string(Trim(cell.substr(0, dash)));
    out.unit = std::string(Trim(cell.substr(dash + 3)));
    return out;
  }
  out.name = std::string(cell);
  return out;
}

std::string AsciiLower(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

std::string QuoteCell(std::string_view cell) {
  std::string out = "\"";
  const std::size_t limit = 40;
  // Bytes that are not UTF-8 (Latin-1 text, binary) are escaped too: the message stays readable
  // and valid UTF-8 on any terminal.
  const bool utf8 = IsValidUtf8(cell.substr(0, std::min(cell.size(), limit)));
  for (std::size_t i = 0; i < cell.size() && i < limit; ++i) {
    const unsigned char c = static_cast<unsigned char>(cell[i]);
    if (c < 0x20 || c == 0x7F || (c >= 0x80 && !utf8)) {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out.push_back(hex[c >> 4]);
      out.push_back(hex[c & 15]);
    } else {
      out.push_back(static_cast<char>(c));
    }
  }
  if (cell.size() > limit) out += "...";
  out += "\"";
  return out;
}

}  // namespace dynosize::logs
