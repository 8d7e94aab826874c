#include "calibration/calibrate.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

#include "common/dual.h"
#include "common/error.h"
#include "catalog/noload_prior.h"
#include "common/units.h"
#include "fit/linear_least_squares.h"
#include "fit/statistics.h"
#include "identification/dc_fit.h"
#include "identification/fit_rows.h"
#include "model/circuit.h"

namespace dynosize::calibration {

namespace {

using logs::Column;
using logs::SteadyTable;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxFree = kParamCount - 1;  // every parameter but tr_sat (profiled)
using D8 = Dual<kMaxFree>;
using identification::C1FromExcess;
using identification::KtFromRatio;
constexpr int kKeI = static_cast<int>(Param::kKe), kKtI = static_cast<int>(Param::kKt),
              kC1I = static_cast<int>(Param::kC1), kC0I = static_cast<int>(Param::kC0),
              kDbI = static_cast<int>(Param::kDeadband);

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

using fit::Median;

// The fit's parameter vector ("internal", identification/parameters.h): slot kKt holds the
// ratio f = KT/(kp*KE) (1 when KT is tied to KE), slot kC1 the ESC excess s = c1 + c0 - 1.1095.
// Both keep the energy rules of model.md section 10 as box bounds.
std::array<double, kParamCount> ToInternal(const MotorParams& m, const EscParams& e) {
  std::array<double, kParamCount> p{};
  p[kKeI] = m.ke_v_s_per_rad;
  p[kKtI] = m.ke_v_s_per_rad > 0.0 ? m.kt_nm_per_a / (kPacPerVllIrms * m.ke_v_s_per_rad) : 1.0;
  p[2] = m.rm_ohm;
  p[3] = m.io_a;
  p[4] = e.resc_ohm;
  p[kC1I] = identification::EscExcess(e.c1, e.c0);
  p[kC0I] = e.c0;
  p[7] = e.tr_sat;
  p[8] = e.sat_slope;
  p[kDbI] = e.deadband;
  return p;
}

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

struct Layout {
  std::array<bool, kParamCount> free{};
  bool tie_kt = true;
  std::vector<int> free_index;  // parameter of each free slot
};

template <typename T>
bool Residuals(const FitData& d, const Layout& lay, const std::array<double, kParamCount>& fixed,
               const T* x, T* r) {
  T p[kParamCount];
  for (int k = 0; k < kParamCount; ++k) p[k] = T(fixed[k]);
  for (std::size_t s = 0; s < lay.free_index.size(); ++s) p[lay.free_index[s]] = x[s];
  const double tr_sat = fixed[static_cast<int>(Param::kTrSat)];
  T pred[kMeasCount];
  T qp;
  for (std::size_t k = 0; k < d.rows(); ++k) {
    if (!PredictGeneric(p, tr_sat, d.vdc[k], d.tr[k], d.omega[k], d.q[k],
                        d.torque_known[k] != 0, pred, &qp, d.idc_in[k])) {
      return false;
    }
    for (int t = d.term_begin[k]; t < d.term_begin[k + 1]; ++t) {
      const Term& term = d.terms[t];
      r[t] = TermResidual(term, pred);
    }
  }
  return true;
}

ResidualFunction MakeResidualFunction(const FitData& d, const Layout& lay,
                                      const std::array<double, kParamCount>& fixed) {
  return [&d, lay, fixed](const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* jac) {
    const int n = static_cast<int>(x.size());
    if (jac == nullptr) return Residuals<double>(d, lay, fixed, x.data(), r->data());
    D8 xd[kMaxFree];
    for (int j = 0; j < n; ++j) xd[j] = D8::Variable(x[j], j);
    std::vector<D8> rd(static_cast<std::size_t>(r->size()));
    if (!Residuals<D8>(d, lay, fixed, xd, rd.data())) return false;
    for (Eigen::Index i = 0; i < r->size(); ++i) {
      (*r)[i] = rd[i].value;
      for (int j = 0; j < n; ++j) (*jac)(i, j) = rd[i].derivative[j];
    }
    return true;
  };
}

// Bounds of each internal parameter: the physical box of identification/parameters.h, with the
// KT slot bounded as the ratio f and the C1 slot as the excess s (model.md section 10).
constexpr std::array<double, kParamCount> MakeLower() {
  std::array<double, kParamCount> b{};
  for (int k = 0; k < kParamCount; ++k) b[k] = identification::kBaseLower[k];
  b[kKtI] = identification::kKtRatioLower;
  b[kC1I] = identification::kEscExcessLower;
  return b;
}
constexpr std::array<double, kParamCount> MakeUpper() {
  std::array<double, kParamCount> b{};
  for (int k = 0; k < kParamCount; ++k) b[k] = identification::kBaseUpper[k];
  b[kKtI] = identification::kKtRatioUpper;
  b[kC1I] = identification::kEscExcessUpper;
  return b;
}
constexpr std::array<double, kParamCount> kLower = MakeLower();
constexpr std::array<double, kParamCount> kUpper = MakeUpper();

std::string FileTag(const SteadyTable& t) { return t.file.empty() ? std::string("log") : t.file; }

struct Prepared {
  FitData data;
  Layout layout;
  std::array<double, kParamCount> start{};
  std::array<std::string, kParamCount> notes;
  std::string mode;
  bool has_throttle = false;
  std::vector<double> levels;
  std::vector<logs::DropCount> dropped;
  std::vector<DroppedRow> dropped_rows;
  std::vector<std::string> warnings;
  double offset_upper = 0.5;  // upper bound of the dead band: below the lowest throttle level
};

void AddDropLocal(std::vector<logs::DropCount>* v, const std::string& reason) {
  for (auto& d : *v) {
    if (d.reason == reason) {
      ++d.count;
      return;
    }
  }
  v->push_back({reason, 1});
}

void DropRow(Prepared* pr, const SteadyTable& t, std::size_t i, const std::string& reason) {
  AddDropLocal(&pr->dropped, reason);
  pr->dropped_rows.push_back({i, i < t.source_line.size() ? t.source_line[i] : 0, reason});
}

// The speed readings of the rows a fit may use (not excluded, not no-load, passing RowRejection)
// that the circuit cannot produce (identification::FindSpuriousSpeeds).
std::vector<identification::SpuriousSpeed> SpuriousSpeedRows(const SteadyTable& t, const CalibrationOptions& o,
                                                             const std::vector<char>* excluded) {
  if (!t.Has(Column::kOmegaRadS) || !t.Has(Column::kVdcV)) return {};
  const bool thr = t.Has(Column::kThrottle);
  const bool has_nl = t.Has(Column::kNoLoad);
  const auto& w_all = t.Get(Column::kOmegaRadS);
  double wmax = 0.0;
  for (double w : w_all) wmax = std::max(wmax, w);
  std::vector<std::size_t> cand;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (excluded != nullptr && (*excluded)[i]) continue;
    if (has_nl && t.Get(Column::kNoLoad)[i] != 0.0) continue;
    const double tr = thr ? t.Get(Column::kThrottle)[i] : o.assumed_throttle;
    if (identification::RowRejection(w_all[i], wmax, o.min_speed_fraction, thr, tr, o.min_throttle,
                                     t.Get(Column::kVdcV)[i]) == nullptr) {
      cand.push_back(i);
    }
  }
  return identification::FindSpuriousSpeeds(t, cand, o.assumed_throttle);
}

// Which columns the log has, beyond those Prepared records (the stages of Prepare share it).
struct LogColumns {
  bool has_q = false;   // torque
  bool has_nl = false;  // no-load flag
  bool ac = false;      // vll_rms_v and irms_a
};

// Prepare, stage 1: the required columns, then the rows used (the others are dropped with the
// reason) and their inputs. Fills pr->data's row vectors and pr->has_throttle.
LogColumns SelectFitRows(const SteadyTable& t, const CalibrationOptions& o, const std::vector<char>* excluded,
                      Prepared* pr) {
  const std::string file = FileTag(t);
  if (!t.Has(Column::kOmegaRadS)) {
    throw DataError(file + ": column omega_rad_s (shaft speed) is absent: calibration needs the speed "
                    "to find the back-EMF constant");
  }
  const bool has_v = t.Has(Column::kVdcV);
  LogColumns c;
  c.ac = t.Has(Column::kVllRmsV) && t.Has(Column::kIrmsA);
  if (!has_v) {
    throw DataError(file + ": column vdc_v (supply voltage) is absent: calibration needs the voltage "
                    "at the ESC (eq 48)");
  }
  pr->has_throttle = t.Has(Column::kThrottle);
  c.has_q = t.Has(Column::kTorqueNm);
  c.has_nl = t.Has(Column::kNoLoad);
  const auto& w_all = t.Get(Column::kOmegaRadS);
  const auto& idc_all = t.Get(Column::kIdcA);
  double wmax = 0.0;
  for (double w : w_all) wmax = std::max(wmax, w);
  bool any_idc = false;
  for (double v : idc_all) any_idc = any_idc || v != 0.0;
  if (!any_idc) throw DataError(file + ": column idc_a is zero in every row: nothing to fit");

  FitData& d = pr->data;
  for (int m = 0; m < kMeasCount; ++m) d.measured[m] = t.Has(kMeasColumn[m]);
  // Speed readings the circuit cannot produce (fit_rows.h) are left out, each with its value (on
  // the first pass; a refit with `excluded` keeps the first pass's rows and list).
  std::vector<char> spurious(t.rows(), 0);
  if (excluded == nullptr) {
    std::string listed;
    for (const auto& sp : SpuriousSpeedRows(t, o, excluded)) {
      spurious[sp.row] = 1;
      const std::string what = identification::SpuriousSpeedText(t, sp);
      AddDropLocal(&pr->dropped, "spurious speed reading (inconsistent with VDC, throttle and current)");
      pr->dropped_rows.push_back({sp.row, sp.row < t.source_line.size() ? t.source_line[sp.row] : 0,
                                  "spurious speed reading: " + what});
      listed += (listed.empty() ? "" : "; ") + what;
    }
    if (!listed.empty()) {
      pr->warnings.push_back("speed readings inconsistent with VDC, throttle and current left out (fit_rows.h "
                             "FindSpuriousSpeeds): " + listed);
    }
  }
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (excluded != nullptr && (*excluded)[i]) continue;
    if (spurious[i]) continue;
    const double w = w_all[i];
    const double tr = pr->has_throttle ? t.Get(Column::kThrottle)[i] : o.assumed_throttle;
    const bool nl = c.has_nl && t.Get(Column::kNoLoad)[i] != 0.0;
    // A no-load row without a speed reading (DriveCalc n = 0) still measures Io: at Q = 0 the
    // model's current I = Io does not depend on the speed (eq 42). Only its current is compared.
    const bool speed_unknown = nl && w == 0.0;
    if (const char* why = identification::RowRejection(w, wmax, o.min_speed_fraction, pr->has_throttle, tr,
                                                       o.min_throttle, t.Get(Column::kVdcV)[i], speed_unknown)) {
      DropRow(pr, t, i, why);
      continue;
    }
    d.table_row.push_back(i);
    d.vdc.push_back(t.Get(Column::kVdcV)[i]);
    d.tr.push_back(tr);
    d.omega.push_back(w);
    d.q.push_back(c.has_q ? t.Get(Column::kTorqueNm)[i] : 0.0);
    d.torque_known.push_back(c.has_q || nl ? 1 : 0);
    d.speed_known.push_back(speed_unknown ? 0 : 1);
    const bool current_input = pr->has_throttle && !c.has_q && !c.ac && !nl && !speed_unknown && idc_all[i] > 0.0;
    d.idc_in.push_back(current_input ? idc_all[i] : kNaN);
  }
  std::size_t with_speed = 0;
  for (char k : d.speed_known) with_speed += k != 0 ? 1 : 0;
  if (with_speed < 2) {
    throw DataError(file + ": only " + std::to_string(with_speed) +
                    " row(s) with the motor turning: calibration needs at least 2");
  }
  return c;
}

// Prepare, stage 2: the residual terms of every row, in percent of the column's median magnitude
// over the rows used; the row's inputs (speed or current) are not terms.
void BuildTerms(const SteadyTable& t, FitData* fd) {
  FitData& d = *fd;
  const std::array<double, kMeasCount> inv_scale = identification::MedianPercentScales(t, d.table_row, &d.measured);
  d.term_begin.push_back(0);
  for (std::size_t k = 0; k < d.rows(); ++k) {
    for (int m = 0; m < kMeasCount; ++m) {
      if (!d.measured[m]) continue;
      const bool current_input = d.idc_in[k] == d.idc_in[k];
      if (m == kMOmega && !d.torque_known[k] && !current_input) continue;  // speed is the input
      if (m == kMOmega && !d.speed_known[k]) continue;   // speed not measured on this row
      if (m == kMIdc && current_input) continue;         // the current is the input
      d.terms.push_back({m, t.Get(kMeasColumn[m])[d.table_row[k]], inv_scale[m]});
    }
    d.term_begin.push_back(static_cast<int>(d.terms.size()));
  }
}

// Prepare, stage 3: which parameters are free, with a note for each one the log cannot identify.
void ChooseFree(const CalibrationOptions& o, const LogColumns& c, Prepared* pr) {
  const FitData& d = pr->data;
  Layout& lay = pr->layout;
  auto& fr = lay.free;
  auto idx = [](Param p) { return static_cast<int>(p); };
  pr->levels = identification::ThrottleLevels(d.tr);
  if (!pr->levels.empty()) pr->offset_upper = std::min(0.5, 0.9 * pr->levels.front());
  const bool multi_level = pr->has_throttle && pr->levels.size() >= 2;
  bool any_torque_known = false;
  for (char k : d.torque_known) any_torque_known = any_torque_known || k;
  pr->mode = c.ac ? "ac" : (pr->has_throttle ? "dc" : "dc_no_throttle");
  fr[idx(Param::kKe)] = true;
  fr[idx(Param::kRm)] = true;
  lay.tie_kt = !(c.has_q && c.ac);
  fr[idx(Param::kKt)] = !lay.tie_kt;
  fr[idx(Param::kIo)] = any_torque_known;
  fr[idx(Param::kResc)] = c.ac && pr->has_throttle;
  const bool esc_ratio = d.measured[kMIdc] && pr->has_throttle && (c.ac || c.has_q) && multi_level;
  fr[idx(Param::kC1)] = esc_ratio;
  fr[idx(Param::kC0)] = esc_ratio;
  fr[idx(Param::kTrSat)] = false;  // profiled
  fr[idx(Param::kSatSlope)] = false;  // freed per knee candidate
  fr[kDbI] = false;                   // freed when the offset is tested (FitWithOffset)
  auto& nt = pr->notes;
  nt[kDbI] = !pr->has_throttle ? "no throttle column: held at prior"
             : pr->levels.size() < 3 ? "fewer than 3 throttle levels: held at prior"
                                     : "";
  if (lay.tie_kt) {
    nt[idx(Param::kKt)] = c.has_q ? "tied: KT = sqrt(27/10)*KE (no AC columns to separate KT from the ESC ratio)"
                                  : "tied: KT = sqrt(27/10)*KE (no torque column)";
  }
  if (!fr[idx(Param::kIo)]) nt[idx(Param::kIo)] = "no torque column and no no-load rows: Io does not enter the predictions";
  if (!fr[idx(Param::kResc)]) {
    nt[idx(Param::kResc)] = "held at prior: without vll_rms_v/irms_a only Rm + RESC is determined (eq 48)";
    nt[idx(Param::kRm)] = "Rm + RESC determined, the split is not (held RESC at its prior)";
  }
  if (!esc_ratio) {
    nt[idx(Param::kC1)] = nt[idx(Param::kC0)] =
        !pr->has_throttle ? "no throttle column: held at prior (rows taken as full throttle)"
        : !d.measured[kMIdc] ? "no idc_a: held at prior"
        : !(c.ac || c.has_q) ? "no torque and no AC columns: only C1/R, C0/R are determined; held at prior"
                             : "one throttle level: C1*TR + C0 not separable; held at prior";
  }
  if (!pr->has_throttle) {
    pr->warnings.push_back("no throttle column: every row taken as throttle " +
                           std::to_string(o.assumed_throttle) +
                           "; KE and R are conditional on that and on the assumed ESC (ideal unless --esc prior)");
  }
}

// The rows of the linear starts: those unlikely to be saturated (all rows if fewer than 3
// qualify); rows without a speed reading cannot enter U = R*I + KE*omega.
std::vector<std::size_t> LinearStartRows(const FitData& d, bool has_throttle) {
  const std::size_t n = d.rows();
  std::vector<std::size_t> lin;
  for (std::size_t k = 0; k < n; ++k) {
    if (d.speed_known[k] && (d.tr[k] <= 0.85 || !has_throttle)) lin.push_back(k);
  }
  if (lin.size() < 3) {
    lin.clear();
    for (std::size_t k = 0; k < n; ++k) {
      if (d.speed_known[k]) lin.push_back(k);
    }
  }
  return lin;
}

// Prepare, stage 4a: KE and R (and RESC with the AC columns) from U = R*I + KE*omega (eq 48), or
// eq 42 with the AC columns, by linear least squares on the rows lin; irms: phase current per row.
void StartKeAndR(const SteadyTable& t, const CalibrationOptions& o, const LogColumns& c, const Prepared& pr,
                 const std::vector<double>& irms, const std::vector<std::size_t>& lin,
                 std::array<double, kParamCount>* start) {
  const FitData& d = pr.data;
  auto& p = *start;
  auto idx = [](Param q) { return static_cast<int>(q); };
  std::vector<double> cur(lin.size()), omega(lin.size()), u(lin.size());
  for (std::size_t j = 0; j < lin.size(); ++j) {
    const std::size_t k = lin[j];
    cur[j] = irms[k];
    omega[j] = d.omega[k];
    u[j] = c.ac ? t.Get(Column::kVllRmsV)[d.table_row[k]] : kVllRmsPerVdc * d.vdc[k] * d.tr[k];
  }
  const identification::CircuitStart lin_start = identification::LinearCircuitStart(cur, omega, u);
  double r0 = lin_start.r_total_ohm, ke0 = lin_start.ke_v_s_per_rad;
  if (o.labels.kv_rpm_per_v) {
    // A label is a better start than the linear fit, which a throttle offset or a nonlinear
    // throttle curve biases: KE from the label, R by least squares with KE held there.
    ke0 = identification::KeFromLabelKv(*o.labels.kv_rpm_per_v);
    const double r_label = identification::ResistanceWithKeHeld(cur, omega, u, ke0);
    if (r_label > 0.0) r0 = r_label;
  }
  p[idx(Param::kKe)] = ke0;
  if (c.ac) {
    p[idx(Param::kRm)] = r0;
    if (pr.layout.free[idx(Param::kResc)]) {
      Eigen::MatrixXd a2(lin.size(), 1);
      Eigen::VectorXd b2(lin.size());
      for (std::size_t j = 0; j < lin.size(); ++j) {
        const std::size_t k = lin[j];
        a2(j, 0) = irms[k];
        b2[j] = kVllRmsPerVdc * d.vdc[k] * d.tr[k] - t.Get(Column::kVllRmsV)[d.table_row[k]];
      }
      p[idx(Param::kResc)] = SolveLinearLeastSquares(a2, b2).coefficients[0];
    }
  } else {
    p[idx(Param::kRm)] = r0 - p[idx(Param::kResc)];
  }
}

// Prepare, stage 4b: KT and Io from Q = KT*Irms - KT*Io with a torque column; otherwise KT tied
// to KE and Io the mean current of the no-load rows (if any).
void StartKtAndIo(const LogColumns& c, const Prepared& pr, const std::vector<double>& irms,
                  std::array<double, kParamCount>* start) {
  const FitData& d = pr.data;
  const std::size_t n = d.rows();
  auto& p = *start;
  auto idx = [](Param q) { return static_cast<int>(q); };
  if (c.has_q) {
    Eigen::MatrixXd a(n, 2);
    Eigen::VectorXd b(n);
    for (std::size_t k = 0; k < n; ++k) {
      a(k, 0) = irms[k];
      a(k, 1) = 1.0;
      b[k] = d.q[k];
    }
    const auto sol = SolveLinearLeastSquares(a, b);
    const double kt = pr.layout.tie_kt ? kPacPerVllIrms * p[idx(Param::kKe)] : sol.coefficients[0];
    p[idx(Param::kKt)] = kt > 0.0 ? kt : kPacPerVllIrms * p[idx(Param::kKe)];
    double io = 0.0;
    for (std::size_t k = 0; k < n; ++k) io += irms[k] - d.q[k] / p[idx(Param::kKt)];
    p[idx(Param::kIo)] = io / static_cast<double>(n);
  } else {
    p[idx(Param::kKt)] = kPacPerVllIrms * p[idx(Param::kKe)];
    bool any_torque_known = false;
    for (char k : d.torque_known) any_torque_known = any_torque_known || k;
    if (any_torque_known) {  // no-load rows: Io is the current there
      double s = 0.0;
      int cnt = 0;
      for (std::size_t k = 0; k < n; ++k) {
        if (d.torque_known[k]) {
          s += irms[k];
          ++cnt;
        }
      }
      p[idx(Param::kIo)] = s / cnt;
    }
  }
}

// Prepare, stage 4: starting values (linear sub-problems) and held values (priors), returned in
// the internal form (KT as the ratio f, C1 as the excess s) inside the box.
void StartingValues(const SteadyTable& t, const CalibrationOptions& o, const LogColumns& c, Prepared* pr) {
  const FitData& d = pr->data;
  const std::size_t n = d.rows();
  const auto& fr = pr->layout.free;
  auto idx = [](Param q) { return static_cast<int>(q); };
  std::array<double, kParamCount>& p = pr->start;
  const EscParams esc0 = o.esc_prior ? *o.esc_prior : EscParams{};
  p[idx(Param::kResc)] = esc0.resc_ohm;
  p[idx(Param::kC1)] = esc0.c1;
  p[idx(Param::kC0)] = esc0.c0;
  p[idx(Param::kTrSat)] = 1.0;
  p[idx(Param::kSatSlope)] = 1.0;
  p[kDbI] = esc0.deadband;
  if (o.motor_prior) {
    p[idx(Param::kIo)] = o.motor_prior->io_a;
  }
  // Phase current estimate per row.
  std::vector<double> irms(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (d.measured[kMIrms]) {
      irms[k] = t.Get(Column::kIrmsA)[d.table_row[k]];
    } else {
      const double g = esc0.c1 * d.tr[k] + esc0.c0;
      irms[k] = t.Get(Column::kIdcA)[d.table_row[k]] / std::max(g, 1e-3);
    }
  }
  const std::vector<std::size_t> lin = LinearStartRows(d, pr->has_throttle);
  StartKeAndR(t, o, c, *pr, irms, lin, &p);
  StartKtAndIo(c, *pr, irms, &p);
  // C1, C0 from IDC = C1*TR*Irms + C0*Irms (eq 57).
  if (fr[idx(Param::kC1)] && d.measured[kMIrms]) {
    Eigen::MatrixXd a(lin.size(), 2);
    Eigen::VectorXd b(lin.size());
    for (std::size_t j = 0; j < lin.size(); ++j) {
      const std::size_t k = lin[j];
      a(j, 0) = d.tr[k] * irms[k];
      a(j, 1) = irms[k];
      b[j] = t.Get(Column::kIdcA)[d.table_row[k]];
    }
    const auto sol = SolveLinearLeastSquares(a, b);
    p[idx(Param::kC1)] = sol.coefficients[0];
    p[idx(Param::kC0)] = sol.coefficients[1];
  }
  if (o.motor_prior) {
    // Values the data cannot identify come from the prior.
    if (!fr[idx(Param::kIo)]) p[idx(Param::kIo)] = o.motor_prior->io_a;
  }
  // Into the internal form (KT as the ratio f, C1 as the excess s; the starts of the linear
  // sub-problems may break the energy rules and are moved onto them), into the box, away from
  // the singular R = 0.
  p[kKeI] = std::clamp(p[kKeI], kLower[kKeI], kUpper[kKeI]);
  p[kKtI] = pr->layout.tie_kt ? 1.0 : p[kKtI] / (kPacPerVllIrms * p[kKeI]);
  p[kC0I] = std::clamp(p[kC0I], kLower[kC0I], kUpper[kC0I]);
  p[kC1I] = identification::EscExcess(p[kC1I], p[kC0I]);
  for (int k = 0; k < kParamCount; ++k) p[k] = std::clamp(p[k], kLower[k], kUpper[k]);
  if (p[idx(Param::kRm)] + p[idx(Param::kResc)] < 1e-4) p[idx(Param::kRm)] = 1e-4 + 0.01 * p[idx(Param::kRm)];
}

// Selects the rows, decides what is free, and finds starting values by linear least squares.
Prepared Prepare(const SteadyTable& t, const CalibrationOptions& o, const std::vector<char>* excluded) {
  Prepared pr;
  const LogColumns c = SelectFitRows(t, o, excluded, &pr);
  BuildTerms(t, &pr.data);
  ChooseFree(o, c, &pr);
  StartingValues(t, o, c, &pr);
  return pr;
}

struct SolveOutcome {
  std::array<double, kParamCount> params{};
  LevenbergMarquardtSummary summary;
  double cost = std::numeric_limits<double>::infinity();
  int free_count = 0;
};

// Gaussian priors on the free slot s holding parameter k: the label (--kv-label, --rm-label,
// --io-label) where given, else the motor prior, with the widths of identification/parameters.h
// and CalibrationOptions.
void AddPriors(const CalibrationOptions& o, int k, int s, std::vector<GaussianPrior>* priors) {
  auto add = [&](double mean, double rel) {
    if (mean > 0.0 && rel > 0.0) priors->push_back({s, mean, rel * mean});
  };
  const auto& lb = o.labels;
  const MotorParams* mp = o.motor_prior ? &*o.motor_prior : nullptr;
  if (k == kKeI) {
    if (lb.kv_rpm_per_v) add(identification::KeFromLabelKv(*lb.kv_rpm_per_v), identification::kKvLabelRelSigma);
    else if (mp) add(mp->ke_v_s_per_rad, o.prior_ke_rel_sigma);
  }
  if (k == static_cast<int>(Param::kRm)) {
    if (lb.rm_ohm) add(*lb.rm_ohm, identification::kRmLabelRelSigma);
    else if (mp) add(mp->rm_ohm, o.prior_rm_rel_sigma);
  }
  if (k == static_cast<int>(Param::kIo)) {
    if (lb.io_a) add(identification::IoFromLabel(*lb.io_a), identification::kIoLabelRelSigma);
    else if (mp) add(mp->io_a, o.prior_io_rel_sigma);
  }
}

SolveOutcome SolveOnce(const Prepared& pr, const CalibrationOptions& o, double tr_sat, bool free_slope,
                       bool free_offset, const std::array<double, kParamCount>& start) {
  Layout lay = pr.layout;
  lay.free[static_cast<int>(Param::kSatSlope)] = free_slope;
  lay.free[kDbI] = free_offset;
  lay.free_index.clear();
  for (int k = 0; k < kParamCount; ++k) {
    if (lay.free[k]) lay.free_index.push_back(k);
  }
  std::array<double, kParamCount> fixed = start;
  fixed[static_cast<int>(Param::kTrSat)] = tr_sat;
  if (!free_slope) fixed[static_cast<int>(Param::kSatSlope)] = 1.0;
  const int nf = static_cast<int>(lay.free_index.size());
  LeastSquaresProblem prob;
  prob.num_residuals = static_cast<int>(pr.data.terms.size());
  prob.num_parameters = nf;
  prob.residuals = MakeResidualFunction(pr.data, lay, fixed);
  prob.lower_bounds.resize(nf);
  prob.upper_bounds.resize(nf);
  Eigen::VectorXd x(nf);
  for (int s = 0; s < nf; ++s) {
    const int k = lay.free_index[s];
    prob.parameter_names.push_back(ParamName(static_cast<Param>(k)));
    prob.lower_bounds[s] = kLower[k];
    prob.upper_bounds[s] = kUpper[k];
    if (k == kDbI) prob.upper_bounds[s] = pr.offset_upper;
    x[s] = std::clamp(start[k], prob.lower_bounds[s], prob.upper_bounds[s]);
    AddPriors(o, k, s, &prob.priors);
  }
  LevenbergMarquardtOptions lo = o.solver;
  lo.loss = o.loss;
  lo.loss_scale = o.loss_scale_percent;
  SolveOutcome out;
  out.free_count = nf;
  out.summary = SolveLeastSquares(prob, lo, &x);
  out.params = fixed;
  for (int s = 0; s < nf; ++s) out.params[lay.free_index[s]] = x[s];
  out.cost = out.summary.IsSolutionUsable() ? out.summary.final_cost : std::numeric_limits<double>::infinity();
  return out;
}

// Physical parameters of the internal vector (KT = kp*KE*f, c1 = 1.1095 + s - c0).
MotorParams ToMotor(const std::array<double, kParamCount>& p) {
  MotorParams m;
  m.ke_v_s_per_rad = p[0];
  m.kt_nm_per_a = KtFromRatio(p[kKeI], p[kKtI]);
  m.rm_ohm = p[2];
  m.io_a = p[3];
  return m;
}

EscParams ToEsc(const std::array<double, kParamCount>& p, const std::optional<EscParams>& prior) {
  EscParams e = prior ? *prior : EscParams{};
  e.resc_ohm = p[4];
  e.c1 = C1FromExcess(p[kC1I], p[kC0I]);
  e.c0 = p[kC0I];
  e.tr_sat = p[7];
  e.sat_slope = p[8];
  e.deadband = p[kDbI];
  return e;
}

// Best fit over the knee candidates (and "no knee"); returns the chosen outcome.
SolveOutcome FitWithKnee(const Prepared& pr, const CalibrationOptions& o, bool free_offset, bool* knee_found,
                         std::string* knee_note) {
  SolveOutcome best = SolveOnce(pr, o, 1.0, false, free_offset, pr.start);
  *knee_found = false;
  if (!pr.has_throttle) {
    *knee_note = "no throttle column";
    return best;
  }
  const SolveOutcome none = best;
  SolveOutcome knee;
  int candidates = 0;
  for (double ts = o.knee_min; ts < 1.0 - 1e-9; ts += o.knee_step) {
    int above = 0, below = 0;
    for (double lv : pr.levels) (lv > ts + 1e-9 ? above : below)++;
    if (above < 2 || below < 2) continue;
    ++candidates;
    std::array<double, kParamCount> start = none.params;
    start[static_cast<int>(Param::kSatSlope)] = 0.8;
    SolveOutcome s = SolveOnce(pr, o, ts, true, free_offset, start);
    if (s.cost < knee.cost) knee = s;
  }
  if (candidates == 0) {
    *knee_note = "fewer than 2 throttle levels on either side of every knee candidate (" +
                 std::to_string(pr.levels.size()) + " levels)";
    return best;
  }
  const double m = static_cast<double>(pr.data.terms.size());
  const double dof = m - knee.free_count - 1.0;
  if (dof <= 0.0 || !std::isfinite(knee.cost)) {
    *knee_note = "no degrees of freedom for a knee";
    return best;
  }
  const double f = ((none.cost - knee.cost) / 2.0) / (std::max(knee.cost, 1e-300) / dof);
  if (f > o.knee_min_f && knee.params[static_cast<int>(Param::kSatSlope)] < 0.97) {
    *knee_found = true;
    std::ostringstream s;
    s << "profile over tr_sat (grid " << o.knee_step << "), F = " << std::setprecision(3) << f;
    *knee_note = s.str();
    return knee;
  }
  std::ostringstream s;
  s << "no knee found: best candidate tr_sat = " << knee.params[static_cast<int>(Param::kTrSat)]
    << " improves the fit by F = " << std::setprecision(3) << f << " <= " << o.knee_min_f;
  *knee_note = s.str();
  return best;
}

std::vector<double> RowResidualMax(const Prepared& pr, const std::array<double, kParamCount>& p) {
  const FitData& d = pr.data;
  std::vector<double> out(d.rows(), 0.0);
  double pred[kMeasCount];
  double qp;
  for (std::size_t k = 0; k < d.rows(); ++k) {
    if (!PredictGeneric(p.data(), p[7], d.vdc[k], d.tr[k], d.omega[k], d.q[k], d.torque_known[k] != 0,
                        pred, &qp, d.idc_in[k])) {
      continue;
    }
    for (int t = d.term_begin[k]; t < d.term_begin[k + 1]; ++t) {
      const Term& term = d.terms[t];
      out[k] = std::max(out[k], std::fabs(TermResidual(term, pred)));
    }
  }
  return out;
}

// "" when the free ESC slots (excess s, c0) of a solve are determined, else why not: a slot on
// its bound, or a standard error above half of c0 or of c1 = 1.1095 + s - c0.
std::string EscUndetermined(const LevenbergMarquardtSummary& s) {
  double ex = kNaN, c0 = kNaN, se_ex = kNaN, se_c0 = kNaN;
  for (std::size_t j = 0; j < s.parameter_names.size(); ++j) {
    const bool c1slot = s.parameter_names[j] == "c1", c0slot = s.parameter_names[j] == "c0";
    if (!c1slot && !c0slot) continue;
    if (j < s.at_bound.size() && s.at_bound[j]) return std::string(c1slot ? "c1 + c0" : "c0") + " on its bound";
    const double se = j < static_cast<std::size_t>(s.standard_errors.size()) ? s.standard_errors[j] : kNaN;
    (c1slot ? ex : c0) = s.parameters[j];
    (c1slot ? se_ex : se_c0) = se;
  }
  std::ostringstream w;
  w << std::setprecision(2);
  if (!(se_c0 <= 0.5 * std::fabs(c0))) {
    w << "c0 = " << c0 << " +- " << se_c0;
    return w.str();
  }
  const double c1 = C1FromExcess(ex, c0);
  if (!(se_ex <= 0.5 * std::fabs(c1))) {
    w << "c1 = " << c1 << " +- " << se_ex;
    return w.str();
  }
  return "";
}

// True when parameter k carries a Gaussian prior in the fit (AddPriors).
bool HasPrior(const CalibrationOptions& o, int k) {
  std::vector<GaussianPrior> pr;
  AddPriors(o, k, 0, &pr);
  return !pr.empty();
}

// The base fit (FitWithKnee), and with three or more throttle levels the same with the throttle
// offset / dead band free; the offset is kept when it lowers the cost by an F statistic above
// knee_min_f for its one extra parameter.
SolveOutcome FitWithOffset(const Prepared& pr, const CalibrationOptions& o, bool* knee_found, std::string* knee_note,
                           bool* offset_found, std::string* offset_note) {
  SolveOutcome none = FitWithKnee(pr, o, false, knee_found, knee_note);
  *offset_found = false;
  if (!o.fit_throttle_offset || !pr.has_throttle || pr.levels.size() < 3) {
    *offset_note = !o.fit_throttle_offset ? "not tested (fit_throttle_offset off)"
                                          : "not testable: fewer than 3 throttle levels";
    return none;
  }
  // The offset enters nonlinearly (a dead band clips at zero): a few starts, the best kept.
  bool kf = false;
  std::string kn;
  SolveOutcome with;
  for (double db0 : {pr.start[kDbI], -0.1, -0.3}) {
    Prepared p2 = pr;
    p2.start[kDbI] = std::clamp(db0, kLower[kDbI], pr.offset_upper);
    bool kf2 = false;
    std::string kn2;
    SolveOutcome w = FitWithKnee(p2, o, true, &kf2, &kn2);
    if (w.cost < with.cost) {
      with = std::move(w);
      kf = kf2;
      kn = kn2;
    }
  }
  const double dof = static_cast<double>(pr.data.terms.size()) - with.free_count;
  if (!std::isfinite(with.cost) || dof <= 0.0) {
    *offset_note = "offset fit failed or has no degrees of freedom";
    return none;
  }
  const double f = (none.cost - with.cost) / (std::max(with.cost, 1e-300) / dof);
  std::ostringstream s;
  s << std::setprecision(3);
  if (f > o.knee_min_f || !std::isfinite(none.cost)) {
    *offset_found = true;
    *knee_found = kf;
    *knee_note = kn;
    s << "throttle offset/dead band fitted: F = " << f << " > " << o.knee_min_f;
    *offset_note = s.str();
    return with;
  }
  s << "no throttle offset: F = " << f << " <= " << o.knee_min_f;
  *offset_note = s.str();
  return none;
}

// Rows whose largest residual exceeds outlier_sigmas robust standard deviations, worst first,
// at most max_outlier_fraction of the rows, never the last row of a throttle level, and only when
// (free + 2) rows stay.
std::vector<DroppedRow> SelectOutliers(const Prepared& pr, const std::array<double, kParamCount>& p,
                                       const SteadyTable& t, const CalibrationOptions& o, int nfree) {
  const std::vector<double> rmax = RowResidualMax(pr, p);
  const double sigma = std::max(1.4826 * Median(rmax), o.outlier_floor_percent);
  const identification::OutlierSelection sel =
      identification::SelectOutlierRows(rmax, pr.data.tr, pr.has_throttle, o.outlier_sigmas * sigma,
                                        o.max_outlier_fraction, static_cast<std::size_t>(nfree) + 3);
  std::vector<DroppedRow> out;
  out.reserve(sel.dropped.size());
  for (std::size_t k : sel.dropped) {
    const std::size_t row = pr.data.table_row[k];
    std::ostringstream why;
    why << std::setprecision(3) << "outlier: largest residual " << rmax[k] << " % > " << o.outlier_sigmas
        << " robust sd (" << sigma << " %)";
    out.push_back({row, row < t.source_line.size() ? t.source_line[row] : 0, why.str()});
  }
  return out;
}

// Standard errors and values of the physical KT and C1 from the internal ratio f and excess s
// (delta method on the covariance): KT = kp*KE*f, c1 = 1.1095 + s - c0.
void TransformStandardErrors(bool tie_kt, const std::vector<int>& slots, const LevenbergMarquardtSummary& s,
                             CalibrationResult* res) {
  auto slot_of = [&](int k) {
    for (std::size_t q = 0; q < slots.size(); ++q) {
      if (slots[q] == k) return static_cast<int>(q);
    }
    return -1;
  };
  const bool cov_ok = s.covariance.rows() == static_cast<Eigen::Index>(slots.size());
  auto cov = [&](int a, int b) { return (a < 0 || b < 0 || !cov_ok) ? 0.0 : s.covariance(a, b); };
  auto& kt = res->params[kKtI];
  const double ke = res->motor.ke_v_s_per_rad, f = kt.value;
  kt.value = res->motor.kt_nm_per_a;
  if (!tie_kt && kt.fitted) {
    const int a = slot_of(kKeI), b = slot_of(kKtI);
    const double var = kPacPerVllIrms * kPacPerVllIrms * (f * f * cov(a, a) + ke * ke * cov(b, b) + 2.0 * ke * f * cov(a, b));
    kt.standard_error = cov_ok && b >= 0 ? std::sqrt(std::max(var, 0.0)) : kNaN;
  }
  auto& c1 = res->params[kC1I];
  c1.value = res->esc.c1;
  if (c1.fitted) {
    const int a = slot_of(kC1I), b = slot_of(kC0I);
    const double var = cov(a, a) + cov(b, b) - 2.0 * cov(a, b);
    c1.standard_error = cov_ok && a >= 0 ? std::sqrt(std::max(var, 0.0)) : kNaN;
  }
}

// Warnings for parameters on a bound (the energy rules named) and for a single throttle level.
void AddBoundWarnings(const Prepared& pr, CalibrationResult* out) {
  CalibrationResult& res = *out;
  for (int k = 0; k < kParamCount; ++k) {
    if (!res.params[k].at_bound) continue;
    if (k == kC1I) {
      res.warnings.push_back("c1 + c0 is on the ideal-ESC bound 1.1095 (model.md section 10): the data ask for an "
                             "ESC that creates energy");
    } else if (k == kKtI && !pr.layout.tie_kt) {
      res.warnings.push_back("kt_nm_per_a is on its bound sqrt(27/10)*KE (model.md section 10): the data ask for a "
                             "motor efficiency above 1");
    } else {
      res.warnings.push_back(std::string(ParamName(static_cast<Param>(k))) + " is at its bound (" +
                             std::to_string(res.params[k].value) + "): the data push it outside the physical range");
    }
  }
  if (pr.has_throttle && pr.levels.size() < 2) {
    res.warnings.push_back("all rows at one throttle level: ESC ratio and saturation not identifiable");
  }
}

// Per measured column: rmse, rmse in percent and median |error| of the final fit (the speed from
// the current on rows whose current is the input, whose current is then not scored), and the no-throttle plausibility warning.
void AddColumnFits(const Prepared& pr, const SteadyTable& table, const CalibrationOptions& options,
                   CalibrationResult* out) {
  CalibrationResult& res = *out;
  for (int m = 0; m < kMeasCount; ++m) {
    if (!pr.data.measured[m]) continue;
    ColumnFit cf;
    cf.column = kMeasColumn[m];
    double sse = 0.0, ss = 0.0;
    std::vector<double> rel;
    for (std::size_t k = 0; k < pr.data.rows(); ++k) {
      const RowPrediction rp = PredictRow(table, pr.data.table_row[k], res.motor, res.esc, options.assumed_throttle);
      // Rows whose current is the fit's input: their speed prediction is the one from the current.
      const bool current_input = pr.data.idc_in[k] == pr.data.idc_in[k];
      // Its current is an input there, not a fitted value: not scored (the held-out report has
      // the current from the measured speed).
      if (current_input && m == kMIdc) continue;
      const double pv[kMeasCount] = {current_input ? rp.omega_from_idc_rad_s : rp.omega_rad_s, rp.idc_a, rp.irms_a,
                                     rp.vll_rms_v, rp.pac_w};
      if (!std::isfinite(pv[m])) continue;
      const double meas = table.Get(kMeasColumn[m])[pr.data.table_row[k]];
      sse += (pv[m] - meas) * (pv[m] - meas);
      ss += meas * meas;
      if (meas != 0.0) rel.push_back(std::fabs(pv[m] - meas) / std::fabs(meas) * 100.0);
      ++cf.points;
    }
    if (cf.points == 0) continue;
    cf.rmse = std::sqrt(sse / static_cast<double>(cf.points));
    cf.rmse_percent = ss > 0.0 ? 100.0 * std::sqrt(sse / ss) : kNaN;
    cf.median_abs_percent = Median(rel);
    res.fit.push_back(cf);
  }
  if (!pr.has_throttle) {
    for (const auto& f : res.fit) {
      if (f.rmse_percent > 10.0) {
        res.warnings.push_back(std::string("no throttle column and ") + logs::ColumnName(f.column) + " misfit by " +
                               std::to_string(f.rmse_percent) +
                               " % rms: the rows do not look like full-throttle points, so KE and R are not "
                               "meaningful; calibrate a log that records the throttle");
        break;
      }
    }
  }
}

}  // namespace

const char* ParamName(Param p) {
  switch (p) {
    case Param::kKe: return "ke_v_s_per_rad";
    case Param::kKt: return "kt_nm_per_a";
    case Param::kRm: return "rm_ohm";
    case Param::kIo: return "io_a";
    case Param::kResc: return "resc_ohm";
    case Param::kC1: return "c1";
    case Param::kC0: return "c0";
    case Param::kTrSat: return "tr_sat";
    case Param::kSatSlope: return "sat_slope";
    case Param::kDeadband: return "deadband";
  }
  return "?";
}

namespace {

// Io where the log cannot identify it (no torque, no no-load rows: Io does not enter the
// predictions): the label (--io-label), else the motor prior, else the no-load prior of
// catalog/noload_prior.h - never 0. The log's largest DC current stands in for the rating and its
// largest supply voltage for the test voltage. Sets motor.io_a, params[kIo] and io_source.
void HeldIo(const Prepared& pr, const SteadyTable& t, const CalibrationOptions& o, CalibrationResult* res) {
  ParamEstimate& e = res->params[static_cast<int>(Param::kIo)];
  if (pr.layout.free[static_cast<int>(Param::kIo)]) {
    res->io_source = "fitted";
    return;
  }
  if (o.labels.io_a) {
    res->motor.io_a = e.value = identification::IoFromLabel(*o.labels.io_a);
    res->io_source = "label";
    e.note += "; held at the label (--io-label)";
    return;
  }
  if (o.motor_prior && o.motor_prior->io_a > 0.0) {
    res->io_source = "motor prior";
    return;
  }
  double imax = 0.0, vmax = 0.0;
  for (std::size_t k = 0; k < pr.data.rows(); ++k) {
    if (t.Has(Column::kIdcA)) imax = std::max(imax, t.Get(Column::kIdcA)[pr.data.table_row[k]]);
    vmax = std::max(vmax, pr.data.vdc[k]);
  }
  const double n0_rpm = identification::KvFromKe(res->motor.ke_v_s_per_rad) * vmax;
  const double io = NoLoadPriorIoA(imax, n0_rpm);
  if (!(io > 0.0)) return;
  res->motor.io_a = e.value = io;
  res->io_source = "no-load prior";
  e.note += "; assumed from the no-load prior (catalog/noload_prior.h)";
  std::ostringstream w;
  w.precision(3);
  w << "io_a = " << io << " A assumed from the no-load prior (no torque and no no-load rows: the log cannot "
    << "identify Io); largest DC current " << imax << " A for the rating, no-load speed " << n0_rpm << " rpm; "
    << NoLoadLawText();
  res->warnings.push_back(w.str());
}

}  // namespace

bool CalibrationOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error != nullptr) *error = m;
    return false;
  };
  if (!(loss_scale_percent > 0.0)) return fail("loss_scale_percent = " + std::to_string(loss_scale_percent) + ": must be > 0");
  if (!(outlier_sigmas >= 0.0)) return fail("outlier_sigmas = " + std::to_string(outlier_sigmas) + ": must be >= 0");
  if (!(min_speed_fraction >= 0.0 && min_speed_fraction < 1.0)) return fail("min_speed_fraction must be in [0, 1)");
  if (!(assumed_throttle > 0.0 && assumed_throttle <= 1.0)) return fail("assumed_throttle = " + std::to_string(assumed_throttle) + ": must be in (0, 1]");
  if (!(knee_min > 0.0 && knee_min < 1.0)) return fail("knee_min = " + std::to_string(knee_min) + ": must be in (0, 1)");
  if (!(knee_step > 0.0 && knee_step <= 0.5)) return fail("knee_step = " + std::to_string(knee_step) + ": must be in (0, 0.5]");
  if (!(knee_min_f >= 0.0)) return fail("knee_min_f must be >= 0");
  if (!(prior_ke_rel_sigma > 0.0 && prior_rm_rel_sigma > 0.0 && prior_io_rel_sigma > 0.0)) {
    return fail("prior_*_rel_sigma must be > 0");
  }
  std::string e;
  if (!solver.IsValid(&e)) return fail("solver." + e);
  return true;
}

CalibrationResult Calibrate(const SteadyTable& table, const CalibrationOptions& options) {
  std::string err;
  if (!options.IsValid(&err)) throw UsageError("calibration options: " + err);
  CalibrationResult res;
  res.solve_called = true;
  Prepared pr = Prepare(table, options, nullptr);
  const int nfree_base = static_cast<int>(std::count(pr.layout.free.begin(), pr.layout.free.end(), true));
  if (pr.data.terms.size() <= static_cast<std::size_t>(nfree_base)) {
    throw DataError(FileTag(table) + ": " + std::to_string(pr.data.terms.size()) +
                    " measured values for " + std::to_string(nfree_base) +
                    " free parameters: calibration needs more rows");
  }
  bool knee_found = false, offset_found = false;
  std::string knee_note, offset_note;
  SolveOutcome best = FitWithOffset(pr, options, &knee_found, &knee_note, &offset_found, &offset_note);
  std::size_t outliers = 0;
  if (options.outlier_sigmas > 0.0 && best.summary.IsSolutionUsable()) {
    const std::vector<DroppedRow> out = SelectOutliers(pr, best.params, table, options, nfree_base);
    if (!out.empty()) {
      std::vector<char> excl(table.rows(), 1);  // rows dropped before stay dropped
      for (std::size_t i : pr.data.table_row) excl[i] = 0;
      for (const auto& o : out) excl[o.row] = 1;
      Prepared pr2 = Prepare(table, options, &excl);
      pr2.dropped = pr.dropped;
      pr2.dropped_rows = pr.dropped_rows;
      pr2.dropped.push_back({"outlier (residual > outlier_sigmas robust sd)", out.size()});
      pr2.dropped_rows.insert(pr2.dropped_rows.end(), out.begin(), out.end());
      pr2.warnings = pr.warnings;
      pr = std::move(pr2);
      outliers = out.size();
      best = FitWithOffset(pr, options, &knee_found, &knee_note, &offset_found, &offset_note);
    }
  }
  // Without AC columns the ESC ratio is only seen through the tied KT (section 5): where the log
  // cannot determine C1, C0 (on a bound, or a standard error above half the value) they are held
  // at the ESC prior (ideal unless --prior-esc) and the fit repeated (issue 12).
  if (pr.mode != "ac" && pr.layout.free[kC1I]) {
    const std::string why = EscUndetermined(best.summary);
    if (!why.empty()) {
      const EscParams e0 = options.esc_prior ? *options.esc_prior : EscParams{};
      pr.layout.free[kC1I] = pr.layout.free[kC0I] = false;
      pr.start[kC0I] = std::clamp(e0.c0, kLower[kC0I], kUpper[kC0I]);
      pr.start[kC1I] = std::clamp(identification::EscExcess(e0.c1, pr.start[kC0I]), kLower[kC1I], kUpper[kC1I]);
      pr.notes[kC1I] = pr.notes[kC0I] = "held at prior: without AC columns this log cannot determine them (" + why + ")";
      best = FitWithOffset(pr, options, &knee_found, &knee_note, &offset_found, &offset_note);
    }
  }
  const auto& s = best.summary;
  res.solver_summary = s;
  res.converged = s.termination_type == TerminationType::kConvergence;
  res.message = std::string(TerminationTypeToString(s.termination_type)) + ": " + s.message;
  res.mode = pr.mode;
  res.motor = ToMotor(best.params);
  res.esc = ToEsc(best.params, options.esc_prior);
  res.dropped = pr.dropped;
  res.dropped_rows = pr.dropped_rows;
  res.points_used = pr.data.rows();
  for (const auto& dc : pr.dropped) res.points_dropped += dc.count;
  res.warnings = pr.warnings;
  if (!res.converged) res.warnings.push_back("fit did not converge: " + s.message);

  // Per-parameter report.
  std::vector<int> slots;
  {
    Layout lay = pr.layout;
    lay.free[8] = knee_found;
    lay.free[kDbI] = offset_found;
    for (int k = 0; k < kParamCount; ++k) {
      if (lay.free[k]) slots.push_back(k);
    }
  }
  for (int k = 0; k < kParamCount; ++k) {
    ParamEstimate& e = res.params[k];
    e.value = best.params[k];
    e.note = pr.notes[k];
  }
  HeldIo(pr, table, options, &res);
  for (std::size_t sl = 0; sl < slots.size() && sl < static_cast<std::size_t>(s.parameters.size()); ++sl) {
    ParamEstimate& e = res.params[slots[sl]];
    e.fitted = true;
    e.identifiable = true;
    e.standard_error = s.standard_errors.size() > static_cast<Eigen::Index>(sl) ? s.standard_errors[sl] : kNaN;
    e.at_bound = sl < s.at_bound.size() && s.at_bound[sl];
  }
  for (const auto& u : s.unidentifiable) {
    res.unidentifiable_directions.push_back(u.description);
    for (Eigen::Index sl = 0; sl < u.direction.size() && sl < static_cast<Eigen::Index>(slots.size()); ++sl) {
      if (std::fabs(u.direction[sl]) > 0.2) {
        ParamEstimate& e = res.params[slots[sl]];
        if (HasPrior(options, slots[sl])) {
          // The prior pins what the data leave flat: its standard error is the prior's.
          e.note = "set by its prior (the data alone do not determine it: " + u.description + ")";
          continue;
        }
        e.identifiable = false;
        e.note = "in a direction the data do not determine: " + u.description;
      }
    }
  }
  TransformStandardErrors(pr.layout.tie_kt, slots, s, &res);
  if (!offset_found) res.params[kDbI].note = pr.notes[kDbI].empty() ? offset_note : pr.notes[kDbI];
  else res.params[kDbI].note = offset_note;
  auto& tk = res.params[static_cast<int>(Param::kTrSat)];
  tk.fitted = knee_found;
  tk.identifiable = knee_found;
  tk.note = knee_note;
  if (knee_found) tk.standard_error = options.knee_step / std::sqrt(12.0);  // grid resolution
  auto& sl = res.params[static_cast<int>(Param::kSatSlope)];
  if (!knee_found) sl.note = "no knee: " + knee_note;
  // KT tied to KE: its error follows KE's.
  auto& kt = res.params[static_cast<int>(Param::kKt)];
  if (pr.layout.tie_kt) {
    const auto& ke = res.params[0];
    kt.standard_error = kPacPerVllIrms * ke.standard_error;
    kt.identifiable = false;
  }
  // Rm + RESC with its error (covariance when both fitted).
  res.r_total_ohm = res.motor.rm_ohm + res.esc.resc_ohm;
  {
    double var = 0.0;
    int irm = -1, iresc = -1;
    for (std::size_t q = 0; q < slots.size(); ++q) {
      if (slots[q] == 2) irm = static_cast<int>(q);
      if (slots[q] == 4) iresc = static_cast<int>(q);
    }
    if (s.covariance.rows() == static_cast<Eigen::Index>(slots.size()) && irm >= 0) {
      var = s.covariance(irm, irm);
      if (iresc >= 0) var += s.covariance(iresc, iresc) + 2.0 * s.covariance(irm, iresc);
      res.r_total_standard_error = std::sqrt(std::max(var, 0.0));
    }
  }
  if (!pr.layout.free[static_cast<int>(Param::kResc)]) {
    res.params[static_cast<int>(Param::kRm)].identifiable = false;
    res.params[static_cast<int>(Param::kResc)].identifiable = false;
  }
  if (s.scaled_singular_values.size() > 0) {
    const double smin = s.scaled_singular_values.minCoeff();
    res.condition_number = smin > 0.0 ? s.scaled_singular_values.maxCoeff() / smin
                                      : std::numeric_limits<double>::infinity();
  }
  AddBoundWarnings(pr, &res);
  if (outliers > 0) res.warnings.push_back(std::to_string(outliers) + " outlier row(s) dropped and the fit repeated");

  AddColumnFits(pr, table, options, &res);
  return res;
}

RowPrediction PredictRow(const SteadyTable& t, std::size_t row, const MotorParams& motor, const EscParams& esc,
                         double assumed_throttle) {
  RowPrediction out;
  const std::array<double, kParamCount> p = ToInternal(motor, esc);
  const bool has_q = t.Has(Column::kTorqueNm);
  const bool nl = t.Has(Column::kNoLoad) && t.Get(Column::kNoLoad)[row] != 0.0;
  const bool tq = has_q || nl;
  const double tr = t.Has(Column::kThrottle) ? t.Get(Column::kThrottle)[row] : assumed_throttle;
  double pred[kMeasCount], qp;
  if (!PredictGeneric(p.data(), esc.tr_sat, t.Get(Column::kVdcV)[row], tr, t.Get(Column::kOmegaRadS)[row],
                      has_q ? t.Get(Column::kTorqueNm)[row] : 0.0, tq, pred, &qp)) {
    return out;
  }
  if (tq) out.omega_rad_s = pred[kMOmega];
  {
    const double tre = circuit::EffectiveThrottle(tr, esc.tr_sat, esc.sat_slope, esc.deadband);
    const double g = esc.c1 * tre + esc.c0;  // (57): IDC = g*I
    const double u = circuit::AppliedVoltage(kVllRmsPerVdc, t.Get(Column::kVdcV)[row], tre);
    if (g > 0.0 && motor.ke_v_s_per_rad > 0.0) {
      out.omega_from_idc_rad_s = circuit::SpeedAtCurrent(u, motor.rm_ohm + esc.resc_ohm,
                                                         t.Get(Column::kIdcA)[row] / g, motor.ke_v_s_per_rad);
    }
  }
  if (!tq) out.torque_nm = qp;
  out.idc_a = pred[kMIdc];
  out.irms_a = pred[kMIrms];
  out.vll_rms_v = pred[kMVll];
  out.pac_w = pred[kMPac];
  return out;
}

std::string CalibrationResult::BriefReport() const {
  if (!solve_called) return message;
  std::ostringstream s;
  s << std::setprecision(4) << "calibrate (" << mode << "): " << (converged ? "converged" : "NOT converged")
    << ", " << points_used << " points (" << points_dropped << " dropped), KE " << motor.ke_v_s_per_rad
    << " V*s/rad, R " << r_total_ohm << " ohm";
  for (const auto& f : fit) s << ", " << logs::ColumnName(f.column) << " rmse " << f.rmse_percent << " %";
  return s.str();
}

namespace {
// A standard error for the table: "-" where there is none (held parameters, bounds).
std::string ErrText(double v) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::setprecision(3) << v;
  return s.str();
}
}  // namespace

std::string CalibrationResult::FullReport() const {
  if (!solve_called) return message + "\n";
  std::ostringstream s;
  s << BriefReport() << "\n" << message << "\n\n";
  s << std::left << std::setw(16) << "parameter" << std::right << std::setw(14) << "value" << std::setw(14)
    << "std error" << "  fitted ident  note\n";
  for (int k = 0; k < kParamCount; ++k) {
    const auto& e = params[k];
    s << std::left << std::setw(16) << ParamName(static_cast<Param>(k)) << std::right << std::setw(14)
      << std::setprecision(6) << e.value << std::setw(14) << ErrText(e.standard_error) << "  "
      << std::left << std::setw(7) << (e.fitted ? "yes" : "no") << std::setw(6)
      << (e.identifiable ? "yes" : "NO") << e.note << std::right << "\n";
  }
  s << std::left << std::setw(16) << "r_total_ohm" << std::right << std::setw(14) << std::setprecision(6)
    << r_total_ohm << std::setw(14) << ErrText(r_total_standard_error) << "\n";
  s << "condition (unit-scaled Jacobian): " << std::setprecision(3) << condition_number << "\n\n";
  for (const auto& f : fit) {
    s << "  " << std::left << std::setw(12) << logs::ColumnName(f.column) << std::right << " n " << f.points
      << "  rmse " << std::setprecision(4) << f.rmse << " (" << f.rmse_percent << " %), median |err| "
      << f.median_abs_percent << " %\n";
  }
  for (const auto& d : dropped) s << "  dropped " << d.count << ": " << d.reason << "\n";
  for (const auto& d : dropped_rows) s << "    line " << d.source_line << ": " << d.reason << "\n";
  for (const auto& u : unidentifiable_directions) s << "  unidentifiable: " << u << "\n";
  for (const auto& w : warnings) s << "  warning: " << w << "\n";
  return s.str();
}

namespace {

// The plain DC model's errors on held-out row i (percent of the measured value), beside the
// rms model's: DC current and speed at the row's torque (tq), speed from its measured current.
void AddDcErrors(const DcMotor& m, const SteadyTable& t, std::size_t i, double assumed_throttle, bool tq,
                 CrossValidation* cv) {
  const identification::DcRowPrediction p = identification::PredictDcRow(m, t, i, assumed_throttle);
  const double w = t.Get(Column::kOmegaRadS)[i], idc = t.Get(Column::kIdcA)[i];
  if (tq && idc > 0.0 && std::isfinite(p.idc_at_torque_a)) {
    cv->dc_idc_error_percent.push_back((p.idc_at_torque_a - idc) / idc * 100.0);
  }
  if (tq && std::isfinite(p.omega_at_torque_rad_s)) {
    cv->dc_omega_error_percent.push_back((p.omega_at_torque_rad_s - w) / w * 100.0);
  }
  if (std::isfinite(p.omega_from_idc_rad_s)) {
    cv->dc_omega_from_idc_error_percent.push_back((p.omega_from_idc_rad_s - w) / w * 100.0);
  }
}

}  // namespace

CrossValidation LeaveOneOut(const SteadyTable& t, const CalibrationOptions& options, bool by_throttle,
                            std::size_t max_folds) {
  CrossValidation cv;
  const std::size_t n = t.rows();
  std::vector<long long> group(n);
  const bool thr = by_throttle && t.Has(Column::kThrottle);
  for (std::size_t i = 0; i < n; ++i) {
    group[i] = thr ? std::llround(t.Get(Column::kThrottle)[i] * 1000.0) : static_cast<long long>(i);
  }
  std::vector<long long> groups = group;
  std::sort(groups.begin(), groups.end());
  groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
  if (max_folds > 0 && groups.size() > max_folds) {
    // Interleaved folds: group j (in sorted order) goes to fold j % max_folds.
    cv.leave_one_out = false;
    for (std::size_t i = 0; i < n; ++i) {
      const auto j = static_cast<std::size_t>(std::lower_bound(groups.begin(), groups.end(), group[i]) - groups.begin());
      group[i] = static_cast<long long>(j % max_folds);
    }
    groups.clear();
    for (std::size_t f = 0; f < max_folds; ++f) groups.push_back(static_cast<long long>(f));
  }
  const bool has_q = t.Has(Column::kTorqueNm);
  const bool has_nl = t.Has(Column::kNoLoad);
  double wmax = 0.0;
  for (double w : t.Get(Column::kOmegaRadS)) wmax = std::max(wmax, w);
  // The rows a fit may use (Prepare's speed and throttle rules; a no-load row without a speed
  // reading counts for the current only).
  const auto usable = [&](std::size_t i, bool* speed_unknown) {
    const double w = t.Get(Column::kOmegaRadS)[i];
    *speed_unknown = has_nl && t.Get(Column::kNoLoad)[i] != 0.0 && w == 0.0;
    if (!*speed_unknown && !(w > options.min_speed_fraction * wmax)) return false;
    return !(t.Has(Column::kThrottle) && t.Get(Column::kThrottle)[i] < options.min_throttle);
  };
  // Spurious speed readings are no test of a prediction (the fits leave them out too).
  std::vector<char> spurious(n, 0);
  for (const auto& sp : SpuriousSpeedRows(t, options, nullptr)) spurious[sp.row] = 1;
  for (long long g : groups) {
    ++cv.folds;
    std::vector<std::size_t> test;
    std::vector<std::size_t> keep;
    for (std::size_t i = 0; i < n; ++i) (group[i] == g ? test : keep).push_back(i);
    const SteadyTable train = SelectRows(t, keep);
    CalibrationResult r;
    try {
      r = Calibrate(train, options);
    } catch (const Error&) {
      ++cv.failed_folds;
      continue;
    }
    std::vector<std::size_t> dc_rows;
    for (std::size_t i : keep) {
      bool unknown = false;
      if (usable(i, &unknown) && !unknown) dc_rows.push_back(i);
    }
    const identification::DcFit dc = identification::FitDcMotor(t, dc_rows, options.assumed_throttle,
                                                                options.labels.kv_rpm_per_v.value_or(0.0));
    for (std::size_t i : test) {
      const double w = t.Get(Column::kOmegaRadS)[i];
      bool speed_unknown = false;
      if (spurious[i] || !usable(i, &speed_unknown)) continue;
      const bool no_load = has_nl && t.Get(Column::kNoLoad)[i] != 0.0;
      if (dc.ok && !speed_unknown) AddDcErrors(dc.motor, t, i, options.assumed_throttle, has_q || no_load, &cv);
      const RowPrediction p = PredictRow(t, i, r.motor, r.esc, options.assumed_throttle);
      const double idc = t.Get(Column::kIdcA)[i];
      if (idc > 0.0 && std::isfinite(p.idc_a)) {
        cv.idc_error_percent.push_back((p.idc_a - idc) / idc * 100.0);
        if (!no_load) cv.idc_loaded_error_percent.push_back(cv.idc_error_percent.back());
      }
      if (speed_unknown) continue;
      const bool tq = has_q || no_load;
      if (std::isfinite(p.omega_from_idc_rad_s)) {
        cv.omega_from_idc_error_percent.push_back((p.omega_from_idc_rad_s - w) / w * 100.0);
      }
      if (tq && std::isfinite(p.omega_rad_s)) cv.omega_error_percent.push_back((p.omega_rad_s - w) / w * 100.0);
    }
  }
  return cv;
}

}  // namespace dynosize::calibration

namespace dynosize::calibration {

CrossValidation CrossValidateForVerdict(const SteadyTable& table, const CalibrationOptions& options) {
  // Up to 15 groups every group is left out in turn (small tables, issue 12); beyond that 10
  // interleaved folds bound the cost of the verdict.
  constexpr std::size_t kMaxLooGroups = 15;
  constexpr std::size_t kFolds = 10;
  const bool thr = table.Has(Column::kThrottle);
  std::vector<long long> g;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    g.push_back(thr ? std::llround(table.Get(Column::kThrottle)[i] * 1000.0) : static_cast<long long>(i));
  }
  std::sort(g.begin(), g.end());
  g.erase(std::unique(g.begin(), g.end()), g.end());
  return LeaveOneOut(table, options, true, g.size() <= kMaxLooGroups ? 0 : kFolds);
}

identification::Verdict JudgeCalibration(const CalibrationResult& r, const SteadyTable& table,
                                         const CalibrationOptions& options, const CrossValidation* cv) {
  identification::VerdictInputs in;
  in.converged = r.converged;
  for (int k = 0; k < kParamCount; ++k) {
    const auto& e = r.params[k];
    identification::ParamState p;
    p.name = ParamName(static_cast<Param>(k));
    p.value = e.value;
    p.standard_error = e.standard_error;
    p.fitted = e.fitted;
    p.identifiable = e.identifiable;
    p.at_bound = e.at_bound;
    // The grid resolution of the profiled knee is not a standard error of the data.
    if (static_cast<Param>(k) == Param::kTrSat) p.standard_error = kNaN;
    // Without AC columns Rm stands for Rm + RESC (RESC held at its prior): the sum is what the
    // data determine, with its own error; only a flat direction makes it unidentifiable.
    if (static_cast<Param>(k) == Param::kRm && !r.param(Param::kResc).fitted && e.fitted &&
        e.note.rfind("in a direction", 0) != 0) {
      p.identifiable = true;
      p.standard_error = r.r_total_standard_error;
    }
    in.params.push_back(p);
  }
  in.motor = r.motor;
  in.esc = r.esc;
  if (table.Has(Column::kVdcV)) {
    const auto& v = table.Get(Column::kVdcV);
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (double x : v) {
      if (x > 0.0) {
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    }
    in.envelope.vdc_min_v = std::isfinite(lo) ? lo : 0.0;
    in.envelope.vdc_max_v = hi;
  }
  in.kv_label_rpm_per_v = options.labels.kv_rpm_per_v;
  if (cv != nullptr) {
    identification::HeldOut h;
    h.folds = cv->folds;
    h.failed_folds = cv->failed_folds;
    h.leave_one_out = cv->leave_one_out;
    auto med_abs = [](std::vector<double> v) {
      for (double& x : v) x = std::fabs(x);
      return Median(v);
    };
    const bool current_input = table.Has(Column::kThrottle) && !table.Has(Column::kTorqueNm) &&
                               !(table.Has(Column::kVllRmsV) && table.Has(Column::kIrmsA));
    if (current_input) {
      // The fit predicts the speed from the measured current (Prepare): that is its held-out test.
      h.median_abs_current_percent = med_abs(cv->omega_from_idc_error_percent);
      h.primary_quantity = "speed predicted from the measured current";
    } else {
      h.median_abs_current_percent = med_abs(cv->idc_error_percent);
      h.median_abs_speed_percent = !cv->omega_error_percent.empty() ? med_abs(cv->omega_error_percent)
                                                                     : med_abs(cv->omega_from_idc_error_percent);
    }
    in.held_out = h;
  }
  if (options.labels.kv_rpm_per_v) {
    in.torque_per_ampere_vs_label = identification::TorquePerAmpereVsLabel(table, *options.labels.kv_rpm_per_v);
  }
  in.has_torque = table.Has(Column::kTorqueNm);
  in.has_ac = table.Has(Column::kVllRmsV) && table.Has(Column::kIrmsA);
  in.has_throttle = table.Has(Column::kThrottle);
  in.pulse_min_us = table.throttle_pulse_min_us;
  in.pulse_max_us = table.throttle_pulse_max_us;
  identification::Verdict v = identification::Judge(in);
  if (r.io_source == "no-load prior") {
    v.summary += " (io_a from the no-load prior: assumed, the log has neither torque nor no-load rows)";
  }
  return v;
}

}  // namespace dynosize::calibration
