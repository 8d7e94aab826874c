#include "calibration/forward_model.h"

#include <Eigen/Core>
#include <algorithm>

#include "common/units.h"
#include "logs/steady_table.h"

namespace dynosize::calibration {
namespace internal {
namespace {

template <typename T>
bool Residuals(const FitData& d, const Layout& lay, const std::array<double, kBaseParamCount>& fixed,
               const T* x, T* r) {
  T p[kBaseParamCount];
  for (int k = 0; k < kBaseParamCount; ++k) p[k] = T(fixed[k]);
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

// Bounds of each internal parameter: the physical box of identification/parameters.h, with the
// KT slot bounded as the ratio f and the C1 slot as the excess s (docs/model.md section 10).
constexpr std::array<double, kBaseParamCount> MakeLower() {
  std::array<double, kBaseParamCount> b{};
  for (int k = 0; k < kBaseParamCount; ++k) b[k] = identification::kParamTable[k].lower;
  return b;
}

constexpr std::array<double, kBaseParamCount> MakeUpper() {
  std::array<double, kBaseParamCount> b{};
  for (int k = 0; k < kBaseParamCount; ++k) b[k] = identification::kParamTable[k].upper;
  return b;
}

}  // namespace

const Params kLower = MakeLower();
const Params kUpper = MakeUpper();

// The fit's parameter vector ("internal", identification/parameters.h): slot kKt holds the
// ratio f = KT/(kp*KE) (1 when KT is tied to KE), slot kC1 the ESC excess s = c1 + c0 - 1.1095.
// Both keep the energy rules of docs/model.md section 10 as box bounds.
std::array<double, kBaseParamCount> ToInternal(const MotorParams& m, const EscParams& e) {
  std::array<double, kBaseParamCount> p{};
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

ResidualFunction MakeResidualFunction(const FitData& d, const Layout& lay,
                                      const std::array<double, kBaseParamCount>& fixed) {
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

// Physical parameters of the internal vector (KT = kp*KE*f, c1 = 1.1095 + s - c0).
MotorParams ToMotor(const std::array<double, kBaseParamCount>& p) {
  MotorParams m;
  m.ke_v_s_per_rad = p[0];
  m.kt_nm_per_a = KtFromRatio(p[kKeI], p[kKtI]);
  m.rm_ohm = p[2];
  m.io_a = p[3];
  return m;
}

EscParams ToEsc(const std::array<double, kBaseParamCount>& p, const std::optional<EscParams>& prior) {
  EscParams e = prior ? *prior : EscParams{};
  e.resc_ohm = p[4];
  e.c1 = C1FromExcess(p[kC1I], p[kC0I]);
  e.c0 = p[kC0I];
  e.tr_sat = p[7];
  e.sat_slope = p[8];
  e.deadband = p[kDbI];
  return e;
}

}  // namespace internal
}  // namespace dynosize::calibration

