// `simulate` as a library call: the points, tables and JSON documents that the CLI prints with
// --json and the Python module returns (python/). One implementation for both front ends; the
// CLI keeps flag parsing, text printing and file writes (apps/cmd_simulate.cc).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "io/points_csv.h"
#include "model/drive.h"
#include "model/drive_batch.h"
#include "model/gear.h"
#include "prop/prop_model.h"
#include "stand/prop_point.h"
#include "stand/throttle_table.h"

namespace dynosize::api {

// One request solved on a drive: a torque law (law = {a, b, c}, SI, with a throttle), throttle
// + torque, throttle + rpm (forward, eq 49) or torque + rpm (the inverse, throttle solved).
OperatingPoint SolvePoint(const Drive& drive, const PointRequest& r, const std::vector<double>& law = {});

// The batch path's results as columns (structure of arrays): one array per key of the point JSON
// (model/drive_batch.h PointColumns over its PointColumnsStorage, left uninitialised until the
// solve writes it), and for rows that name a propeller its thrust and g/W. A figure of merit
// above 1 (the propeller data beat momentum theory, docs/model.md section 10) makes a row
// infeasible.
class BatchResult {
 public:
  explicit BatchResult(std::size_t n = 0);
  std::size_t size() const { return storage_.size(); }
  const PointColumns& columns() const { return storage_.columns(); }
  OperatingPoint point(std::size_t i) const { return columns().Get(i); }
  bool has_prop(std::size_t i) const { return !prop_rows_.empty() && prop_rows_[i] != 0; }
  double thrust_n(std::size_t i) const { return thrust_n_[i]; }
  double g_per_w(std::size_t i) const { return g_per_w_[i]; }
  bool beats_momentum_theory(std::size_t i) const { return has_prop(i) && beats_[i]; }
  bool feasible(std::size_t i) const { return columns().feasible[i] && !beats_momentum_theory(i); }
  // The drive's limit names, then "beats_momentum_theory" (the JSON's "limits").
  std::vector<std::string> LimitNames(std::size_t i) const;

 private:
  friend BatchResult SimulateBatch(const Catalog&, const Drive&, const std::vector<PointRequest>&,
                                   const std::string&);
  PointColumnsStorage storage_;
  std::vector<char> prop_rows_;  // empty when no row names a propeller
  std::vector<double> thrust_n_, g_per_w_;
  std::unique_ptr<bool[]> beats_;
};

// The names of a batch point's limits: the drive's (model/drive.h LimitNames), then
// "beats_momentum_theory" for a propeller point above a figure of merit of 1.
std::vector<std::string> BatchLimitNames(std::uint32_t limits, bool beats_momentum_theory);

// The batch path (`simulate --batch`): one result per request, in order. Runs of rows without a
// propeller are solved together by the model's structure-of-arrays batch (model/drive_batch.h);
// a row that names a propeller is solved on its own, propellers looked up once per id. A row
// whose propeller is unknown or whose thrust cannot be reached is bad data: DataError
// "<source>:<row>: <rule>".
BatchResult SimulateBatch(const Catalog& catalog, const Drive& drive, const std::vector<PointRequest>& requests,
                          const std::string& source);

// One input column of a batch given as arrays: n values, or one value for every point (a
// broadcast scalar); absent when data is null.
struct BatchColumn {
  const double* data = nullptr;
  bool broadcast = false;
  explicit operator bool() const { return data != nullptr; }
  double operator[](std::size_t i) const { return broadcast ? data[0] : data[i]; }
};
// A batch whose points all give the same keys (dynosize.simulate's arrays): the keys and rules
// of a --batch row (io/points_csv.h), rpm at the edge as in the file.
struct BatchColumns {
  std::size_t n = 0;
  BatchColumn vdc_v, throttle, torque_nm, rpm, thrust_n;
  std::string prop;  // a catalog propeller id for every point, or ""
};
// Where a propeller batch writes its own outputs (n each).
struct PropColumns {
  double* thrust_n = nullptr;
  double* g_per_w = nullptr;
  bool* beats_momentum_theory = nullptr;
};
// The rules of CheckPointRequest on every point, column by column: UsageError "<source>:<i>:
// <rule>" for the first point that breaks one (i counted from 0).
void CheckBatchColumns(const BatchColumns& in, const std::string& source);
// The batch path over columns, written in place into out (and prop with a propeller); checks
// the columns first (CheckBatchColumns). The same numbers as SimulateBatch on the same points.
void SimulateColumns(const Catalog& catalog, const Drive& drive, const BatchColumns& in, const std::string& source,
                     const PointColumns& out, const PropColumns& prop = {});

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
