#include "stand/in_system_fit.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "catalog/catalog.h"
#include "catalog/conventions.h"
#include "common/error.h"
#include "common/units.h"
#include "fit/nonlinear_least_squares.h"
#include "fit/statistics.h"
#include "model/drive.h"

namespace dynosize::stand {

namespace {

// Relative residuals beyond this count linearly (soft-L1): the sheets print torque to 0.01 N*m,
// which at the lowest commands of the small motors is a 10-30 % error of the point itself.
constexpr double kResidualLossScale = 0.05;
// Points whose needed effective throttle is this close to 1 say nothing about a dead band
// ((TR - TR_eff)/(1 - TR_eff) divides by the distance).
constexpr double kDeadbandMaxEffectiveThrottle = 0.95;

// The datasheet motor in the catalog's rms circuit (catalog/conventions.h 1., docs/model.md section 8).
MotorParams RawParams(const DatasheetMotor& ds) {
  MotorParams p;
  p.ke_v_s_per_rad = KeFromKvBldc(ds.kv_rpm_per_v);
  p.kt_nm_per_a = kPacPerVllIrms * p.ke_v_s_per_rad;  // section 5: ideal waveforms
  p.rm_ohm = RmsCircuitResistanceFromDc(ds.r_dc_ohm);
  p.io_a = RmsNoLoadCurrentFromDc(ds.io_dc_a);
  return p;
}

Drive LawDrive(const LawMotor& m, const InSystemLaw& law, double ratio_r, double ratio_io,
               double deadband = 0.0) {
  EscParams esc;  // the ideal ESC of eq (56)
  esc.deadband = deadband;
  return Drive(InSystemMotorParams(RawParams(m.datasheet), m.datasheet, law, true, true, ratio_r, ratio_io), esc);
}

bool Usable(const LawPoint& p) {
  return std::isfinite(p.torque_nm) && p.torque_nm > 0.0 && p.idc_a > 0.0 && p.omega_rad_s > 0.0 &&
         p.vdc_v > 0.0;
}

int UsableCount(const LawMotor& m) {
  int n = 0;
  for (const auto& p : m.points) n += Usable(p) ? 1 : 0;
  return n;
}

// Fits the free entries of `x` (law coefficients or ratios) by soft-L1 least squares of the
// relative current errors; `law_of` maps x to (law, ratio_r, ratio_io).
struct Mapped {
  InSystemLaw law;
  double ratio_r = 1.0, ratio_io = 1.0;
};
template <typename MapFn>
Eigen::VectorXd FitRelativeCurrent(const std::vector<const LawMotor*>& motors, MapFn law_of,
                                   Eigen::VectorXd x, const Eigen::VectorXd& lo,
                                   const Eigen::VectorXd& hi) {
  int total = 0;
  for (const LawMotor* m : motors) total += UsableCount(*m);
  if (total <= x.size()) throw DataError("in-system law: " + std::to_string(total) + " usable points for " + std::to_string(x.size()) + " coefficients");
  const double mean_n = static_cast<double>(total) / static_cast<double>(motors.size());
  LeastSquaresProblem pr;
  pr.num_residuals = total;
  pr.num_parameters = static_cast<int>(x.size());
  pr.lower_bounds = lo;
  pr.upper_bounds = hi;
  pr.residuals = NumericDiffResiduals([&](const Eigen::VectorXd& v, Eigen::VectorXd* r) {
    const Mapped mp = law_of(v);
    int i = 0;
    for (const LawMotor* m : motors) {
      const double w = std::sqrt(mean_n / UsableCount(*m));  // every motor alike
      const Drive d = LawDrive(*m, mp.law, mp.ratio_r, mp.ratio_io);
      for (const auto& p : m->points) {
        if (!Usable(p)) continue;
        (*r)[i++] = w * (d.InverseLight(p.vdc_v, p.torque_nm, p.omega_rad_s).idc_a / p.idc_a - 1.0);
      }
    }
    return r->allFinite();
  });
  LevenbergMarquardtOptions opt;
  opt.loss = LossType::kSoftL1;
  opt.loss_scale = kResidualLossScale;
  SolveLeastSquares(pr, opt, &x);
  return x;
}

// Lower-case letters and digits only, "goldline" dropped (FAST-UAV writes "AXI 2814/20 GOLD LINE",
// DriveCalc "AXI 2814-20").
std::string NameKey(const std::string& name) {
  std::string k;
  for (char ch : name) {
    if (std::isalnum(static_cast<unsigned char>(ch))) k += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  }
  const auto g = k.find("goldline");
  if (g != std::string::npos) k.erase(g, 8);
  return k;
}


}  // namespace

std::string LawForm::Describe() const {
  std::string s = "R_dc,sys = r_scale*R_dc";
  if (r_add) s += " + r_add";
  s += "; Io_dc,sys = Io_dc*(io_scale";
  if (io_speed) s += " + io_speed*omega/omega_test";
  return s + ")";
}

double PredictIdc(const LawMotor& motor, const InSystemLaw& law, const LawPoint& p, double ratio_r,
                  double ratio_io) {
  return LawDrive(motor, law, ratio_r, ratio_io).InverseLight(p.vdc_v, p.torque_nm, p.omega_rad_s).idc_a;
}

InSystemLaw FitLaw(const std::vector<LawMotor>& motors, const LawForm& form, int leave_out) {
  std::vector<const LawMotor*> use;
  for (int i = 0; i < static_cast<int>(motors.size()); ++i) {
    if (i != leave_out) use.push_back(&motors[static_cast<std::size_t>(i)]);
  }
  // x = [r_scale, io_scale, (r_add), (io_speed)].
  const int n = 2 + (form.r_add ? 1 : 0) + (form.io_speed ? 1 : 0);
  Eigen::VectorXd x(n), lo(n), hi(n);
  x << 1.5, 2.0, Eigen::VectorXd::Constant(n - 2, 0.01);
  lo << 0.5, 0.2, Eigen::VectorXd::Zero(n - 2);
  hi << 6.0, 10.0, Eigen::VectorXd::Constant(n - 2, 5.0);  // r_add ohm, io_speed per unit
  auto law_of = [&](const Eigen::VectorXd& v) {
    Mapped m;
    m.law.r_scale = v[0];
    m.law.io_scale = v[1];
    int k = 2;
    if (form.r_add) m.law.r_add_ohm = v[k++];
    if (form.io_speed) m.law.io_speed = v[k++];
    return m;
  };
  x = FitRelativeCurrent(use, law_of, x, lo, hi);
  InSystemLaw law = law_of(x).law;
  law.motors = static_cast<int>(use.size());
  return law;
}

MotorRatios FitMotorRatios(const LawMotor& motor, const InSystemLaw& law) {
  Eigen::VectorXd x(2), lo(2), hi(2);
  x << 1.0, 1.0;
  lo << 0.05, 0.05;
  hi << 20.0, 20.0;
  auto law_of = [&](const Eigen::VectorXd& v) { return Mapped{law, v[0], v[1]}; };
  x = FitRelativeCurrent({&motor}, law_of, x, lo, hi);
  return {x[0], x[1]};
}

SweepErrors CurrentErrorsBySweep(const LawMotor& motor, const InSystemLaw& law) {
  const Drive d = LawDrive(motor, law, 1.0, 1.0);
  std::map<int, std::vector<double>> by_sweep;
  for (const auto& p : motor.points) {
    if (!Usable(p)) continue;
    by_sweep[p.sweep].push_back(d.InverseLight(p.vdc_v, p.torque_nm, p.omega_rad_s).idc_a / p.idc_a - 1.0);
  }
  SweepErrors e;
  for (const auto& [s, v] : by_sweep) {
    e.median_abs.push_back(fit::MedianAbs(v));
    e.median_signed.push_back(fit::Median(v));
  }
  return e;
}

double FitMotorDeadband(const LawMotor& motor, const InSystemLaw& law) {
  const MotorRatios own = FitMotorRatios(motor, law);
  const Drive d = LawDrive(motor, law, own.r_ratio, own.io_ratio);
  std::vector<double> db;
  for (const auto& p : motor.points) {
    if (!Usable(p)) continue;
    const double tr_eff = d.InverseLight(p.vdc_v, p.torque_nm, p.omega_rad_s).throttle;
    // TR_eff = (TR - db)/(1 - db) (docs/model.md section 9, Drive::EffectiveThrottle) solved for db.
    if (tr_eff < kDeadbandMaxEffectiveThrottle) db.push_back((p.throttle - tr_eff) / (1.0 - tr_eff));
  }
  return db.empty() ? 0.0 : fit::Median(db);
}

double ForwardSpeedError(const LawMotor& motor, const InSystemLaw& law, double deadband) {
  const Drive d = LawDrive(motor, law, 1.0, 1.0, deadband);
  std::map<int, std::vector<double>> by_sweep;
  for (const auto& p : motor.points) {
    if (!Usable(p)) continue;
    const OperatingPoint op = d.AtTorque(p.vdc_v, p.throttle, p.torque_nm);
    by_sweep[p.sweep].push_back(op.omega_rad_s / p.omega_rad_s - 1.0);
  }
  std::vector<double> med;
  for (const auto& [s, v] : by_sweep) med.push_back(fit::MedianAbs(v));
  return fit::Median(med);
}

namespace {

void SetSpreads(const std::vector<MotorRatios>& ratios, InSystemLaw* law) {
  std::vector<double> r, io;
  for (const auto& x : ratios) {
    r.push_back(x.r_ratio);
    io.push_back(x.io_ratio);
  }
  law->r_ratio_p10 = fit::Quantile(r, 0.1);
  law->r_ratio_p90 = fit::Quantile(r, 0.9);
  law->io_ratio_p10 = fit::Quantile(io, 0.1);
  law->io_ratio_p90 = fit::Quantile(io, 0.9);
}

LeftOutCheck CheckLeftOut(const std::vector<LawMotor>& motors, const LawForm& form, int m) {
  const LawMotor& motor = motors[static_cast<std::size_t>(m)];
  LeftOutCheck c;
  c.name = motor.name;
  c.law = FitLaw(motors, form, m);
  std::vector<MotorRatios> others;
  std::vector<double> deadbands;
  for (int k = 0; k < static_cast<int>(motors.size()); ++k) {
    if (k == m) continue;
    others.push_back(FitMotorRatios(motors[static_cast<std::size_t>(k)], c.law));
    deadbands.push_back(FitMotorDeadband(motors[static_cast<std::size_t>(k)], c.law));
  }
  SetSpreads(others, &c.law);
  c.own = FitMotorRatios(motor, c.law);
  const SweepErrors ds = CurrentErrorsBySweep(motor, InSystemLaw{});
  const SweepErrors lw = CurrentErrorsBySweep(motor, c.law);
  c.sweeps = static_cast<int>(lw.median_abs.size());
  c.datasheet_error = fit::Median(ds.median_abs);
  c.datasheet_bias = fit::Median(ds.median_signed);
  c.law_error = fit::Median(lw.median_abs);
  c.law_bias = fit::Median(lw.median_signed);
  int inside = 0;
  const Drive lo = LawDrive(motor, c.law, c.law.r_ratio_p10, c.law.io_ratio_p10);
  const Drive hi = LawDrive(motor, c.law, c.law.r_ratio_p90, c.law.io_ratio_p90);
  for (const auto& p : motor.points) {
    if (!Usable(p)) continue;
    ++c.points;
    const double a = lo.InverseLight(p.vdc_v, p.torque_nm, p.omega_rad_s).idc_a;
    const double b = hi.InverseLight(p.vdc_v, p.torque_nm, p.omega_rad_s).idc_a;
    inside += p.idc_a >= std::min(a, b) && p.idc_a <= std::max(a, b) ? 1 : 0;
  }
  c.coverage = c.points ? static_cast<double>(inside) / c.points : 0.0;
  c.deadband_prior = fit::Median(deadbands);
  c.rpm_error_forward = ForwardSpeedError(motor, c.law, c.deadband_prior);
  return c;
}

}  // namespace

LawReport LeaveOneMotorOut(const std::vector<LawMotor>& motors, const LawForm& form) {
  if (motors.size() < 3) throw DataError("in-system law: leaving one out needs at least 3 motors with torque");
  LawReport rep;
  rep.form = form;
  rep.law = FitLaw(motors, form);
  std::vector<MotorRatios> all;
  std::vector<double> deadbands;
  for (const auto& m : motors) {
    all.push_back(FitMotorRatios(m, rep.law));
    deadbands.push_back(FitMotorDeadband(m, rep.law));
  }
  SetSpreads(all, &rep.law);
  rep.throttle.deadband_p10 = fit::Quantile(deadbands, 0.1);
  rep.throttle.deadband_p50 = fit::Quantile(deadbands, 0.5);
  rep.throttle.deadband_p90 = fit::Quantile(deadbands, 0.9);
  rep.throttle.motors = static_cast<int>(motors.size());
  std::vector<double> ds_abs, ds_sig, lw_abs, lw_sig, rpm;
  int inside = 0;
  for (int m = 0; m < static_cast<int>(motors.size()); ++m) {
    rep.left_out.push_back(CheckLeftOut(motors, form, m));
    const LeftOutCheck& c = rep.left_out.back();
    const SweepErrors ds = CurrentErrorsBySweep(motors[static_cast<std::size_t>(m)], InSystemLaw{});
    const SweepErrors lw = CurrentErrorsBySweep(motors[static_cast<std::size_t>(m)], c.law);
    ds_abs.insert(ds_abs.end(), ds.median_abs.begin(), ds.median_abs.end());
    ds_sig.insert(ds_sig.end(), ds.median_signed.begin(), ds.median_signed.end());
    lw_abs.insert(lw_abs.end(), lw.median_abs.begin(), lw.median_abs.end());
    lw_sig.insert(lw_sig.end(), lw.median_signed.begin(), lw.median_signed.end());
    rpm.push_back(c.rpm_error_forward);
    rep.points += c.points;
    rep.sweeps += c.sweeps;
    inside += static_cast<int>(std::lround(c.coverage * c.points));
  }
  rep.datasheet_error = fit::Median(ds_abs);
  rep.datasheet_bias = fit::Median(ds_sig);
  rep.law_error = fit::Median(lw_abs);
  rep.law_bias = fit::Median(lw_sig);
  rep.coverage = rep.points ? static_cast<double>(inside) / rep.points : 0.0;
  rep.rpm_error_forward = fit::Median(rpm);
  return rep;
}

namespace {

InSystemLaw FitRefitSubset(const std::vector<const RefitPair*>& pairs) {
  LeastSquaresProblem pr;
  pr.num_residuals = static_cast<int>(pairs.size());
  pr.num_parameters = 2;
  pr.lower_bounds = Eigen::Vector2d(0.2, 0.0);
  pr.upper_bounds = Eigen::Vector2d(10.0, 1.0);
  pr.residuals = AutoDiffResiduals<2>(
      [&pairs](const auto* x, auto* r) {
        for (std::size_t i = 0; i < pairs.size(); ++i) {
          r[i] = (x[0] * pairs[i]->r_dc_datasheet_ohm + x[1]) / pairs[i]->r_dc_refit_ohm - 1.0;
        }
        return true;
      },
      2);
  LevenbergMarquardtOptions opt;
  opt.loss = LossType::kSoftL1;
  opt.loss_scale = 0.1;  // refits of 3-10 points: a tenth is their typical R error
  Eigen::VectorXd x = Eigen::Vector2d(1.0, 0.01);
  SolveLeastSquares(pr, opt, &x);
  InSystemLaw law;
  law.r_scale = x[0];
  law.r_add_ohm = x[1];
  std::vector<double> io, rr, ir;
  for (const RefitPair* p : pairs) io.push_back(p->io_dc_refit_a / p->io_dc_datasheet_a);
  law.io_scale = fit::Median(io);
  for (const RefitPair* p : pairs) {
    rr.push_back(p->r_dc_refit_ohm / (law.r_scale * p->r_dc_datasheet_ohm + law.r_add_ohm));
    ir.push_back(p->io_dc_refit_a / (law.io_scale * p->io_dc_datasheet_a));
  }
  law.r_ratio_p10 = fit::Quantile(rr, 0.1);
  law.r_ratio_p90 = fit::Quantile(rr, 0.9);
  law.io_ratio_p10 = fit::Quantile(ir, 0.1);
  law.io_ratio_p90 = fit::Quantile(ir, 0.9);
  law.motors = static_cast<int>(pairs.size());
  return law;
}

}  // namespace

InSystemLaw FitLawFromRefits(const std::vector<RefitPair>& pairs, RefitLawCheck* held_out) {
  std::vector<const RefitPair*> use;
  for (const auto& p : pairs) {
    if (p.r_dc_datasheet_ohm > 0 && p.r_dc_refit_ohm > 0 && p.io_dc_datasheet_a > 0 && p.io_dc_refit_a > 0) {
      use.push_back(&p);
    }
  }
  if (use.size() < 20) throw DataError("in-system law: " + std::to_string(use.size()) + " refit pairs (at least 20 needed)");
  const InSystemLaw law = FitRefitSubset(use);
  if (held_out != nullptr) {
    constexpr int kFolds = 10;
    std::vector<double> e_law, e_ds;
    int in_r = 0, in_io = 0;
    for (int f = 0; f < kFolds; ++f) {
      std::vector<const RefitPair*> train, test;
      for (std::size_t i = 0; i < use.size(); ++i) (static_cast<int>(i % kFolds) == f ? test : train).push_back(use[i]);
      const InSystemLaw l = FitRefitSubset(train);
      for (const RefitPair* p : test) {
        const double r_pred = l.r_scale * p->r_dc_datasheet_ohm + l.r_add_ohm;
        const double io_pred = l.io_scale * p->io_dc_datasheet_a;
        e_law.push_back(r_pred / p->r_dc_refit_ohm - 1.0);
        e_ds.push_back(p->r_dc_datasheet_ohm / p->r_dc_refit_ohm - 1.0);
        in_r += p->r_dc_refit_ohm >= l.r_ratio_p10 * r_pred && p->r_dc_refit_ohm <= l.r_ratio_p90 * r_pred;
        in_io += p->io_dc_refit_a >= l.io_ratio_p10 * io_pred && p->io_dc_refit_a <= l.io_ratio_p90 * io_pred;
      }
    }
    held_out->pairs = static_cast<int>(use.size());
    held_out->r_error_law = fit::MedianAbs(e_law);
    held_out->r_error_datasheet = fit::MedianAbs(e_ds);
    held_out->r_bias_law = fit::Median(e_law);
    held_out->r_bias_datasheet = fit::Median(e_ds);
    held_out->coverage_r = static_cast<double>(in_r) / static_cast<double>(use.size());
    held_out->coverage_io = static_cast<double>(in_io) / static_cast<double>(use.size());
  }
  return law;
}

RefitErrors EvaluateOnRefits(const std::vector<RefitPair>& pairs, const InSystemLaw& law) {
  std::vector<double> er, ei;
  int in_r = 0, in_io = 0;
  for (const auto& p : pairs) {
    const double r_pred = law.r_scale * p.r_dc_datasheet_ohm + law.r_add_ohm;
    const double io_pred = law.io_scale * p.io_dc_datasheet_a;  // at the database's test speed
    er.push_back(r_pred / p.r_dc_refit_ohm - 1.0);
    ei.push_back(io_pred / p.io_dc_refit_a - 1.0);
    in_r += p.r_dc_refit_ohm >= law.r_ratio_p10 * r_pred && p.r_dc_refit_ohm <= law.r_ratio_p90 * r_pred;
    in_io += p.io_dc_refit_a >= law.io_ratio_p10 * io_pred && p.io_dc_refit_a <= law.io_ratio_p90 * io_pred;
  }
  RefitErrors e;
  e.pairs = static_cast<int>(pairs.size());
  if (pairs.empty()) return e;
  e.r_error = fit::MedianAbs(er);
  e.r_bias = fit::Median(er);
  e.io_error = fit::MedianAbs(ei);
  e.io_bias = fit::Median(ei);
  e.coverage_r = static_cast<double>(in_r) / static_cast<double>(pairs.size());
  e.coverage_io = static_cast<double>(in_io) / static_cast<double>(pairs.size());
  return e;
}

// DriveCalc's database motors beside their refits (drivecalc.json "dc_m_N", drivecalc_fitted.json
// "dc_m_N_fit"), both as the files state them (no law applied).
std::vector<RefitPair> DriveCalcRefitPairs(const Catalog& raw) {
  std::map<std::string, const MotorEntry*> by_id;
  for (const auto& m : raw.motors()) by_id[m.id] = &m;
  std::vector<RefitPair> out;
  const std::string suffix = "_fit";
  for (const auto& fit : raw.motors()) {
    if (fit.id.size() <= suffix.size() || fit.id.compare(fit.id.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    const auto db = by_id.find(fit.id.substr(0, fit.id.size() - suffix.size()));
    if (db == by_id.end() || db->second->params.type != MotorType::kBldc) continue;
    const InSystemApplicability a = InSystemApplicabilityOf(*db->second);
    if (!a.r || !a.io) continue;
    out.push_back({db->first, a.datasheet.r_dc_ohm, a.datasheet.io_dc_a, fit.params.rm_ohm / kRmsPerDcResistance,
                   fit.params.io_a * kIdealIdcPerIrmsPerThrottle});
  }
  return out;
}

// Manufacturer-stated motors of another maker than KDE (FAST-UAV's datasheet copies) that
// DriveCalc measured: the same name (NameKey equal, or contained in DriveCalc's) and Kv within 5 %.
std::vector<RefitPair> ManufacturerRefitPairs(const Catalog& raw, const std::vector<RefitPair>& drivecalc) {
  std::vector<RefitPair> out;
  for (const auto& m : raw.motors()) {
    if (m.tier != DataTier::kManufacturerStated || IsKdeDirectName(m.name) || !m.kv_rpm_per_v) continue;
    const InSystemApplicability a = InSystemApplicabilityOf(m);
    if (!a.r || !a.io) continue;
    const std::string key = NameKey(m.name);
    if (key.size() < 6) continue;
    for (const auto& d : drivecalc) {
      const MotorEntry& db = raw.motor(d.id);
      if (!db.kv_rpm_per_v || std::fabs(*db.kv_rpm_per_v / *m.kv_rpm_per_v - 1.0) > 0.05) continue;
      const std::string dk = NameKey(db.name);
      if (dk != key && dk.find(key) == std::string::npos) continue;
      out.push_back({m.id, a.datasheet.r_dc_ohm, a.datasheet.io_dc_a, d.r_dc_refit_ohm, d.io_dc_refit_a});
      break;
    }
  }
  return out;
}

}  // namespace dynosize::stand
