// Row rules shared by `calibrate` (src/calibration) and `diagnose` (src/diagnosis), the
// identification layer: the measured columns a fit compares and its residual terms, which rows
// of a log a fit uses, the throttle levels of those rows, the magnitude that scales a column's
// residuals to percent, and the robust outlier screen. Each rule exists once, here.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "logs/steady_table.h"

namespace dynosize::identification {

// The measured columns a fit compares with the model's predictions, in this order: the index of
// a prediction array pred[kMeasCount].
enum Meas : int { kMOmega = 0, kMIdc, kMIrms, kMVll, kMPac, kMeasCount };
inline constexpr logs::Column kMeasColumn[kMeasCount] = {logs::Column::kOmegaRadS, logs::Column::kIdcA,
                                                         logs::Column::kIrmsA, logs::Column::kVllRmsV,
                                                         logs::Column::kPacW};

// One residual term of a fit: the measured value of column meas on one row, and the factor that
// makes (prediction - value) a percent (each command chooses its scale).
struct ResidualTerm {
  int meas;
  double value;
  double inv_scale;
};

// The term's residual from the row's predictions pred[kMeasCount]; generic for dual numbers.
template <typename T>
T TermResidual(const ResidualTerm& term, const T* pred) {
  return (pred[term.meas] - term.value) * term.inv_scale;
}

// The rows of a log a fit uses, as the model's inputs, and the residual terms they carry; both
// commands build one (calibrate adds the rows' DC-current inputs, diagnose its model choices).
struct FitRows {
  std::vector<std::size_t> table_row;     // the log row of each fit row
  std::vector<double> vdc, tr, omega, q;  // VDC [V], throttle, omega [rad/s], torque [N*m]
  std::vector<char> torque_known;         // q is measured (else omega is the row's load input)
  std::vector<int> term_begin;            // terms of row k: [term_begin[k], term_begin[k+1])
  std::vector<ResidualTerm> terms;
  std::array<bool, kMeasCount> measured{};
  std::size_t rows() const { return table_row.size(); }
};

// Why a log row is left out of a fit, or nullptr when the fit uses it. The rules, checked in
// this order:
//  1. the shaft speed must exceed min_speed_fraction of the largest logged speed (the motor is
//     turning; below it the steady-state model of docs/model.md section 3 does not hold) - unless
//     the row's speed was not measured (speed_unknown: a DriveCalc no-load row, n = 0);
//  2. with a throttle column, the throttle must reach min_throttle;
//  3. the supply voltage must be positive (eq 48 needs it).
// The reasons are the texts calibrate lists with every dropped row.
const char* RowRejection(double omega_rad_s, double omega_max_rad_s, double min_speed_fraction,
                         bool has_throttle, double throttle, double min_throttle, double vdc_v,
                         bool speed_unknown = false);

// Speed readings the circuit cannot produce (an optical tachometer counting a reflection twice,
// a dropped pulse): eq 48 with the ideal ESC of eq 56 makes the speed linear in the row's known
// values, omega = a*VDC*TR + b*IDC/TR + c*VDC (a ~ 0.675/KE, b ~ -R/(1.1095*KE), c for a throttle
// offset: docs/model.md sections 3, 8, 9). Fitted by least median of squares over deterministic
// triples of rows (a half of the rows may be wrong), its robust scale is
// s = 1.4826*(1 + 5/(n - 3))*sqrt(median r^2) of the relative residuals r = (omega - pred)/pred;
// a reading is spurious when r > max(kSpuriousSpeedSigmas*s, kSpuriousSpeedMinRel): only readings
// above the circuit's speed, which eq 48 caps at the row's voltage, throttle and current (an
// optical sensor counting twice); a low reading can be a load or ESC effect at low command and is
// left to the fits' outlier screens; and only at or above the median command (below it an ESC's
// output is often not proportional to the command, and a high reading there is the ESC's curve).
// At most a quarter of the rows are flagged (worst first); fewer than 8 rows: none.
// rows: the candidate rows of the table (turning, throttle above the floor, VDC > 0); the
// throttle is assumed_throttle where the log has none.
inline constexpr double kSpuriousSpeedSigmas = 6.0;
inline constexpr double kSpuriousSpeedMinRel = 0.15;
struct SpuriousSpeed {
  std::size_t row = 0;               // table row
  double omega_rad_s = 0.0;          // the reading
  double expected_omega_rad_s = 0.0; // the robust circuit fit at the row's VDC, throttle, current
};
std::vector<SpuriousSpeed> FindSpuriousSpeeds(const logs::SteadyTable& t, const std::vector<std::size_t>& rows,
                                              double assumed_throttle);
// "line 12: 16040 rpm (expected about 3150 rpm)" for warnings and dropped-row reasons.
std::string SpuriousSpeedText(const logs::SteadyTable& t, const SpuriousSpeed& s);

// The distinct throttle levels of the rows (rounded to 0.001), ascending.
std::vector<double> ThrottleLevels(const std::vector<double>& throttle);

// Median of |column[row]| over the rows: the typical magnitude a residual of this column is a
// percent of (dyno sensor noise is mostly relative). NaN when rows is empty.
double MedianMagnitude(const std::vector<double>& column, const std::vector<std::size_t>& rows);

// The percent scale of every measured column over the rows: 100 / MedianMagnitude. A column whose
// median magnitude is not positive carries nothing to compare: its scale is 0 and it is marked
// not measured. Columns already not measured get 0.
std::array<double, kMeasCount> MedianPercentScales(const logs::SteadyTable& t, const std::vector<std::size_t>& rows,
                                                   std::array<bool, kMeasCount>* measured);

// The log's torque per DC ampere at its highest throttle command (>= 0.95) against a motor of
// the label Kv at full duty: the median over those rows of Q/(KT_dc*IDC), KT_dc = 60/(2*pi*Kv).
// At TR_eff = 1 an ESC that conserves energy has IDC = (C1 + C0)*Irms >= 1.1095*Irms (eq 57,
// docs/model.md section 10), and KT <= sqrt(27/10)*KE (eq 41), so Q <= KT*Irms <= KT_dc*IDC with
// KT_dc = sqrt(27/10)*KE/1.1095 = 60/(2*pi*Kv) (section 8). A ratio well above 1 is a log no
// motor near its label can produce: the torque or current sensor's calibration, or the label.
// NaN without torque, current, throttle or a row at >= 0.95.
double TorquePerAmpereVsLabel(const logs::SteadyTable& t, double kv_label_rpm_per_v);

// The linear start of the circuit (eq 48, U = R*I + KE*omega, R = Rm + RESC) by least squares
// over rows of (I, omega, U): both commands start their nonlinear fit from it. A non-positive KE
// (a log without enough speed spread) falls back on the no-load relation KE ~ max(U/omega); R is
// returned as solved (the caller decides what a non-positive R means for it).
struct CircuitStart {
  double ke_v_s_per_rad = 0.0;
  double r_total_ohm = 0.0;
};
CircuitStart LinearCircuitStart(const std::vector<double>& current_a, const std::vector<double>& omega_rad_s,
                                const std::vector<double>& u_v);
// R of eq 48 by least squares with KE held (a label's KE): R = sum I*(U - KE*omega) / sum I^2; 0
// without current.
double ResistanceWithKeHeld(const std::vector<double>& current_a, const std::vector<double>& omega_rad_s,
                            const std::vector<double>& u_v, double ke_v_s_per_rad);

// Robust outlier screening (never more than 10 % of the points or a whole throttle
// level). rmax[k]: the largest |percent residual| of row k; throttle[k]: its throttle. The rows
// with rmax above threshold (the caller's outlier_sigmas robust standard deviations) are taken
// worst first; one is dropped while fewer than cap = floor(max_fraction * rows) are dropped, at
// least min_kept rows are left before the drop, and (with a throttle column) it is not the last
// row left at its throttle level (levels to 0.001). The others beyond the threshold are spared.
struct OutlierSelection {
  std::vector<std::size_t> dropped;  // indices into rmax, worst first
  std::size_t spared = 0;            // rows beyond the threshold kept by the limits above
  std::size_t cap = 0;               // floor(max_fraction * rows)
};
OutlierSelection SelectOutlierRows(const std::vector<double>& rmax, const std::vector<double>& throttle,
                                   bool has_throttle, double threshold, double max_fraction,
                                   std::size_t min_kept);

}  // namespace dynosize::identification
