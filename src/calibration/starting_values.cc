#include "calibration/starting_values.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "catalog/noload_prior.h"
#include "common/units.h"
#include "fit/linear_least_squares.h"
#include "fit/statistics.h"

namespace dynosize::calibration::internal {

using fit::Median;
using logs::Column;
using logs::SteadyTable;

namespace {

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
                 std::array<double, kBaseParamCount>* start) {
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
                  std::array<double, kBaseParamCount>* start) {
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

}  // namespace

// Prepare, stage 4: starting values (linear sub-problems) and held values (priors), returned in
// the internal form (KT as the ratio f, C1 as the excess s) inside the box.
void StartingValues(const SteadyTable& t, const CalibrationOptions& o, const LogColumns& c, Prepared* pr) {
  const FitData& d = pr->data;
  const std::size_t n = d.rows();
  const auto& fr = pr->layout.free;
  auto idx = [](Param q) { return static_cast<int>(q); };
  std::array<double, kBaseParamCount>& p = pr->start;
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
  for (int k = 0; k < kBaseParamCount; ++k) p[k] = std::clamp(p[k], kLower[k], kUpper[k]);
  if (p[idx(Param::kRm)] + p[idx(Param::kResc)] < 1e-4) p[idx(Param::kRm)] = 1e-4 + 0.01 * p[idx(Param::kRm)];
}

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
}  // namespace dynosize::calibration::internal
