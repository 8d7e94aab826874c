#include "identification/parameters.h"

#include <cmath>

#include "common/units.h"

namespace dynosize::identification {

std::array<bool, kParamCount> FreeBaseParams(const LogContent& c) {
  std::array<bool, kParamCount> free{};
  free[ParamIndex(Param::kKe)] = true;
  free[ParamIndex(Param::kRm)] = true;
  free[ParamIndex(Param::kKt)] = !TieKt(c);
  free[ParamIndex(Param::kIo)] = c.any_torque_known;
  free[ParamIndex(Param::kResc)] = c.ac && c.has_throttle;
  const bool esc_ratio = c.has_idc && c.has_throttle && c.throttle_levels >= 2 && (c.ac || c.has_torque);
  free[ParamIndex(Param::kC1)] = esc_ratio;
  free[ParamIndex(Param::kC0)] = esc_ratio;
  return free;
}

bool LabelPriors::IsValid(std::string* error) const {
  auto fail = [error](const std::string& why) {
    if (error != nullptr) *error = why;
    return false;
  };
  auto positive = [](const std::optional<double>& v) { return !v || (std::isfinite(*v) && *v > 0.0); };
  if (!positive(kv_rpm_per_v)) return fail("--kv-label " + std::to_string(*kv_rpm_per_v) + ": must be > 0 (rpm per volt)");
  if (!positive(rm_ohm)) return fail("--rm-label " + std::to_string(*rm_ohm) + ": must be > 0 (ohm)");
  if (io_a && !(std::isfinite(*io_a) && *io_a >= 0.0)) return fail("--io-label " + std::to_string(*io_a) + ": must be >= 0 (A)");
  if (!positive(io_v)) return fail("--io-label-v " + std::to_string(*io_v) + ": must be > 0 (V)");
  if (io_a.has_value() != io_v.has_value()) return fail("--io-label and --io-label-v go together (no-load current at a voltage)");
  return true;
}

double KeFromLabelKv(double kv_rpm_per_v, MotorType type) {
  return type == MotorType::kBldc ? KeFromKvBldc(kv_rpm_per_v) : KeFromKvBrushed(kv_rpm_per_v);
}

double KvFromKe(double ke_v_s_per_rad, MotorType type) {
  const double k = type == MotorType::kBldc ? kVllRmsPerVdc : 1.0;
  return k / (ke_v_s_per_rad * kRadPerSecPerRpm);
}

double IoFromLabel(double io_dc_a, MotorType type) {
  return io_dc_a / IdealIdcPerIrmsPerThrottle(type);
}

}  // namespace dynosize::identification
