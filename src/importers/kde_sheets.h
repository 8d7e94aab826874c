// KDE Direct's stand sheets (../shared/data/kde_direct_mfr_sheets, README there): for each of
// 11 motors the datasheet values (kde_motor_specs.csv, printed with their units: "105 RPM/V",
// "0.023 Ω", "1.0 A", "1075 g (1180 g with Wires/Bullets)") and the measured sweeps
// (kde_performance.csv: one block per propeller and supply voltage, throttle 25-100 %).
// Read for the in-system law of catalog/in_system.h (stand/in_system_fit.h).
#pragma once

#include <string>
#include <vector>

namespace dynosize {

struct KdeSheetRow {
  int line = 0;           // line in kde_performance.csv
  int block = 0;          // the sheet's sweep (one propeller and voltage)
  double vdc_v = 0.0;     // V_from_P_over_I: the real supply voltage (README)
  double throttle = 0.0;  // the ESC command, 0..1
  double idc_a = 0.0;
  double rpm = 0.0;
  double torque_nm = 0.0;  // NaN where the sheet has no torque column (two older sheets)
  double thrust_n = 0.0;   // measured at the site (thrust_N), not KDE's sea-level estimate
  double thrust_sealevel_est_n = 0.0;  // KDE's calculated sea-level estimate; NaN when empty
  std::string prop;        // "30.5x9.7 DUAL"
};

struct KdeSheetMotor {
  std::string name;  // "KDE5215XF-330"
  double kv_rpm_per_v = 0.0;
  double kt_nm_per_a = 0.0;
  double io_dc_a = 0.0;             // no-load current at io_test_voltage_v
  double io_test_voltage_v = 10.0;  // "no-load current at 10 V" (the data set's README)
  double r_dc_ohm = 0.0;            // phase resistance as printed (the DC circuit's R)
  double mass_kg = 0.0;             // without wires
  double max_current_a = 0.0;
  std::vector<KdeSheetRow> rows;
  bool has_torque() const;
};

// Both files of the folder. Throws NoInputError when a file is missing, DataError naming the
// file, line, column and value when a cell cannot be read or a motor of the sweeps has no
// datasheet row.
std::vector<KdeSheetMotor> ReadKdeSheets(const std::string& dir);

}  // namespace dynosize
