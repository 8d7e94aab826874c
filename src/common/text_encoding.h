// Text encodings of input files. Spreadsheets re-save CSV files as Latin-1 (German names in
// DriveCalc, µ in RCbenchmark headers); dynosize works in UTF-8 and decodes anything that is
// not valid UTF-8 as Latin-1 (ISO-8859-1), which maps every byte to one code point.
#pragma once

#include <string>
#include <string_view>

namespace dynosize {

// True when `s` is well-formed UTF-8 (no overlong 2-byte forms, nothing above U+10FFFF, no
// truncated sequence).
bool IsValidUtf8(std::string_view s);

// `s` as UTF-8: unchanged when it is valid UTF-8, else decoded as Latin-1; `was_latin1` (when
// given) says which.
std::string ToUtf8(std::string_view s, bool* was_latin1 = nullptr);

// The start of a text file in an encoding dynosize does not read (UTF-16 or UTF-32, told by a
// byte-order mark or by NUL bytes between ASCII characters, as Windows "Unicode text" exports
// give): a phrase naming it ("UTF-16 little-endian (byte-order mark FF FE)"), else "".
// `head` is the first bytes of the file (64 are enough).
std::string UnsupportedTextEncoding(std::string_view head);

}  // namespace dynosize
