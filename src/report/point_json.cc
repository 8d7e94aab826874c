#include "report/point_json.h"

#include <sstream>

namespace dynosize {

Json PointToJson(const OperatingPoint& p) {
  Json j;
  j["rpm"] = p.rpm;
  j["omega_rad_s"] = p.omega_rad_s;
  j["torque_nm"] = p.torque_nm;
  j["irms_a"] = p.irms_a;
  j["vll_rms_v"] = p.vll_rms_v;
  j["pac_w"] = p.pac_w;
  j["idc_a"] = p.idc_a;
  j["pdc_w"] = p.pdc_w;
  j["pesc_w"] = p.pesc_w;
  j["pmech_w"] = p.pmech_w;
  j["eta_motor"] = p.eta_motor;
  j["eta_esc"] = p.eta_esc;
  j["eta_system"] = p.eta_system;
  j["throttle"] = p.throttle;
  j["throttle_effective"] = p.throttle_effective;
  j["saturated"] = p.saturated;
  j["feasible"] = p.feasible();
  j["vdc_v"] = p.vdc_v;
  j["limits"] = LimitNames(p.limits);
  CheckJsonFinite(j, "operating point");
  return j;
}

const std::vector<std::string>& PointCsvColumns() {
  static const std::vector<std::string> kColumns = {
      "vdc_v",   "throttle", "throttle_effective", "saturated", "rpm",       "omega_rad_s",
      "torque_nm", "irms_a", "vll_rms_v",          "pac_w",     "idc_a",     "pdc_w",
      "pesc_w",  "pmech_w",  "eta_motor",          "eta_esc",   "eta_system", "feasible",
      "limits"};
  return kColumns;
}

std::string PointToCsvRow(const OperatingPoint& p) {
  const Json j = PointToJson(p);  // also checks finiteness
  std::ostringstream row;
  row.precision(10);
  bool first = true;
  for (const auto& key : PointCsvColumns()) {
    if (!first) row << ',';
    first = false;
    const Json& v = j[key];
    if (v.is_boolean()) {
      row << (v.get<bool>() ? 1 : 0);
    } else if (v.is_array()) {
      std::string names;
      for (const auto& n : v) names += (names.empty() ? "" : ";") + n.get<std::string>();
      row << names;
    } else {
      row << v.get<double>();
    }
  }
  return row.str();
}

}  // namespace dynosize
