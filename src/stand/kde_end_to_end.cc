#include "stand/kde_end_to_end.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "catalog/in_system.h"
#include "common/atmosphere.h"
#include "common/error.h"
#include "common/units.h"
#include "fit/statistics.h"
#include "model/dc_motor.h"
#include "model/drive.h"
#include "prop/prop_drive.h"
#include "prop/prop_model.h"
#include "stand/dc_baseline.h"

namespace dynosize::stand {

namespace {

// Rows below this measured thrust do not enter the sea-level ratio (the sheets print thrust in
// grams; below 2 N the rounding is a visible share of the ratio), as in importers/kde_catalog.cc.
constexpr double kMinThrustForDensityN = 2.0;

struct Prediction {
  double thrust_n = 0.0, idc_a = 0.0, omega_rad_s = 0.0;
  bool ok = false;
};

// The rms model (eqs 42-59) forward at the command: drive torque = propeller torque.
Prediction PredictRms(const Drive& drive, const PropModel& prop, const KdeSheetRow& r, double rho) {
  const PropDrivePoint p = SolveDriveWithProp(drive, prop, r.vdc_v, r.throttle, rho);
  return {p.prop.thrust_n, p.drive.idc_a, p.drive.omega_rad_s, p.converged};
}

// The plain DC model forward at the command (model/dc_motor.h DcAtThrottleLoad, by bisection).
Prediction PredictPlainDc(const DcMotor& dc, const PropModel& prop, const KdeSheetRow& r, double rho) {
  const DcPoint p = DcAtThrottleLoad(dc, r.vdc_v, r.throttle,
                                     [&](double w) { return prop.Evaluate(w, rho).torque_nm; });
  return {prop.Evaluate(p.omega_rad_s, rho).thrust_n, p.idc_a, p.omega_rad_s, p.omega_rad_s > 0.0};
}

bool Usable(const KdeSheetRow& r) {
  return r.vdc_v > 0.0 && r.throttle > 0.0 && r.throttle <= 1.0 && r.idc_a > 0.0 && r.rpm > 0.0 &&
         r.thrust_n > 0.0;
}

// Relative errors of one column over one sweep's rows.
struct ColumnErrors {
  std::vector<double> thrust, idc, rpm;
  void Add(const Prediction& p, const KdeSheetRow& r) {
    thrust.push_back(p.thrust_n / r.thrust_n - 1.0);
    idc.push_back(p.idc_a / r.idc_a - 1.0);
    rpm.push_back(RadPerSecToRpm(p.omega_rad_s) / r.rpm - 1.0);
  }
};

void Append(const std::vector<double>& from, std::vector<double>* to) {
  to->insert(to->end(), from.begin(), from.end());
}

// Per-sweep medians |.| (and signed) of every sweep of a set (a motor, or all motors), per column.
struct SweepMedians {
  std::vector<double> thrust, idc, rpm, thrust_s, idc_s, rpm_s;
  void Add(const ColumnErrors& e) {
    thrust.push_back(fit::MedianAbs(e.thrust));
    idc.push_back(fit::MedianAbs(e.idc));
    rpm.push_back(fit::MedianAbs(e.rpm));
    thrust_s.push_back(fit::Median(e.thrust));
    idc_s.push_back(fit::Median(e.idc));
    rpm_s.push_back(fit::Median(e.rpm));
  }
  void Append(const SweepMedians& o) {
    stand::Append(o.thrust, &thrust);
    stand::Append(o.idc, &idc);
    stand::Append(o.rpm, &rpm);
    stand::Append(o.thrust_s, &thrust_s);
    stand::Append(o.idc_s, &idc_s);
    stand::Append(o.rpm_s, &rpm_s);
  }
  ThrustCurrentSpeedErrors Summary() const {
    if (thrust.empty()) return {NAN, NAN, NAN, NAN, NAN, NAN};
    return {fit::Median(thrust), fit::Median(idc),      fit::Median(rpm),
            fit::Median(thrust_s), fit::Median(idc_s), fit::Median(rpm_s)};
  }
};

struct MotorSweepMedians {
  SweepMedians dynosize, plain_dc, rms_datasheet;
};

// What one motor is predicted with.
struct MotorSetup {
  const MotorEntry* entry = nullptr;  // the raw catalog entry (datasheet values)
  InSystemLaw law;                    // fitted without this motor
  double deadband = 0.0;
};

// Predicts every sweep of one motor with the three models; fills the counts of *out.
MotorSweepMedians EvaluateMotor(const KdeSheetMotor& sheet, const MotorSetup& setup, const EscEntry& esc,
                                const Catalog& raw, const std::set<std::string>& prop_ids,
                                double rho, KdeEndToEndMotor* out, std::vector<std::string>* skipped) {
  const InSystemApplicability a = InSystemApplicabilityOf(*setup.entry);
  EscParams esc_params = esc.params;
  esc_params.deadband = setup.deadband;
  const Drive law_drive(InSystemMotorParams(setup.entry->params, a.datasheet, setup.law, a.r, a.io), esc_params);
  const Drive rms_drive(setup.entry->params, esc_params);
  const DcMotor dc = DcMotorFromCatalog(*setup.entry, esc, DcBaselineNumbers::kDatasheet);

  std::map<int, std::vector<const KdeSheetRow*>> by_sweep;
  for (const auto& r : sheet.rows) by_sweep[r.block].push_back(&r);
  MotorSweepMedians med;
  for (const auto& [block, rows] : by_sweep) {
    const std::string label = rows.front()->prop;
    const std::string id = KdePropId(label);
    if (id.empty() || prop_ids.count(id) == 0) {
      ++out->sweeps_without_prop;
      skipped->push_back(sheet.name + " sweep " + std::to_string(block) + " (prop \"" + label +
                         "\"): no catalog propeller " + (id.empty() ? "(label not read)" : id));
      continue;
    }
    const PropModel prop(raw.prop(id));
    ColumnErrors law_e, dc_e, rms_e;
    for (const KdeSheetRow* r : rows) {
      if (!Usable(*r)) continue;
      const Prediction pl = PredictRms(law_drive, prop, *r, rho);
      const Prediction pd = PredictPlainDc(dc, prop, *r, rho);
      const Prediction pr = PredictRms(rms_drive, prop, *r, rho);
      if (!pl.ok || !pd.ok || !pr.ok) {
        ++out->unconverged;
        continue;
      }
      law_e.Add(pl, *r);
      dc_e.Add(pd, *r);
      rms_e.Add(pr, *r);
      ++out->points;
    }
    if (law_e.idc.empty()) continue;
    ++out->sweeps;
    med.dynosize.Add(law_e);
    med.plain_dc.Add(dc_e);
    med.rms_datasheet.Add(rms_e);
  }
  out->dynosize = med.dynosize.Summary();
  out->plain_dc = med.plain_dc.Summary();
  out->rms_datasheet = med.rms_datasheet.Summary();
  return med;
}

LawMotor LawMotorOf(const KdeSheetMotor& k) {
  LawMotor m{k.name, {k.kv_rpm_per_v, k.r_dc_ohm, k.io_dc_a, k.io_test_voltage_v}, {}};
  for (const auto& r : k.rows) {
    m.points.push_back({r.vdc_v, r.throttle, r.idc_a, RpmToRadPerSec(r.rpm), r.torque_nm, r.block});
  }
  return m;
}

// The catalog's entry of a sheet's motor: KDE's own datasheet copy (heavy_lift_motors.json,
// "hl_m_..."), else any KDE entry of the same name (FAST-UAV's copies state the same R and Io
// with another test voltage).
const MotorEntry* FindKdeMotor(const Catalog& raw, const std::string& name) {
  const MotorEntry* any = nullptr;
  for (const auto& m : raw.motors()) {
    if (m.name != name || !IsKdeDirectName(m.name)) continue;
    if (m.id.rfind("hl_m_", 0) == 0) return &m;
    if (any == nullptr) any = &m;
  }
  return any;
}

std::string Percent(double x) {
  if (!std::isfinite(x)) return "-";
  char b[16];
  std::snprintf(b, sizeof b, "%.1f %%", 100.0 * x);
  return b;
}

std::string SignedPercent(double x) {
  return std::isfinite(x) && x > 0.0 ? "+" + Percent(x) : Percent(x);
}

std::string Cell(const ThrustCurrentSpeedErrors& e) {
  return Percent(e.thrust) + " / " + Percent(e.idc) + " / " + Percent(e.rpm);
}

}  // namespace

double KdeSiteDensityKgM3(const std::vector<KdeSheetMotor>& sheets) {
  std::vector<double> ratio;
  for (const auto& m : sheets) {
    for (const auto& r : m.rows) {
      if (std::isfinite(r.thrust_sealevel_est_n) && r.thrust_n > kMinThrustForDensityN) {
        ratio.push_back(r.thrust_sealevel_est_n / r.thrust_n);
      }
    }
  }
  if (ratio.empty()) throw DataError("KDE sheets: no row with a sea-level thrust estimate");
  return kIsaSeaLevelRhoKgM3 / fit::Median(ratio);
}

std::string KdePropId(const std::string& label) {
  const auto sp = label.find(' '), x = label.find('x');
  if (sp == std::string::npos || x == std::string::npos || x == 0 || x + 1 >= sp) return "";
  const std::string kind = label.substr(sp + 1);
  const int blades = kind == "DUAL" ? 2 : kind == "TRIPLE" ? 3 : 0;
  char* end = nullptr;
  const std::string d_text = label.substr(0, x), p_text = label.substr(x + 1, sp - x - 1);
  const double d = std::strtod(d_text.c_str(), &end);
  if (blades == 0 || *end != '\0') return "";
  const double p = std::strtod(p_text.c_str(), &end);
  if (*end != '\0' || !(d > 0.0) || !(p > 0.0)) return "";
  char id[64];
  std::snprintf(id, sizeof id, "kde_p_%gx%gx%d", d, p, blades);
  return id;
}

KdeEndToEndReport KdeSheetsEndToEnd(const std::vector<KdeSheetMotor>& sheets, const Catalog& raw,
                                    const KdeEndToEndOptions& options) {
  if (!(options.rho_kg_m3 > 0.0)) throw UsageError("KDE end to end: rho_kg_m3 must be > 0");
  const EscEntry& esc = raw.esc(options.esc_id);
  std::vector<LawMotor> with_torque;
  for (const auto& k : sheets) {
    if (k.has_torque()) with_torque.push_back(LawMotorOf(k));
  }
  const LawReport loo = LeaveOneMotorOut(with_torque, options.form);
  std::set<std::string> prop_ids;
  for (const auto& p : raw.props()) prop_ids.insert(p.id);

  KdeEndToEndReport rep;
  rep.rho_kg_m3 = options.rho_kg_m3;
  MotorSweepMedians all;
  for (const auto& k : sheets) {
    KdeEndToEndMotor m;
    m.name = k.name;
    MotorSetup setup;
    setup.entry = FindKdeMotor(raw, k.name);
    if (setup.entry == nullptr) {
      rep.skipped.push_back(k.name + ": no catalog motor of that name");
      continue;
    }
    m.motor_id = setup.entry->id;
    // A motor without torque on its sheet was never in the law's fit: the law on every motor
    // with torque and the prior of all of them are held out for it already.
    setup.law = loo.law;
    setup.deadband = loo.throttle.deadband_p50;
    m.law_left_out = false;
    for (const auto& c : loo.left_out) {
      if (c.name != k.name) continue;
      setup.law = c.law;
      setup.deadband = c.deadband_prior;
      m.law_left_out = true;
    }
    m.deadband_prior = setup.deadband;
    const MotorSweepMedians med = EvaluateMotor(k, setup, esc, raw, prop_ids, options.rho_kg_m3, &m, &rep.skipped);
    all.dynosize.Append(med.dynosize);
    all.plain_dc.Append(med.plain_dc);
    all.rms_datasheet.Append(med.rms_datasheet);
    rep.sweeps += m.sweeps;
    rep.points += m.points;
    rep.sweeps_without_prop += m.sweeps_without_prop;
    rep.unconverged += m.unconverged;
    rep.motors.push_back(std::move(m));
  }
  rep.dynosize = all.dynosize.Summary();
  rep.plain_dc = all.plain_dc.Summary();
  rep.rms_datasheet = all.rms_datasheet.Summary();
  return rep;
}

std::string KdeEndToEndReport::Table() const {
  std::string t =
      "| motor | catalog entry | sweeps (skipped: no prop) | points | dead band | dynosize: law left out + "
      "KDE ESC | plain DC, datasheet | rms model, datasheet |\n"
      "|---|---|---|---|---|---|---|---|\n";
  char b[64];
  for (const auto& m : motors) {
    std::snprintf(b, sizeof b, "%d (%d) | %d | %.3f", m.sweeps, m.sweeps_without_prop, m.points, m.deadband_prior);
    t += "| " + m.name + (m.law_left_out ? "" : " (no torque: not in the law's fit)") + " | " + m.motor_id +
         " | " + b + " | " + Cell(m.dynosize) + " | " + Cell(m.plain_dc) + " | " + Cell(m.rms_datasheet) + " |\n";
  }
  std::snprintf(b, sizeof b, "%d (%d) | %d | ", sweeps, sweeps_without_prop, points);
  t += "| **all** | | " + std::string(b) + " | **" + Cell(dynosize) + "** | **" + Cell(plain_dc) + "** | **" +
       Cell(rms_datasheet) + "** |\n";
  return t;
}

std::string KdeEndToEndReport::Biases() const {
  auto line = [](const char* name, const ThrustCurrentSpeedErrors& e) {
    return std::string(name) + ": thrust " + SignedPercent(e.thrust_bias) + ", IDC " + SignedPercent(e.idc_bias) +
           ", rpm " + SignedPercent(e.rpm_bias) + "\n";
  };
  return "signed (median over sweeps of the median pred/meas - 1)\n" + line("dynosize", dynosize) +
         line("plain DC, datasheet", plain_dc) + line("rms model, datasheet", rms_datasheet);
}

}  // namespace dynosize::stand
