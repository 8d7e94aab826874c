// Number formatting for reports and messages (one implementation).
#pragma once

#include <sstream>
#include <string>

namespace dynosize {

// x in fixed notation with `digits` decimals ("24.36").
inline std::string FixedText(double x, int digits) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(digits);
  o << x;
  return o.str();
}

}  // namespace dynosize
