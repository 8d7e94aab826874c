#include "stand/stand.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/units.h"
#include "model/physics.h"
#include "prop/prop_drive.h"

namespace dynosize::stand {

namespace {

using logs::Column;

std::optional<double> At(const logs::SteadyTable& t, Column c, std::size_t i) {
  if (!t.Has(c)) return std::nullopt;
  return t.Get(c)[i];
}

void Drop(StandTable* t, const std::string& reason) {
  for (auto& d : t->dropped) {
    if (d.reason == reason) {
      ++d.count;
      return;
    }
  }
  t->dropped.push_back({reason, 1});
}

}  // namespace

const char* StandModeName(int mode) {
  return mode == kAtMeasuredRpm ? "at_measured_rpm" : mode == kAtMeasuredTorque ? "at_measured_rpm_and_torque" : "from_throttle";
}
const char* StandModelName(int model) { return model == kDynosize ? "dynosize" : "plain_dc"; }

StandTable StandTableFromLog(const logs::SteadyTable& t, const StandReadOptions& o) {
  StandTable s;
  s.file = t.file;
  s.has_throttle = t.Has(Column::kThrottle);
  s.has_rpm = t.Has(Column::kOmegaRadS);
  s.has_thrust = t.Has(Column::kThrustN);
  s.has_torque = t.Has(Column::kTorqueNm);
  const bool has_vdc = t.Has(Column::kVdcV);
  if (!has_vdc && !o.vdc_v) {
    throw DataError(t.file + ": no supply-voltage column (vdc_v): map one (--map vdc_v=Header) "
                    "or give --vdc V");
  }
  s.vdc_from_option = !has_vdc;
  if (!s.has_rpm && !s.has_throttle) {
    throw DataError(t.file + ": neither an rpm nor a throttle column: a stand row needs its speed "
                    "or its throttle to be predicted");
  }
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const std::size_t line = t.source_line[i];
    if ((o.first_line && line < o.first_line) || (o.last_line && line > o.last_line)) {
      Drop(&s, "outside the line range");
      continue;
    }
    StandRow r;
    r.line = line;
    r.vdc_v = has_vdc ? t.Get(Column::kVdcV)[i] : *o.vdc_v;
    r.throttle = At(t, Column::kThrottle, i);
    r.omega_rad_s = At(t, Column::kOmegaRadS, i);
    r.thrust_n = At(t, Column::kThrustN, i);
    r.idc_a = At(t, Column::kIdcA, i);
    r.torque_nm = At(t, Column::kTorqueNm, i);
    if ((r.omega_rad_s && !(*r.omega_rad_s > 0.0)) || (r.idc_a && !(*r.idc_a > 0.0)) ||
        (!r.omega_rad_s && r.throttle && !(*r.throttle > 0.0))) {
      Drop(&s, "motor at rest (rpm, current or throttle 0)");
      continue;
    }
    if (!(r.vdc_v > 0.0)) {
      Drop(&s, "supply voltage <= 0");
      continue;
    }
    s.rows.push_back(r);
  }
  if (s.rows.empty()) {
    throw DataError(t.file + ": no row left to predict (" + std::to_string(t.rows()) +
                    " read; all at rest or outside the line range)");
  }
  return s;
}

namespace {

StandPrediction FromDrive(const OperatingPoint& p) {
  StandPrediction s;
  s.valid = true;
  s.rpm = p.rpm;
  s.torque_nm = p.torque_nm;
  s.idc_a = p.idc_a;
  s.throttle = p.throttle;
  s.feasible = p.feasible();
  s.limits = LimitNames(p.limits);
  return s;
}

StandPrediction FromDc(const DcPoint& p) {
  StandPrediction s;
  s.valid = true;
  s.rpm = RadPerSecToRpm(p.omega_rad_s);
  s.torque_nm = p.torque_nm;
  s.idc_a = p.idc_a;
  s.throttle = p.duty;
  s.feasible = p.duty <= 1.0;
  if (!s.feasible) s.limits = {"throttle_above_one"};
  return s;
}

// At the measured rpm: the load torque of the propeller (else the measured torque).
void PredictAtRpm(const StandRow& row, const Drive& drive, const DcMotor& dc,
                  const PropModel* prop, const StandOptions& o, StandRowResult* out) {
  const double w = *row.omega_rad_s;
  double q = 0.0;
  std::optional<double> thrust;
  if (prop) {
    const PropEvaluation ev = prop->Evaluate(w, o.rho_kg_m3);
    q = ev.torque_nm;
    thrust = ev.thrust_n;
    if (!ev.InData()) out->prop_note = ev.Message();
  } else {
    q = *row.torque_nm;
  }
  out->pred[kAtMeasuredRpm][kDynosize] = FromDrive(drive.Inverse(row.vdc_v, q, w));
  out->pred[kAtMeasuredRpm][kPlainDc] = FromDc(DcAtSpeedTorque(dc, row.vdc_v, w, q));
  const bool beats_momentum =
      prop && FigureOfMerit(*thrust, q * w, prop->diameter_m(), o.rho_kg_m3) > 1.0;
  for (auto& p : out->pred[kAtMeasuredRpm]) {
    p.thrust_n = thrust;
    if (beats_momentum) {  // docs/model.md section 10: not a credible point
      p.feasible = false;
      p.limits.push_back("beats_momentum_theory");
    }
  }
  if (prop && row.torque_nm) {
    // The motor + ESC alone: the measured torque instead of the propeller's.
    const double qm = *row.torque_nm;
    out->pred[kAtMeasuredTorque][kDynosize] = FromDrive(drive.Inverse(row.vdc_v, qm, w));
    out->pred[kAtMeasuredTorque][kPlainDc] = FromDc(DcAtSpeedTorque(dc, row.vdc_v, w, qm));
  }
}

// Forward from the throttle: the propeller's torque law (else the measured torque, constant).
void PredictFromThrottle(const StandRow& row, const Drive& drive, const DcMotor& dc,
                         const PropModel* prop, const StandOptions& o, StandRowResult* out) {
  const double tr = std::clamp(*row.throttle, 0.0, 1.0);
  StandPrediction& dyn = out->pred[kFromThrottle][kDynosize];
  StandPrediction& base = out->pred[kFromThrottle][kPlainDc];
  if (prop) {
    const PropDrivePoint pd = SolveDriveWithProp(drive, *prop, row.vdc_v, tr, o.rho_kg_m3);
    if (pd.converged) {
      dyn = FromDrive(pd.drive);
      dyn.thrust_n = pd.prop.thrust_n;
      if (!pd.prop.InData() && out->prop_note.empty()) out->prop_note = pd.prop.Message();
    }
    const auto q_of_w = [&](double w) { return prop->Evaluate(w, o.rho_kg_m3).torque_nm; };
    base = FromDc(DcAtThrottleLoad(dc, row.vdc_v, tr, q_of_w));
    base.thrust_n = prop->Evaluate(RpmToRadPerSec(base.rpm), o.rho_kg_m3).thrust_n;
  } else {
    dyn = FromDrive(drive.AtTorque(row.vdc_v, tr, *row.torque_nm));
    base = FromDc(DcAtThrottleTorque(dc, row.vdc_v, tr, *row.torque_nm));
  }
  // The throttle is the input here, not a prediction.
  dyn.throttle = base.throttle = tr;
}

// Accumulates 100*(pred - meas)/meas (or pred - meas in points for throttle).
struct Accumulator {
  ColumnError e;
  void Add(double pred, double meas, bool relative) {
    if (relative && !(meas > 0.0)) return;
    const double err = relative ? 100.0 * (pred - meas) / meas : 100.0 * (pred - meas);
    ++e.n;
    e.mae += std::fabs(err);
    e.bias += err;
    e.max_abs = std::max(e.max_abs, std::fabs(err));
  }
  ColumnError Done() const {
    ColumnError out = e;
    if (out.n) {
      out.mae /= static_cast<double>(out.n);
      out.bias /= static_cast<double>(out.n);
    }
    return out;
  }
};

std::vector<ColumnError> Errors(const StandTable& t, const StandResult& r, int mode, int model) {
  Accumulator thrust{{"thrust_n"}}, idc{{"idc_a"}}, rpm{{"rpm"}}, torque{{"torque_nm"}},
      thr{{"throttle"}};
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const StandRow& row = t.rows[i];
    const StandPrediction& p = r.rows[i].pred[mode][model];
    if (!p.valid) continue;
    if (row.thrust_n && p.thrust_n) thrust.Add(*p.thrust_n, *row.thrust_n, true);
    if (row.idc_a) idc.Add(p.idc_a, *row.idc_a, true);
    if (mode == kFromThrottle && row.omega_rad_s) rpm.Add(p.rpm, RadPerSecToRpm(*row.omega_rad_s), true);
    // The torque is an output only where a propeller sets the load (else it is the input).
    if (row.torque_nm && r.prop_load[mode]) torque.Add(p.torque_nm, *row.torque_nm, true);
    if (mode != kFromThrottle && row.throttle) thr.Add(p.throttle, *row.throttle, false);
  }
  std::vector<ColumnError> out;
  for (const Accumulator* a : {&thrust, &idc, &rpm, &torque, &thr}) {
    if (a->e.n) out.push_back(a->Done());
  }
  return out;
}

}  // namespace

StandResult PredictStand(const StandTable& t, const Drive& drive, const DcMotor& dc,
                         const PropModel* prop, const StandOptions& o) {
  if (!prop && !t.has_torque) {
    throw DataError(t.file + ": no torque column and no --prop: the load at each row is unknown "
                    "(give the table's propeller with --prop ID, or map a torque_nm column)");
  }
  if (!(o.rho_kg_m3 > 0.0 && std::isfinite(o.rho_kg_m3))) {
    throw UsageError("air density " + std::to_string(o.rho_kg_m3) + " kg/m^3: must be > 0");
  }
  StandResult r;
  r.mode_used[kAtMeasuredRpm] = t.has_rpm;
  r.mode_used[kAtMeasuredTorque] = t.has_rpm && t.has_torque && prop;
  r.mode_used[kFromThrottle] = t.has_throttle;
  const std::string load = prop ? "propeller " + prop->entry().id : "measured torque";
  r.load[kAtMeasuredRpm] = load;
  r.load[kAtMeasuredTorque] = "measured torque";
  r.prop_load[kAtMeasuredRpm] = r.prop_load[kFromThrottle] = prop != nullptr;
  r.load[kFromThrottle] = prop ? load : "measured torque, held constant";
  r.rows.resize(t.rows.size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const StandRow& row = t.rows[i];
    StandRowResult& out = r.rows[i];
    const bool load_known = prop || row.torque_nm;
    if (row.omega_rad_s && load_known) PredictAtRpm(row, drive, dc, prop, o, &out);
    if (row.throttle && load_known) PredictFromThrottle(row, drive, dc, prop, o, &out);
    if (!out.prop_note.empty()) ++r.rows_outside_prop_data;
    for (int m = 0; m < kStandModes; ++m) {
      if (out.pred[m][kDynosize].valid && !out.pred[m][kDynosize].feasible) ++r.rows_infeasible[m];
    }
  }
  for (int mode = 0; mode < kStandModes; ++mode) {
    if (!r.mode_used[mode]) continue;
    for (int model = 0; model < 2; ++model) r.errors[mode][model] = Errors(t, r, mode, model);
  }
  return r;
}

const ColumnError* FindError(const StandResult& r, int mode, int model, const std::string& column) {
  for (const ColumnError& e : r.errors[mode][model]) {
    if (e.column == column) return &e;
  }
  return nullptr;
}

EscParams IdealEsc(const EscParams& esc, MotorType type) {
  EscParams e;  // the defaults are the ideal ESC of eq (56) for a BLDC
  e.c1 = IdealIdcPerIrmsPerThrottle(type);
  e.max_current_a = esc.max_current_a;
  e.vdc_max_v = esc.vdc_max_v;
  return e;
}

}  // namespace dynosize::stand
