// Catalog conventions that every importer and every hand-written entry follows, in one place.
//
// 1. Resistance (docs/model.md sections 2, 6, 8). The catalog's rm_ohm is the resistance of the rms
//    circuit of eq (42)/(48): VLL,rms = Rm*Irms + KE*omega. Hobby datasheets, DriveCalc and
//    every stand-table fit state instead the resistance of the DC equivalent circuit at full
//    throttle (docs/model.md section 2 with V = VDC):
//        VDC = R_dc*IDC + n/Kv                                                    (DC model)
//    With the ideal ESC at TR = 1, eq (48) reads K*VDC = Rm*Irms + KE*omega, K = 3/(sqrt(2)*pi),
//    and eq (56) gives IDC = g*Irms, g = (3/pi)*sqrt(27/20) = K*sqrt(27/10). With KE from Kv
//    (section 8: KE*omega = K*n/Kv), multiplying the DC model by K gives
//        K*VDC = K*g*R_dc*Irms + KE*omega,   so   Rm = K*g*R_dc = 0.7492*R_dc.
//    The same factor keeps the copper loss: sqrt(27/10)*Rm*Irms^2 = R_dc*IDC^2 (g^2/sqrt(27/10)
//    = K*g). The no-load current converts as Io = Io_dc/g (eq 56), and then the torque
//    KT*(Irms - Io) with KT = sqrt(27/10)*KE equals the DC model's (IDC - Io_dc)/Kv_SI exactly:
//    at full throttle the rms model and the DC model are the same machine
//    (tests/catalog/conventions_test.cc ties them numerically through Drive).
//    Importers store the source's number as rm_dc_ohm (its provenance) and rm_ohm converted.
//
// 2. Trust tiers (source.tier): where an entry's performance numbers come from, best first:
//        measured               stand, dynamometer or wind-tunnel measurements (UIUC, stand
//                               tables, dyno fits)
//        manufacturer_computed  the manufacturer's own simulation (APC PER3 blade-element tables)
//        manufacturer_stated    datasheet figures (T-Motor tables, FAST-UAV spec sheets)
//        user_contributed       hobbyist submissions (DriveCalc's database and power laws)
//        assumed                a documented prior only
//    An entry without a tier gets one inferred from source.values (InferTier in catalog.cc).
//
// 3. Motor ratings from mass (src/catalog/conventions.h, EstimatedMotorPowerW). A motor whose
//    source gives neither a current nor a power rating gets, marked "assumed", the specific-
//    power law of hobby outrunners
//        P_max [W] = 10.81 * m[g]^0.8777
//    fitted (least squares in log-log) to the 117 AXI, Scorpion and KDE outrunners of the
//    FAST-UAV catalogue that state Imax and a nominal voltage (P = Imax*V; 12-1043 g; scatter
//    of ln P about the law 0.61, i.e. a factor 1.8 either way). Brushed motors and motors
//    without a mass are not estimated: they carry "exclude" (not used by default).
//    The importers write only the power rating. A power rating does not bound the current of a
//    motor run far below its Kv's voltage (a 40 g, 1964 Kv motor at 42 A rms and 8 %
//    throttle draws 100 W), so the sizing (optimization/credibility.h) also holds such motors
//    to the current law of hobby outrunners
//        I_max [A] = 0.5956 * (m / 1 kg)^1.2816 * Kv^0.9629          (Kv in rpm/V)
//    fitted (least squares in logs) to the 204 FAST-UAV motors with mass, Kv and I_max (log
//    scatter 0.55): at a fixed design speed the voltage falls as 1/Kv, so the current rises
//    about as m*Kv.
#pragma once

#include <cmath>

#include "common/units.h"

namespace dynosize {

// Rm of the rms circuit (eq 42/48) from the resistance of the DC equivalent circuit at full
// throttle, VDC = R_dc*IDC + n/Kv: Rm = K*g*R_dc (derivation above).
inline constexpr double kRmsPerDcResistance = kVllRmsPerVdc * kIdealIdcPerIrmsPerThrottle;

inline constexpr double RmsCircuitResistanceFromDc(double r_dc_ohm) {
  return kRmsPerDcResistance * r_dc_ohm;
}
// Io of eq (42) (rms) from a DC no-load current at full throttle: eq (56).
inline constexpr double RmsNoLoadCurrentFromDc(double io_dc_a) {
  return io_dc_a / kIdealIdcPerIrmsPerThrottle;
}

// Specific-power law of hobby outrunners (see 3. above).
struct MotorPowerLaw {
  double coef_w = 10.8116;    // W at 1 g
  double exponent = 0.8777;
  double log_sd = 0.608;      // scatter of ln(P) about the law
  int sample_size = 117;
};

inline const MotorPowerLaw& DefaultMotorPowerLaw() {
  static const MotorPowerLaw kLaw;
  return kLaw;
}

// Estimated continuous power rating [W] of a hobby outrunner of mass m [kg] (> 0).
inline double EstimatedMotorPowerW(double mass_kg, const MotorPowerLaw& law = DefaultMotorPowerLaw()) {
  return law.coef_w * std::pow(mass_kg * 1e3, law.exponent);
}

// Current law of hobby outrunners (see 3. above).
struct MotorCurrentLaw {
  double coef_a = 0.5956;       // A at 1 kg and 1 rpm/V
  double mass_exponent = 1.2816;
  double kv_exponent = 0.9629;
  double log_sd = 0.55;         // scatter of ln(I_max) about the law
  int sample_size = 204;
};

inline const MotorCurrentLaw& DefaultMotorCurrentLaw() {
  static const MotorCurrentLaw kLaw;
  return kLaw;
}

// Estimated current rating [A] of a hobby outrunner of mass m [kg] and Kv [rpm/V] (both > 0).
inline double EstimatedMotorCurrentA(double mass_kg, double kv_rpm_per_v,
                                     const MotorCurrentLaw& law = DefaultMotorCurrentLaw()) {
  return law.coef_a * std::pow(mass_kg, law.mass_exponent) * std::pow(kv_rpm_per_v, law.kv_exponent);
}

}  // namespace dynosize
