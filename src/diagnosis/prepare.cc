#include "diagnosis/prepare.h"

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <random>
#include <sstream>

#include "common/error.h"
#include "common/units.h"
#include "diagnosis/candidates.h"
#include "fit/statistics.h"

namespace dynosize::diagnosis::internal {

using logs::Column;
using logs::SteadyTable;
using fit::Median;

namespace {

// Starting values of the base parameters from calibrate's fit without the throttle offset
// (CalibrationFits::base; src/calibration: the same base model, its robust fit and its knee
// profile; the offset is a candidate here): the linear start alone can leave the first-order fit in a stalled local
// minimum on logs whose throttle is not the voltage fraction. Kept only when that fit converged
// and is physical; the linear start stays otherwise.
void BaseStartFromCalibration(const CalibrationFits& cal, Values* v) {
  if (!cal.ok) return;
  const calibration::CalibrationResult& r = cal.base;
  if (!r.converged || !std::isfinite(r.motor.ke_v_s_per_rad) || !std::isfinite(r.motor.rm_ohm)) return;
  for (int k = 0; k < calibration::kBaseParamCount; ++k) {
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
// max_outlier_fraction of the rows and never the last row of a throttle level; each
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

// Stage 2a: linear starts of the base parameters when no catalog entry is given:
// U = R*I + KE*omega (eq 48) by least squares, I from the AC current or IDC/(C1*TR + C0); then
// calibrate's fit where it is physical (BaseStartFromCalibration).
void LinearBaseStarts(const SteadyTable& t, const Prepared& p, const CalibrationFits& cal, Values* values) {
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
  BaseStartFromCalibration(cal, &v);
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
  // The scales that do not depend on the log (kParamTable: the KT ratio, the ESC excess, c0, the
  // knee, slope and dead band), then those that do.
  for (int k = 0; k < kSlotCount; ++k) sc[k] = id::kParamTable[k].scale;
  sc[kKe] = std::max(v[kKe], 1e-6);
  sc[kRm] = rm_s;
  sc[kIo] = std::max({v[kIo], 0.02 * imax, 1e-3});
  sc[kResc] = rm_s;
  sc[kIo1] = sc[kIo] / std::max(p.wmax, 1.0);
  sc[kRth] = 0.1 / (kAlphaCopperPerK * kPacPerVllIrms * rm_s * imax * imax);  // x=1: +10 % Rm
  sc[kDroop] = 0.1 / imax;                                                  // x=1: -10 % KT
  sc[kRsupply] = rm_s;
  const double min_level = p.levels.empty() ? 1.0 : p.levels.front();
  // Physical box of identification/parameters.h (kParamTable); the KT and c1 slots are bounded as
  // the ratio KT/(kp*KE) <= 1 and the excess c1 + c0 - 1.1095 >= 0 (docs/model.md section 10), c0 >= 0.
  Values lower{}, upper{};
  for (int k = 0; k < kSlotCount; ++k) {
    lower[k] = id::kParamTable[k].lower;
    upper[k] = id::kParamTable[k].upper;
  }
  upper[kDeadband] = std::min(upper[kDeadband], std::max(0.0, 0.9 * min_level));  // below the lowest level
  base->lower = lower;
  base->upper = upper;
}

}  // namespace

CalibrationFits CalibrateForDiagnosis(const SteadyTable& t, const DiagnoseOptions& o) {
  CalibrationFits cal;
  if (o.motor) return cal;
  calibration::CalibrationOptions& co = cal.entry_options;
  co.assumed_throttle = o.assumed_throttle;
  co.min_speed_fraction = o.min_speed_fraction;
  co.min_throttle = o.min_throttle;
  co.labels.kv_rpm_per_v = o.kv_label_rpm_per_v;
  if (o.esc) co.esc_prior = *o.esc;
  cal.has_entry = o.calibration_entry;
  co.fit_throttle_offset = cal.has_entry;  // without the entry, only the fit without the offset
  try {
    if (cal.has_entry) {
      cal.entry = calibration::Calibrate(t, co, &cal.base);
    } else {
      cal.base = calibration::Calibrate(t, co);
    }
  } catch (const Error&) {
    return cal;
  }
  cal.ok = true;
  return cal;
}

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
  d.tie_kt = id::TieKt({p.ac, p.has_q});
  return p;
}

// Stage 2: the base (first-order) model: what is free, held values, starts, scales and bounds.
Model BuildBaseModel(const SteadyTable& t, const DiagnoseOptions& o, const Prepared& p, const CalibrationFits& cal,
                     DiagnoseResult* res) {
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
  id::LogContent content;
  content.ac = p.ac;
  content.has_torque = p.has_q;
  content.has_throttle = p.has_tr;
  content.has_idc = d.measured[kMIdc];
  content.any_torque_known = p.any_tk;
  content.throttle_levels = p.levels.size();
  base.free = id::FreeBaseParams(content);
  if (!o.motor) LinearBaseStarts(t, p, cal, &v);
  ScalesAndBounds(p, &base);
  for (int s = 0; s < kSlotCount; ++s) {
    if (base.free[s]) res->base_free_parameters.push_back(SlotName(s));
  }
  return base;
}

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
// variables fitting): s = sqrt(y^2 + (dy/dVDC*VDC)^2 + (dy/dx*x)^2), x = omega or torque.
// Without this the F test sees heteroscedastic residuals and calls low-throttle noise an effect.
// The derivatives are those of the model being fitted, recomputed at every trial (model_fit.cc,
// Residuals): with the spreads of a preliminary fit held fixed the fit is ordinary weighted least
// squares with noisy inputs, which flattens KE and R (the noise of the speed input looks like a
// weaker back-EMF), and any extension that lets the noise-free throttle column carry the back-EMF
// instead - a throttle offset - recovers that bias and passes its F test on a clean log (clean
// campaigns without torque: 8 in 200 named a dead band). With the spreads following the
// parameters the sum of squares is the errors-in-variables likelihood, profiled over the true
// inputs (exact where the prediction is linear in them, as the first-order circuit is at a given
// throttle). term.inv_scale keeps the preliminary fit's scales: the cross-validation's yardstick,
// the same for every model compared, and the centre of the range the followed spreads may take.
void ApplyEffectiveVarianceWeights(const std::vector<std::size_t>& used, const Model& base, Prepared* p) {
  Data& d = p->d;
  const FitOut pre = FitModel(d, used, base, LossType::kHuber, 1.0);
  if (!pre.ok) return;
  MotorParams mp;
  EscParams ep;
  ToParams(d, pre.values, &mp, &ep);
  const Drive drive(mp, ep);
  for (int m = 0; m < kMeasCount; ++m) d.spread_floor[m] = 5.0 / p->inv_scale[m];
  double pred[kMeasCount], inv_scale[kMeasCount];
  for (std::size_t k = 0; k < d.rows(); ++k) {
    PredictRow(d, drive, k, pred);
    if (!EffectiveVarianceScales(d, drive, k, pred, inv_scale)) continue;
    for (int tt = d.term_begin[k]; tt < d.term_begin[k + 1]; ++tt) d.terms[tt].inv_scale = inv_scale[tt - d.term_begin[k]];
  }
  // Without a throttle column every row is taken at an assumed command, a model known to be
  // wrong wherever the rows are not at that command; there the spreads stay those of the
  // preliminary fit (following the model, the fit of such a log ran to KE on its bound).
  d.weights_follow_model = p->has_tr;
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

}  // namespace dynosize::diagnosis::internal
