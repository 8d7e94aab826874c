// Physical constants of the model and unit conversions at the edges.
//
// SI inside dynosize: omega in rad/s, torque in N*m, V, A, W, kg, m. Datasheet units (rpm,
// Kv in rpm/V, g, mOhm, inches, mAh) are converted here and only here.
#pragma once

#include <cmath>

namespace dynosize {

inline constexpr double kPi = 3.14159265358979323846;

// Eq (46): VLL,rms = 3/(sqrt(2)*pi) * VDC * TR for an ideal ESC (~0.675).
inline constexpr double kVllRmsPerVdc = 0.67523723711782957;  // 3/(sqrt(2)*pi)

// Eq (41): PAC = sqrt(27/10) * VLL,rms * Irms for trapezoidal voltage, rectangular current
// (~1.643); by the power balance of section 5 it is also the ideal KT/KE ratio.
inline constexpr double kPacPerVllIrms = 1.6431676725154984;  // sqrt(27/10)

// Eq (56): IDC/Irms = (3/pi)*sqrt(27/20)*TR for an ideal ESC (~10/9 = 1.1094).
inline constexpr double kIdealIdcPerIrmsPerThrottle = 1.1095279993106997;  // (3/pi)*sqrt(27/20)

inline constexpr double kRadPerSecPerRpm = kPi / 30.0;

inline constexpr double RpmToRadPerSec(double rpm) { return rpm * kRadPerSecPerRpm; }
inline constexpr double RadPerSecToRpm(double omega_rad_s) { return omega_rad_s / kRadPerSecPerRpm; }
inline constexpr double GramsToKg(double g) { return g * 1e-3; }
inline constexpr double MilliohmToOhm(double mohm) { return mohm * 1e-3; }
inline constexpr double InchToMeter(double in) { return in * 0.0254; }
inline constexpr double MahToAh(double mah) { return mah * 1e-3; }
inline constexpr double AhToCoulomb(double ah) { return ah * 3600.0; }
// rev/s from rpm (the n of the UIUC coefficient definitions).
inline constexpr double RpmToRevPerSec(double rpm) { return rpm / 60.0; }

// docs/model.md section 8: datasheet Kv [rpm per DC volt] is the no-load speed at full throttle of
// an ideal ESC, omega = 0.675*VDC/KE, hence KE = (3/(sqrt(2)*pi)) / (Kv*pi/30)
// [V*s/rad, line-line rms].
inline constexpr double KeFromKvBldc(double kv_rpm_per_v) {
  return kVllRmsPerVdc / (kv_rpm_per_v * kRadPerSecPerRpm);
}
// For a brushed motor the terminal voltage is DC: KE = 1/(Kv*pi/30).
inline constexpr double KeFromKvBrushed(double kv_rpm_per_v) {
  return 1.0 / (kv_rpm_per_v * kRadPerSecPerRpm);
}

// Force, torque and other stand units (thrust-stand exports write the unit the user chose).
inline constexpr double kStandardGravity = 9.80665;          // m/s^2, exact (CGPM 1901)
inline constexpr double kNewtonPerGramForce = kStandardGravity * 1e-3;
inline constexpr double kNewtonPerKilogramForce = kStandardGravity;
inline constexpr double kNewtonPerPoundForce = 4.4482216152605;   // 0.45359237 kg * g0, exact
inline constexpr double kNewtonPerOunceForce = kNewtonPerPoundForce / 16.0;
inline constexpr double kNmPerOunceForceInch = kNewtonPerOunceForce * 0.0254;
inline constexpr double kNmPerPoundForceFoot = kNewtonPerPoundForce * 0.3048;
inline constexpr double kNmPerKilogramForceCm = kNewtonPerKilogramForce * 0.01;

inline constexpr double GramForceToNewton(double gf) { return gf * kNewtonPerGramForce; }
inline constexpr double KilogramForceToNewton(double kgf) { return kgf * kNewtonPerKilogramForce; }

}  // namespace dynosize
