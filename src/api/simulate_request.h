// `simulate --json` (without --batch, --out or --plot) as one library call: the request as the
// CLI's flags give it, its checks with the CLI's messages, and the document the CLI prints. The
// CLI (apps/cmd_simulate.cc, which also prints text, batches and figures) and the web server
// (src/server) share them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "io/points_csv.h"
#include "stand/prop_point.h"
#include "stand/throttle_table.h"

namespace dynosize::api {

// The flags of `simulate` that choose what it solves (SI; rpm at the edge as on the command line).
struct SimulateRequest {
  std::string motor_id, esc_id;
  std::optional<double> vdc_v, throttle, torque_nm, rpm;
  std::vector<double> torque_law;  // a, b, c of Q = a + b*omega + c*omega^2 (SI), or empty
  std::string prop_id;             // a catalog propeller as the load
  // Or a propeller from its size alone: "DxP[xB]" in inches and a family ("" = the default);
  // importers/sized_prop.h.
  std::string prop_param, prop_family;
  std::optional<double> thrust_n;  // with prop_id: the static thrust to hold, N
  double rho_kg_m3 = 1.225;
};

// Whether the request names a propeller (or a thrust, which needs one): the propeller path.
inline bool IsPropRequest(const SimulateRequest& r) {
  return !r.prop_id.empty() || !r.prop_param.empty() || r.thrust_n.has_value();
}
// The request's propeller: the catalog's prop_id, or the sized propeller of prop_param
// (importers/sized_prop.h). Throws UsageError for both or a bad size, DataError for an unknown id.
PropEntry ResolveProp(const Catalog& catalog, const SimulateRequest& r);
// Whether it asks for one point (else the table over throttle).
bool IsPointRequest(const SimulateRequest& r);

// Without a propeller: the checked point request (vdc_v and, in point mode, throttle, torque,
// rpm; the torque law's coefficients checked). Throws UsageError with the CLI's message naming
// the flag (--vdc, --throttle, --torque, --rpm, --torque-law).
PointRequest PointRequestOf(const SimulateRequest& r);

// With a propeller: the checked request. Throws UsageError (--thrust-n without --prop, --torque
// or --torque-law beside --prop, --vdc missing, a value out of range).
PropPointRequest PropPointRequestOf(const SimulateRequest& r);

// simulate --prop P --json without a point: the table over throttle with its ids and figures.
Json PropTableRunJson(const MotorEntry& motor, const EscEntry& esc, const PropEntry& prop, double vdc_v,
                      double rho_kg_m3, const std::vector<ThrottleTableRow>& rows,
                      const std::vector<std::string>& figures);

// What `simulate ... --json` prints for the request (no figures: "figures" is []): the table over
// throttle, one point with its range, or the propeller's point or table. Throws UsageError for a
// request that breaks a rule or names an unknown entry.
Json SimulateJson(const Catalog& catalog, const SimulateRequest& r);

}  // namespace dynosize::api
