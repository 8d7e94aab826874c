#include "stand/dc_baseline.h"

#include "catalog/conventions.h"
#include "common/units.h"

namespace dynosize {

DcMotor DcMotorFromCatalog(const MotorEntry& motor, const EscEntry& esc, DcBaselineNumbers numbers) {
  DcMotor m;
  const bool bldc = motor.params.type == MotorType::kBldc;
  if (motor.kv_rpm_per_v) {
    m.kv_rpm_per_v = *motor.kv_rpm_per_v;
  } else {
    // Invert docs/model.md section 8 (KE = 0.675/(Kv*pi/30); brushed: KE = 1/(Kv*pi/30)).
    const double k = bldc ? kVllRmsPerVdc : 1.0;
    m.kv_rpm_per_v = k / (motor.params.ke_v_s_per_rad * kRadPerSecPerRpm);
  }
  if (numbers == DcBaselineNumbers::kAsStored || !bldc) {
    m.r_ohm = motor.params.rm_ohm + esc.params.resc_ohm;
    m.io_a = motor.params.io_a;
    return m;
  }
  // catalog/conventions.h: Rm = 0.7492*R_dc (RESC alike, eq 48), Io = Io_dc/1.1095 (eq 56).
  const auto stored_dc = motor.json.find("rm_dc_ohm");  // end() for a non-object (hand-built entry)
  const double rm_dc_ohm = stored_dc != motor.json.end() && stored_dc->is_number()
                               ? stored_dc->get<double>()
                               : motor.params.rm_ohm / kRmsPerDcResistance;
  m.r_ohm = rm_dc_ohm + esc.params.resc_ohm / kRmsPerDcResistance;
  m.io_a = motor.params.io_a * kIdealIdcPerIrmsPerThrottle;
  return m;
}

const char* DcBaselineName(DcBaselineNumbers numbers) {
  return numbers == DcBaselineNumbers::kAsStored ? "as-stored" : "datasheet";
}

}  // namespace dynosize
