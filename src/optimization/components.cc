#include "optimization/components.h"

#include <algorithm>
#include <cmath>

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

}  // namespace dynosize
