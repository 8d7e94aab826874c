// Stand-table predictions: a measured thrust-stand or manufacturer table
// (rows of VDC, throttle and/or rpm, and measured thrust, DC current, rpm, torque where present)
// predicted row by row through catalog entries, by dynosize's rms model (model/drive.h, eqs
// 42-59) and by the plain first-order DC model (stand/dc_baseline.h) side by side.
//
// Two ways to predict a row:
//  - at the measured rpm (StandMode::kAtMeasuredRpm): the load torque is the propeller's at
//    that speed (PropModel, src/prop/prop_model.h) or, without a propeller, the measured torque;
//    thrust is the propeller's at that speed; the current and the throttle needed follow from
//    the inverse model (Drive::Inverse; baseline: I = Io + Q/KT_dc, U = n/Kv + R*I, IDC = U*I/VDC).
//    This separates the motor + ESC from the throttle mapping, and is what the goals
//    measure ("predicted at the measured rpm through the catalog's propeller entries").
//  - at the measured rpm and torque (StandMode::kAtMeasuredTorque), when a propeller is given
//    and the table has torque: the motor + ESC alone, without the propeller's error.
//  - forward from the throttle (StandMode::kFromThrottle), where the table has throttle: VDC and
//    throttle given, the load (the propeller's torque law, else the measured torque held
//    constant) sets the speed (SolveDriveWithProp / Drive::AtTorque; baseline: d = throttle).
//
// Error per column: 100*(predicted - measured)/measured on rows with a measured value > 0;
// reported as the mean absolute value (MAE %), the mean (bias %) and the largest magnitude.
// Throttle errors are in percentage points (absolute), not relative.
//
// No I/O here (the table is read by src/logs; the CLI formats the result).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "logs/steady_table.h"
#include "model/drive.h"
#include "prop/prop_model.h"
#include "stand/dc_baseline.h"

namespace dynosize::stand {

struct StandRow {
  std::size_t line = 0;  // 1-based line of the file (first averaged sample)
  double vdc_v = 0.0;
  std::optional<double> throttle, omega_rad_s, thrust_n, idc_a, torque_nm;
};

struct StandReadOptions {
  // Supply voltage for tables without a voltage column (MIT's KDE2814 logs); ignored when the
  // table has one.
  std::optional<double> vdc_v;
  // Keep only rows whose source line lies in [first_line, last_line] (0: no bound): one block
  // of a file that holds several propellers (sjkim's AT3520 table).
  std::size_t first_line = 0, last_line = 0;
};

struct StandTable {
  std::string file;
  std::vector<StandRow> rows;
  bool has_throttle = false, has_rpm = false, has_thrust = false, has_torque = false;
  bool vdc_from_option = false;
  std::vector<logs::DropCount> dropped;  // rows left out here, per reason
};

// Rows of a table read by logs::ReadLog. Rows at rest (rpm 0 or no current) and outside the
// line range are dropped and counted. DataError (naming the file and the missing column) when
// there is no voltage and no --vdc, neither rpm nor throttle, or no row is left.
StandTable StandTableFromLog(const logs::SteadyTable& table, const StandReadOptions& options);

enum StandMode { kAtMeasuredRpm = 0, kAtMeasuredTorque = 1, kFromThrottle = 2 };
inline constexpr int kStandModes = 3;
enum StandModel { kDynosize = 0, kPlainDc = 1 };
const char* StandModeName(int mode);    // "at_measured_rpm", "at_measured_rpm_and_torque", "from_throttle"
const char* StandModelName(int model);  // "dynosize", "plain_dc"

// One row predicted by one model in one mode.
struct StandPrediction {
  bool valid = false;  // false: the mode does not apply to the row, or no converged point
  double rpm = 0.0;
  double torque_nm = 0.0;
  double idc_a = 0.0;
  double throttle = 0.0;  // at measured rpm: the throttle the model needs (0..1, may exceed 1)
  std::optional<double> thrust_n;  // with a propeller
  bool feasible = true;   // dynosize: no limit violated (Drive limits, creates_energy);
                          // baseline: duty <= 1
  std::vector<std::string> limits;
};

struct StandRowResult {
  StandPrediction pred[kStandModes][2];  // [StandMode][StandModel]
  std::string prop_note;       // propeller data held at an edge at the measured (or predicted) rpm
};

struct ColumnError {
  std::string column;  // thrust_n, idc_a, rpm, torque_nm, throttle
  std::size_t n = 0;
  double mae = 0.0;      // mean absolute error: % (throttle: percentage points)
  double bias = 0.0;     // mean signed error, same unit
  double max_abs = 0.0;  // largest magnitude, same unit
};

struct StandOptions {
  double rho_kg_m3 = 1.225;  // air density (ISA sea level; stand tables rarely state it)
};

struct StandResult {
  std::vector<StandRowResult> rows;  // one per StandTable row
  bool mode_used[kStandModes] = {false, false, false};
  std::string load[kStandModes];  // what loads the motor ("propeller x", "measured torque")
  bool prop_load[kStandModes] = {false, false, false};  // the propeller's torque (an output)
  std::vector<ColumnError> errors[kStandModes][2];  // [StandMode][StandModel]
  std::size_t rows_outside_prop_data = 0;
  std::size_t rows_infeasible[kStandModes] = {0, 0, 0};  // dynosize points flagged, per mode
};

// Predicts every row. `prop` may be null (then the table needs a torque column). DataError
// naming the file when neither a propeller nor a torque column gives the load, or when the
// table has no rpm column and no throttle column.
StandResult PredictStand(const StandTable& table, const Drive& drive, const DcMotor& dc,
                         const PropModel* prop, const StandOptions& options);

// The ESC as eq (56)'s ideal chopper: RESC = 0, C1 = K*kp, C0 = 0, no saturation knee, no
// deadband, no supply resistance; the current and voltage limits are kept. For a stand table
// whose ESC is not in the catalog and whose motor resistance was fitted on full-throttle rows
// with that ESC in the loop (V = R*I + rpm/Kv, importers/mfr_tables.cc): the fit already holds
// the ESC's drop, so a catalog ESC's resistance and the prior's knee (tr_sat 0.9, slope 0.61)
// would count it twice.
EscParams IdealEsc(const EscParams& esc, MotorType type);

// The error of `column` in (mode, model); nullptr when not computed.
const ColumnError* FindError(const StandResult& r, int mode, int model, const std::string& column);

}  // namespace dynosize::stand
