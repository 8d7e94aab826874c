#include "api/simulate_request.h"

#include "importers/sized_prop.h"

#include <cmath>

#include "api/simulate.h"
#include "common/error.h"
#include "common/text_format.h"
#include "importers/sized_prop.h"
#include "model/drive.h"
#include "model/gear.h"
#include "prop/prop_model.h"

namespace dynosize::api {

bool IsPointRequest(const SimulateRequest& r) {
  if (IsPropRequest(r)) return r.throttle || r.rpm || r.thrust_n;
  return r.throttle || r.torque_nm || r.rpm || !r.torque_law.empty();
}

namespace {

void CheckTorqueLaw(const SimulateRequest& r) {
  if (r.torque_nm || r.rpm) throw UsageError("--torque-law replaces --torque and --rpm");
  if (!r.throttle) throw UsageError("--torque-law needs --throttle");
  if (r.torque_law.size() != 3) throw UsageError("--torque-law: give three coefficients A,B,C");
  for (double c : r.torque_law) {
    if (!(std::fabs(c) <= kMaxTorqueLawCoefficient)) {
      throw UsageError("--torque-law " + SignificantText(c) + ": coefficients must be finite, at most " +
                       SignificantText(kMaxTorqueLawCoefficient) + " in magnitude (SI)");
    }
  }
  if (r.torque_law[2] < 0.0) throw UsageError("--torque-law: C must be >= 0 (a propeller's torque grows with speed)");
}

}  // namespace

PointRequest PointRequestOf(const SimulateRequest& r) {
  if (!r.vdc_v) throw UsageError("--vdc is required (supply voltage, V)");
  PointRequest req;
  req.vdc_v = *r.vdc_v;
  if (!(req.vdc_v > 0.0 && req.vdc_v <= kMaxRequestVdcV)) {
    throw UsageError("--vdc " + SignificantText(*r.vdc_v) + ": must be a finite number > 0 V and <= " +
                     SignificantText(kMaxRequestVdcV) + " V");
  }
  if (!IsPointRequest(r)) return req;
  req.throttle = r.throttle;
  req.torque_nm = r.torque_nm;
  req.rpm = r.rpm;
  if (!r.torque_law.empty()) {
    CheckTorqueLaw(r);
    req.torque_nm = 0.0;  // for the checks below: one load given (its coefficients are checked above)
  }
  if (r.throttle && !(*r.throttle >= 0.0 && *r.throttle <= 1.0)) {
    throw UsageError("--throttle " + SignificantText(*r.throttle) +
                     ": must be between 0 and 1 (a fraction: 0.6 for 60 %)");
  }
  if (r.torque_nm && !(*r.torque_nm >= 0.0 && *r.torque_nm <= kMaxRequestTorqueNm)) {
    throw UsageError("--torque " + SignificantText(*r.torque_nm) + ": must be a finite number >= 0 N*m and <= " +
                     SignificantText(kMaxRequestTorqueNm) + " N*m");
  }
  if (r.rpm && !(*r.rpm >= 0.0 && *r.rpm <= kMaxRequestRpm)) {
    throw UsageError("--rpm " + SignificantText(*r.rpm) + ": must be a finite number >= 0 and <= " +
                     SignificantText(kMaxRequestRpm));
  }
  if (!CheckPointRequest(req).empty()) {
    throw UsageError("give --throttle with one of --torque, --rpm, --torque-law (forward model), "
                     "or --torque and --rpm without --throttle (inverse)");
  }
  return req;
}

PropEntry ResolveProp(const Catalog& catalog, const SimulateRequest& r) {
  if (!r.prop_param.empty() && !r.prop_id.empty()) throw UsageError("--prop and --prop-param: give one propeller");
  if (!r.prop_family.empty() && r.prop_param.empty()) throw UsageError("--prop-family goes with --prop-param");
  if (r.prop_param.empty()) return catalog.prop(r.prop_id);
  PropSize size = ParsePropParam(r.prop_param);
  size.family = r.prop_family;
  return PropEntryFromJson(SizedPropJson(size));
}

PropPointRequest PropPointRequestOf(const SimulateRequest& r) {
  if (r.prop_id.empty() && r.prop_param.empty()) throw UsageError("--thrust-n needs --prop (the propeller that gives the thrust)");
  if (r.torque_nm || !r.torque_law.empty()) {
    throw UsageError("--prop is the load: do not combine it with --torque or --torque-law");
  }
  if (!r.vdc_v) throw UsageError("--vdc is required (supply voltage, V)");
  PropPointRequest req;
  req.vdc_v = *r.vdc_v;
  req.throttle = r.throttle;
  req.rpm = r.rpm;
  req.thrust_n = r.thrust_n;
  req.rho_kg_m3 = r.rho_kg_m3;
  PropPointRequest check = req;
  if (!IsPointRequest(r)) check.throttle = 0.5;  // the table: only VDC and rho to check
  if (const std::string rule = CheckPropPointRequest(check); !rule.empty()) {
    throw UsageError("--prop: " + rule + " (flags --throttle, --rpm, --thrust-n, --vdc, --rho-kg-m3)");
  }
  return req;
}

Json PropTableRunJson(const MotorEntry& motor, const EscEntry& esc, const PropEntry& prop, double vdc_v,
                      double rho_kg_m3, const std::vector<ThrottleTableRow>& rows,
                      const std::vector<std::string>& figures) {
  Json j;
  j["motor"] = motor.id;
  j["esc"] = esc.id;
  j["prop"] = prop.id;
  j["vdc_v"] = vdc_v;
  j["rho_kg_m3"] = rho_kg_m3;
  j["throttles"] = PropTableJson(rows);
  j["figures"] = figures;
  const std::string assumed = AssumedNote(motor, esc, &prop);
  if (!assumed.empty()) j["assumed"] = assumed;
  return j;
}

Json SimulateJson(const Catalog& catalog, const SimulateRequest& r) {
  if (IsPropRequest(r)) {
    const PropPointRequest req = PropPointRequestOf(r);
    const MotorEntry& motor = catalog.motor(r.motor_id);
    const EscEntry& esc = catalog.esc(r.esc_id);
    const PropEntry prop = ResolveProp(catalog, r);
    if (IsPointRequest(r)) return PropPointRunJson(RunPropPoint(motor, esc, prop, req), motor, esc, prop, r.rho_kg_m3);
    // The table is the propeller's: solved at its shaft through the gearbox (model/gear.h).
    const Drive drive(MotorAtPropellerShaft(motor.params, motor.gear), esc.params);
    const auto rows = PropThrottleTable(drive, PropModel(prop), req.vdc_v, r.rho_kg_m3);
    return PropTableRunJson(motor, esc, prop, req.vdc_v, r.rho_kg_m3, rows, {});
  }
  const PointRequest req = PointRequestOf(r);
  const MotorEntry& motor = catalog.motor(r.motor_id);
  const EscEntry& esc = catalog.esc(r.esc_id);
  if (IsPointRequest(r)) return PointWithRangeJson(motor, esc, SolvePointRange(motor, esc, req, r.torque_law));
  return DriveTableJson(motor, esc, req.vdc_v, {});
}

}  // namespace dynosize::api
