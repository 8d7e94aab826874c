#include "calibration/calibrate.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

#include "common/dual.h"
#include "common/error.h"
#include "common/units.h"
#include "fit/linear_least_squares.h"

namespace dynosize::calibration {

namespace {

using logs::Column;
using logs::SteadyTable;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxFree = 8;  // every parameter but tr_sat (profiled)
using D8 = Dual<kMaxFree>;

// Measured columns the fit compares with predictions, in this order.
enum Meas : int { kMOmega = 0, kMIdc, kMIrms, kMVll, kMPac, kMeasCount };
constexpr Column kMeasColumn[kMeasCount] = {Column::kOmegaRadS, Column::kIdcA, Column::kIrmsA,
                                            Column::kVllRmsV, Column::kPacW};

struct Term {
  int meas;
  double value;
  double inv_scale;  // 100 / median |column|: residual in percent of the typical value
};

struct FitData {
  std::vector<std::size_t> rows;  // rows of the table used
  std::vector<double> vdc, tr, omega, q;
  std::vector<char> torque_known;
  std::vector<char> speed_known;  // 0: a no-load row whose speed was not measured (omega = 0)
  std::vector<int> term_begin;  // terms of row k: [term_begin[k], term_begin[k+1])
  std::vector<Term> terms;
  std::array<bool, kMeasCount> measured{};
};

double Median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  const std::size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h), v.end());
  double m = v[h];
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h)));
  return m;
}

// The throttle-saturation law of section 7, for data throttle `tr`.
template <typename T>
T EffThrottle(double tr, double tr_sat, const T& slope) {
  if (tr <= tr_sat) return T(tr);
  return tr_sat + slope * (tr - tr_sat);
}

// Forward predictions of one row (see the header): fills pred[kMeasCount] (and the torque).
// Returns false outside the model's domain (non-positive KE, KT or resistance).
template <typename T>
bool PredictGeneric(const T* p, double tr_sat, bool tie_kt, double vdc, double tr, double omega,
                    double q, bool torque_known, T* pred, T* q_pred) {
  const T& ke = p[0];
  const T kt = tie_kt ? kPacPerVllIrms * ke : p[1];
  const T& rm = p[2];
  const T& io = p[3];
  const T& resc = p[4];
  const T& c1 = p[5];
  const T& c0 = p[6];
  const T& slope = p[8];
  const T r = rm + resc;
  if (!(ke > 0.0) || !(kt > 0.0) || !(r > 1e-12)) return false;
  const T tre = EffThrottle(tr, tr_sat, slope);
  const T u = kVllRmsPerVdc * vdc * tre;
  T i, w;
  if (torque_known) {
    i = q / kt + io;
    w = (u - r * i) / ke;
    *q_pred = T(q);
  } else {
    w = T(omega);
    i = (u - ke * omega) / r;
    *q_pred = kt * (i - io);
  }
  const T vll = u - resc * i;
  pred[kMOmega] = w;
  pred[kMIdc] = (c1 * tre + c0) * i;
  pred[kMIrms] = i;
  pred[kMVll] = vll;
  pred[kMPac] = kPacPerVllIrms * vll * i;
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
  for (std::size_t k = 0; k < d.rows.size(); ++k) {
    if (!PredictGeneric(p, tr_sat, lay.tie_kt, d.vdc[k], d.tr[k], d.omega[k], d.q[k],
                        d.torque_known[k] != 0, pred, &qp)) {
      return false;
    }
    for (int t = d.term_begin[k]; t < d.term_begin[k + 1]; ++t) {
      const Term& term = d.terms[t];
      r[t] = (pred[term.meas] - term.value) * term.inv_scale;
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

// Bounds of each parameter (physical: no negative resistance or no-load current).
// Rm stays above 1 micro-ohm (the catalog requires rm_ohm > 0); C0 and sat_slope within the
// catalog's ranges (schema.cc).
constexpr double kLower[kParamCount] = {1e-7, 1e-7, 1e-6, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0};
constexpr double kUpper[kParamCount] = {10.0, 20.0, 100.0, 200.0, 10.0, 5.0, 1.0, 1.0, 1.0};

std::string FileTag(const SteadyTable& t) { return t.file.empty() ? std::string("log") : t.file; }

// Distinct throttle levels (rounded to 0.001).
std::vector<double> ThrottleLevels(const std::vector<double>& tr) {
  std::vector<double> lv;
  for (double v : tr) lv.push_back(std::round(v * 1000.0) / 1000.0);
  std::sort(lv.begin(), lv.end());
  lv.erase(std::unique(lv.begin(), lv.end()), lv.end());
  return lv;
}

struct Prepared {
  FitData data;
  Layout layout;
  std::array<double, kParamCount> start{};
  std::array<std::string, kParamCount> notes;
  std::string mode;
  bool has_throttle = false;
  std::vector<double> levels;
  std::vector<logs::DropCount> dropped;
  std::vector<std::string> warnings;
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

// Selects the rows, decides what is free, and finds starting values by linear least squares.
Prepared Prepare(const SteadyTable& t, const CalibrationOptions& o, const std::vector<char>* excluded) {
  Prepared pr;
  const std::string file = FileTag(t);
  if (!t.Has(Column::kOmegaRadS)) {
    throw DataError(file + ": column omega_rad_s (shaft speed) is absent: calibration needs the speed "
                    "to find the back-EMF constant");
  }
  const bool has_v = t.Has(Column::kVdcV);
  const bool ac = t.Has(Column::kVllRmsV) && t.Has(Column::kIrmsA);
  if (!has_v) {
    throw DataError(file + ": column vdc_v (supply voltage) is absent: calibration needs the voltage "
                    "at the ESC (eq 48)");
  }
  pr.has_throttle = t.Has(Column::kThrottle);
  const bool has_q = t.Has(Column::kTorqueNm);
  const bool has_nl = t.Has(Column::kNoLoad);
  const auto& w_all = t.Get(Column::kOmegaRadS);
  const auto& idc_all = t.Get(Column::kIdcA);
  double wmax = 0.0;
  for (double w : w_all) wmax = std::max(wmax, w);
  bool any_idc = false;
  for (double v : idc_all) any_idc = any_idc || v != 0.0;
  if (!any_idc) throw DataError(file + ": column idc_a is zero in every row: nothing to fit");

  FitData& d = pr.data;
  for (int m = 0; m < kMeasCount; ++m) d.measured[m] = t.Has(kMeasColumn[m]);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (excluded != nullptr && (*excluded)[i]) continue;
    const double w = w_all[i];
    const double tr = pr.has_throttle ? t.Get(Column::kThrottle)[i] : o.assumed_throttle;
    const bool nl = has_nl && t.Get(Column::kNoLoad)[i] != 0.0;
    // A no-load row without a speed reading (DriveCalc n = 0) still measures Io: at Q = 0 the
    // model's current I = Io does not depend on the speed (eq 42). Only its current is compared.
    const bool speed_unknown = nl && w == 0.0;
    if (!speed_unknown && !(w > o.min_speed_fraction * wmax)) {
      AddDropLocal(&pr.dropped, "speed below min_speed_fraction of the largest");
      continue;
    }
    if (pr.has_throttle && tr < o.min_throttle) {
      AddDropLocal(&pr.dropped, "throttle below min_throttle");
      continue;
    }
    if (!(t.Get(Column::kVdcV)[i] > 0.0)) {
      AddDropLocal(&pr.dropped, "vdc_v not positive");
      continue;
    }
    d.rows.push_back(i);
    d.vdc.push_back(t.Get(Column::kVdcV)[i]);
    d.tr.push_back(tr);
    d.omega.push_back(w);
    d.q.push_back(has_q ? t.Get(Column::kTorqueNm)[i] : 0.0);
    d.torque_known.push_back(has_q || nl ? 1 : 0);
    d.speed_known.push_back(speed_unknown ? 0 : 1);
  }
  const std::size_t n = d.rows.size();
  std::size_t with_speed = 0;
  for (char c : d.speed_known) with_speed += c != 0 ? 1 : 0;
  if (with_speed < 2) {
    throw DataError(file + ": only " + std::to_string(with_speed) +
                    " row(s) with the motor turning: calibration needs at least 2");
  }
  // Column scales: median magnitude of each measured column over the rows used.
  std::array<double, kMeasCount> inv_scale{};
  for (int m = 0; m < kMeasCount; ++m) {
    if (!d.measured[m]) continue;
    std::vector<double> mag;
    for (std::size_t i : d.rows) mag.push_back(std::fabs(t.Get(kMeasColumn[m])[i]));
    const double med = Median(mag);
    inv_scale[m] = med > 0.0 ? 100.0 / med : 0.0;
    if (!(med > 0.0)) d.measured[m] = false;
  }
  d.term_begin.push_back(0);
  for (std::size_t k = 0; k < n; ++k) {
    for (int m = 0; m < kMeasCount; ++m) {
      if (!d.measured[m]) continue;
      if (m == kMOmega && !d.torque_known[k]) continue;  // speed is the input on this row
      if (m == kMOmega && !d.speed_known[k]) continue;   // speed not measured on this row
      d.terms.push_back({m, t.Get(kMeasColumn[m])[d.rows[k]], inv_scale[m]});
    }
    d.term_begin.push_back(static_cast<int>(d.terms.size()));
  }

  // --- What is free.
  Layout& lay = pr.layout;
  auto& fr = lay.free;
  auto idx = [](Param p) { return static_cast<int>(p); };
  pr.levels = ThrottleLevels(d.tr);
  const bool multi_level = pr.has_throttle && pr.levels.size() >= 2;
  bool any_torque_known = false;
  for (char c : d.torque_known) any_torque_known = any_torque_known || c;
  pr.mode = ac ? "ac" : (pr.has_throttle ? "dc" : "dc_no_throttle");
  fr[idx(Param::kKe)] = true;
  fr[idx(Param::kRm)] = true;
  lay.tie_kt = !(has_q && ac);
  fr[idx(Param::kKt)] = !lay.tie_kt;
  fr[idx(Param::kIo)] = any_torque_known;
  fr[idx(Param::kResc)] = ac && pr.has_throttle;
  const bool esc_ratio = d.measured[kMIdc] && pr.has_throttle && (ac || has_q) && multi_level;
  fr[idx(Param::kC1)] = esc_ratio;
  fr[idx(Param::kC0)] = esc_ratio;
  fr[idx(Param::kTrSat)] = false;  // profiled
  fr[idx(Param::kSatSlope)] = false;  // freed per knee candidate
  auto& nt = pr.notes;
  if (lay.tie_kt) {
    nt[idx(Param::kKt)] = has_q ? "tied: KT = sqrt(27/10)*KE (no AC columns to separate KT from the ESC ratio)"
                                : "tied: KT = sqrt(27/10)*KE (no torque column)";
  }
  if (!fr[idx(Param::kIo)]) nt[idx(Param::kIo)] = "no torque column and no no-load rows: Io does not enter the predictions";
  if (!fr[idx(Param::kResc)]) {
    nt[idx(Param::kResc)] = "held at prior: without vll_rms_v/irms_a only Rm + RESC is determined (eq 48)";
    nt[idx(Param::kRm)] = "Rm + RESC determined, the split is not (held RESC at its prior)";
  }
  if (!esc_ratio) {
    nt[idx(Param::kC1)] = nt[idx(Param::kC0)] =
        !pr.has_throttle ? "no throttle column: held at prior (rows taken as full throttle)"
        : !d.measured[kMIdc] ? "no idc_a: held at prior"
        : !(ac || has_q) ? "no torque and no AC columns: only C1/R, C0/R are determined; held at prior"
                         : "one throttle level: C1*TR + C0 not separable; held at prior";
  }
  if (!pr.has_throttle) {
    pr.warnings.push_back("no throttle column: every row taken as throttle " +
                          std::to_string(o.assumed_throttle) +
                          "; KE and R are conditional on that and on the assumed ESC (ideal unless --esc prior)");
  }

  // --- Starting values and held values.
  std::array<double, kParamCount>& p = pr.start;
  const EscParams esc0 = o.esc_prior ? *o.esc_prior : EscParams{};
  p[idx(Param::kResc)] = esc0.resc_ohm;
  p[idx(Param::kC1)] = esc0.c1;
  p[idx(Param::kC0)] = esc0.c0;
  p[idx(Param::kTrSat)] = 1.0;
  p[idx(Param::kSatSlope)] = 1.0;
  if (o.motor_prior) {
    p[idx(Param::kIo)] = o.motor_prior->io_a;
  }
  // Phase current estimate per row.
  std::vector<double> irms(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (d.measured[kMIrms]) {
      irms[k] = t.Get(Column::kIrmsA)[d.rows[k]];
    } else {
      const double g = esc0.c1 * d.tr[k] + esc0.c0;
      irms[k] = t.Get(Column::kIdcA)[d.rows[k]] / std::max(g, 1e-3);
    }
  }
  // Rows unlikely to be saturated for the linear starts (all rows if fewer than 3 qualify).
  std::vector<std::size_t> lin;
  // Rows without a speed reading cannot enter U = R*I + KE*omega.
  for (std::size_t k = 0; k < n; ++k) {
    if (d.speed_known[k] && (d.tr[k] <= 0.85 || !pr.has_throttle)) lin.push_back(k);
  }
  if (lin.size() < 3) {
    lin.clear();
    for (std::size_t k = 0; k < n; ++k) {
      if (d.speed_known[k]) lin.push_back(k);
    }
  }
  // KE and R from U = R*I + KE*omega (eq 48), or eq 42 with the AC columns.
  {
    Eigen::MatrixXd a(lin.size(), 2);
    Eigen::VectorXd b(lin.size());
    for (std::size_t j = 0; j < lin.size(); ++j) {
      const std::size_t k = lin[j];
      a(j, 0) = irms[k];
      a(j, 1) = d.omega[k];
      b[j] = ac ? t.Get(Column::kVllRmsV)[d.rows[k]] : kVllRmsPerVdc * d.vdc[k] * d.tr[k];
    }
    const auto sol = SolveLinearLeastSquares(a, b);
    double r0 = sol.coefficients[0], ke0 = sol.coefficients[1];
    if (!(ke0 > 0.0)) {
      // Fall back on the no-load relation KE ~ U/omega.
      ke0 = b.cwiseQuotient(a.col(1)).maxCoeff();
    }
    p[idx(Param::kKe)] = ke0;
    if (ac) {
      p[idx(Param::kRm)] = r0;
      if (fr[idx(Param::kResc)]) {
        Eigen::MatrixXd a2(lin.size(), 1);
        Eigen::VectorXd b2(lin.size());
        for (std::size_t j = 0; j < lin.size(); ++j) {
          const std::size_t k = lin[j];
          a2(j, 0) = irms[k];
          b2[j] = kVllRmsPerVdc * d.vdc[k] * d.tr[k] - t.Get(Column::kVllRmsV)[d.rows[k]];
        }
        p[idx(Param::kResc)] = SolveLinearLeastSquares(a2, b2).coefficients[0];
      }
    } else {
      p[idx(Param::kRm)] = r0 - p[idx(Param::kResc)];
    }
  }
  // KT and Io from Q = KT*Irms - KT*Io.
  if (has_q) {
    Eigen::MatrixXd a(n, 2);
    Eigen::VectorXd b(n);
    for (std::size_t k = 0; k < n; ++k) {
      a(k, 0) = irms[k];
      a(k, 1) = 1.0;
      b[k] = d.q[k];
    }
    const auto sol = SolveLinearLeastSquares(a, b);
    const double kt = lay.tie_kt ? kPacPerVllIrms * p[idx(Param::kKe)] : sol.coefficients[0];
    p[idx(Param::kKt)] = kt > 0.0 ? kt : kPacPerVllIrms * p[idx(Param::kKe)];
    double io = 0.0;
    for (std::size_t k = 0; k < n; ++k) io += irms[k] - d.q[k] / p[idx(Param::kKt)];
    p[idx(Param::kIo)] = io / static_cast<double>(n);
  } else {
    p[idx(Param::kKt)] = kPacPerVllIrms * p[idx(Param::kKe)];
    if (any_torque_known) {  // no-load rows: Io is the current there
      double s = 0.0;
      int c = 0;
      for (std::size_t k = 0; k < n; ++k) {
        if (d.torque_known[k]) {
          s += irms[k];
          ++c;
        }
      }
      p[idx(Param::kIo)] = s / c;
    }
  }
  // C1, C0 from IDC = C1*TR*Irms + C0*Irms (eq 57).
  if (esc_ratio && d.measured[kMIrms]) {
    Eigen::MatrixXd a(lin.size(), 2);
    Eigen::VectorXd b(lin.size());
    for (std::size_t j = 0; j < lin.size(); ++j) {
      const std::size_t k = lin[j];
      a(j, 0) = d.tr[k] * irms[k];
      a(j, 1) = irms[k];
      b[j] = t.Get(Column::kIdcA)[d.rows[k]];
    }
    const auto sol = SolveLinearLeastSquares(a, b);
    p[idx(Param::kC1)] = sol.coefficients[0];
    p[idx(Param::kC0)] = sol.coefficients[1];
  }
  if (o.motor_prior) {
    // Values the data cannot identify come from the prior.
    if (!fr[idx(Param::kIo)]) p[idx(Param::kIo)] = o.motor_prior->io_a;
  }
  // Into the box, away from the singular R = 0.
  for (int k = 0; k < kParamCount; ++k) p[k] = std::clamp(p[k], kLower[k], kUpper[k]);
  if (p[idx(Param::kRm)] + p[idx(Param::kResc)] < 1e-4) p[idx(Param::kRm)] = 1e-4 + 0.01 * p[idx(Param::kRm)];
  if (lay.tie_kt) p[idx(Param::kKt)] = kPacPerVllIrms * p[idx(Param::kKe)];
  return pr;
}

struct SolveOutcome {
  std::array<double, kParamCount> params{};
  LevenbergMarquardtSummary summary;
  double cost = std::numeric_limits<double>::infinity();
  int free_count = 0;
};

SolveOutcome SolveOnce(const Prepared& pr, const CalibrationOptions& o, double tr_sat, bool free_slope,
                       const std::array<double, kParamCount>& start) {
  Layout lay = pr.layout;
  lay.free[static_cast<int>(Param::kSatSlope)] = free_slope;
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
    x[s] = std::clamp(start[k], kLower[k], kUpper[k]);
    if (o.motor_prior) {
      const MotorParams& mp = *o.motor_prior;
      auto add = [&](double mean, double rel) {
        if (mean > 0.0 && rel > 0.0) prob.priors.push_back({s, mean, rel * mean});
      };
      if (k == static_cast<int>(Param::kKe)) add(mp.ke_v_s_per_rad, o.prior_ke_rel_sigma);
      if (k == static_cast<int>(Param::kRm)) add(mp.rm_ohm, o.prior_rm_rel_sigma);
      if (k == static_cast<int>(Param::kIo)) add(mp.io_a, o.prior_io_rel_sigma);
    }
  }
  LevenbergMarquardtOptions lo = o.solver;
  lo.loss = o.loss;
  lo.loss_scale = o.loss_scale_percent;
  SolveOutcome out;
  out.free_count = nf;
  out.summary = SolveLeastSquares(prob, lo, &x);
  out.params = fixed;
  for (int s = 0; s < nf; ++s) out.params[lay.free_index[s]] = x[s];
  if (lay.tie_kt) out.params[static_cast<int>(Param::kKt)] = kPacPerVllIrms * out.params[0];
  out.cost = out.summary.IsSolutionUsable() ? out.summary.final_cost : std::numeric_limits<double>::infinity();
  return out;
}

MotorParams ToMotor(const std::array<double, kParamCount>& p) {
  MotorParams m;
  m.ke_v_s_per_rad = p[0];
  m.kt_nm_per_a = p[1];
  m.rm_ohm = p[2];
  m.io_a = p[3];
  return m;
}

EscParams ToEsc(const std::array<double, kParamCount>& p, const std::optional<EscParams>& prior) {
  EscParams e = prior ? *prior : EscParams{};
  e.resc_ohm = p[4];
  e.c1 = p[5];
  e.c0 = p[6];
  e.tr_sat = p[7];
  e.sat_slope = p[8];
  return e;
}

// Best fit over the knee candidates (and "no knee"); returns the chosen outcome.
SolveOutcome FitWithKnee(const Prepared& pr, const CalibrationOptions& o, bool* knee_found,
                         std::string* knee_note) {
  SolveOutcome best = SolveOnce(pr, o, 1.0, false, pr.start);
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
    SolveOutcome s = SolveOnce(pr, o, ts, true, start);
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

std::vector<double> RowResidualMax(const Prepared& pr, const std::array<double, kParamCount>& p,
                                   bool tie) {
  const FitData& d = pr.data;
  std::vector<double> out(d.rows.size(), 0.0);
  double pred[kMeasCount];
  double qp;
  for (std::size_t k = 0; k < d.rows.size(); ++k) {
    if (!PredictGeneric(p.data(), p[7], tie, d.vdc[k], d.tr[k], d.omega[k], d.q[k], d.torque_known[k] != 0,
                        pred, &qp)) {
      continue;
    }
    for (int t = d.term_begin[k]; t < d.term_begin[k + 1]; ++t) {
      const Term& term = d.terms[t];
      out[k] = std::max(out[k], std::fabs((pred[term.meas] - term.value) * term.inv_scale));
    }
  }
  return out;
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
  }
  return "?";
}

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
  bool knee_found = false;
  std::string knee_note;
  SolveOutcome best = FitWithKnee(pr, options, &knee_found, &knee_note);
  std::size_t outliers = 0;
  if (options.outlier_sigmas > 0.0 && best.summary.IsSolutionUsable()) {
    const std::vector<double> rmax = RowResidualMax(pr, best.params, pr.layout.tie_kt);
    std::vector<double> all;
    for (double v : rmax) all.push_back(v);
    const double sigma = std::max(1.4826 * Median(all), options.outlier_floor_percent);
    std::vector<char> excl(table.rows(), 0);
    for (std::size_t k = 0; k < rmax.size(); ++k) {
      if (rmax[k] > options.outlier_sigmas * sigma) {
        excl[pr.data.rows[k]] = 1;
        ++outliers;
      }
    }
    // Keep at least (free + 2) rows; otherwise the "outliers" are the data.
    if (outliers > 0 && pr.data.rows.size() - outliers >= static_cast<std::size_t>(nfree_base) + 2) {
      // Rows dropped before stay dropped: mark them too.
      std::vector<char> keep(table.rows(), 1);
      for (std::size_t i : pr.data.rows) keep[i] = 0;
      for (std::size_t i = 0; i < table.rows(); ++i) excl[i] = excl[i] || keep[i];
      Prepared pr2 = Prepare(table, options, &excl);
      pr2.dropped = pr.dropped;
      pr2.dropped.push_back({"outlier (residual > outlier_sigmas robust sd)", outliers});
      pr = std::move(pr2);
      best = FitWithKnee(pr, options, &knee_found, &knee_note);
    } else {
      outliers = 0;
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
  res.points_used = pr.data.rows.size();
  for (const auto& dc : pr.dropped) res.points_dropped += dc.count;
  res.warnings = pr.warnings;
  if (!res.converged) res.warnings.push_back("fit did not converge: " + s.message);

  // Per-parameter report.
  std::vector<int> slots;
  {
    Layout lay = pr.layout;
    lay.free[8] = knee_found;
    for (int k = 0; k < kParamCount; ++k) {
      if (lay.free[k]) slots.push_back(k);
    }
  }
  for (int k = 0; k < kParamCount; ++k) {
    ParamEstimate& e = res.params[k];
    e.value = best.params[k];
    e.note = pr.notes[k];
  }
  for (std::size_t sl = 0; sl < slots.size() && sl < static_cast<std::size_t>(s.parameters.size()); ++sl) {
    ParamEstimate& e = res.params[slots[sl]];
    e.fitted = true;
    e.identifiable = true;
    e.standard_error = s.standard_errors.size() > static_cast<Eigen::Index>(sl) ? s.standard_errors[sl] : kNaN;
    e.at_bound = sl < s.at_bound.size() && s.at_bound[sl];
  }
  for (const auto& u : s.unidentifiable) {
    res.unidentifiable_directions.push_back(u.description);
    for (Eigen::Index sl = 0; sl < u.direction.size(); ++sl) {
      if (std::fabs(u.direction[sl]) > 0.2) {
        ParamEstimate& e = res.params[slots[sl]];
        e.identifiable = false;
        e.note = "in a direction the data do not determine: " + u.description;
      }
    }
  }
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
  for (int k = 0; k < kParamCount; ++k) {
    if (res.params[k].at_bound) {
      res.warnings.push_back(std::string(ParamName(static_cast<Param>(k))) + " is at its bound (" +
                             std::to_string(res.params[k].value) + "): the data push it outside the physical range");
    }
  }
  if (pr.has_throttle && pr.levels.size() < 2) {
    res.warnings.push_back("all rows at one throttle level: ESC ratio and saturation not identifiable");
  }
  if (outliers > 0) res.warnings.push_back(std::to_string(outliers) + " outlier row(s) dropped and the fit repeated");

  // Column fit statistics.
  for (int m = 0; m < kMeasCount; ++m) {
    if (!pr.data.measured[m]) continue;
    ColumnFit cf;
    cf.column = kMeasColumn[m];
    double sse = 0.0, ss = 0.0;
    std::vector<double> rel;
    for (std::size_t k = 0; k < pr.data.rows.size(); ++k) {
      const RowPrediction rp = PredictRow(table, pr.data.rows[k], res.motor, res.esc, options.assumed_throttle);
      const double pv[kMeasCount] = {rp.omega_rad_s, rp.idc_a, rp.irms_a, rp.vll_rms_v, rp.pac_w};
      if (!std::isfinite(pv[m])) continue;
      const double meas = table.Get(kMeasColumn[m])[pr.data.rows[k]];
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
  return res;
}

RowPrediction PredictRow(const SteadyTable& t, std::size_t row, const MotorParams& motor, const EscParams& esc,
                         double assumed_throttle) {
  RowPrediction out;
  const double p[kParamCount] = {motor.ke_v_s_per_rad, motor.kt_nm_per_a, motor.rm_ohm, motor.io_a, esc.resc_ohm,
                                 esc.c1, esc.c0, esc.tr_sat, esc.sat_slope};
  const bool has_q = t.Has(Column::kTorqueNm);
  const bool nl = t.Has(Column::kNoLoad) && t.Get(Column::kNoLoad)[row] != 0.0;
  const bool tq = has_q || nl;
  const double tr = t.Has(Column::kThrottle) ? t.Get(Column::kThrottle)[row] : assumed_throttle;
  double pred[kMeasCount], qp;
  if (!PredictGeneric(p, esc.tr_sat, false, t.Get(Column::kVdcV)[row], tr, t.Get(Column::kOmegaRadS)[row],
                      has_q ? t.Get(Column::kTorqueNm)[row] : 0.0, tq, pred, &qp)) {
    return out;
  }
  if (tq) out.omega_rad_s = pred[kMOmega];
  {
    const double tre = EffThrottle(tr, esc.tr_sat, esc.sat_slope);
    const double g = esc.c1 * tre + esc.c0;
    const double u = kVllRmsPerVdc * t.Get(Column::kVdcV)[row] * tre;
    if (g > 0.0 && motor.ke_v_s_per_rad > 0.0) {
      out.omega_from_idc_rad_s = (u - (motor.rm_ohm + esc.resc_ohm) * t.Get(Column::kIdcA)[row] / g) / motor.ke_v_s_per_rad;
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
  for (const auto& u : unidentifiable_directions) s << "  unidentifiable: " << u << "\n";
  for (const auto& w : warnings) s << "  warning: " << w << "\n";
  return s.str();
}

CrossValidation LeaveOneOut(const SteadyTable& t, const CalibrationOptions& options, bool by_throttle) {
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
  const bool has_q = t.Has(Column::kTorqueNm);
  const bool has_nl = t.Has(Column::kNoLoad);
  double wmax = 0.0;
  for (double w : t.Get(Column::kOmegaRadS)) wmax = std::max(wmax, w);
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
    for (std::size_t i : test) {
      const double w = t.Get(Column::kOmegaRadS)[i];
      const bool no_load = has_nl && t.Get(Column::kNoLoad)[i] != 0.0;
      const bool speed_unknown = no_load && w == 0.0;  // see Prepare(): current only
      if (!speed_unknown && !(w > options.min_speed_fraction * wmax)) continue;
      if (t.Has(Column::kThrottle) && t.Get(Column::kThrottle)[i] < options.min_throttle) continue;
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

SteadyTable SelectRows(const SteadyTable& t, const std::vector<std::size_t>& keep) {
  SteadyTable out = t;
  for (int c = 0; c < logs::kColumnCount; ++c) {
    auto& col = out.columns[c];
    col.clear();
    if (!t.info[c].present) continue;
    for (std::size_t i : keep) col.push_back(t.columns[c][i]);
  }
  out.source_line.clear();
  out.samples.clear();
  for (std::size_t i : keep) {
    out.source_line.push_back(t.source_line[i]);
    out.samples.push_back(i < t.samples.size() ? t.samples[i] : 1);
  }
  return out;
}

SteadyTable MergeLogs(const std::vector<SteadyTable>& tables) {
  if (tables.empty()) throw UsageError("no log to calibrate");
  if (tables.size() == 1) return tables[0];
  SteadyTable out = tables[0];
  for (std::size_t k = 1; k < tables.size(); ++k) {
    const SteadyTable& t = tables[k];
    out.file += ", " + t.file;
    for (int c = 0; c < logs::kColumnCount; ++c) {
      if (!out.info[c].present) continue;
      if (!t.info[c].present) {
        out.info[c].present = false;
        out.info[c].note = std::string("absent from ") + t.file;
        out.columns[c].clear();
        continue;
      }
      out.columns[c].insert(out.columns[c].end(), t.columns[c].begin(), t.columns[c].end());
    }
    out.source_line.insert(out.source_line.end(), t.source_line.begin(), t.source_line.end());
    for (std::size_t i = 0; i < t.rows(); ++i) out.samples.push_back(i < t.samples.size() ? t.samples[i] : 1);
    for (const auto& d : t.dropped) logs::AddDrop(&out, d.reason, d.count);
  }
  return out;
}

}  // namespace dynosize::calibration
