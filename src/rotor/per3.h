// APC's computed propeller performance (PER3 files: APC's own blade-element code), as a table of
// rows (rpm, airspeed, thrust, torque), and its interpolation at a speed and airspeed: the side
// of the comparison in docs/validation.md that APC publishes. No I/O
// (importers/blade_geometry.h reads the files).
#pragma once

#include <string>
#include <vector>

namespace dynosize {

struct Per3Row {
  double rpm = 0.0;
  double airspeed_m_s = 0.0;
  double thrust_n = 0.0;
  double torque_nm = 0.0;
};

struct Per3Table {
  std::string name;
  std::vector<Per3Row> rows;  // by rpm blocks, airspeed increasing within a block
};

// Thrust and torque at (rpm, airspeed): linear in airspeed within the two rpm blocks around rpm,
// then linear in rpm between them. False outside the table (rpm beyond its blocks, airspeed
// beyond a block's last row).
bool Per3At(const Per3Table& table, double rpm, double airspeed_m_s, double* thrust_n, double* torque_nm);

}  // namespace dynosize
