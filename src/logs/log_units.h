// Units written in log headers ("Thrust (gf)", "Torque [N*m]", "ESC signal (µs)") and their
// conversion to the SI units of the steady table. The factors themselves live in
// common/units.h; this file only recognises the spellings.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace dynosize::logs {

// What a column measures; decides which units are valid for it.
enum class Quantity {
  kTime,         // -> s
  kVoltage,      // -> V
  kCurrent,      // -> A
  kSpeed,        // -> rad/s
  kTorque,       // -> N*m
  kForce,        // -> N
  kPower,        // -> W
  kTemperature,  // -> degrees Celsius
  kThrottle,     // -> fraction 0..1 (or a pulse width in us, mapped through ESC end points)
  kFlag,         // -> 0/1, no unit
  kId,           // -> an integer identifier, no unit
};

// si = raw * scale + offset. `pulse_width_us` marks an ESC pulse width (throttle only): the
// reader maps it through the ESC end points instead of scale/offset.
struct UnitConversion {
  double scale = 1.0;
  double offset = 0.0;
  bool pulse_width_us = false;
};

// Recognises `unit` for `quantity` (case-insensitive; µ as U+00B5 or U+03BC or 'u'; the
// product dot as '·', '*', '.', '-' or nothing; '°'/'º' before C/F optional). An empty unit is
// valid only where the quantity has an obvious default: throttle (fraction), flag, id.
// Returns nullopt when the unit is not valid for the quantity.
std::optional<UnitConversion> ParseUnit(Quantity quantity, std::string_view unit);

// The accepted spellings for `quantity`, for error messages ("gf, g, kgf, kg, N, lbf, ozf").
std::string ValidUnits(Quantity quantity);

// The SI unit the table stores for `quantity` ("N*m", "rad/s", "fraction").
const char* SiUnit(Quantity quantity);

}  // namespace dynosize::logs
