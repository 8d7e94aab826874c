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

BatchResult::BatchResult(std::size_t n) : storage_(n) {}

std::vector<std::string> BatchLimitNames(std::uint32_t limits, bool beats_momentum_theory) {
  std::vector<std::string> names = LimitNames(limits);
  if (beats_momentum_theory) names.push_back("beats_momentum_theory");
  return names;
}

std::vector<std::string> BatchResult::LimitNames(std::size_t i) const {
  return BatchLimitNames(storage_.columns().limits[i], beats_momentum_theory(i));
}

namespace {

// Points gathered per call of the model's batch: the scratch arrays stay in the L1 cache.
constexpr std::size_t kGather = 512;

// SolvePoint's choice of solve for a request without a torque law.
BatchMode ModeOf(bool throttle, bool torque, bool rpm) {
  if (throttle && torque) return BatchMode::kAtTorque;
  if (throttle && rpm) return BatchMode::kAtSpeed;
  return BatchMode::kInverse;
}
BatchMode ModeOf(const PointRequest& r) { return ModeOf(r.throttle.has_value(), r.torque_nm.has_value(), r.rpm.has_value()); }

PointRequest RequestAt(const BatchColumns& in, std::size_t i) {
  PointRequest r;
  r.row = i;
  r.vdc_v = in.vdc_v[i];
  if (in.throttle) r.throttle = in.throttle[i];
  if (in.torque_nm) r.torque_nm = in.torque_nm[i];
  if (in.rpm) r.rpm = in.rpm[i];
  if (in.thrust_n) r.thrust_n = in.thrust_n[i];
  r.prop = in.prop;
  return r;
}

// The first index of x[0, n) outside its range (n if none); blocks scanned branch-free.
template <typename InRange>
std::size_t FirstOutOfRange(const double* x, std::size_t n, InRange in_range) {
  constexpr std::size_t kBlock = 256;
  for (std::size_t begin = 0; begin < n; begin += kBlock) {
    const std::size_t end = std::min(n, begin + kBlock);
    unsigned bad = 0;
    for (std::size_t i = begin; i < end; ++i) bad |= in_range(x[i]) ? 0u : 1u;
    if (bad == 0) continue;
    for (std::size_t i = begin; i < end; ++i) {
      if (!in_range(x[i])) return i;
    }
  }
  return n;
}

// A column's values for points [begin, begin + m): its own memory, or the scratch filled with
// the broadcast value.
const double* Slice(const BatchColumn& c, std::size_t begin, const double* broadcast_fill) {
  if (!c) return nullptr;
  return c.broadcast ? broadcast_fill : c.data + begin;
}

}  // namespace

BatchResult SimulateBatch(const Catalog& catalog, const Drive& drive, const std::vector<PointRequest>& requests,
                          const std::string& source) {
  const std::size_t n = requests.size();
  BatchResult out(n);
  const bool any_prop = std::any_of(requests.begin(), requests.end(), [](const PointRequest& r) { return !r.prop.empty(); });
  if (any_prop) {
    out.prop_rows_.assign(n, 0);
    out.thrust_n_.assign(n, 0.0);
    out.g_per_w_.assign(n, 0.0);
    out.beats_.reset(new bool[n]());
  }
  std::map<std::string, PropModel> props;  // built once per propeller id
  double vdc[kGather], throttle[kGather], torque[kGather], omega[kGather];
  for (std::size_t i = 0; i < n;) {
    const PointRequest& r = requests[i];
    if (!r.prop.empty()) {
      const PropPoint pp = BatchPropPoint(catalog, drive, source, r, &props);
      out.columns().Set(i, pp.drive);
      out.prop_rows_[i] = 1;
      out.thrust_n_[i] = pp.thrust_n;
      out.g_per_w_[i] = pp.g_per_w;
      out.beats_[i] = pp.figure_of_merit > 1.0;
      ++i;
      continue;
    }
    // A run of rows of one mode without a propeller: gathered, then solved together.
    const BatchMode mode = ModeOf(r);
    std::size_t m = 0;
    for (; m < kGather && i + m < n && requests[i + m].prop.empty() && ModeOf(requests[i + m]) == mode; ++m) {
      const PointRequest& q = requests[i + m];
      vdc[m] = q.vdc_v;
      throttle[m] = q.throttle.value_or(0.0);
      torque[m] = q.torque_nm.value_or(0.0);
      omega[m] = q.rpm ? RpmToRadPerSec(*q.rpm) : 0.0;
    }
    SolveBatch(drive, mode, m, {vdc, throttle, torque, omega}, out.columns().From(i));
    i += m;
  }
  return out;
}

void CheckBatchColumns(const BatchColumns& in, const std::string& source) {
  std::size_t first = in.n;
  const auto scan = [&](const BatchColumn& c, auto in_range) {
    if (!c || first == 0) return;
    const std::size_t len = c.broadcast ? 1 : first;  // a broadcast value fails at point 0
    const std::size_t bad = FirstOutOfRange(c.data, len, in_range);
    if (bad < len) first = bad;
  };
  // Lambdas, not function pointers: the scans inline the rule.
  scan(in.vdc_v, [](double x) { return RequestVdcInRange(x); });
  scan(in.throttle, [](double x) { return RequestThrottleInRange(x); });
  scan(in.torque_nm, [](double x) { return RequestTorqueInRange(x); });
  scan(in.rpm, [](double x) { return RequestRpmInRange(x); });
  scan(in.thrust_n, [](double x) { return RequestThrustInRange(x); });
  // Every point gives the same keys: a combination CheckPointRequest refuses fails at point 0.
  if (in.n > 0 && first == in.n && !CheckPointRequest(RequestAt(in, 0)).empty()) first = 0;
  if (first < in.n) {
    throw UsageError(source + ":" + std::to_string(first) + ": " + CheckPointRequest(RequestAt(in, first)));
  }
}

void SimulateColumns(const Catalog& catalog, const Drive& drive, const BatchColumns& in, const std::string& source,
                     const PointColumns& out, const PropColumns& prop) {
  CheckBatchColumns(in, source);
  if (!in.prop.empty()) {
    std::map<std::string, PropModel> props;
    for (std::size_t i = 0; i < in.n; ++i) {
      const PropPoint pp = BatchPropPoint(catalog, drive, source, RequestAt(in, i), &props);
      out.Set(i, pp.drive);
      prop.thrust_n[i] = pp.thrust_n;
      prop.g_per_w[i] = pp.g_per_w;
      prop.beats_momentum_theory[i] = pp.figure_of_merit > 1.0;
    }
    return;
  }
  const BatchMode mode = ModeOf(static_cast<bool>(in.throttle), static_cast<bool>(in.torque_nm), static_cast<bool>(in.rpm));
  // Broadcast values fill their scratch once; the speed is converted chunk by chunk (rpm at the edge).
  double vdc[kGather], throttle[kGather], torque[kGather], omega[kGather];
  if (in.vdc_v.broadcast) std::fill(vdc, vdc + kGather, in.vdc_v[0]);
  if (in.throttle && in.throttle.broadcast) std::fill(throttle, throttle + kGather, in.throttle[0]);
  if (in.torque_nm && in.torque_nm.broadcast) std::fill(torque, torque + kGather, in.torque_nm[0]);
  if (in.rpm && in.rpm.broadcast) std::fill(omega, omega + kGather, RpmToRadPerSec(in.rpm[0]));
  for (std::size_t begin = 0; begin < in.n; begin += kGather) {
    const std::size_t m = std::min(kGather, in.n - begin);
    BatchInputs bi;
    bi.vdc_v = Slice(in.vdc_v, begin, vdc);
    bi.throttle = Slice(in.throttle, begin, throttle);
    bi.torque_nm = Slice(in.torque_nm, begin, torque);
    if (in.rpm) {
      if (!in.rpm.broadcast) {
        const double* rpm = in.rpm.data + begin;
        for (std::size_t k = 0; k < m; ++k) omega[k] = RpmToRadPerSec(rpm[k]);
      }
      bi.omega_rad_s = omega;
    }
    SolveBatch(drive, mode, m, bi, out.From(begin));
  }
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
  j["prop_torque_nm"] = run.point.prop.torque_nm;
  j["prop_power_w"] = run.point.prop.power_w;
  // Where the propeller's numbers come from (for a sized propeller: its family, the model, the
  // measured range of the size-only estimate; importers/sized_prop.h).
  if (const auto src = prop.json.find("source"); src != prop.json.end()) j["prop_source"] = *src;
  j["rho_kg_m3"] = rho_kg_m3;
  const std::string assumed = AssumedNote(motor, esc, &prop);
  if (!assumed.empty()) j["assumed"] = assumed;
  return j;
}

}  // namespace dynosize::api
