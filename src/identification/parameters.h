// The identification layer shared by `calibrate` (src/calibration) and `diagnose`
// (src/diagnosis): the parameter table of the Brown & Chopra model with its SI names and
// physical bounds, the reparametrisation that turns the energy rules of model.md section 10
// into box bounds of the fit, and the label priors.
//
// Physics as constraints of the fit (model.md section 10, src/model/physics.h):
//  - KE, KT, Rm > 0 and Io, RESC >= 0: box bounds (kBaseLower/kBaseUpper below).
//  - ESC energy conservation, PESC >= 0 at every throttle and current, holds exactly when
//        c0 >= 0   and   c1 + c0 >= K*kp   (K*kp = (3/pi)*sqrt(27/20) = 1.1095, eq 56).
//    The second inequality couples two parameters; the fit keeps box bounds by optimising the
//    excess  s = c1 + c0 - K*kp >= 0  instead of c1:   c1 = K*kp + s - c0   (s >= 0, c0 >= 0).
//    The ideal ESC is s = 0, c0 = 0.
//  - Motor efficiency <= 1 needs KT <= kp*KE (kp = sqrt(27/10), eq 41). Where KT is fitted (torque
//    + AC columns) the fit optimises the ratio  f = KT/(kp*KE)  in (0, 1]:  KT = kp*KE*f. Where
//    KT is not fitted it is tied to KE by the power balance (section 5), f = 1.
// A parameter that ends on one of these bounds is reported "at bound": the data push it out of
// the physical range, and such a fit is never "ok" (src/identification/verdict.h).
//
// Label priors (model.md section 10): the Kv printed on a motor is a strong prior. DriveCalc's
// 8,214 measured points reproduce the stored Kv with a median ratio of 0.997 under
// U = n/Kv + R*I; labels are printed to 2-3 digits and makers state tolerances of about 5-10 %,
// so the prior is Gaussian on KE with a 1-sigma of kKvLabelRelSigma = 10 % of the label's KE
// (section 8: KE = (3/(sqrt(2)*pi))/(Kv*pi/30)); the acceptance test "Kv within 25 % of the
// label" is then 2.5 sigma. A datasheet Rm (ohmmeter, line-line, winding temperature unknown) and
// Io (DC current at a stated voltage, with the ESC's losses) are measured differently from the
// model's quasi-single-phase Rm and rms Io (section 8), so their priors are wide: 30 % and 50 %.
#pragma once

#include <optional>
#include <string>

#include "model/drive.h"
#include "model/physics.h"

namespace dynosize::identification {

// Base parameters of the model (both commands), in this order.
enum class BaseParam : int { kKe = 0, kKt, kRm, kIo, kResc, kC1, kC0, kTrSat, kSatSlope, kDeadband };
inline constexpr int kBaseParamCount = 10;

// SI names, as in the catalog ("ke_v_s_per_rad", ..., "deadband").
const char* BaseParamName(BaseParam p);

// Physical box of each base parameter (catalog ranges of src/catalog/schema.cc where they are
// tighter): KE, KT, Rm strictly positive (a micro-unit floor), Io and RESC >= 0, c0 >= 0 (section
// 10), tr_sat and sat_slope in [0, 1], deadband in [-0.5, 0.5] (negative: a throttle offset).
// The c1 slot is bounded through the excess s (ParamsFromFit), the KT slot through f.
inline constexpr double kBaseLower[kBaseParamCount] = {1e-7, 1e-7, 1e-6, 0.0, 0.0,
                                                       0.0,  0.0,  0.0,  0.0, -0.5};
inline constexpr double kBaseUpper[kBaseParamCount] = {10.0, 20.0, 100.0, 200.0, 10.0,
                                                       5.0,  1.0,  1.0,  1.0,   0.5};
// Box of the ESC excess s = c1 + c0 - K*kp and of the KT ratio f = KT/(kp*KE).
inline constexpr double kEscExcessLower = 0.0;
inline constexpr double kEscExcessUpper = 4.0;
inline constexpr double kKtRatioLower = 0.05;
inline constexpr double kKtRatioUpper = 1.0;

// c1 from the optimised excess and c0 (the inverse of EscExcess); generic for dual numbers.
template <typename T>
T C1FromExcess(const T& excess, const T& c0, MotorType type = MotorType::kBldc) {
  return IdealIdcPerIrmsPerThrottle(type) + excess - c0;
}
inline double EscExcess(double c1, double c0, MotorType type = MotorType::kBldc) {
  return c1 + c0 - IdealIdcPerIrmsPerThrottle(type);
}
// KT from KE and the optimised ratio f (KT = kp*KE*f, f <= 1 keeps eta_motor <= 1).
template <typename T>
T KtFromRatio(const T& ke, const T& ratio, MotorType type = MotorType::kBldc) {
  return MaxKtPerKe(type) * ke * ratio;
}

// Prior widths (1-sigma, relative to the label value); see the header comment.
inline constexpr double kKvLabelRelSigma = 0.10;
inline constexpr double kRmLabelRelSigma = 0.30;
inline constexpr double kIoLabelRelSigma = 0.50;
// Acceptance: a fitted Kv further than this from the label is refused (model.md section 10).
inline constexpr double kKvLabelMaxRelDeviation = 0.25;

// What the motor's label or datasheet says (--kv-label, --rm-label, --io-label/--io-label-v).
struct LabelPriors {
  std::optional<double> kv_rpm_per_v;  // rpm per DC volt
  std::optional<double> rm_ohm;
  std::optional<double> io_a;          // DC no-load current at io_v
  std::optional<double> io_v;
  bool any() const { return kv_rpm_per_v || rm_ohm || io_a; }
  // "" or the first invalid value (non-positive, io without its voltage).
  std::string Validate() const;
};

// KE of a label Kv (model.md section 8; brushed: KE = 1/(Kv*pi/30)).
double KeFromLabelKv(double kv_rpm_per_v, MotorType type = MotorType::kBldc);
// Kv in rpm per DC volt of a fitted KE (the inverse).
double KvFromKe(double ke_v_s_per_rad, MotorType type = MotorType::kBldc);
// The model's rms no-load current of a label's DC no-load current: at full throttle of the ideal
// ESC IDC = 1.1095*Irms (eq 56), so Io = Io_dc/1.1095 (brushed: Io = Io_dc).
double IoFromLabel(double io_dc_a, MotorType type = MotorType::kBldc);

}  // namespace dynosize::identification
