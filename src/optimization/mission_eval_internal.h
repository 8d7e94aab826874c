// What the files of the mission evaluator share and nobody else uses (mission_eval.cc,
// mission_eval_flight.cc, mission_eval_continuous.cc, mission_eval_early_exits.cc,
// mission_eval_summary.cc). Not included by anything outside them.
#pragma once

#include <limits>

namespace dynosize {
namespace eval_internal {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace eval_internal
}  // namespace dynosize
