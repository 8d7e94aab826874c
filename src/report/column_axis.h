// How a log column is labelled on a figure axis: its name for a person, the unit shown, and the
// factor from the table's SI value to that unit. Shared by the calibration and diagnosis figures.
#pragma once

#include "common/units.h"
#include "logs/steady_table.h"

namespace dynosize {

struct ColumnAxis {
  const char* label;
  const char* unit;
  double scale;  // SI -> shown unit
};

inline ColumnAxis DescribeColumn(logs::Column c) {
  using logs::Column;
  switch (c) {
    case Column::kOmegaRadS: return {"speed", "rpm", 1.0 / kRadPerSecPerRpm};
    case Column::kIdcA: return {"DC current IDC", "A", 1.0};
    case Column::kIrmsA: return {"rms phase current Irms", "A", 1.0};
    case Column::kVllRmsV: return {"line-line rms voltage VLL", "V", 1.0};
    case Column::kPacW: return {"AC power PAC", "W", 1.0};
    case Column::kThrottle: return {"throttle", "%", 100.0};
    case Column::kVdcV: return {"supply voltage VDC", "V", 1.0};
    case Column::kTorqueNm: return {"torque", "N*m", 1.0};
    case Column::kTimeS: return {"time", "s", 1.0};
    case Column::kTempC: return {"temperature", "C", 1.0};
    default: return {logs::ColumnName(c), "", 1.0};
  }
}

}  // namespace dynosize
