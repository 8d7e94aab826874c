// Calibrate's forward model (the equations of calibrate.h) and its parametrisation: the fit
// rows, the internal parameter vector (KT as the ratio f, c1 as the ESC excess s:
// identification/parameters.h), the generic predictions of one row (double or dual numbers) and
// the residual function whose Jacobian comes from dual numbers (common/dual.h). Internal to
// src/calibration.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "calibration/calibration_types.h"
#include "common/dual.h"
#include "common/numbers.h"
#include "fit/nonlinear_least_squares.h"
#include "identification/fit_rows.h"
#include "identification/parameters.h"
#include "model/circuit.h"
#include "model/drive.h"

namespace dynosize::calibration::internal {

inline constexpr int kMaxFree = kBaseParamCount - 1;  // every parameter but tr_sat (profiled)
using D8 = Dual<kMaxFree>;
using identification::C1FromExcess;
using identification::KtFromRatio;
inline constexpr int kKeI = identification::ParamIndex(Param::kKe), kKtI = identification::ParamIndex(Param::kKt),
                     kC1I = identification::ParamIndex(Param::kC1), kC0I = identification::ParamIndex(Param::kC0),
                     kDbI = identification::ParamIndex(Param::kDeadband);
using Params = std::array<double, kBaseParamCount>;

// Measured columns the fit compares with predictions and the residual terms
// (identification/fit_rows.h); calibrate's term scale is 100 / median |column|: a residual in
// percent of the column's typical value.
using identification::kMeasColumn;
using identification::kMeasCount;
using identification::kMIdc;
using identification::kMIrms;
using identification::kMOmega;
using identification::kMPac;
using identification::kMVll;
using Term = identification::ResidualTerm;
using identification::TermResidual;

struct FitData : identification::FitRows {
  std::vector<char> speed_known;  // 0: a no-load row whose speed was not measured (omega = 0)
  // DC logs with a throttle but neither torque nor AC columns: the measured current is the row's
  // input and the speed is predicted (the well-conditioned direction: I = (U - KE*omega)/R is a
  // small difference at low throttle, omega = (U - R*I)/KE is not). NaN where not an input.
  std::vector<double> idc_in;
};

struct Layout {
  std::array<bool, kBaseParamCount> free{};
  bool tie_kt = true;
  std::vector<int> free_index;  // parameter of each free slot
};

// The fit's parameter vector ("internal", identification/parameters.h): slot kKt holds the
// ratio f = KT/(kp*KE) (1 when KT is tied to KE), slot kC1 the ESC excess s = c1 + c0 - 1.1095.
// Both keep the energy rules of docs/model.md section 10 as box bounds.
Params ToInternal(const MotorParams& m, const EscParams& e);
// Physical parameters of the internal vector (KT = kp*KE*f, c1 = 1.1095 + s - c0).
MotorParams ToMotor(const Params& p);
EscParams ToEsc(const Params& p, const std::optional<EscParams>& prior);

// Forward predictions of one row (see the header) from internal parameters: fills
// pred[kMeasCount] (and the torque). Returns false outside the model's domain (non-positive KE,
// KT or resistance).
template <typename T>
bool PredictGeneric(const T* p, double tr_sat, double vdc, double tr, double omega,
                    double q, bool torque_known, T* pred, T* q_pred,
                    double idc_in = std::numeric_limits<double>::quiet_NaN()) {
  const T& ke = p[0];
  const T kt = KtFromRatio(ke, p[kKtI]);
  const T& rm = p[2];
  const T& io = p[3];
  const T& resc = p[4];
  const T& c0 = p[kC0I];
  const T c1 = C1FromExcess(p[kC1I], c0);
  const T& slope = p[8];
  const T r = rm + resc;
  if (!(ke > 0.0) || !(kt > 0.0) || !(r > 1e-12)) return false;
  // The rms circuit of model/circuit.h, the same equations Drive evaluates.
  const T tre = circuit::EffectiveThrottle(tr, tr_sat, slope, p[kDbI]);
  const T u = circuit::AppliedVoltage(kVllRmsPerVdc, vdc, tre);
  T i, w;
  if (torque_known) {
    i = circuit::CurrentAtTorque(q, kt, io);
    w = circuit::SpeedAtCurrent(u, r, i, ke);
    *q_pred = T(q);
  } else if (idc_in == idc_in) {
    // The measured DC current is the input: I = IDC/(C1*TR_eff + C0) (57), speed from (48).
    const T g = c1 * tre + c0;
    if (!(g > 1e-6)) return false;
    i = idc_in / g;
    w = circuit::SpeedAtCurrent(u, r, i, ke);
    *q_pred = circuit::ShaftTorque(kt, i, io);
  } else {
    w = T(omega);
    i = circuit::CurrentAtSpeed(u, ke, omega, r);
    *q_pred = circuit::ShaftTorque(kt, i, io);
  }
  const T vll = circuit::LineVoltage(u, resc, i);
  pred[kMOmega] = w;
  pred[kMIdc] = circuit::DcCurrent(c1, tre, c0, i);
  pred[kMIrms] = i;
  pred[kMVll] = vll;
  pred[kMPac] = circuit::AcPower(kPacPerVllIrms, vll, i);
  return true;
}

// The residuals of every row with the free slots of `lay` (the rest at `fixed`); the Jacobian
// by dual numbers.
ResidualFunction MakeResidualFunction(const FitData& d, const Layout& lay, const Params& fixed);

// Bounds of each internal parameter: the box of identification/parameters.h (kParamTable), with
// the KT slot bounded as the ratio f and the C1 slot as the excess s (docs/model.md section 10).
extern const Params kLower;
extern const Params kUpper;

}  // namespace dynosize::calibration::internal
