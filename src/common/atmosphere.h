// Air density for the propeller model and the importers.
//
// International Standard Atmosphere (ISO 2533) troposphere: p(h) = p0*(1 - L*h/T0)^(g*M/(R*L))
// with p0 = 101325 Pa, T0 = 288.15 K, L = 0.0065 K/m, exponent 5.25588; and the ideal gas law
// rho = p/(R_air*T) with R_air = 287.058 J/(kg*K).
#pragma once

#include <cmath>

namespace dynosize {

inline constexpr double kIsaSeaLevelRhoKgM3 = 1.225;
inline constexpr double kIsaSeaLevelPressurePa = 101325.0;
inline constexpr double kIsaSeaLevelTemperatureK = 288.15;
inline constexpr double kDryAirGasConstantJPerKgK = 287.058;

// Air's dynamic viscosity at 15 C (ISA sea level), Pa*s, and the speed of sound there,
// sqrt(1.4*287.058*288.15) m/s: the Reynolds and Mach numbers of the blade sections
// (docs/model.md eq B3) and the Re figures of the propeller reports.
inline constexpr double kAirViscosityPaS = 1.789e-5;
inline constexpr double kIsaSeaLevelSpeedOfSoundMS = 340.294;

inline double CelsiusToKelvin(double t_c) { return t_c + 273.15; }

// ISA static pressure at geometric altitude h (troposphere, h < 11 km), Pa.
inline double IsaPressurePa(double altitude_m) {
  return kIsaSeaLevelPressurePa * std::pow(1.0 - 2.25577e-5 * altitude_m, 5.25588);
}

// Density of dry air at the ISA pressure of `altitude_m` and the actual temperature, kg/m^3.
inline double AirDensityKgM3(double altitude_m, double temperature_c) {
  return IsaPressurePa(altitude_m) / (kDryAirGasConstantJPerKgK * CelsiusToKelvin(temperature_c));
}

}  // namespace dynosize
