#include "optimization/components.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dynosize {

double AssumedPropMassKg(double diameter_m) {
  return 0.014 * std::pow(diameter_m / 0.254, 2.5);
}

double AssumedEscMassKg(double max_current_a) {
  const double rating = std::isfinite(max_current_a) ? max_current_a : 30.0;
  return 0.005 + 0.001 * rating;
}

double AssumedMotorRthKPerW(double motor_mass_kg) {
  return 1.5 * std::pow(std::max(motor_mass_kg, 1e-3) / 0.1, -2.0 / 3.0);
}

ComponentMass PropMass(const PropEntry& prop) {
  if (prop.mass_kg) return {*prop.mass_kg, false};
  return {AssumedPropMassKg(prop.diameter_m), true};
}

ComponentMass EscMass(const EscEntry& esc) {
  if (esc.mass_kg) return {*esc.mass_kg, false};
  return {AssumedEscMassKg(esc.params.max_current_a), true};
}

BatteryPackParams MissionPackParams(const MissionBattery& battery, const BatteryEntry& entry,
                                    int cells_series) {
  BatteryPackParams p = PackFromEntry(entry, cells_series / entry.cells_series, battery.cells_parallel);
  p.mass_factor = battery.mass_factor;
  return p;
}

PropSpeedLimit PropSpeedLimitOf(const Mission& m, const PropEntry& prop) {
  PropSpeedLimit out{std::numeric_limits<double>::infinity(), nullptr};
  if (prop.max_rpm) out = {*prop.max_rpm, "prop_max_rpm"};
  if (m.constraints.max_tip_mach > 0 && prop.diameter_m > 0) {
    constexpr double kGammaAir = 1.4, kGasConstantAirJPerKgK = 287.05;
    const double sound_m_s = std::sqrt(kGammaAir * kGasConstantAirJPerKgK * (m.air_temperature_c + 273.15));
    const double rpm = 60.0 * m.constraints.max_tip_mach * sound_m_s / (kPi * prop.diameter_m);
    if (rpm < out.rpm) out = {rpm, "prop_tip_mach"};
  }
  return out;
}

}  // namespace dynosize
