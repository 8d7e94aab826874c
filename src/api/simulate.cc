#include "api/simulate.h"

#include <algorithm>

#include "catalog/in_system.h"
#include "common/error.h"
#include "common/units.h"
#include "model/sweep.h"
#include "report/point_json.h"

namespace dynosize::api {

OperatingPoint SolvePoint(const Drive& d, const PointRequest& r, const std::vector<double>& law) {
  if (!law.empty()) return d.AtLoad(r.vdc_v, *r.throttle, TorqueLaw{law[0], law[1], law[2]});
  if (r.throttle && r.torque_nm) return d.AtTorque(r.vdc_v, *r.throttle, *r.torque_nm);
  if (r.throttle && r.rpm) return d.AtSpeed(r.vdc_v, *r.throttle, RpmToRadPerSec(*r.rpm));
  return d.Inverse(r.vdc_v, *r.torque_nm, RpmToRadPerSec(*r.rpm));
}

std::vector<std::string> BatchPoint::LimitNames() const {
  std::vector<std::string> names = dynosize::LimitNames(drive.limits);
  if (beats_momentum_theory) names.push_back("beats_momentum_theory");
  return names;
}

namespace {

// A batch row that names a propeller: an unknown id or an unreachable thrust is bad data in the
// file (exit 65, file:line), not a command-line error.
PropPoint BatchPropPoint(const Catalog& catalog, const Drive& drive, const std::string& source,
                         const PointRequest& r, std::map<std::string, PropModel>* props) {
  const std::string where = source + ":" + std::to_string(r.row) + ": ";
  try {
    auto it = props->find(r.prop);
    if (it == props->end()) it = props->emplace(r.prop, PropModel(catalog.prop(r.prop))).first;
    PropPointRequest q;
    q.vdc_v = r.vdc_v;
    q.throttle = r.throttle;
    q.rpm = r.rpm;
    q.thrust_n = r.thrust_n;
    PropPoint pp = SolvePropPoint(drive, it->second, q);
    (void)PropPointJson(pp);  // numerical guard
    return pp;
  } catch (const UsageError& e) {
    throw DataError(where + e.what());
  }
}

std::string Assumed(const EntryBase& e) {
  std::string s;
  for (const auto& k : e.assumed_keys) s += (s.empty() ? "" : ", ") + k;
  return s;
}

}  // namespace

std::vector<BatchPoint> SimulateBatch(const Catalog& catalog, const Drive& drive,
                                      const std::vector<PointRequest>& requests, const std::string& source) {
  std::vector<BatchPoint> out(requests.size());
  std::map<std::string, PropModel> props;  // built once per propeller id
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const PointRequest& r = requests[i];
    BatchPoint& b = out[i];
    if (r.prop.empty()) {
      b.drive = SolvePoint(drive, r);
      continue;
    }
    const PropPoint pp = BatchPropPoint(catalog, drive, source, r, &props);
    b.drive = pp.drive;
    b.has_prop = true;
    b.thrust_n = pp.thrust_n;
    b.g_per_w = pp.g_per_w;
    b.beats_momentum_theory = pp.figure_of_merit > 1.0;
  }
  return out;
}

std::string AssumedNote(const MotorEntry& motor, const EscEntry& esc, const PropEntry* prop) {
  std::string assumed;
  const auto add = [&](const char* what, const EntryBase& e) {
    if (e.assumed_keys.empty()) return;
    assumed += (assumed.empty() ? "" : "; ") + std::string(what) + " " + e.id + ": " + Assumed(e);
  };
  add("motor", motor);
  add("ESC", esc);
  if (prop) add("propeller", *prop);
  return assumed;
}

Json PropPointJson(const PropPoint& pp) {
  Json j = PointToJson(pp.drive);
  j["thrust_n"] = pp.thrust_n;
  j["g_per_w"] = pp.g_per_w;
  j["figure_of_merit"] = pp.figure_of_merit;
  if (pp.figure_of_merit > 1.0) {
    // Momentum theory is a limit like the drive's (docs/model.md section 10): not feasible.
    j["feasible"] = false;
    j["limits"].push_back("beats_momentum_theory");
  }
  j["prop_in_data"] = pp.prop.InData();
  if (!pp.prop.InData()) j["prop_note"] = pp.prop.Message();
  j["converged"] = pp.converged;
  if (!pp.converged) j["message"] = pp.note;
  CheckJsonFinite(j, "operating point");
  return j;
}

Json PropTableJson(const std::vector<ThrottleTableRow>& rows) {
  Json out = Json::array();
  for (const auto& r : rows) {
    PropPoint pp;
    pp.drive = r.point.drive;
    pp.prop = r.point.prop;
    pp.converged = r.point.converged;
    pp.note = r.point.message;
    pp.thrust_n = r.thrust_n;
    pp.g_per_w = r.g_per_w;
    pp.figure_of_merit = r.figure_of_merit;
    out.push_back(PropPointJson(pp));
  }
  return out;
}

Json ThrottleTableJson(const Drive& d, double vdc_v) {
  Json rows = Json::array();
  for (const auto& r : SummarizeThrottles(d, vdc_v)) {
    Json j;
    j["throttle"] = r.throttle;
    j["throttle_effective"] = r.throttle_effective;
    j["no_load_rpm"] = r.no_load_rpm;
    j["stall_torque_nm"] = r.stall_torque_nm;
    j["max_power_rpm"] = r.max_power_rpm;
    j["max_power_w"] = r.max_power_w;
    j["max_efficiency_rpm"] = r.max_efficiency_rpm;
    j["max_eta_system"] = r.max_eta_system;
    j["at_max_efficiency"] = PointToJson(r.at_max_efficiency);
    j["esc_timing_figure"] = d.EscTimingFigure(r.throttle);
    rows.push_back(j);
  }
  return rows;
}

PointRange SolvePointRange(const MotorEntry& motor, const EscEntry& esc, const PointRequest& req,
                           const std::vector<double>& law) {
  PointRange r;
  r.point = SolvePoint(Drive(motor.params, esc.params), req, law);
  r.lo = SolvePoint(Drive(MotorSpreadParams(motor, false), esc.params), req, law);
  r.hi = SolvePoint(Drive(MotorSpreadParams(motor, true), esc.params), req, law);
  return r;
}

Json PointWithRangeJson(const MotorEntry& motor, const EscEntry& esc, const PointRange& r) {
  const OperatingPoint& p = r.point;
  const OperatingPoint& lo = r.lo;
  const OperatingPoint& hi = r.hi;
  const auto range = [](double x, double y) { return Json::array({std::min(x, y), std::max(x, y)}); };
  Json j = PointToJson(p);
  j["idc_a_range"] = range(lo.idc_a, hi.idc_a);
  j["pdc_w_range"] = range(lo.pdc_w, hi.pdc_w);
  j["range_basis"] = motor.datasheet_params ? "in-system law p10-p90 (docs/in-system-law.md)"
                                            : std::string("tier band of the motor's Rm and Io (") + TierName(motor.tier) + ")";
  CheckJsonFinite(j, "operating point");
  j["motor"] = motor.id;
  j["esc"] = esc.id;
  const std::string assumed = AssumedNote(motor, esc, nullptr);
  if (!assumed.empty()) j["assumed"] = assumed;
  return j;
}

Json DriveTableJson(const MotorEntry& motor, const EscEntry& esc, double vdc_v,
                    const std::vector<std::string>& figures) {
  const Drive drive(motor.params, esc.params);
  Json j;
  j["motor"] = motor.id;
  j["esc"] = esc.id;
  j["vdc_v"] = vdc_v;
  j["throttles"] = ThrottleTableJson(drive, vdc_v);
  j["figures"] = figures;
  const std::string assumed = AssumedNote(motor, esc, nullptr);
  if (!assumed.empty()) j["assumed"] = assumed;
  return j;
}

PropPointRun RunPropPoint(const MotorEntry& motor, const EscEntry& esc, const PropEntry& prop_entry,
                          PropPointRequest req) {
  // A geared motor turns the propeller through its gearbox (model/gear.h): the point is solved
  // at the propeller shaft and reported at the motor's, with the propeller's speed beside it.
  const Gear& gear = motor.gear;
  const Drive drive(MotorAtPropellerShaft(motor.params, gear), esc.params);
  if (req.rpm) req.rpm = *req.rpm / gear.ratio;  // the motor's speed, as without a propeller
  const PropModel prop(prop_entry);
  PropPointRun run;
  run.point = SolvePropPoint(drive, prop, req);
  run.prop_rpm = run.point.drive.rpm;
  run.shaft = MotorShaftOf(run.point.drive.omega_rad_s, run.point.drive.torque_nm, gear);
  run.point.drive = MotorSidePoint(run.point.drive, gear);
  return run;
}

Json PropPointRunJson(const PropPointRun& run, const MotorEntry& motor, const EscEntry& esc,
                      const PropEntry& prop, double rho_kg_m3) {
  const Gear& gear = motor.gear;
  Json j = PropPointJson(run.point);
  j["prop_rpm"] = run.prop_rpm;
  if (gear.geared()) {
    j["gear_ratio"] = gear.ratio;
    j["gear_efficiency"] = gear.efficiency;
    j["gear_loss_w"] = run.shaft.gear_loss_w;
  }
  j["motor"] = motor.id;
  j["esc"] = esc.id;
  j["prop"] = prop.id;
  j["rho_kg_m3"] = rho_kg_m3;
  const std::string assumed = AssumedNote(motor, esc, &prop);
  if (!assumed.empty()) j["assumed"] = assumed;
  return j;
}

}  // namespace dynosize::api
