// Readers of the motors that state their constants (Kv, R, Io) next to what eVTOL makers state
// (mass, power, torque, speed, voltage): the references MotorEstimateLaw (catalog/
// motor_estimate.h) is fitted on, and the stated values of the eVTOL survey's motors to
// estimate from.
//
// Usage (the data folder is ../shared/data from the project root):
//     const std::vector<ReferenceMotor> refs = ReadReferenceMotors(data_dir);
//     const MotorEstimateLaw law = MotorEstimateLaw::Fit(refs);
//     for (const EvtolStatedRow& row : ReadEvtolStatedMotors(data_dir + "/evtol_motors/evtol_motors.csv"))
//       MotorConstantsEstimate e = law.Estimate(row.stated);   // e.FullReport(), e.AllKnown()
//
// Conventions (catalog/conventions.h 1.): R is the DC equivalent circuit's, i.e. the
// line-to-line ohmmeter value; Io the DC no-load current at the stated test voltage.
// - evtol_motors.csv: EMRAX rows give Kv and R (r_phase_ohm is "measured phase to phase, then
//   divided by 2", so R_dc = 2*r_phase_ohm) and no Io; Beyond Motors, Rotex and T-Motor rows
//   give Kv only; the other makers' rows no constant (not references).
// - neumotors_windings.csv: Kv, Rm, Io at io_test_v. The 88xx sheet's Rm and Io columns are
//   swapped (flagged in the file: Rm rises with Kv); the reader swaps them back. Values below
//   0.010 (printed with 3 decimals, so > 5 % rounding) are treated as not stated. Mass is the
//   model block's (blank for five models: those windings then have no mass).
// - heavy_lift_motors.csv: T-Motor and KDE rows with Kv, R, Io at 10 V, mass and p_max_w (as
//   p_cont_w); rows also in kde_datasheets.csv (in_kde_datasheets "yes ...") are skipped.
// - kde_datasheets.csv: the 21 KDE Direct datasheets (mass without wires, v_max_v).
// A malformed number in a column the reader uses throws DataError naming file:line, column and
// value; a missing file throws NoInputError.
#pragma once

#include <string>
#include <vector>

#include "catalog/motor_estimate.h"

namespace dynosize {

std::vector<ReferenceMotor> ReadEvtolReferenceMotors(const std::string& evtol_motors_csv);
std::vector<ReferenceMotor> ReadNeuMotorsWindings(const std::string& neumotors_windings_csv);
std::vector<ReferenceMotor> ReadHeavyLiftMotors(const std::string& heavy_lift_motors_csv);
std::vector<ReferenceMotor> ReadKdeDatasheetMotors(const std::string& kde_datasheets_csv);

// All four files of `data_dir` (evtol_motors/, heavy_lift_motors/): the references of the law.
std::vector<ReferenceMotor> ReadReferenceMotors(const std::string& data_dir);

// Every row of evtol_motors.csv as stated (kv_rpm_per_v where printed), model = "model, variant".
struct EvtolStatedRow {
  StatedMotor stated;
  std::string where;  // "file:line"
};
std::vector<EvtolStatedRow> ReadEvtolStatedMotors(const std::string& evtol_motors_csv);

}  // namespace dynosize
