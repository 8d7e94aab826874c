// Human-readable JSON for the terminal: like Json::dump(indent), but an array whose elements
// are all scalars (numbers, strings, booleans, null) is written on one line. Propeller and
// battery tables (`catalog show`) then take a few lines instead of thousands.
#pragma once

#include <string>

#include "common/json_file.h"

namespace dynosize {

// Checks finiteness like DumpJson (throws InternalError naming the path) and ends with '\n'.
std::string DumpJsonReadable(const Json& value, int indent = 2);

}  // namespace dynosize
