#include "diagnosis/diagnose.h"

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <optional>
#include <random>
#include <sstream>

#include "calibration/calibrate.h"
#include "common/error.h"
#include "common/units.h"
#include "fit/nonlinear_least_squares.h"
#include "fit/statistics.h"
#include "identification/fit_rows.h"
#include "identification/parameters.h"

namespace dynosize::diagnosis {

using logs::Column;
using logs::SteadyTable;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using fit::Aicc;
using fit::Median;

// ---------------------------------------------------------------------------------------------
// Parameters. Every model is a subset of these slots made free; the rest are held.
enum Slot : int {
  kKe = 0, kKt, kRm, kIo, kResc, kC1, kC0, kTrSat, kSatSlope, kDeadband, kIo1, kRth, kDroop,
  kRsupply, kSlotCount
};
constexpr const char* kSlotName[kSlotCount] = {
    "ke_v_s_per_rad", "kt_nm_per_a", "rm_ohm",   "io_a",           "resc_ohm",
    "c1",             "c0",          "tr_sat",   "sat_slope",      "deadband",
    "io1_a_s_per_rad", "rth_k_per_w", "kt_droop_per_a", "rsupply_ohm"};
constexpr bool kSlotIsBase[kSlotCount] = {true,  true,  true,  true,  true,  true, true,
                                          false, false, false, false, false, false, false};

using Values = std::array<double, kSlotCount>;
using FreeSet = std::array<bool, kSlotCount>;

// Measured columns the model predicts and the residual terms (identification/fit_rows.h);
// diagnose's term scale is 100 / max(|value|, 5 % of the column median): a residual in percent
// of the measured value (then the effective-variance weights, ApplyEffectiveVarianceWeights).
using identification::kMeasColumn;
using identification::kMeasCount;
using identification::kMIdc;
using identification::kMIrms;
using identification::kMOmega;
using identification::kMPac;
using identification::kMVll;
using Term = identification::ResidualTerm;
using identification::TermResidual;

struct Data : identification::FitRows {
  bool tie_kt = true;
  MotorType motor_type = MotorType::kBldc;
};

struct Model {
  FreeSet free{};
  Values values{};  // starts for free slots, held values otherwise
  Values scale{};   // optimisation unit of each slot (x = value/scale)
  Values lower{}, upper{};
  bool profile_knee = false;  // tr_sat chosen on a grid
};

void ToParams(const Data& d, const Values& v, MotorParams* m, EscParams* e) {
  m->type = d.motor_type;
  m->ke_v_s_per_rad = v[kKe];
  m->kt_nm_per_a = d.tie_kt ? kPacPerVllIrms * v[kKe] : v[kKt];
  m->rm_ohm = v[kRm];
  m->io_a = v[kIo];
  m->io1_a_s_per_rad = v[kIo1];
  m->rth_k_per_w = v[kRth];
  m->kt_droop_per_a = v[kDroop];
  e->resc_ohm = v[kResc];
  e->c1 = v[kC1];
  e->c0 = v[kC0];
  e->tr_sat = v[kTrSat];
  e->sat_slope = v[kSatSlope];
  e->deadband = v[kDeadband];
  e->rsupply_ohm = v[kRsupply];
}

// Predictions of row k (every measured column) by the model with these values.
bool PredictRow(const Data& d, const Drive& drive, std::size_t k, double* pred) {
  const OperatingPoint p = d.torque_known[k] ? drive.AtTorque(d.vdc[k], d.tr[k], d.q[k])
                                             : drive.AtSpeed(d.vdc[k], d.tr[k], d.omega[k]);
  pred[kMOmega] = p.omega_rad_s;
  pred[kMIdc] = p.idc_a;
  pred[kMIrms] = p.irms_a;
  pred[kMVll] = p.vll_rms_v;
  pred[kMPac] = p.pac_w;
  for (int m = 0; m < kMeasCount; ++m) {
    if (!std::isfinite(pred[m])) return false;
  }
  // A stalled prediction (omega = 0) is kept: its large residual steers the fit away, where
  // rejecting it would stop the fit at a poor start.
  return (p.limits & kLimitThermalRunaway) == 0;
}

bool Residuals(const Data& d, const std::vector<std::size_t>& rows, const Values& v, double* r) {
  MotorParams m;
  EscParams e;
  ToParams(d, v, &m, &e);
  if (!(m.ke_v_s_per_rad > 0.0) || !(m.kt_nm_per_a > 0.0) || !(m.rm_ohm + e.resc_ohm > 0.0)) {
    return false;
  }
  const Drive drive(m, e);
  double pred[kMeasCount];
  int out = 0;
  for (std::size_t k : rows) {
    if (!PredictRow(d, drive, k, pred)) return false;
    for (int t = d.term_begin[k]; t < d.term_begin[k + 1]; ++t) {
      const Term& term = d.terms[t];
      r[out++] = TermResidual(term, pred);
    }
  }
  return true;
}

int TermCount(const Data& d, const std::vector<std::size_t>& rows) {
  int n = 0;
  for (std::size_t k : rows) n += d.term_begin[k + 1] - d.term_begin[k];
  return n;
}

struct FitOut {
  bool ok = false;
  Values values{};
  double sse = 0.0;  // sum of squared percent residuals (trivial loss)
  int n_terms = 0;
  int n_free = 0;    // incl. a profiled knee
  Values stderr_{};
  double max_corr_ext_base = 0.0;
  std::string corr_with;
};

// The optimised coordinate of slot s (identification/parameters.h): the ESC excess
// s = c1 + c0 - 1.1095 for the c1 slot and the ratio f = KT/(kp*KE) for the KT slot, so that the
// energy rules of model.md section 10 are box bounds; the value itself for every other slot.
double ToCoordinate(int s, const Values& v) {
  if (s == kC1) return identification::EscExcess(v[kC1], v[kC0]);
  if (s == kKt) return v[kKe] > 0.0 ? v[kKt] / (kPacPerVllIrms * v[kKe]) : 1.0;
  return v[s];
}
// The inverse for a vector whose free slots hold coordinates.
void FromCoordinates(const FreeSet& free, Values* v) {
  if (free[kC1]) (*v)[kC1] = identification::C1FromExcess((*v)[kC1], (*v)[kC0]);
  if (free[kKt]) (*v)[kKt] = identification::KtFromRatio((*v)[kKe], (*v)[kKt]);
}

FitOut FitModel(const Data& d, const std::vector<std::size_t>& rows, const Model& model,
                LossType loss, double loss_scale) {
  FitOut out;
  std::vector<int> slots;
  for (int s = 0; s < kSlotCount; ++s) {
    if (model.free[s]) slots.push_back(s);
  }
  const int n = static_cast<int>(slots.size());
  out.n_terms = TermCount(d, rows);
  out.n_free = n + (model.profile_knee ? 1 : 0);
  out.values = model.values;
  out.stderr_.fill(kNaN);
  if (out.n_terms <= out.n_free) return out;
  const Values base = model.values;
  const auto& scale = model.scale;
  auto unpack = [&](const Eigen::VectorXd& x) {
    Values v = base;
    for (int j = 0; j < n; ++j) v[slots[j]] = x[j] * scale[slots[j]];
    FromCoordinates(model.free, &v);
    return v;
  };
  LeastSquaresProblem prob;
  prob.num_residuals = out.n_terms;
  prob.num_parameters = n;
  prob.residuals = NumericDiffResiduals(
      [&](const Eigen::VectorXd& x, Eigen::VectorXd* r) {
        return Residuals(d, rows, unpack(x), r->data());
      },
      1e-6);
  prob.lower_bounds.resize(n);
  prob.upper_bounds.resize(n);
  Eigen::VectorXd x(n);
  for (int j = 0; j < n; ++j) {
    const int s = slots[j];
    prob.parameter_names.push_back(kSlotName[s]);
    prob.lower_bounds[j] = model.lower[s] / scale[s];
    prob.upper_bounds[j] = model.upper[s] / scale[s];
    x[j] = std::clamp(ToCoordinate(s, model.values) / scale[s], prob.lower_bounds[j], prob.upper_bounds[j]);
  }
  LevenbergMarquardtOptions lo;
  lo.max_num_iterations = 100;
  lo.loss = loss;
  lo.loss_scale = loss_scale;
  lo.use_geodesic_acceleration = false;
  lo.function_tolerance = 1e-9;
  lo.parameter_tolerance = 1e-9;
  LevenbergMarquardtSummary s;
  if (n > 0) {
    s = SolveLeastSquares(prob, lo, &x);
    if (!s.IsSolutionUsable()) return out;
  }
  out.values = unpack(x);
  Eigen::VectorXd r(out.n_terms);
  if (!Residuals(d, rows, out.values, r.data())) return out;
  out.sse = r.squaredNorm();
  out.ok = std::isfinite(out.sse);
  if (n > 0 && s.standard_errors.size() == n) {
    for (int j = 0; j < n; ++j) out.stderr_[slots[j]] = s.standard_errors[j] * scale[slots[j]];
    // KT's error from its ratio's (KE's share neglected: reporting only).
    if (model.free[kKt]) out.stderr_[kKt] *= kPacPerVllIrms * out.values[kKe];
    if (s.correlation.rows() == n) {
      for (int a = 0; a < n; ++a) {
        if (kSlotIsBase[slots[a]]) continue;
        for (int b = 0; b < n; ++b) {
          if (!kSlotIsBase[slots[b]]) continue;
          const double c = std::fabs(s.correlation(a, b));
          if (std::isfinite(c) && c > out.max_corr_ext_base) {
            out.max_corr_ext_base = c;
            out.corr_with = kSlotName[slots[b]];
          }
        }
      }
    }
  }
  return out;
}

// Fits the model, profiling tr_sat over `knees` when the model asks for it.
FitOut FitProfiled(const Data& d, const std::vector<std::size_t>& rows, const Model& model,
                   const std::vector<double>& knees, LossType loss, double loss_scale) {
  if (!model.profile_knee) return FitModel(d, rows, model, loss, loss_scale);
  FitOut best;
  std::size_t jbest = 0;
  for (std::size_t j = 0; j < knees.size(); ++j) {
    Model m = model;
    m.values[kTrSat] = knees[j];
    FitOut f = FitModel(d, rows, m, loss, loss_scale);
    if (f.ok && (!best.ok || f.sse < best.sse)) best = f, jbest = j;
  }
  if (!best.ok) return best;
  // The true knee lies between throttle levels, not on the grid: the knee is refined as a free
  // parameter between the grid neighbours of the best grid knee, starting there. A knee held on
  // the grid biases the slope (the row between the true and the grid knee is bent wrongly and
  // the slope and the base parameters absorb it: a hidden 0.45 came out 0.32, issue 23); free,
  // the slope's standard error also carries the knee's uncertainty.
  Model m = model;
  m.values = best.values;
  m.profile_knee = false;
  m.free[kTrSat] = true;
  m.lower[kTrSat] = jbest > 0 ? knees[jbest - 1] : std::max(0.0, knees[jbest] - 0.05);
  m.upper[kTrSat] = jbest + 1 < knees.size() ? knees[jbest + 1] : std::min(1.0, knees[jbest] + 0.05);
  const FitOut refined = FitModel(d, rows, m, loss, loss_scale);
  if (refined.ok && refined.sse <= best.sse) return refined;
  return best;
}

// ---------------------------------------------------------------------------------------------
// Cross-validation.
struct CvOut {
  double rms_percent = kNaN;  // all terms, percent residuals
  std::array<std::vector<double>, kMeasCount> pred;  // per data row
  int failed_folds = 0;
};

CvOut CrossValidate(const Data& d, const std::vector<std::size_t>& used,
                    const std::vector<int>& fold_of, int folds, const Model& model,
                    const FitOut& full, const std::vector<double>& knees) {
  CvOut cv;
  for (auto& p : cv.pred) p.assign(d.rows(), kNaN);
  double ss = 0.0;
  int nt = 0;
  for (int f = 0; f < folds; ++f) {
    std::vector<std::size_t> train, test;
    for (std::size_t k : used) (fold_of[k] == f ? test : train).push_back(k);
    if (test.empty()) continue;
    Model m = model;
    m.values = full.values;  // warm start
    // The knee is re-profiled inside the fold around the full-data knee (its grid neighbours),
    // so that no score uses a knee chosen on the scored rows' own fit... up to the neighbourhood.
    std::vector<double> local;
    if (model.profile_knee) {
      // The grid knee nearest to the full-data knee (refined off the grid by FitProfiled).
      std::ptrdiff_t c = 0;
      for (std::size_t j = 1; j < knees.size(); ++j) {
        if (std::fabs(knees[j] - full.values[kTrSat]) < std::fabs(knees[c] - full.values[kTrSat])) {
          c = static_cast<std::ptrdiff_t>(j);
        }
      }
      for (std::ptrdiff_t j = std::max<std::ptrdiff_t>(0, c - 2);
           j <= std::min<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(knees.size()) - 1, c + 2); ++j) {
        local.push_back(knees[static_cast<std::size_t>(j)]);
      }
    }
    FitOut fit = FitProfiled(d, train, m, local, LossType::kTrivial, 1.0);
    if (!fit.ok) {
      // Too few rows left to fit: the fold is reported, its rows count as a 100 % miss and have
      // no prediction (the full fit standing in would score rows it has seen).
      ++cv.failed_folds;
      for (std::size_t k : test) {
        for (int t = d.term_begin[k]; t < d.term_begin[k + 1]; ++t) {
          ss += 100.0 * 100.0;
          ++nt;
        }
      }
      continue;
    }
    MotorParams mp;
    EscParams ep;
    ToParams(d, fit.values, &mp, &ep);
    const Drive drive(mp, ep);
    double pred[kMeasCount];
    for (std::size_t k : test) {
      const bool ok = PredictRow(d, drive, k, pred);
      for (int t = d.term_begin[k]; t < d.term_begin[k + 1]; ++t) {
        const Term& term = d.terms[t];
        const double r = ok ? TermResidual(term, pred) : 100.0;
        ss += r * r;
        ++nt;
        cv.pred[term.meas][k] = ok ? pred[term.meas] : kNaN;
      }
    }
  }
  cv.rms_percent = nt > 0 ? std::sqrt(ss / nt) : kNaN;
  return cv;
}

std::vector<ColumnError> ColumnErrors(const Data& d, const std::vector<std::size_t>& used,
                                      const CvOut& cv) {
  std::vector<ColumnError> out;
  for (int m = 0; m < kMeasCount; ++m) {
    if (!d.measured[m]) continue;
    ColumnError ce;
    ce.column = kMeasColumn[m];
    double sse = 0.0, ss = 0.0;
    for (std::size_t k : used) {
      for (int t = d.term_begin[k]; t < d.term_begin[k + 1]; ++t) {
        if (d.terms[t].meas != m || !std::isfinite(cv.pred[m][k])) continue;
        const double e = cv.pred[m][k] - d.terms[t].value;
        sse += e * e;
        ss += d.terms[t].value * d.terms[t].value;
        ++ce.points;
      }
    }
    if (ce.points == 0) continue;
    ce.rmse = std::sqrt(sse / static_cast<double>(ce.points));
    ce.rmse_percent = ss > 0.0 ? 100.0 * std::sqrt(sse / ss) : kNaN;
    out.push_back(ce);
  }
  return out;
}

}  // namespace

const char* CauseId(Cause c) {
  switch (c) {
    case Cause::kEscSaturation: return "esc_saturation";
    case Cause::kSpeedDependentNoLoadCurrent: return "speed_dependent_no_load_current";
    case Cause::kWindingTemperatureRise: return "winding_temperature_rise";
    case Cause::kTorqueConstantDroop: return "torque_constant_droop";
    case Cause::kThrottleDeadband: return "throttle_deadband";
    case Cause::kSupplyResistance: return "supply_resistance";
  }
  return "?";
}

const char* CauseDescription(Cause c) {
  switch (c) {
    case Cause::kEscSaturation:
      return "ESC saturation: above tr_sat the ESC delivers only sat_slope of the nominal "
             "voltage slope (model.md section 7)";
    case Cause::kSpeedDependentNoLoadCurrent:
      return "no-load current grows with speed (iron, eddy-current, bearing and windage losses): "
             "Io = io_a + io1*omega (model.md section 9)";
    case Cause::kWindingTemperatureRise:
      return "winding resistance rises with copper temperature heated by I^2*R: Rm = Rm0*(1 + "
             "0.00393*rth*P_cu) (model.md section 9)";
    case Cause::kTorqueConstantDroop:
      return "torque constant falls at high current (magnetic saturation, armature reaction): "
             "KT = KT0/(1 + kt_droop*I) (model.md section 9)";
    case Cause::kThrottleDeadband:
      return "ESC throttle dead band or offset: TR_eff = (TR - deadband)/(1 - deadband); positive: "
             "the first part of the command range produces no voltage, negative: voltage already "
             "at zero command (model.md section 9)";
    case Cause::kSupplyResistance:
      return "supply sag: VDC is not measured at the ESC; wires and connectors drop "
             "rsupply*IDC before it (model.md section 9)";
  }
  return "?";
}

bool ParseCause(const std::string& id, Cause* c) {
  for (int k = 0; k < kCauseCount; ++k) {
    if (id == CauseId(static_cast<Cause>(k))) {
      *c = static_cast<Cause>(k);
      return true;
    }
  }
  return false;
}

bool DiagnoseOptions::IsValid(std::string* error) const {
  auto bad = [error](const std::string& m) {
    *error = m;
    return false;
  };
  if (folds < 2) return bad("folds = " + std::to_string(folds) + ": must be >= 2");
  if (!(alpha > 0.0 && alpha < 1.0)) return bad("alpha = " + std::to_string(alpha) + ": must be in (0, 1)");
  if (!(min_gain_percent >= 0.0)) return bad("min_gain_percent must be >= 0");
  if (!(outlier_sigmas >= 0.0)) return bad("outlier_sigmas must be >= 0");
  if (max_findings < 0) return bad("max_findings must be >= 0");
  if (!(assumed_throttle > 0.0 && assumed_throttle <= 1.0)) return bad("assumed_throttle must be in (0, 1]");
  return true;
}

namespace {

// Which slots each cause adds.
std::vector<int> CauseSlots(Cause c) {
  switch (c) {
    case Cause::kEscSaturation: return {kSatSlope};  // + the profiled tr_sat
    case Cause::kSpeedDependentNoLoadCurrent: return {kIo1};
    case Cause::kWindingTemperatureRise: return {kRth};
    case Cause::kTorqueConstantDroop: return {kDroop};
    case Cause::kThrottleDeadband: return {kDeadband};
    case Cause::kSupplyResistance: return {kRsupply};
  }
  return {};
}

int CauseExtraParams(Cause c) { return c == Cause::kEscSaturation ? 2 : 1; }

void AddCause(Model* m, Cause c) {
  for (int s : CauseSlots(c)) m->free[s] = true;
  if (c == Cause::kEscSaturation) {
    m->profile_knee = true;
    if (m->values[kSatSlope] >= 1.0) m->values[kSatSlope] = 0.8;
  } else {
    const int s = CauseSlots(c)[0];
    if (m->values[s] == 0.0) m->values[s] = 0.05 * m->scale[s];
  }
}

// Fits model `m` (the current model plus candidate `c`) from several starts and keeps the best:
// the current fit's values, and - for the offset-like dead band and supply resistance, or when
// a base parameter of the current fit sits on a bound (the first-order model could not follow
// the data) - the linear starting values of the base model with the candidate's own starts
// (dead band: +0.05, -0.1, -0.3, i.e. a dead band or a throttle offset).
FitOut FitCandidate(const Data& d, const std::vector<std::size_t>& rows, const Model& m, Cause c,
                    const Values& fresh, bool base_at_bound, const std::vector<double>& knees) {
  std::vector<Model> starts = {m};
  const bool offset_like = c == Cause::kThrottleDeadband || c == Cause::kSupplyResistance;
  if (offset_like || base_at_bound) {
    Model f = m;
    for (int s = 0; s < kSlotCount; ++s) {
      if (kSlotIsBase[s]) f.values[s] = fresh[s];
    }
    starts.push_back(f);
  }
  if (c == Cause::kThrottleDeadband) {
    const std::size_t k = starts.size();
    for (std::size_t j = 0; j < k; ++j) {
      for (double db : {-0.1, -0.3}) {
        Model v = starts[j];
        v.values[kDeadband] = std::clamp(db, v.lower[kDeadband], v.upper[kDeadband]);
        starts.push_back(v);
      }
    }
  }
  FitOut best;
  for (const Model& st : starts) {
    FitOut f = FitProfiled(d, rows, st, knees, LossType::kTrivial, 1.0);
    if (f.ok && (!best.ok || f.sse < best.sse)) best = f;
  }
  return best;
}

// True when free slot s of values v sits on a bound of its coordinate (ToCoordinate).
bool SlotAtBound(const Model& m, const Values& v, int s) {
  const double tol = 1e-6 * std::max(std::fabs(m.upper[s] - m.lower[s]), 1e-12);
  const double c = ToCoordinate(s, v);
  return c - m.lower[s] <= tol || m.upper[s] - c <= tol;
}

bool BaseAtBound(const Model& m, const Values& v) {
  for (int s = 0; s < kSlotCount; ++s) {
    if (kSlotIsBase[s] && m.free[s] && SlotAtBound(m, v, s)) return true;
  }
  return false;
}

std::string Separation(Cause a, Cause b) {
  auto is = [&](Cause x, Cause y) { return (a == x && b == y) || (a == y && b == x); };
  if (is(Cause::kWindingTemperatureRise, Cause::kTorqueConstantDroop)) {
    return "log the winding temperature (temp_c), or repeat a high-current point after a "
           "cool-down: a thermal effect drifts with time and temperature, magnetic droop does not";
  }
  if (is(Cause::kWindingTemperatureRise, Cause::kSupplyResistance)) {
    return "measure VDC at the ESC input terminals (supply sag vanishes) or log the winding "
           "temperature (heating does not)";
  }
  if (is(Cause::kEscSaturation, Cause::kThrottleDeadband)) {
    return "add throttle levels at both ends of the range (below 20 % and between 85 % and 100 %)";
  }
  if (is(Cause::kSpeedDependentNoLoadCurrent, Cause::kTorqueConstantDroop)) {
    return "no-load runs at several speeds (torque = 0) isolate Io(omega); high-torque points at "
           "low speed isolate KT(I)";
  }
  if (is(Cause::kSpeedDependentNoLoadCurrent, Cause::kWindingTemperatureRise)) {
    return "no-load runs at several speeds (low current, high speed) and locked-rotor-like "
           "high-torque points at low speed (high current) separate speed from current effects";
  }
  if (is(Cause::kSupplyResistance, Cause::kEscSaturation) ||
      is(Cause::kSupplyResistance, Cause::kThrottleDeadband)) {
    return "measure VDC at the ESC input terminals, and run the same throttle levels at two "
           "loads (props): supply sag follows the current, the ESC law follows the throttle";
  }
  return "more throttle levels and voltages, a torque column, or the AC-side columns "
         "(vll_rms_v, irms_a) to see the motor and the ESC separately";
}

// calibrate on the same rows with diagnose's options (throttle map, speed and throttle floors, Kv
// label, ESC prior), the options used in *co; false when calibrate refuses the table.
bool CalibrateWithDiagnoseOptions(const SteadyTable& t, const DiagnoseOptions& o, bool fit_throttle_offset,
                                  calibration::CalibrationOptions* co, calibration::CalibrationResult* r) {
  *co = calibration::CalibrationOptions{};
  co->fit_throttle_offset = fit_throttle_offset;
  co->assumed_throttle = o.assumed_throttle;
  co->min_speed_fraction = o.min_speed_fraction;
  co->min_throttle = o.min_throttle;
  co->labels.kv_rpm_per_v = o.kv_label_rpm_per_v;
  if (o.esc) co->esc_prior = *o.esc;
  try {
    *r = calibration::Calibrate(t, *co);
  } catch (const Error&) {
    return false;
  }
  return true;
}

// Starting values of the base parameters from the calibration engine (src/calibration: the same
// base model, its robust fit and its knee profile, without the throttle offset, which is a
// candidate here): the linear start alone can leave the first-order fit in a stalled local
// minimum on logs whose throttle is not the voltage fraction. Kept only when that fit converged
// and is physical; the linear start stays otherwise.
void BaseStartFromCalibration(const SteadyTable& t, const DiagnoseOptions& o, Values* v) {
  calibration::CalibrationOptions co;
  calibration::CalibrationResult r;
  if (!CalibrateWithDiagnoseOptions(t, o, /*fit_throttle_offset=*/false, &co, &r)) return;
  if (!r.converged || !std::isfinite(r.motor.ke_v_s_per_rad) || !std::isfinite(r.motor.rm_ohm)) return;
  for (int k = 0; k < calibration::kParamCount; ++k) {
    if (r.params[k].at_bound) return;
  }
  (*v)[kKe] = r.motor.ke_v_s_per_rad;
  (*v)[kKt] = r.motor.kt_nm_per_a;
  (*v)[kRm] = r.motor.rm_ohm;
  (*v)[kIo] = r.motor.io_a;
  (*v)[kResc] = r.esc.resc_ohm;
  (*v)[kC1] = r.esc.c1;
  (*v)[kC0] = r.esc.c0;
}

// Rows whose largest |residual| exceeds outlier_sigmas robust sd (sigma): worst first, at most
// max_outlier_fraction of the rows and never the last row of a throttle level (issue 12); each
// is listed in res with its reason. Returns the rows kept (indices into d).
std::vector<std::size_t> ScreenOutliers(const Data& d, const SteadyTable& t, const Eigen::VectorXd& r,
                                        double sigma, const DiagnoseOptions& o, DiagnoseResult* res) {
  const std::size_t n = d.rows();
  std::vector<double> rmax(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    for (int tt = d.term_begin[k]; tt < d.term_begin[k + 1]; ++tt) rmax[k] = std::max(rmax[k], std::fabs(r[tt]));
  }
  const identification::OutlierSelection sel = identification::SelectOutlierRows(
      rmax, d.tr, t.Has(Column::kThrottle), o.outlier_sigmas * sigma, o.max_outlier_fraction, 0);
  std::vector<char> drop(n, 0);
  for (std::size_t k : sel.dropped) {
    drop[k] = 1;
    const std::size_t row = d.table_row[k];
    std::ostringstream why;
    why << std::setprecision(3) << "line " << t.source_line[row] << ": outlier, largest residual " << rmax[k]
        << " % > " << o.outlier_sigmas << " robust sd (" << sigma << " %)";
    res->outlier_rows.push_back(row);
    res->outlier_reasons.push_back(why.str());
  }
  if (sel.spared > 0) {
    res->warnings.push_back(std::to_string(sel.spared) + " more row(s) beyond the outlier threshold kept: at most " +
                            std::to_string(sel.cap) + " rows (10 %) and never a whole throttle level are dropped");
  }
  std::vector<std::size_t> keep;
  for (std::size_t k = 0; k < n; ++k) {
    if (!drop[k]) keep.push_back(k);
  }
  return keep;
}

// The status contract (identification/verdict.h) of the extended model: its free parameters
// (base and findings) on a bound or undetermined, the energy rules over the envelope, the label,
// and the held-out current error of the final model's cross-validation.
identification::Verdict JudgeExtended(const Data& d, const SteadyTable& t, const Model& m, const FitOut& fit,
                                      const std::vector<std::size_t>& used, const CvOut& cv,
                                      const DiagnoseResult& res, const DiagnoseOptions& o) {
  identification::VerdictInputs in;
  in.converged = fit.ok;
  for (int s = 0; s < kSlotCount; ++s) {
    if (!m.free[s]) continue;
    identification::ParamState p;
    p.name = kSlotName[s];
    p.value = fit.values[s];
    p.standard_error = fit.stderr_[s];
    p.fitted = true;
    p.identifiable = std::isfinite(fit.stderr_[s]);
    // A knee slope of 0 (no voltage gain above the knee) is a physical value, not a clip.
    p.at_bound = s != kSatSlope && SlotAtBound(m, fit.values, s);
    in.params.push_back(p);
  }
  in.motor = res.extended_motor;
  in.esc = res.extended_esc;
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (std::size_t k : used) {
    lo = std::min(lo, d.vdc[k]);
    hi = std::max(hi, d.vdc[k]);
  }
  in.envelope.vdc_min_v = std::isfinite(lo) ? lo : 0.0;
  in.envelope.vdc_max_v = hi;
  in.kv_label_rpm_per_v = o.kv_label_rpm_per_v;
  if (o.kv_label_rpm_per_v) in.torque_per_ampere_vs_label = identification::TorquePerAmpereVsLabel(t, *o.kv_label_rpm_per_v);
  identification::HeldOut h;
  h.folds = static_cast<std::size_t>(res.cv_folds);
  h.failed_folds = static_cast<std::size_t>(cv.failed_folds);
  h.leave_one_out = res.leave_one_out;
  std::vector<double> ei, ew;
  for (std::size_t k : used) {
    for (int tt = d.term_begin[k]; tt < d.term_begin[k + 1]; ++tt) {
      const Term& term = d.terms[tt];
      const double p = cv.pred[term.meas][k];
      if (term.value == 0.0) continue;
      // A row without a prediction is a 100 % miss.
      const double e = std::isfinite(p) ? 100.0 * std::fabs(p - term.value) / std::fabs(term.value) : 100.0;
      if (term.meas == kMIdc || (term.meas == kMIrms && !d.measured[kMIdc])) ei.push_back(e);
      if (term.meas == kMOmega) ew.push_back(e);
    }
  }
  h.median_abs_current_percent = Median(ei);
  h.median_abs_speed_percent = Median(ew);
  h.rms_percent = cv.rms_percent;
  h.first_order_rms_percent = res.baseline_cv_rms_percent;
  in.held_out = h;
  in.has_torque = t.Has(Column::kTorqueNm);
  in.has_ac = t.Has(Column::kVllRmsV) && t.Has(Column::kIrmsA);
  in.has_throttle = t.Has(Column::kThrottle);
  in.pulse_min_us = t.throttle_pulse_min_us;
  in.pulse_max_us = t.throttle_pulse_max_us;
  return identification::Judge(in);
}

// ---------------------------------------------------------------------------------------------
// The stages of Diagnose(), in the order it runs them.

// Stage 1: what the log offers, and the rows and terms of the fit.
struct Prepared {
  Data d;
  bool has_tr = false;  // throttle column
  bool has_q = false;   // torque column
  bool has_nl = false;  // no-load flag column
  bool ac = false;      // AC-side columns (vll_rms_v and irms_a)
  bool any_tk = false;  // some row has a known torque (torque column or a no-load row)
  double wmax = 0.0;    // largest logged speed, rad/s
  std::vector<double> levels;                  // distinct throttle levels (none without throttle)
  std::array<double, kMeasCount> inv_scale{};  // 100 / column median: percent of a typical value
};

Prepared PrepareDiagnosisData(const SteadyTable& t, const DiagnoseOptions& o, DiagnoseResult* res) {
  const std::string& file = res->file;
  if (!t.Has(Column::kOmegaRadS)) {
    throw DataError(file + ": column omega_rad_s (shaft speed) is absent: the diagnosis compares "
                    "the model's speed/current with the measured ones and needs the speed");
  }
  if (!t.Has(Column::kVdcV)) {
    throw DataError(file + ": column vdc_v (supply voltage) is absent: the model needs the voltage "
                    "at the ESC (eq 48)");
  }
  Prepared p;
  p.has_tr = t.Has(Column::kThrottle);
  p.has_q = t.Has(Column::kTorqueNm);
  p.has_nl = t.Has(Column::kNoLoad);
  p.ac = t.Has(Column::kVllRmsV) && t.Has(Column::kIrmsA);
  res->mode = p.ac ? "ac" : (p.has_tr ? "dc" : "dc_no_throttle");

  Data& d = p.d;
  d.motor_type = o.motor ? o.motor->type : MotorType::kBldc;
  for (int m = 0; m < kMeasCount; ++m) d.measured[m] = t.Has(kMeasColumn[m]);
  for (double w : t.Get(Column::kOmegaRadS)) p.wmax = std::max(p.wmax, w);
  res->row_used.assign(t.rows(), 0);
  std::vector<std::size_t> cand;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const double tr = p.has_tr ? t.Get(Column::kThrottle)[i] : o.assumed_throttle;
    if (identification::RowRejection(t.Get(Column::kOmegaRadS)[i], p.wmax, o.min_speed_fraction, p.has_tr, tr,
                                     o.min_throttle, t.Get(Column::kVdcV)[i]) == nullptr &&
        !(p.has_nl && t.Get(Column::kNoLoad)[i] != 0.0)) {
      cand.push_back(i);
    }
  }
  // Speed readings the circuit cannot produce are left out, as calibrate does (fit_rows.h).
  std::vector<char> spurious(t.rows(), 0);
  std::string listed;
  for (const auto& sp : identification::FindSpuriousSpeeds(t, cand, o.assumed_throttle)) {
    spurious[sp.row] = 1;
    listed += (listed.empty() ? "" : "; ") + identification::SpuriousSpeedText(t, sp);
  }
  if (!listed.empty()) {
    res->warnings.push_back("speed readings inconsistent with VDC, throttle and current left out: " + listed);
  }
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const double w = t.Get(Column::kOmegaRadS)[i];
    const double tr = p.has_tr ? t.Get(Column::kThrottle)[i] : o.assumed_throttle;
    const double vdc = t.Get(Column::kVdcV)[i];
    if (spurious[i] ||
        identification::RowRejection(w, p.wmax, o.min_speed_fraction, p.has_tr, tr, o.min_throttle, vdc) != nullptr) {
      continue;
    }
    const bool nl = p.has_nl && t.Get(Column::kNoLoad)[i] != 0.0;
    d.table_row.push_back(i);
    d.vdc.push_back(vdc);
    d.tr.push_back(tr);
    d.omega.push_back(w);
    d.q.push_back(p.has_q ? t.Get(Column::kTorqueNm)[i] : 0.0);
    d.torque_known.push_back(p.has_q || nl ? 1 : 0);
  }
  const std::size_t n = d.rows();
  if (n < 6) {
    throw DataError(file + ": only " + std::to_string(n) +
                    " row(s) with the motor turning: the diagnosis needs at least 6");
  }
  p.inv_scale = identification::MedianPercentScales(t, d.table_row, &d.measured);
  d.term_begin.push_back(0);
  for (std::size_t k = 0; k < n; ++k) {
    for (int m = 0; m < kMeasCount; ++m) {
      if (!d.measured[m]) continue;
      if (m == kMOmega && !d.torque_known[k]) continue;  // the speed is this row's input
      // Percent of the measured value (the noise of dyno sensors is mostly relative), floored
      // at 5 % of the column's median so that near-zero readings do not dominate.
      const double val = t.Get(kMeasColumn[m])[d.table_row[k]];
      const double den = std::max(std::fabs(val), 5.0 / p.inv_scale[m]);
      d.terms.push_back({m, val, 100.0 / den});
    }
    d.term_begin.push_back(static_cast<int>(d.terms.size()));
  }
  if (d.terms.empty()) {
    throw DataError(file + ": nothing to predict: the log needs idc_a, the AC columns (vll_rms_v, "
                    "irms_a) or a torque column besides the speed");
  }
  for (int m = 0; m < kMeasCount; ++m) {
    if (d.measured[m] && !(m == kMOmega && !p.has_q && !p.has_nl)) res->predicted_columns.push_back(kMeasColumn[m]);
  }
  if (p.has_tr) p.levels = identification::ThrottleLevels(d.tr);
  for (char c : d.torque_known) p.any_tk = p.any_tk || c;
  d.tie_kt = !(p.has_q && p.ac);
  return p;
}

// Stage 2a: linear starts of the base parameters when no catalog entry is given:
// U = R*I + KE*omega (eq 48) by least squares, I from the AC current or IDC/(C1*TR + C0); then
// the calibration engine's fit where it is physical (BaseStartFromCalibration).
void LinearBaseStarts(const SteadyTable& t, const DiagnoseOptions& o, const Prepared& p, Values* values) {
  const Data& d = p.d;
  const std::size_t n = d.rows();
  Values& v = *values;
  std::vector<double> cur(n), u(n);
  double imax = 0.0, umax = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = d.table_row[k];
    const double g = std::max(v[kC1] * d.tr[k] + v[kC0], 1e-3);
    cur[k] = p.ac ? t.Get(Column::kIrmsA)[i] : (d.measured[kMIdc] ? t.Get(Column::kIdcA)[i] / g : 0.0);
    u[k] = kVllRmsPerVdc * d.vdc[k] * d.tr[k];
    imax = std::max(imax, cur[k]);
    umax = std::max(umax, u[k]);
  }
  const identification::CircuitStart lin = identification::LinearCircuitStart(cur, d.omega, u);
  const double ke = lin.ke_v_s_per_rad;
  double r = lin.r_total_ohm;
  if (!(r > 1e-4)) r = imax > 0.0 ? 0.05 * umax / imax : 0.1;
  v[kKe] = ke;
  v[kRm] = std::max(r - v[kResc], 1e-4);
  v[kKt] = kPacPerVllIrms * ke;
  if (p.any_tk) {
    double s = 0.0;
    int c = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (!d.torque_known[k]) continue;
      s += cur[k] - d.q[k] / v[kKt];
      ++c;
    }
    v[kIo] = c > 0 ? std::max(s / c, 0.0) : 0.0;
  }
  BaseStartFromCalibration(t, o, &v);
}

// Stage 2b: optimisation scales (x = value/scale) and the physical box of every slot.
void ScalesAndBounds(const Prepared& p, Model* base) {
  const Data& d = p.d;
  const Values& v = base->values;
  double imax = 0.0;
  {
    MotorParams mp;
    EscParams ep;
    ToParams(d, v, &mp, &ep);
    const Drive drive(mp, ep);
    for (std::size_t k = 0; k < d.rows(); ++k) {
      const auto op = d.torque_known[k] ? drive.AtTorque(d.vdc[k], d.tr[k], d.q[k])
                                        : drive.AtSpeed(d.vdc[k], d.tr[k], d.omega[k]);
      if (std::isfinite(op.irms_a)) imax = std::max(imax, std::fabs(op.irms_a));
    }
    if (!(imax > 0.0)) imax = 10.0;
  }
  const double rm_s = std::max(v[kRm], 1e-3);
  Values& sc = base->scale;
  sc[kKe] = std::max(v[kKe], 1e-6);
  sc[kKt] = 1.0;  // the ratio KT/(kp*KE)
  sc[kRm] = rm_s;
  sc[kIo] = std::max({v[kIo], 0.02 * imax, 1e-3});
  sc[kResc] = rm_s;
  sc[kC1] = 1.0;
  sc[kC0] = 0.1;
  sc[kTrSat] = 1.0;
  sc[kSatSlope] = 1.0;
  sc[kDeadband] = 0.1;
  sc[kIo1] = sc[kIo] / std::max(p.wmax, 1.0);
  sc[kRth] = 0.1 / (kAlphaCopperPerK * kPacPerVllIrms * rm_s * imax * imax);  // x=1: +10 % Rm
  sc[kDroop] = 0.1 / imax;                                                  // x=1: -10 % KT
  sc[kRsupply] = rm_s;
  const double min_level = p.levels.empty() ? 1.0 : p.levels.front();
  // Physical box of identification/parameters.h; the KT and c1 slots are bounded as the ratio
  // KT/(kp*KE) <= 1 and the excess c1 + c0 - 1.1095 >= 0 (model.md section 10), c0 >= 0.
  namespace id = identification;
  // Slots 0..9 are the base parameters of identification/parameters.h in the same order (checked
  // below); the extension slots follow with their own physical ranges.
  static_assert(kDeadband == static_cast<int>(id::BaseParam::kDeadband) && kIo1 == id::kBaseParamCount);
  Values lower{}, upper{};
  for (int k = 0; k < id::kBaseParamCount; ++k) {
    lower[k] = id::kBaseLower[k];
    upper[k] = id::kBaseUpper[k];
  }
  lower[kKt] = id::kKtRatioLower;
  upper[kKt] = id::kKtRatioUpper;
  lower[kC1] = id::kEscExcessLower;
  upper[kC1] = id::kEscExcessUpper;
  upper[kDeadband] = std::min(upper[kDeadband], std::max(0.0, 0.9 * min_level));  // below the lowest level
  lower[kIo1] = 0.0;   // Io must not fall with speed (section 10: no energy created)
  upper[kIo1] = 1.0;
  lower[kRth] = 0.0;
  upper[kRth] = 1000.0;
  lower[kDroop] = 0.0;
  upper[kDroop] = 10.0;
  lower[kRsupply] = 0.0;
  upper[kRsupply] = 10.0;
  base->lower = lower;
  base->upper = upper;
}

// Stage 2: the base (first-order) model: what is free, held values, starts, scales and bounds.
Model BuildBaseModel(const SteadyTable& t, const DiagnoseOptions& o, const Prepared& p, DiagnoseResult* res) {
  const Data& d = p.d;
  Model base;
  const MotorParams m0 = o.motor ? *o.motor : MotorParams{};
  const EscParams e0 = o.esc ? *o.esc : EscParams{};
  Values& v = base.values;
  v[kKe] = m0.ke_v_s_per_rad;
  v[kKt] = m0.kt_nm_per_a;
  v[kRm] = m0.rm_ohm;
  v[kIo] = m0.io_a;
  v[kResc] = e0.resc_ohm;
  v[kC1] = e0.c1;
  v[kC0] = e0.c0;
  // The extensions start from the first-order model whatever the catalog says: the diagnosis
  // asks whether the data need them.
  v[kTrSat] = 1.0;
  v[kSatSlope] = 1.0;
  v[kDeadband] = 0.0;
  v[kIo1] = v[kRth] = v[kDroop] = v[kRsupply] = 0.0;
  FreeSet& fr = base.free;
  fr[kKe] = fr[kRm] = true;
  fr[kKt] = !d.tie_kt;
  fr[kIo] = p.any_tk;
  fr[kResc] = p.ac && p.has_tr;
  fr[kC1] = fr[kC0] = d.measured[kMIdc] && p.has_tr && p.levels.size() >= 2 && (p.ac || p.has_q);
  if (!o.motor) LinearBaseStarts(t, o, p, &v);
  ScalesAndBounds(p, &base);
  for (int s = 0; s < kSlotCount; ++s) {
    if (base.free[s]) res->base_free_parameters.push_back(kSlotName[s]);
  }
  return base;
}

// Knee candidates: midpoints between throttle levels from 0.5 up (or a 0.02 grid when the
// throttle is continuous), each with at least one level above.
std::vector<double> KneeGrid(const std::vector<double>& levels) {
  std::vector<double> knees;
  if (levels.size() >= 3) {
    if (levels.size() <= 40) {
      for (std::size_t j = 0; j + 1 < levels.size(); ++j) {
        const double mid = 0.5 * (levels[j] + levels[j + 1]);
        if (mid >= 0.5) knees.push_back(mid);
      }
    } else {
      for (double k = 0.5; k < levels.back() - 1e-9; k += 0.02) knees.push_back(k);
    }
  }
  return knees;
}

// Stage 3: the candidates this log can test; the others go to res->not_testable with the reason.
std::vector<Cause> TestableCandidates(const DiagnoseOptions& o, const Prepared& p,
                                      const std::vector<double>& knees, DiagnoseResult* res) {
  std::vector<Cause> candidates;
  for (Cause c : o.candidates) {
    CandidateScore cs;
    cs.cause = c;
    std::string reason;
    switch (c) {
      case Cause::kEscSaturation:
        if (!p.has_tr) reason = "no throttle column";
        else if (knees.empty()) reason = "fewer than 3 throttle levels or none above 50 %";
        break;
      case Cause::kSpeedDependentNoLoadCurrent:
        if (!p.any_tk) reason = "no torque column and no no-load rows: with the speed as input the no-load current does not enter the predicted columns";
        break;
      case Cause::kTorqueConstantDroop:
        if (!p.has_q) reason = "no torque column: the torque constant does not enter the predicted columns";
        break;
      case Cause::kThrottleDeadband:
        if (!p.has_tr) reason = "no throttle column";
        else if (p.levels.size() < 3) reason = "fewer than 3 throttle levels";
        break;
      case Cause::kSupplyResistance:
        if (!p.has_tr) reason = "no throttle column: at one throttle a supply resistance is indistinguishable from Rm";
        else if (!p.d.measured[kMIdc]) reason = "no idc_a column";
        else if (p.levels.size() < 3) reason = "fewer than 3 throttle levels";
        break;
      case Cause::kWindingTemperatureRise:
        break;
    }
    if (reason.empty()) {
      candidates.push_back(c);
    } else {
      cs.not_testable_reason = reason;
      res->not_testable.push_back(cs);
    }
  }
  return candidates;
}

// Stage 4: cross-validation folds, seeded. Leave-one-out below kLooRows rows (small tables,
// issue 12: "fewer than about 15"; from 12 rows on, o.folds folds hold out at least 2 rows each
// and keep 9 or more to fit).
struct Folds {
  int count = 0;
  std::vector<int> fold_of;  // per data row
};

Folds AssignFolds(std::size_t n, const DiagnoseOptions& o) {
  constexpr std::size_t kLooRows = 12;
  Folds f;
  f.count = n < kLooRows ? static_cast<int>(n) : o.folds;
  f.fold_of.resize(n);
  std::vector<std::size_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937 rng(o.seed);
  std::shuffle(perm.begin(), perm.end(), rng);
  for (std::size_t j = 0; j < n; ++j) f.fold_of[perm[j]] = static_cast<int>(j % static_cast<std::size_t>(f.count));
  return f;
}

// Stage 5: effective-variance weights. The known inputs (VDC, and the speed or the torque) are
// measured with the same relative noise as the outputs, and at low throttle a small error in
// U = kv*VDC*TR or in KE*omega is a large error in the current (I = (U - KE*omega)/R is a
// small difference there). Each residual is therefore divided by the spread that relative
// noise of the output and of the inputs gives it (the "effective variance" of errors-in-
// variables fitting): s = sqrt(y^2 + (dy/dVDC*VDC)^2 + (dy/dx*x)^2), x = omega or torque,
// with the derivatives of a preliminary fit of the first-order model. Without this the F test
// sees heteroscedastic residuals and calls low-throttle noise an effect.
void ApplyEffectiveVarianceWeights(const std::vector<std::size_t>& used, const Model& base, Prepared* p) {
  Data& d = p->d;
  const FitOut pre = FitModel(d, used, base, LossType::kHuber, 1.0);
  if (!pre.ok) return;
  MotorParams mp;
  EscParams ep;
  ToParams(d, pre.values, &mp, &ep);
  const Drive drive(mp, ep);
  double p0[kMeasCount], pv[kMeasCount], px[kMeasCount];
  for (std::size_t k = 0; k < d.rows(); ++k) {
    const double h = 1e-4;
    const bool tk = d.torque_known[k] != 0;
    const double x = tk ? d.q[k] : d.omega[k];
    auto predict = [&](double vdc, double xin, double* out) {
      const OperatingPoint op = tk ? drive.AtTorque(vdc, d.tr[k], xin) : drive.AtSpeed(vdc, d.tr[k], xin);
      out[kMOmega] = op.omega_rad_s;
      out[kMIdc] = op.idc_a;
      out[kMIrms] = op.irms_a;
      out[kMVll] = op.vll_rms_v;
      out[kMPac] = op.pac_w;
    };
    predict(d.vdc[k], x, p0);
    predict(d.vdc[k] * (1.0 + h), x, pv);
    predict(d.vdc[k], x == 0.0 ? h : x * (1.0 + h), px);
    for (int tt = d.term_begin[k]; tt < d.term_begin[k + 1]; ++tt) {
      Term& term = d.terms[tt];
      const double sv = (pv[term.meas] - p0[term.meas]) / h;  // dy/dVDC * VDC
      const double sx = x == 0.0 ? 0.0 : (px[term.meas] - p0[term.meas]) / h;
      const double spread = std::sqrt(term.value * term.value + sv * sv + sx * sx);
      const double floor = 5.0 / p->inv_scale[term.meas];
      if (std::isfinite(spread)) term.inv_scale = 100.0 / std::max(spread, floor);
    }
  }
}

// Stage 6: outlier screen with the union model (the base model plus every testable candidate).
// Returns the rows used by every later fit and score; fills res's outlier lists and row_used.
std::vector<std::size_t> ScreenWithUnionModel(const SteadyTable& t, const DiagnoseOptions& o, const Data& d,
                                              const Model& base, const std::vector<Cause>& candidates,
                                              const std::vector<double>& knees, std::vector<std::size_t> used,
                                              DiagnoseResult* res) {
  if (o.outlier_sigmas > 0.0) {
    Model uni = base;
    for (Cause c : candidates) AddCause(&uni, c);
    std::vector<double> coarse;
    for (std::size_t j = 0; j < knees.size(); j += 2) coarse.push_back(knees[j]);
    FitOut fu = FitProfiled(d, used, uni, coarse, LossType::kHuber, 1.0);
    if (!fu.ok) fu = FitModel(d, used, base, LossType::kHuber, 1.0);
    if (fu.ok) {
      const int nt = TermCount(d, used);
      Eigen::VectorXd r(nt);
      Residuals(d, used, fu.values, r.data());
      std::vector<double> a(r.data(), r.data() + nt);
      for (double& x : a) x = std::fabs(x);
      const double sigma = std::max(1.4826 * Median(a), o.outlier_floor_percent);
      used = ScreenOutliers(d, t, r, sigma, o, res);
    }
  }
  if (!res->outlier_rows.empty()) {
    res->warnings.push_back(std::to_string(res->outlier_rows.size()) +
                            " outlier row(s) left out of every fit and score");
  }
  res->points_used = used.size();
  for (std::size_t k : used) res->row_used[d.table_row[k]] = 1;
  return used;
}

// Held-out predictions of cv as full table columns (NaN on rows not used).
void CvTable(const Data& d, std::size_t table_rows, const std::vector<std::size_t>& used, const CvOut& cv,
             std::map<Column, std::vector<double>>* out) {
  for (int m = 0; m < kMeasCount; ++m) {
    if (!d.measured[m]) continue;
    std::vector<double> col(table_rows, kNaN);
    for (std::size_t k : used) col[d.table_row[k]] = cv.pred[m][k];
    (*out)[kMeasColumn[m]] = col;
  }
}

// A model, its fit on the used rows and its cross-validation: the state of the forward selection.
struct Step {
  Model model;
  FitOut fit;
  CvOut cv;
};

// Stage 7: the first-order model fitted and cross-validated.
Step FitBaseline(const SteadyTable& t, const Data& d, const std::vector<std::size_t>& used, const Folds& folds,
                 const Model& base, const std::vector<double>& knees, DiagnoseResult* res) {
  Step cur;
  cur.model = base;
  cur.fit = FitModel(d, used, cur.model, LossType::kTrivial, 1.0);
  if (!cur.fit.ok) {
    throw DataError(res->file + ": the first-order model could not be fitted to the log (no finite "
                    "prediction at the start values): check the units of the columns");
  }
  cur.model.values = cur.fit.values;
  if (BaseAtBound(cur.model, cur.fit.values)) {
    std::string which;
    for (int s = 0; s < kSlotCount; ++s) {
      if (!kSlotIsBase[s] || !cur.model.free[s]) continue;
      if (SlotAtBound(cur.model, cur.fit.values, s)) which += (which.empty() ? "" : ", ") + std::string(kSlotName[s]);
    }
    res->warnings.push_back("first-order fit has " + which +
                            " on a physical bound: the first-order model cannot follow this log");
  }
  cur.cv = CrossValidate(d, used, folds.fold_of, folds.count, cur.model, cur.fit, knees);
  res->cv_folds = folds.count;
  res->leave_one_out = folds.count == static_cast<int>(d.rows());
  res->baseline_cv_failed_folds = cur.cv.failed_folds;
  ToParams(d, cur.fit.values, &res->base_motor, &res->base_esc);
  res->baseline_cv = ColumnErrors(d, used, cur.cv);
  res->baseline_cv_rms_percent = cur.cv.rms_percent;
  CvTable(d, t.rows(), used, cur.cv, &res->baseline_cv_prediction);
  return cur;
}

// Stage 8a: the 5 worst held-out points of the baseline.
std::vector<WorstPoint> WorstPoints(const SteadyTable& t, const Data& d, const std::vector<std::size_t>& used,
                                    const CvOut& cv) {
  std::vector<WorstPoint> all;
  for (std::size_t k : used) {
    for (int tt = d.term_begin[k]; tt < d.term_begin[k + 1]; ++tt) {
      const Term& term = d.terms[tt];
      const double p = cv.pred[term.meas][k];
      if (!std::isfinite(p) || term.value == 0.0) continue;
      WorstPoint w;
      w.row = d.table_row[k];
      w.source_line = t.source_line[w.row];
      w.column = kMeasColumn[term.meas];
      w.measured = term.value;
      w.predicted = p;
      w.error_percent = (p - term.value) / term.value * 100.0;
      all.push_back(w);
    }
  }
  std::sort(all.begin(), all.end(), [](const WorstPoint& a, const WorstPoint& b) {
    return std::fabs(a.error_percent) > std::fabs(b.error_percent);
  });
  if (all.size() > 5) all.resize(5);
  return all;
}

// A quadratic trend of the held-out percent errors ys against the variable xs; nullopt when
// there are fewer than 6 points or xs does not vary. Structured: p < alpha and r2 >= 0.2.
std::optional<ResidualTrend> FitTrend(const std::vector<double>& xs, const std::vector<double>& ys, double alpha) {
  if (xs.size() < 6) return std::nullopt;
  const auto [lo_it, hi_it] = std::minmax_element(xs.begin(), xs.end());
  const double lo = *lo_it, span = *hi_it - *lo_it;
  if (!(span > 0.0)) return std::nullopt;
  const Eigen::Index nn = static_cast<Eigen::Index>(xs.size());
  Eigen::MatrixXd a(nn, 3);
  Eigen::VectorXd y(nn);
  for (Eigen::Index i = 0; i < nn; ++i) {
    const double u = (xs[static_cast<std::size_t>(i)] - lo) / span;
    a(i, 0) = 1.0;
    a(i, 1) = u;
    a(i, 2) = u * u;
    y[i] = ys[static_cast<std::size_t>(i)];
  }
  const Eigen::VectorXd c3 = a.colPivHouseholderQr().solve(y);
  const double mean = y.mean();
  const double sst = (y.array() - mean).square().sum();
  const double ssr = (a * c3 - y).squaredNorm();
  ResidualTrend tr;
  tr.r2 = sst > 0.0 ? 1.0 - ssr / sst : 0.0;
  const double df2 = static_cast<double>(nn) - 3.0;
  tr.p_value = tr.r2 < 1.0 ? FDistributionUpperTail((tr.r2 / 2.0) / ((1.0 - tr.r2) / df2), 2.0, df2) : 0.0;
  const Eigen::VectorXd c2 = a.leftCols(2).colPivHouseholderQr().solve(y);
  tr.slope_percent_per_range = c2[1];
  tr.structured = tr.p_value < alpha && tr.r2 >= 0.2;
  return tr;
}

// Stage 8b: residual structure of the baseline: the held-out percent error of every predicted
// column against each logged variable.
std::vector<ResidualTrend> ResidualTrends(const SteadyTable& t, const Prepared& p,
                                          const std::vector<std::size_t>& used, const CvOut& cv, double alpha) {
  const Data& d = p.d;
  struct Var {
    const char* name;
    Column col;
  };
  std::vector<Var> vars;
  if (p.has_tr) vars.push_back({"throttle", Column::kThrottle});
  vars.push_back({"rpm", Column::kOmegaRadS});
  if (d.measured[kMIrms]) vars.push_back({"current_a", Column::kIrmsA});
  else if (d.measured[kMIdc]) vars.push_back({"current_a", Column::kIdcA});
  vars.push_back({"vdc_v", Column::kVdcV});
  if (p.has_q) vars.push_back({"torque_nm", Column::kTorqueNm});
  if (t.Has(Column::kTimeS)) vars.push_back({"time_s", Column::kTimeS});
  if (t.Has(Column::kTempC)) vars.push_back({"temp_c", Column::kTempC});
  std::vector<ResidualTrend> trends;
  for (int m = 0; m < kMeasCount; ++m) {
    if (!d.measured[m]) continue;
    for (const Var& var : vars) {
      std::vector<double> xs, ys;
      for (std::size_t k : used) {
        const double pr = cv.pred[m][k];
        double meas = kNaN;
        for (int tt = d.term_begin[k]; tt < d.term_begin[k + 1]; ++tt) {
          if (d.terms[tt].meas == m) meas = d.terms[tt].value;
        }
        if (!std::isfinite(pr) || !std::isfinite(meas) || meas == 0.0) continue;
        xs.push_back(t.Get(var.col)[d.table_row[k]]);
        ys.push_back((pr - meas) / meas * 100.0);
      }
      std::optional<ResidualTrend> tr = FitTrend(xs, ys, alpha);
      if (!tr) continue;
      tr->variable = var.name;
      tr->column = kMeasColumn[m];
      trends.push_back(*tr);
    }
  }
  return trends;
}

// What the forward selection shares between its steps (fixed for the whole search).
struct SearchContext {
  const Data& d;
  const std::vector<std::size_t>& used;
  const Folds& folds;
  const std::vector<double>& knees;
  const Values& base_values;  // the base model's starts, a second start for candidates
  const DiagnoseOptions& o;
};

// One candidate fitted on top of the current model and scored.
struct Scored {
  CandidateScore cs;
  FitOut fit;
  CvOut cv;
  Model model;
};

// Stage 9a: candidate c added to the current model: fitted from several starts, tested (F test,
// AICc, its own parameter determined and not clipped) and, when it passes, cross-validated.
Scored ScoreCandidate(const SearchContext& x, const Step& cur, bool base_at_bound, double aicc0, Cause c,
                      std::size_t tested) {
  Scored sc;
  Model& m = sc.model;
  m = cur.model;
  AddCause(&m, c);
  const FitOut f = FitCandidate(x.d, x.used, m, c, x.base_values, base_at_bound, x.knees);
  CandidateScore& cs = sc.cs;
  cs.cause = c;
  cs.testable = true;
  sc.fit = f;
  if (!f.ok) return sc;
  m.values = f.values;
  for (int s : CauseSlots(c)) {
    cs.parameters[kSlotName[s]] = f.values[s];
    cs.stderrs[kSlotName[s]] = f.stderr_[s];
  }
  if (c == Cause::kEscSaturation) {
    cs.parameters["tr_sat"] = f.values[kTrSat];
    double step = 0.02;
    for (std::size_t j = 0; j + 1 < x.knees.size(); ++j) {
      if (x.knees[j] <= f.values[kTrSat]) step = x.knees[j + 1] - x.knees[j];
    }
    // The refined knee's own standard error (FitProfiled), else the grid resolution.
    cs.stderrs["tr_sat"] = std::isfinite(f.stderr_[kTrSat]) ? f.stderr_[kTrSat] : step / std::sqrt(12.0);
  }
  cs.sse = f.sse;
  cs.aicc = Aicc(f.sse, f.n_terms, f.n_free);
  cs.delta_aicc = cs.aicc - aicc0;
  const int q = CauseExtraParams(c);
  const double df2 = static_cast<double>(f.n_terms - f.n_free);
  if (df2 > 0.0 && f.sse < cur.fit.sse) {
    cs.f_statistic = ((cur.fit.sse - f.sse) / q) / (f.sse / df2);
    cs.p_value = FDistributionUpperTail(cs.f_statistic, q, df2);
    if (c == Cause::kEscSaturation) cs.p_value = std::min(1.0, cs.p_value * static_cast<double>(x.knees.size()));
    // Every candidate of the step is a test of "the current model is enough": alpha holds for the
    // step (Bonferroni over the `tested` candidates), not for each candidate. Per candidate, a
    // clean campaign's noise passed p < alpha as a second cause now and then (issue 23: rth at
    // p = 0.00094 beside a hidden io1, 5 candidates tested).
    cs.p_value = std::min(1.0, cs.p_value * static_cast<double>(std::max<std::size_t>(tested, 1)));
  }
  // The extension's own parameter must be determined: at least 2 standard errors from
  // its "no effect" value (0; 1 for sat_slope). A parameter the data cannot separate from
  // the base parameters (|corr| -> 1, huge error) is not a finding, whatever the F test.
  bool determined = true;
  for (int sl : CauseSlots(c)) {
    const double null_value = sl == kSatSlope ? 1.0 : 0.0;
    const double se = f.stderr_[sl];
    if (std::isfinite(se) && std::fabs(f.values[sl] - null_value) < 2.0 * se) determined = false;
    // On a bound of its physical range the parameter is not estimated but clipped: the
    // misfit is bigger than, or different from, what this mechanism can produce. (A knee
    // slope of 0 - no voltage gain above the knee - is a physical value, not a clip.)
    const double tol = 1e-6 * (m.upper[sl] - m.lower[sl]);
    const bool at_lower = f.values[sl] - m.lower[sl] <= tol && sl != kSatSlope;
    const bool at_upper = m.upper[sl] - f.values[sl] <= tol && sl != kSatSlope;
    if (at_lower || at_upper) {
      determined = false;
      cs.note = std::string(kSlotName[sl]) + " clipped at the bound of its physical range";
    }
  }
  if (!determined && cs.note.empty()) cs.note = "parameter within 2 standard errors of no effect";
  const bool pre = cs.p_value < x.o.alpha && cs.delta_aicc < 0.0 && determined;
  if (pre) {
    sc.cv = CrossValidate(x.d, x.used, x.folds.fold_of, x.folds.count, m, f, x.knees);
    cs.cv_rms_percent = sc.cv.rms_percent;
    cs.gain_percent = 100.0 * (1.0 - sc.cv.rms_percent / cur.cv.rms_percent);
    cs.significant = cs.gain_percent >= x.o.min_gain_percent;
  }
  return sc;
}

// Stage 9b: the rivals of the winner bs (significant and within ambiguity_aicc of it, or close
// in gain) that are no longer significant once the winner is in the model (cur) explain the same
// thing: the data cannot tell the two apart. Each becomes an ambiguity and leaves `remaining`.
void ResolveRivals(const SearchContext& x, const Step& cur, bool base_at_bound, const std::vector<Scored>& scored,
                   int best, std::vector<Cause>* remaining, DiagnoseResult* res) {
  const CandidateScore& bs = scored[best].cs;
  std::vector<Cause> rivals;
  for (std::size_t j = 0; j < scored.size(); ++j) {
    if (static_cast<int>(j) == best || !scored[j].cs.significant) continue;
    if (scored[j].cs.aicc - bs.aicc < x.o.ambiguity_aicc ||
        scored[j].cs.gain_percent >= x.o.ambiguity_gain_ratio * bs.gain_percent) {
      rivals.push_back(scored[j].cs.cause);
    }
  }
  for (Cause rc : rivals) {
    Model m = cur.model;
    AddCause(&m, rc);
    const FitOut f = FitCandidate(x.d, x.used, m, rc, x.base_values, base_at_bound, x.knees);
    bool still = false;
    if (f.ok && f.sse < cur.fit.sse) {
      const int q = CauseExtraParams(rc);
      const double df2 = static_cast<double>(f.n_terms - f.n_free);
      const double fs = ((cur.fit.sse - f.sse) / q) / (f.sse / df2);
      still = FDistributionUpperTail(fs, q, df2) < x.o.alpha;
    }
    if (still) continue;
    Ambiguity a;
    a.causes = {bs.cause, rc};
    std::ostringstream s;
    const auto it = std::find_if(scored.begin(), scored.end(), [&](const Scored& y) { return y.cs.cause == rc; });
    s << std::setprecision(3) << CauseId(bs.cause) << " (gain " << bs.gain_percent << " %, AICc "
      << bs.aicc << ") and " << CauseId(rc) << " (gain " << it->cs.gain_percent << " %, AICc "
      << it->cs.aicc << ") both explain the misfit and the second adds nothing once the first is "
      << "in the model: the data cannot tell them apart";
    a.reason = s.str();
    a.measurement = Separation(bs.cause, rc);
    res->ambiguous.push_back(a);
    remaining->erase(std::remove(remaining->begin(), remaining->end(), rc), remaining->end());
  }
}

// Stage 9: greedy forward selection from the baseline cur: at each step every remaining
// candidate is scored and the significant one with the largest CV gain joins the model.
// Returns the final (extended) model.
Step SearchCandidates(const SearchContext& x, bool has_tr, std::vector<Cause> remaining, Step cur,
                      DiagnoseResult* res) {
  const DiagnoseOptions& o = x.o;
  if (!has_tr && res->baseline_cv_rms_percent > o.no_throttle_max_percent) {
    // Without a throttle column every row is taken at assumed_throttle; when the model misses
    // by this much the rows are not such points and any "cause" would explain the wrong
    // throttle, not the drive.
    std::ostringstream w;
    w << std::setprecision(3) << "no throttle column and the first-order model misses by "
      << res->baseline_cv_rms_percent << " % rms: the rows are not full-throttle points, so no "
      << "cause is named; diagnose a log that records the throttle";
    res->warnings.push_back(w.str());
    remaining.clear();
  }
  while (static_cast<int>(res->findings.size()) < o.max_findings && !remaining.empty()) {
    const double aicc0 = Aicc(cur.fit.sse, cur.fit.n_terms, cur.fit.n_free);
    const bool base_at_bound = BaseAtBound(cur.model, cur.fit.values);
    std::vector<Scored> scored;
    std::vector<CandidateScore> scores;
    for (Cause c : remaining) {
      scored.push_back(ScoreCandidate(x, cur, base_at_bound, aicc0, c, remaining.size()));
      scores.push_back(scored.back().cs);
    }
    int best = -1;
    for (std::size_t j = 0; j < scores.size(); ++j) {
      if (scores[j].significant && (best < 0 || scores[j].gain_percent > scores[best].gain_percent)) {
        best = static_cast<int>(j);
      }
    }
    if (best < 0) {
      res->last_step_scores = scores;
      break;
    }
    Scored& win = scored[best];
    const CandidateScore& bs = win.cs;
    Finding fd;
    fd.cause = bs.cause;
    fd.description = CauseDescription(bs.cause);
    fd.parameters = bs.parameters;
    fd.stderrs = bs.stderrs;
    fd.gain_percent = bs.gain_percent;
    fd.f_statistic = bs.f_statistic;
    fd.p_value = bs.p_value;
    fd.delta_aicc = bs.delta_aicc;
    fd.max_abs_correlation = win.fit.max_corr_ext_base;
    fd.most_correlated_with = win.fit.corr_with;
    fd.cv_after = ColumnErrors(x.d, x.used, win.cv);
    fd.step_scores = scores;
    cur.model = win.model;
    cur.model.values = win.fit.values;
    // Extensions added are fitted from now on (the knee stays profiled).
    cur.fit = win.fit;
    cur.cv = std::move(win.cv);
    res->findings.push_back(fd);
    remaining.erase(std::find(remaining.begin(), remaining.end(), bs.cause));
    ResolveRivals(x, cur, base_at_bound, scored, best, &remaining, res);
  }
  return cur;
}

// Stage 9c: without AC columns C1, C0 are seen only through the tied KT (section 5). Where the
// extended model leaves them on a bound of model.md section 10 (the data alone ask for an ESC
// that creates energy), the slot on the bound is held at the ESC prior (--esc, else ideal) and
// the extended model refitted; if the other ESC slot is then on a bound or undetermined
// (relative standard error above 50 %), it is held too. c0 = 0 on its bound thus leaves a c1 the
// log does determine free (held both, xNova-SR-steps-up predicted its held-out rows at 9.6 %
// instead of 3.3 %). The findings keep their scores; the written model and its status are the
// held one.
bool EscSlotWeak(const Model& m, const FitOut& f, int s) {
  if (!m.free[s]) return false;
  if (SlotAtBound(m, f.values, s)) return true;
  const double se = f.stderr_[s];
  return !std::isfinite(se) ||
         std::fabs(se) > 0.01 * identification::kMaxRelStdErrorPercent * std::fabs(f.values[s]);
}

Step HoldEscOnBound(const SearchContext& x, bool ac, Step cur, DiagnoseResult* res) {
  if (ac) return cur;
  std::vector<int> held_slots;
  for (int s : {kC1, kC0}) {
    if (cur.model.free[s] && SlotAtBound(cur.model, cur.fit.values, s)) held_slots.push_back(s);
  }
  if (held_slots.empty()) return cur;
  const EscParams e0 = x.o.esc ? *x.o.esc : EscParams{};
  // The extended model refitted from its own values with the held slots at the prior.
  const auto refit = [&](const std::vector<int>& slots, Step* out) {
    *out = cur;
    for (int s : slots) {
      out->model.free[s] = false;
      out->model.values[s] = s == kC0 ? e0.c0 : e0.c1;  // values hold c1 itself (ToCoordinate)
    }
    if (!out->model.free[kC1] && out->model.free[kC0]) {
      // c1 held, c0 free: c1 + c0 >= K*kp (model.md section 10) becomes a floor on c0 when the
      // prior's c1 is below the ideal ratio.
      const double floor = IdealIdcPerIrmsPerThrottle(x.d.motor_type) - out->model.values[kC1];
      out->model.lower[kC0] = std::max(out->model.lower[kC0], floor);
      out->model.values[kC0] = std::max(out->model.values[kC0], out->model.lower[kC0]);
    }
    out->fit = FitProfiled(x.d, x.used, out->model, x.knees, LossType::kTrivial, 1.0);
    out->model.values = out->fit.values;
    return out->fit.ok;
  };
  Step held;
  if (!refit(held_slots, &held)) return cur;
  const int other = held_slots.size() == 1 ? (held_slots[0] == kC0 ? kC1 : kC0) : -1;
  if (other >= 0 && EscSlotWeak(held.model, held.fit, other)) {
    held_slots.push_back(other);
    if (!refit(held_slots, &held)) return cur;
  }
  held.cv = CrossValidate(x.d, x.used, x.folds.fold_of, x.folds.count, held.model, held.fit, x.knees);
  const std::string names = held_slots.size() == 2 ? "c1, c0" : (held_slots[0] == kC0 ? "c0" : "c1");
  res->warnings.push_back(names + " held at the " + (x.o.esc ? "ESC entry's" : "ideal ESC's") +
                          " value in the extended model: fitted freely the ESC sits on a bound of model.md "
                          "section 10 (log torque and the AC columns to identify it)");
  return held;
}

// Stage 10: the extended model into res: parameters, ratings from the catalog entries, its
// cross-validation, warnings and the status contract.
void AssembleResult(const SteadyTable& t, const DiagnoseOptions& o, const Data& d,
                    const std::vector<std::size_t>& used, const Folds& folds, const Step& cur,
                    DiagnoseResult* res) {
  ToParams(d, cur.fit.values, &res->extended_motor, &res->extended_esc);
  if (!res->findings.empty() && BaseAtBound(cur.model, cur.fit.values)) {
    res->warnings.push_back("the extended model still has a base parameter on a physical bound: its "
                            "values describe this log, they are not physical motor constants");
  }
  // Ratings and held values from the catalog entries.
  if (o.motor) {
    res->extended_motor.max_current_a = o.motor->max_current_a;
    res->extended_motor.max_power_w = o.motor->max_power_w;
  }
  if (o.esc) {
    res->extended_esc.max_current_a = o.esc->max_current_a;
    res->extended_esc.vdc_max_v = o.esc->vdc_max_v;
  }
  res->extended_cv = ColumnErrors(d, used, cur.cv);
  res->extended_cv_rms_percent = cur.cv.rms_percent;
  CvTable(d, t.rows(), used, cur.cv, &res->extended_cv_prediction);
  if (cur.cv.failed_folds > 0) {
    res->warnings.push_back(std::to_string(cur.cv.failed_folds) + " of " + std::to_string(folds.count) +
                            " cross-validation fold(s) could not be fitted (too few points to cross-validate): "
                            "their rows count as a 100 % miss");
  }
  res->extended_cv_failed_folds = cur.cv.failed_folds;
  res->verdict = JudgeExtended(d, t, cur.model, cur.fit, used, cur.cv, *res, o);
}

// Stage 11 (DiagnoseOptions::calibration_entry): where calibrate's model holds every finding - no
// finding, or only a throttle offset / saturation knee that calibrate's own F tests also keep -
// the entry and its status are calibrate's, so that a log has one status. Diagnose weighs its residuals for its tests (errors in variables, diagnose.h) and
// calibrate for its entry (percent of the column median, Huber): on a log the first-order model
// cannot follow at low command (tytodb AG5008) the two weightings put Rm in different places.
void UseCalibrationEntry(const SteadyTable& t, const DiagnoseOptions& o, DiagnoseResult* res) {
  if (!o.calibration_entry || o.motor) return;
  bool deadband = false, knee = false;
  for (const auto& f : res->findings) {
    if (f.cause == Cause::kThrottleDeadband) deadband = true;
    else if (f.cause == Cause::kEscSaturation) knee = true;
    else return;  // an extension calibrate does not fit: diagnose's own entry
  }
  calibration::CalibrationOptions co;
  calibration::CalibrationResult r;
  if (!CalibrateWithDiagnoseOptions(t, o, /*fit_throttle_offset=*/true, &co, &r)) return;
  const bool cal_deadband = r.param(calibration::Param::kDeadband).fitted;
  const bool cal_knee = r.param(calibration::Param::kTrSat).fitted;
  // Calibrate's model must hold every finding; an offset or knee it keeps beyond them is its own F
  // test's call on its own weighting (diagnose.h: the two weigh residuals differently).
  if ((deadband && !cal_deadband) || (knee && !cal_knee)) {
    res->warnings.push_back(std::string("calibrate's fit of this log keeps ") +
                            (cal_deadband ? "a throttle offset" : "no throttle offset") + " and " +
                            (cal_knee ? "a saturation knee" : "no knee") +
                            ": it does not hold these findings, so the entry and status are diagnose's own");
    return;
  }
  const calibration::CrossValidation cv = calibration::CrossValidateForVerdict(t, co);
  res->verdict = calibration::JudgeCalibration(r, t, co, &cv);
  res->extended_motor = r.motor;
  res->extended_esc = r.esc;
  res->entry_from_calibration = true;
  // Diagnose's own fit's complaint about its base parameters is not about this entry.
  const std::string own = "the extended model still has a base parameter on a physical bound";
  res->warnings.erase(std::remove_if(res->warnings.begin(), res->warnings.end(),
                                     [&](const std::string& w) { return w.rfind(own, 0) == 0; }),
                      res->warnings.end());
  res->warnings.push_back("entry and status: calibrate's fit, which holds these findings (first order" +
                          std::string(cal_deadband ? " + throttle offset" : "") + (cal_knee ? " + saturation knee" : "") +
                          "), so both commands give this log one status");
}

}  // namespace

DiagnoseResult Diagnose(const SteadyTable& t, const DiagnoseOptions& o) {
  std::string why;
  if (!o.IsValid(&why)) throw UsageError("diagnose options: " + why);
  DiagnoseResult res;
  res.file = t.file.empty() ? "log" : t.file;
  Prepared p = PrepareDiagnosisData(t, o, &res);
  const Model base = BuildBaseModel(t, o, p, &res);
  const std::vector<double> knees = KneeGrid(p.levels);
  const std::vector<Cause> candidates = TestableCandidates(o, p, knees, &res);
  const std::size_t n = p.d.rows();
  const Folds folds = AssignFolds(n, o);
  std::vector<std::size_t> all(n);
  std::iota(all.begin(), all.end(), 0);
  ApplyEffectiveVarianceWeights(all, base, &p);
  const Data& d = p.d;
  const std::vector<std::size_t> used = ScreenWithUnionModel(t, o, d, base, candidates, knees, all, &res);
  Step cur = FitBaseline(t, d, used, folds, base, knees, &res);
  res.worst_points = WorstPoints(t, d, used, cur.cv);
  res.residual_trends = ResidualTrends(t, p, used, cur.cv, o.alpha);
  const SearchContext x{d, used, folds, knees, base.values, o};
  cur = SearchCandidates(x, p.has_tr, candidates, std::move(cur), &res);
  cur = HoldEscOnBound(x, p.ac, std::move(cur), &res);
  AssembleResult(t, o, d, used, folds, cur, &res);
  UseCalibrationEntry(t, o, &res);
  return res;
}

std::string DiagnoseResult::FullReport() const {
  std::ostringstream s;
  s << std::setprecision(4);
  s << "diagnose " << file << " (" << mode << "): " << points_used << " points";
  if (!outlier_rows.empty()) s << ", " << outlier_rows.size() << " outlier(s) left out";
  s << "\nbase model fitted on the log, free: ";
  for (std::size_t j = 0; j < base_free_parameters.size(); ++j) s << (j ? ", " : "") << base_free_parameters[j];
  s << "\n\nWhat the first-order model gets wrong (cross-validated, held-out rows):\n";
  for (const auto& c : baseline_cv) {
    s << "  " << std::left << std::setw(12) << logs::ColumnName(c.column) << std::right << " rmse "
      << c.rmse << " (" << c.rmse_percent << " %), " << c.points << " points\n";
  }
  s << "  all columns: " << baseline_cv_rms_percent << " % rms (percent of each measured value)\n";
  if (!worst_points.empty()) {
    s << "  worst points:\n";
    for (const auto& w : worst_points) {
      s << "    line " << w.source_line << " " << logs::ColumnName(w.column) << ": measured "
        << w.measured << ", predicted " << w.predicted << " (" << std::showpos << w.error_percent
        << std::noshowpos << " %)\n";
    }
  }
  bool any_trend = false;
  for (const auto& tr : residual_trends) {
    if (!tr.structured) continue;
    if (!any_trend) s << "  residual structure (quadratic trend of the error, R^2, p):\n";
    any_trend = true;
    s << "    " << logs::ColumnName(tr.column) << " error vs " << tr.variable << ": R^2 " << tr.r2
      << ", p " << tr.p_value << ", linear change " << std::showpos << tr.slope_percent_per_range
      << std::noshowpos << " % over the range\n";
  }
  if (!any_trend) s << "  no residual structure against the logged variables\n";
  s << "\nFindings:\n";
  if (findings.empty()) {
    if (any_trend) {
      s << "  none: the residuals have structure (above) that no candidate explains";
      std::string closest;
      for (const auto& c : last_step_scores) {
        if (c.p_value < 1e-3 && !c.note.empty()) closest += std::string(closest.empty() ? "" : "; ") + CauseId(c.cause) + " (" + c.note + ")";
      }
      if (!closest.empty()) s << "; rejected: " << closest;
      s << "\n";
    } else if (baseline_cv_rms_percent <= kNoiseLevelPercent && baseline_cv_failed_folds == 0) {
      s << "  none: nothing significant beyond noise\n";
    } else {
      s << "  none found, but the first-order model misses held-out rows by " << baseline_cv_rms_percent
        << " % rms" << (baseline_cv_failed_folds > 0 ? " (" + std::to_string(baseline_cv_failed_folds) +
                                                          " fold(s) could not be fitted)" : std::string())
        << ": this is not noise; the model does not follow this log\n";
    }
  }
  int k = 0;
  for (const auto& f : findings) {
    s << "  " << ++k << ". " << CauseId(f.cause) << ": " << f.description << "\n     ";
    for (const auto& [name, val] : f.parameters) {
      s << name << " = " << val;
      const auto e = f.stderrs.find(name);
      if (e != f.stderrs.end() && std::isfinite(e->second)) s << " +- " << e->second;
      s << "  ";
    }
    s << "\n     gain " << f.gain_percent << " % (CV rms), F " << f.f_statistic << ", p "
      << f.p_value << ", dAICc " << f.delta_aicc;
    if (f.max_abs_correlation > 0.0) {
      s << ", max |corr| " << f.max_abs_correlation << " with " << f.most_correlated_with;
    }
    s << "\n     after:";
    for (const auto& c : f.cv_after) s << " " << logs::ColumnName(c.column) << " " << c.rmse_percent << " %";
    s << "\n";
  }
  for (const auto& a : ambiguous) {
    s << "  ambiguous: " << a.reason << "\n    to separate them: " << a.measurement << "\n";
  }
  for (const auto& nt : not_testable) {
    s << "  not testable: " << CauseId(nt.cause) << " (" << nt.not_testable_reason << ")\n";
  }
  s << "\nExtended model (cross-validated):";
  for (const auto& c : extended_cv) s << " " << logs::ColumnName(c.column) << " " << c.rmse_percent << " %";
  s << "; all columns " << extended_cv_rms_percent << " % (baseline " << baseline_cv_rms_percent << " %)\n";
  for (const auto& r : outlier_reasons) s << "dropped " << r << "\n";
  for (const auto& w : warnings) s << "warning: " << w << "\n";
  s << verdict.summary << "\n";
  if (!verdict.advice.empty()) s << "next: " << verdict.advice << "\n";
  return s.str();
}

}  // namespace dynosize::diagnosis
