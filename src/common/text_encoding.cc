#include "common/text_encoding.h"

#include <algorithm>

namespace dynosize {

bool IsValidUtf8(std::string_view s) {
  std::size_t i = 0;
  const std::size_t n = s.size();
  while (i < n) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    std::size_t extra;
    if (c < 0x80) {
      extra = 0;
    } else if ((c & 0xE0) == 0xC0 && c >= 0xC2) {
      extra = 1;
    } else if ((c & 0xF0) == 0xE0) {
      extra = 2;
    } else if ((c & 0xF8) == 0xF0 && c <= 0xF4) {
      extra = 3;
    } else {
      return false;
    }
    if (i + extra >= n && extra > 0) return false;  // truncated sequence
    for (std::size_t k = 1; k <= extra; ++k) {
      if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return false;
    }
    i += extra + 1;
  }
  return true;
}

std::string ToUtf8(std::string_view s, bool* was_latin1) {
  if (IsValidUtf8(s)) {
    if (was_latin1 != nullptr) *was_latin1 = false;
    return std::string(s);
  }
  if (was_latin1 != nullptr) *was_latin1 = true;
  std::string out;
  out.reserve(s.size() + 8);
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out.push_back(ch);
    } else {
      out.push_back(static_cast<char>(0xC0 | (c >> 6)));
      out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
    }
  }
  return out;
}

std::string UnsupportedTextEncoding(std::string_view head) {
  auto at = [&](std::size_t i) { return i < head.size() ? static_cast<unsigned char>(head[i]) : 0x100u; };
  if (at(0) == 0xFF && at(1) == 0xFE && at(2) == 0 && at(3) == 0) {
    return "UTF-32 little-endian (byte-order mark FF FE 00 00)";
  }
  if (at(0) == 0 && at(1) == 0 && at(2) == 0xFE && at(3) == 0xFF) {
    return "UTF-32 big-endian (byte-order mark 00 00 FE FF)";
  }
  if (at(0) == 0xFF && at(1) == 0xFE) return "UTF-16 little-endian (byte-order mark FF FE)";
  if (at(0) == 0xFE && at(1) == 0xFF) return "UTF-16 big-endian (byte-order mark FE FF)";
  // Without a mark: ASCII text in UTF-16 has a NUL in every other byte.
  const std::size_t n = std::min<std::size_t>(head.size(), 64) & ~std::size_t{1};
  if (n >= 8) {
    std::size_t even_nul = 0, odd_nul = 0;
    for (std::size_t i = 0; i < n; i += 2) {
      even_nul += head[i] == '\0';
      odd_nul += head[i + 1] == '\0';
    }
    if (odd_nul == n / 2 && even_nul == 0) return "UTF-16 little-endian (NUL after every character)";
    if (even_nul == n / 2 && odd_nul == 0) return "UTF-16 big-endian (NUL before every character)";
  }
  return "";
}

}  // namespace dynosize
