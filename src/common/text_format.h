// Number formatting for reports and messages: the one implementation every report, figure and
// message uses (so that a number reads the same everywhere and outputs stay byte-stable).
#pragma once

#include <cmath>
#include <sstream>
#include <string>

namespace dynosize {

// x in fixed notation with `digits` decimals ("24.36"), as printf's "%.*f".
inline std::string FixedText(double x, int digits) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(digits);
  o << x;
  return o.str();
}

// x with at most `significant` significant digits, as printf's "%.*g" ("0.0625", "1.2e+06");
// with the default 6 it is what `std::cout << x` prints.
inline std::string SignificantText(double x, int significant = 6) {
  std::ostringstream o;
  o.precision(significant);
  o << x;
  return o.str();
}

// SignificantText, or `none` ("-" in a table, "" in a CSV cell) where x is NaN or infinite:
// no output prints "nan".
inline std::string SignificantTextOr(double x, const char* none, int significant = 6) {
  return std::isfinite(x) ? SignificantText(x, significant) : none;
}

// A fraction as a percentage with `digits` decimals and the unit ("12.5 %" for 0.125).
inline std::string PercentText(double fraction, int digits = 1) { return FixedText(100.0 * fraction, digits) + " %"; }

}  // namespace dynosize
