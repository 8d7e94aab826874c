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

}  // namespace dynosize
