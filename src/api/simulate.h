// `simulate` as a library call: the points, tables and JSON documents that the CLI prints with
// --json and the Python module returns (python/). One implementation for both front ends; the
// CLI keeps flag parsing, text printing and file writes (apps/cmd_simulate.cc).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "io/points_csv.h"
#include "model/drive.h"
#include "model/gear.h"
#include "prop/prop_model.h"
#include "stand/prop_point.h"
#include "stand/throttle_table.h"

namespace dynosize::api {

// One request solved on a drive: a torque law (law = {a, b, c}, SI, with a throttle), throttle
// + torque, throttle + rpm (forward, eq 49) or torque + rpm (the inverse, throttle solved).
OperatingPoint SolvePoint(const Drive& drive, const PointRequest& r, const std::vector<double>& law = {});

// One row of the batch path. A row that names a propeller carries its thrust; a figure of merit
// above 1 (the propeller data beat momentum theory, docs/model.md section 10) makes it infeasible.
struct BatchPoint {
  OperatingPoint drive;
  bool has_prop = false;
  double thrust_n = 0.0;
  double g_per_w = 0.0;
  bool beats_momentum_theory = false;
  bool feasible() const { return drive.feasible() && !beats_momentum_theory; }
  // The drive's limit names, then "beats_momentum_theory" (the JSON's "limits").
  std::vector<std::string> LimitNames() const;
};

// The batch path (`simulate --batch`, and dynosize.simulate in Python): one result per request,
// in order; propellers are looked up once per id. A row whose propeller is unknown or whose
// thrust cannot be reached is bad data: DataError "<source>:<row>: <rule>".
std::vector<BatchPoint> SimulateBatch(const Catalog& catalog, const Drive& drive,
                                      const std::vector<PointRequest>& requests, const std::string& source);

// "motor m: rm_ohm, io_a; ESC e: c1; propeller p: mass_kg" (only the parts with assumed keys;
// prop may be null), "" when nothing is assumed.
std::string AssumedNote(const MotorEntry& motor, const EscEntry& esc, const PropEntry* prop);

// The point JSON (report/point_json.h) plus the propeller's outputs.
Json PropPointJson(const PropPoint& pp);

// The per-throttle table of report's SummarizeThrottles (model/sweep.h) as JSON rows.
Json ThrottleTableJson(const Drive& drive, double vdc_v);

// simulate with a point (--throttle with a load, or --torque --rpm): the point and its p10-p90
// range, the same point with the motor at the low and high end of its data's spread
// (catalog/in_system.h MotorSpreadParams: the in-system law's scatter, else the tier's band).
struct PointRange {
  OperatingPoint point, lo, hi;
};
PointRange SolvePointRange(const MotorEntry& motor, const EscEntry& esc, const PointRequest& req,
                           const std::vector<double>& law = {});
// Its --json document: the point, idc_a_range, pdc_w_range, range_basis, the ids, the assumed note.
Json PointWithRangeJson(const MotorEntry& motor, const EscEntry& esc, const PointRange& r);

// simulate --json without a point: the table per throttle at vdc_v.
Json DriveTableJson(const MotorEntry& motor, const EscEntry& esc, double vdc_v,
                    const std::vector<std::string>& figures);

// simulate --prop P with a point: solved at the propeller shaft through the motor's gearbox
// (model/gear.h) and reported at the motor's shaft. req.rpm is the motor's speed.
struct PropPointRun {
  PropPoint point;        // at the motor's shaft
  double prop_rpm = 0.0;  // the propeller's speed
  MotorShaft shaft;
};
PropPointRun RunPropPoint(const MotorEntry& motor, const EscEntry& esc, const PropEntry& prop,
                          PropPointRequest req);
Json PropPointRunJson(const PropPointRun& run, const MotorEntry& motor, const EscEntry& esc,
                      const PropEntry& prop, double rho_kg_m3);

// simulate --prop P without a point: the rows of the table over throttle as JSON.
Json PropTableJson(const std::vector<ThrottleTableRow>& rows);

}  // namespace dynosize::api
