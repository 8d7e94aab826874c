#include "identification/parameters.h"

#include <cmath>

#include "common/units.h"

namespace dynosize::identification {

const char* BaseParamName(BaseParam p) {
  switch (p) {
    case BaseParam::kKe: return "ke_v_s_per_rad";
    case BaseParam::kKt: return "kt_nm_per_a";
    case BaseParam::kRm: return "rm_ohm";
    case BaseParam::kIo: return "io_a";
    case BaseParam::kResc: return "resc_ohm";
    case BaseParam::kC1: return "c1";
    case BaseParam::kC0: return "c0";
    case BaseParam::kTrSat: return "tr_sat";
    case BaseParam::kSatSlope: return "sat_slope";
    case BaseParam::kDeadband: return "deadband";
  }
  return "?";
}

std::string LabelPriors::Validate() const {
  auto positive = [](const std::optional<double>& v) { return !v || (std::isfinite(*v) && *v > 0.0); };
  if (!positive(kv_rpm_per_v)) return "--kv-label " + std::to_string(*kv_rpm_per_v) + ": must be > 0 (rpm per volt)";
  if (!positive(rm_ohm)) return "--rm-label " + std::to_string(*rm_ohm) + ": must be > 0 (ohm)";
  if (io_a && !(std::isfinite(*io_a) && *io_a >= 0.0)) return "--io-label " + std::to_string(*io_a) + ": must be >= 0 (A)";
  if (!positive(io_v)) return "--io-label-v " + std::to_string(*io_v) + ": must be > 0 (V)";
  if (io_a.has_value() != io_v.has_value()) return "--io-label and --io-label-v go together (no-load current at a voltage)";
  return "";
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
