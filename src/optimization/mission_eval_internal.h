// What the files of the mission evaluator share and nobody else uses (mission_eval.cc,
// mission_eval_flight.cc, mission_eval_continuous.cc, mission_eval_early_exits.cc,
// mission_eval_summary.cc). Not included by anything outside them.
#pragma once

#include <limits>
#include <sstream>
#include <string>

namespace dynosize {
namespace eval_internal {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// x with `precision` significant digits, as an ostream prints it ("3.14", "1e+03"): the
// evaluator's warnings and solver reports.
inline std::string Num(double x, int precision = 4) {
  std::ostringstream o;
  o.precision(precision);
  o << x;
  return o.str();
}

}  // namespace eval_internal
}  // namespace dynosize
