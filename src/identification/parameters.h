// The identification layer shared by `calibrate` (src/calibration) and `diagnose`
// (src/diagnosis): the parameter table of the Brown & Chopra model with its SI names and
// physical bounds, the reparametrisation that turns the energy rules of docs/model.md section 10
// into box bounds of the fit, and the label priors.
//
// Physics as constraints of the fit (docs/model.md section 10, src/model/physics.h):
//  - KE, KT, Rm > 0 and Io, RESC >= 0: box bounds (kParamTable below).
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
// Label priors (docs/model.md section 10): the Kv printed on a motor is a strong prior. DriveCalc's
// 8,214 measured points reproduce the stored Kv with a median ratio of 0.997 under
// U = n/Kv + R*I; labels are printed to 2-3 digits and makers state tolerances of about 5-10 %,
// so the prior is Gaussian on KE with a 1-sigma of kKvLabelRelSigma = 10 % of the label's KE
// (section 8: KE = (3/(sqrt(2)*pi))/(Kv*pi/30)); the acceptance test "Kv within 25 % of the
// label" is then 2.5 sigma. A datasheet Rm (ohmmeter, line-line, winding temperature unknown) and
// Io (DC current at a stated voltage, with the ESC's losses) are measured differently from the
// model's quasi-single-phase Rm and rms Io (section 8), so their priors are wide: 30 % and 50 %.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>

#include "model/drive.h"
#include "model/physics.h"

namespace dynosize::identification {

// The parameter table: every parameter an identification fit can free, in this order. The first
// kBaseParamCount are calibrate's model (the first-order model with the ESC's knee and dead
// band); the others are the extensions that `diagnose` tests (docs/model.md section 9). An array indexed by ParamIndex(p) holds
// one value per parameter (calibrate's result: the base ones; diagnose's models: all).
enum class Param : int {
  kKe = 0, kKt, kRm, kIo, kResc, kC1, kC0, kTrSat, kSatSlope, kDeadband,  // base
  kIo1, kRth, kDroop, kRsupply                                            // extensions
};
inline constexpr int kBaseParamCount = 10;
inline constexpr int kParamCount = 14;
constexpr int ParamIndex(Param p) { return static_cast<int>(p); }

// Which command frees a parameter.
enum class FreedBy : int {
  kBoth,      // the first-order fit of calibrate and diagnose (when the log identifies it: FreeBaseParams)
  kProfiled,  // tr_sat: chosen on a grid of knees by both commands, then refined
  kBothTest,  // sat_slope and deadband: freed by both when their F test is run (knee, offset)
  kDiagnose,  // an extension only diagnose tests
};

// One row of the table.
//  name:   SI name, as in the catalog and the JSON ("ke_v_s_per_rad", ..., "rsupply_ohm").
//  lower, upper: the box of the optimised coordinate. For every parameter but two this is the
//    physical range (catalog ranges of src/catalog/schema.cc where they are tighter): KE, KT,
//    Rm strictly positive (a micro-unit floor), Io and RESC >= 0, c0 >= 0 (section 10), tr_sat
//    and sat_slope in [0, 1], deadband in [-0.5, 0.5] (negative: a throttle offset), Io may not
//    fall with speed (io1 >= 0: no energy created, section 10), rth, droop, rsupply >= 0. The KT
//    slot is optimised as the ratio f = KT/(kp*KE) and the c1 slot as the ESC excess
//    s = c1 + c0 - K*kp (see the header comment), so their boxes are those of f and s.
//  scale:  the optimisation unit (x = value/scale) where it does not depend on the log; 0 where
//    it does (diagnose derives it from the first-order fit: src/diagnosis/base_model.cc).
//  freed_by: which command frees it.
struct ParamSpec {
  const char* name;
  double lower;
  double upper;
  double scale;
  FreedBy freed_by;
};
inline constexpr ParamSpec kParamTable[kParamCount] = {
    {"ke_v_s_per_rad", 1e-7, 10.0, 0.0, FreedBy::kBoth},
    {"kt_nm_per_a", 0.05, 1.0, 1.0, FreedBy::kBoth},  // the ratio f = KT/(kp*KE)
    {"rm_ohm", 1e-6, 100.0, 0.0, FreedBy::kBoth},
    {"io_a", 0.0, 200.0, 0.0, FreedBy::kBoth},
    {"resc_ohm", 0.0, 10.0, 0.0, FreedBy::kBoth},
    {"c1", 0.0, 4.0, 1.0, FreedBy::kBoth},  // the excess s = c1 + c0 - K*kp
    {"c0", 0.0, 1.0, 0.1, FreedBy::kBoth},
    {"tr_sat", 0.0, 1.0, 1.0, FreedBy::kProfiled},
    {"sat_slope", 0.0, 1.0, 1.0, FreedBy::kBothTest},
    {"deadband", -0.5, 0.5, 0.1, FreedBy::kBothTest},
    {"io1_a_s_per_rad", 0.0, 1.0, 0.0, FreedBy::kDiagnose},
    {"rth_k_per_w", 0.0, 1000.0, 0.0, FreedBy::kDiagnose},
    {"kt_droop_per_a", 0.0, 10.0, 0.0, FreedBy::kDiagnose},
    {"rsupply_ohm", 0.0, 10.0, 0.0, FreedBy::kDiagnose},
};
inline constexpr const ParamSpec& Spec(Param p) { return kParamTable[ParamIndex(p)]; }
inline constexpr const char* ParamName(Param p) { return Spec(p).name; }
// The first-order model of docs/model.md sections 5-8 (KE, KT, Rm, Io, RESC, C1, C0): the first
// kFirstOrderParamCount slots. The knee, slope and dead band (sections 7 and 9) complete
// calibrate's base fit through its F tests; diagnose tests them as extensions.
inline constexpr int kFirstOrderParamCount = 7;
inline constexpr bool IsFirstOrderParam(int index) { return index < kFirstOrderParamCount; }

// What a log offers a first-order fit (the columns and rows it has).
struct LogContent {
  bool ac = false;                // vll_rms_v and irms_a
  bool has_torque = false;        // a torque column
  bool has_throttle = false;      // a throttle column
  bool has_idc = false;           // an idc_a column
  bool any_torque_known = false;  // some row has a known torque (torque column or a no-load row)
  std::size_t throttle_levels = 0;
};
// KT is tied to KE by the power balance KT = sqrt(27/10)*KE (docs/model.md section 5) unless torque
// and the AC columns separate it from the ESC ratio.
inline bool TieKt(const LogContent& c) { return !(c.has_torque && c.ac); }
// The base parameters the first-order fit frees on such a log (calibrate.h explains what each
// column set identifies): KE and Rm always; KT unless tied; Io with a known torque; RESC with
// the AC columns and a throttle; C1, C0 with idc_a, two or more throttle levels and torque or AC
// columns. tr_sat, sat_slope and deadband are not freed here (profiled / tested).
std::array<bool, kParamCount> FreeBaseParams(const LogContent& c);

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
// Acceptance: a fitted Kv further than this from the label is refused (docs/model.md section 10).
inline constexpr double kKvLabelMaxRelDeviation = 0.25;

// What the motor's label or datasheet says (--kv-label, --rm-label, --io-label/--io-label-v).
struct LabelPriors {
  std::optional<double> kv_rpm_per_v;  // rpm per DC volt
  std::optional<double> rm_ohm;
  std::optional<double> io_a;          // DC no-load current at io_v
  std::optional<double> io_v;
  bool any() const { return kv_rpm_per_v || rm_ohm || io_a; }
  // Names the first invalid value (non-positive, io without its voltage) in *error.
  bool IsValid(std::string* error) const;
};

// KE of a label Kv (docs/model.md section 8; brushed: KE = 1/(Kv*pi/30)).
double KeFromLabelKv(double kv_rpm_per_v, MotorType type = MotorType::kBldc);
// Kv in rpm per DC volt of a fitted KE (the inverse).
double KvFromKe(double ke_v_s_per_rad, MotorType type = MotorType::kBldc);
// The model's rms no-load current of a label's DC no-load current: at full throttle of the ideal
// ESC IDC = 1.1095*Irms (eq 56), so Io = Io_dc/1.1095 (brushed: Io = Io_dc).
double IoFromLabel(double io_dc_a, MotorType type = MotorType::kBldc);

}  // namespace dynosize::identification
