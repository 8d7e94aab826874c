#include "server/simulate_arrays.h"

#include <memory>
#include <string>
#include <vector>

#include "api/simulate.h"
#include "common/error.h"
#include "model/drive.h"
#include "model/drive_batch.h"

namespace dynosize::server {

namespace {

constexpr const char* kPointKeys[] = {"vdc_v", "throttle", "torque_nm", "rpm", "thrust_n"};

// One input column: its values (a scalar is one value), absent when the key is.
struct InputColumn {
  bool given = false;
  std::vector<double> values;
};

InputColumn ColumnOf(const RequestBody& b, const char* key) {
  InputColumn c;
  const Json* v = b.Find(key);
  if (!v) return c;
  c.given = true;
  if (v->is_array()) {
    c.values = b.Numbers(key);
    if (c.values.empty()) throw UsageError(b.Where(key) + ": an empty array");
  } else {
    c.values.push_back(*b.Number(key));
  }
  return c;
}

api::BatchColumn BatchColumnOf(const InputColumn& c) {
  if (!c.given) return {};
  return {c.values.data(), c.values.size() == 1};
}

// The length every array has (1 when all are scalars), as the Python module's message says it.
std::size_t BroadcastLength(const std::vector<std::pair<const char*, const InputColumn*>>& cols) {
  std::size_t n = 1;
  for (const auto& [name, c] : cols) {
    const std::size_t m = c->values.size();
    if (m <= 1) continue;
    if (n != 1 && m != n) {
      throw UsageError(std::string(name) + ": " + std::to_string(m) + " values where the other arrays have " +
                       std::to_string(n));
    }
    n = m;
  }
  return n;
}

Json NumberArray(const double* v, std::size_t n) {
  Json a = Json::array();
  for (std::size_t i = 0; i < n; ++i) a.push_back(NumberOrNull(v[i]));
  return a;
}

}  // namespace

bool HasPointArrays(const RequestBody& body) {
  for (const char* key : kPointKeys) {
    const Json* v = body.Find(key);
    if (v && v->is_array()) return true;
  }
  return false;
}

Json SimulateArrays(const Catalog& catalog, const RequestBody& b) {
  if (b.Find("torque_law") || b.Find("rho_kg_m3")) {
    throw UsageError("simulate: torque_law and rho_kg_m3 do not go with arrays (the batch's keys: vdc_v, throttle, "
                     "torque_nm, rpm, thrust_n, prop)");
  }
  const InputColumn vdc = ColumnOf(b, "vdc_v"), throttle = ColumnOf(b, "throttle"), torque = ColumnOf(b, "torque_nm"),
                    rpm = ColumnOf(b, "rpm"), thrust = ColumnOf(b, "thrust_n");
  if (!vdc.given) throw UsageError("--vdc is required (supply voltage, V)");
  const std::size_t n = BroadcastLength(
      {{"vdc_v", &vdc}, {"throttle", &throttle}, {"torque_nm", &torque}, {"rpm", &rpm}, {"thrust_n", &thrust}});
  if (n > kMaxArrayPoints) {
    throw UsageError("simulate: " + std::to_string(n) + " points: at most " + std::to_string(kMaxArrayPoints) +
                     " in one request (the Python module takes more)");
  }
  const MotorEntry& motor = catalog.motor(b.Text("motor"));
  const EscEntry& esc = catalog.esc(b.Text("esc"));
  api::BatchColumns in;
  in.n = n;
  in.vdc_v = BatchColumnOf(vdc);
  in.throttle = BatchColumnOf(throttle);
  in.torque_nm = BatchColumnOf(torque);
  in.rpm = BatchColumnOf(rpm);
  in.thrust_n = BatchColumnOf(thrust);
  in.prop = b.Text("prop");
  const PointColumnsStorage storage(n);
  const PointColumns& out = storage.columns();
  std::vector<double> thrust_n(in.prop.empty() ? 0 : n), g_per_w(in.prop.empty() ? 0 : n);
  std::unique_ptr<bool[]> beats(new bool[n]());
  api::PropColumns pc;
  if (!in.prop.empty()) pc = {thrust_n.data(), g_per_w.data(), beats.get()};
  api::SimulateColumns(catalog, Drive(motor.params, esc.params), in, "simulate: point", out, pc);
  Json j;
  const std::pair<const char*, double*> numbers[] = {
      {"vdc_v", out.vdc_v},         {"throttle", out.throttle}, {"throttle_effective", out.throttle_effective},
      {"rpm", out.rpm},             {"omega_rad_s", out.omega_rad_s}, {"torque_nm", out.torque_nm},
      {"irms_a", out.irms_a},       {"vll_rms_v", out.vll_rms_v}, {"pac_w", out.pac_w},
      {"idc_a", out.idc_a},         {"pdc_w", out.pdc_w},       {"pesc_w", out.pesc_w},
      {"pmech_w", out.pmech_w},     {"eta_motor", out.eta_motor}, {"eta_esc", out.eta_esc},
      {"eta_system", out.eta_system}};
  for (const auto& [key, column] : numbers) j[key] = NumberArray(column, n);
  if (!in.prop.empty()) {
    j["thrust_n"] = NumberArray(thrust_n.data(), n);
    j["g_per_w"] = NumberArray(g_per_w.data(), n);
  }
  Json saturated = Json::array(), feasible = Json::array(), limits = Json::array();
  for (std::size_t i = 0; i < n; ++i) {
    saturated.push_back(out.saturated[i]);
    feasible.push_back(out.feasible[i] && !beats[i]);
    std::string joined;
    for (const auto& name : api::BatchLimitNames(out.limits[i], beats[i])) joined += (joined.empty() ? "" : ";") + name;
    limits.push_back(joined);
  }
  j["saturated"] = std::move(saturated);
  j["feasible"] = std::move(feasible);
  j["limits"] = std::move(limits);
  return j;
}

}  // namespace dynosize::server
