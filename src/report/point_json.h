// Serialisation of model results to JSON and CSV (the `simulate` output contract).
#pragma once

#include <string>
#include <vector>

#include "common/json_file.h"
#include "model/drive.h"

namespace dynosize {

// Keys: rpm, omega_rad_s, torque_nm, irms_a, vll_rms_v, pac_w, idc_a, pdc_w, pesc_w, pmech_w,
// eta_motor, eta_esc, eta_system, throttle, throttle_effective, saturated, feasible, and vdc_v and
// limits (names of the violated limits, empty when feasible).
Json PointToJson(const OperatingPoint& p);

// CSV header and one row with the same keys, in the same order.
const std::vector<std::string>& PointCsvColumns();
std::string PointToCsvRow(const OperatingPoint& p);

}  // namespace dynosize
