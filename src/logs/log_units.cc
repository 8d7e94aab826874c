#include "logs/log_units.h"

#include <cstring>

#include "common/units.h"
#include "logs/csv_scan.h"

namespace dynosize::logs {

namespace {

struct UnitRow {
  Quantity quantity;
  const char* spelling;  // normalised: lower case, no product dot, 'u' for micro, no degree sign
  double scale;
  double offset;
  bool pulse;
};

// Normalised spellings. Order within a quantity is the order listed in error messages.
const UnitRow kUnits[] = {
    {Quantity::kTime, "s", 1.0, 0.0, false},
    {Quantity::kTime, "ms", 1e-3, 0.0, false},
    {Quantity::kTime, "us", 1e-6, 0.0, false},
    {Quantity::kTime, "min", 60.0, 0.0, false},
    {Quantity::kTime, "sec", 1.0, 0.0, false},
    {Quantity::kVoltage, "v", 1.0, 0.0, false},
    {Quantity::kVoltage, "mv", 1e-3, 0.0, false},
    {Quantity::kCurrent, "a", 1.0, 0.0, false},
    {Quantity::kCurrent, "ma", 1e-3, 0.0, false},
    {Quantity::kSpeed, "rpm", kRadPerSecPerRpm, 0.0, false},
    {Quantity::kSpeed, "rad/s", 1.0, 0.0, false},
    {Quantity::kSpeed, "krpm", 1000.0 * kRadPerSecPerRpm, 0.0, false},
    {Quantity::kSpeed, "1/min", kRadPerSecPerRpm, 0.0, false},
    {Quantity::kSpeed, "rps", 2.0 * kPi, 0.0, false},
    {Quantity::kSpeed, "hz", 2.0 * kPi, 0.0, false},
    {Quantity::kTorque, "nm", 1.0, 0.0, false},
    {Quantity::kTorque, "mnm", 1e-3, 0.0, false},
    {Quantity::kTorque, "nmm", 1e-3, 0.0, false},
    {Quantity::kTorque, "kgfcm", kNmPerKilogramForceCm, 0.0, false},
    {Quantity::kTorque, "gfcm", kNmPerKilogramForceCm * 1e-3, 0.0, false},  // jmajew's "G cm"
    {Quantity::kTorque, "gcm", kNmPerKilogramForceCm * 1e-3, 0.0, false},
    {Quantity::kTorque, "ozfin", kNmPerOunceForceInch, 0.0, false},
    {Quantity::kTorque, "ozin", kNmPerOunceForceInch, 0.0, false},
    {Quantity::kTorque, "lbfft", kNmPerPoundForceFoot, 0.0, false},
    {Quantity::kForce, "n", 1.0, 0.0, false},
    {Quantity::kForce, "gf", kNewtonPerGramForce, 0.0, false},
    {Quantity::kForce, "g", kNewtonPerGramForce, 0.0, false},
    {Quantity::kForce, "kgf", kNewtonPerKilogramForce, 0.0, false},
    {Quantity::kForce, "kg", kNewtonPerKilogramForce, 0.0, false},
    {Quantity::kForce, "lbf", kNewtonPerPoundForce, 0.0, false},
    {Quantity::kForce, "lb", kNewtonPerPoundForce, 0.0, false},
    {Quantity::kForce, "ozf", kNewtonPerOunceForce, 0.0, false},
    {Quantity::kForce, "oz", kNewtonPerOunceForce, 0.0, false},
    {Quantity::kForce, "mn", 1e-3, 0.0, false},
    {Quantity::kPower, "w", 1.0, 0.0, false},
    {Quantity::kPower, "kw", 1e3, 0.0, false},
    {Quantity::kPower, "mw", 1e-3, 0.0, false},
    {Quantity::kTemperature, "c", 1.0, 0.0, false},
    {Quantity::kTemperature, "degc", 1.0, 0.0, false},
    {Quantity::kTemperature, "k", 1.0, -273.15, false},
    {Quantity::kTemperature, "f", 5.0 / 9.0, -32.0 * 5.0 / 9.0, false},
    {Quantity::kThrottle, "", 1.0, 0.0, false},
    {Quantity::kThrottle, "1", 1.0, 0.0, false},
    {Quantity::kThrottle, "fraction", 1.0, 0.0, false},
    {Quantity::kThrottle, "%", 0.01, 0.0, false},
    {Quantity::kThrottle, "us", 1.0, 0.0, true},
    {Quantity::kFlag, "", 1.0, 0.0, false},
    {Quantity::kId, "", 1.0, 0.0, false},
};

// Lower-cases, maps micro signs to 'u', drops product dots, blanks and degree signs.
std::string Normalise(std::string_view unit) {
  std::string out;
  out.reserve(unit.size());
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(unit[i]);
    const unsigned char d = i + 1 < unit.size() ? static_cast<unsigned char>(unit[i + 1]) : 0;
    if ((c == 0xC2 && d == 0xB5) || (c == 0xCE && d == 0xBC)) {  // µ U+00B5, μ U+03BC
      out.push_back('u');
      ++i;
    } else if (c == 0xC2 && (d == 0xB7 || d == 0xB0 || d == 0xBA)) {  // · ° º
      ++i;
    } else if (c == 0xE2 && d == 0x8B && i + 2 < unit.size() &&
               static_cast<unsigned char>(unit[i + 2]) == 0x85) {  // ⋅ U+22C5
      i += 2;
    } else if (c == '*' || c == ' ' || c == '-' || (c == '.' && !out.empty())) {
      // product dots; a '.' leading the unit is kept (none is valid anyway)
    } else if (c >= 'A' && c <= 'Z') {
      out.push_back(static_cast<char>(c - 'A' + 'a'));
    } else {
      out.push_back(static_cast<char>(c));
    }
  }
  return out;
}

}  // namespace

std::optional<UnitConversion> ParseUnit(Quantity quantity, std::string_view unit) {
  const std::string norm = Normalise(Trim(unit));
  for (const UnitRow& row : kUnits) {
    if (row.quantity == quantity && norm == row.spelling) {
      UnitConversion u;
      u.scale = row.scale;
      u.offset = row.offset;
      u.pulse_width_us = row.pulse;
      return u;
    }
  }
  return std::nullopt;
}

std::string ValidUnits(Quantity quantity) {
  std::string out;
  for (const UnitRow& row : kUnits) {
    if (row.quantity != quantity) continue;
    if (!out.empty()) out += ", ";
    out += row.spelling[0] == '\0' ? "(none)" : row.spelling;
  }
  return out;
}

const char* SiUnit(Quantity quantity) {
  switch (quantity) {
    case Quantity::kTime: return "s";
    case Quantity::kVoltage: return "V";
    case Quantity::kCurrent: return "A";
    case Quantity::kSpeed: return "rad/s";
    case Quantity::kTorque: return "N*m";
    case Quantity::kForce: return "N";
    case Quantity::kPower: return "W";
    case Quantity::kTemperature: return "degC";
    case Quantity::kThrottle: return "fraction";
    case Quantity::kFlag: return "0/1";
    case Quantity::kId: return "id";
  }
  return "";
}

}  // namespace dynosize::logs
