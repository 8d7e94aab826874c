// Numeric constants shared by every module.
#pragma once

#include <limits>

namespace dynosize {

// "No value": a quantity that was not measured, not computed or does not apply. Reports print
// it as "-" or an empty cell, never as "nan" (common/text_format.h).
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace dynosize
