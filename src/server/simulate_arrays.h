// POST /api/simulate with arrays: the Python module's dynosize.simulate (docs/python.md) over
// JSON. Any of vdc_v, throttle, torque_nm, rpm and thrust_n may be an array; scalars and arrays
// of one value are broadcast to the length of the others. Each point is a row of
// `simulate --batch` (api/simulate.h SimulateColumns, the model's batch path), with the same
// rules and messages ("simulate: point:I: <rule>", I counted from 0). The answer holds one array
// per key of the point JSON, as the Python module's dict: vdc_v ... eta_system, with a propeller
// thrust_n and g_per_w, then saturated, feasible and limits (the violated limits joined with ';',
// "" when feasible). A number that is not finite is null.
#pragma once

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "server/request_body.h"

namespace dynosize::server {

// Whether a simulate body gives any of its point keys as an array.
bool HasPointArrays(const RequestBody& body);

// The answer above. Throws UsageError for lengths that differ, more than kMaxArrayPoints points,
// torque_law or rho_kg_m3 beside arrays, or a point that breaks a batch row's rule.
Json SimulateArrays(const Catalog& catalog, const RequestBody& body);

inline constexpr std::size_t kMaxArrayPoints = 100000;

}  // namespace dynosize::server
