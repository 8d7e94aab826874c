// Readers of blade geometry for the blade-element model (rotor/blade.h):
//   - UIUC's geometry tables (shared/data/uiuc_propdb/volume{1,2,3}_geom.csv: BladeName, Family,
//     D [in], P [in], c/R, r/R, beta [deg], one row per station);
//   - APC's PE0 files (shared/data/apc_geometry/geometry/<prop>-PERF.PE0 and
//     large_props_apc/geometry/): per station the radius [in], chord [in], thickness ratio and
//     TWIST [deg] (the angle of the line from leading to trailing edge, APC's "LE-TE" datum),
//     then "RADIUS:", "HUBTRA:" (hub transition) and "BLADES:" lines.
// Errors: DataError naming the file, line and rule; NoInputError for a missing file.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "catalog/entries.h"
#include "rotor/airfoil_fit.h"
#include "rotor/blade.h"
#include "rotor/family.h"
#include "rotor/per3.h"

namespace dynosize {

// Every blade of one volume's geometry CSV, in file order (blades = 2: the measured propellers
// name their blade count, catalog/uiuc_propdb.json). The lifting blade starts at the first
// station (UIUC measured from r/R 0.15, or 0.30 for volume 3's small propellers).
std::vector<FamilyBlade> ReadUiucGeometry(const std::string& csv_path);

// One APC PE0 file. name = the file name without "-PERF.PE0" (e.g. "10x5E").
BladeGeometry ReadApcPe0(const std::string& path);

// APC's computed performance as the PER3 CSV files of shared/data hold it (RPM, Torque (N-m),
// V(speed) (m/s), Thrust (kg)); rows APC truncated (empty torque or thrust) are skipped.
Per3Table ReadApcPer3Csv(const std::string& path);

// An APC file name's diameter and pitch in inches: "10x45MR" -> 10, 4.5; "95x5MR" -> 9.5, 5;
// "8x10" -> 8, 10 (a two-digit diameter above 30 in and a pitch above 1.5 diameters carry an
// implied decimal point). False when the name does not start with "<digits>x<digits>".
bool ParseApcSize(const std::string& name, double* diameter_in, double* pitch_in);

// UIUC's name of an APC propeller as APC files it: family "apce", 10.0 x 5.0 in -> "10x5E";
// "apcsf" 10.0 x 4.7 -> "10x47SF"; "apcsp" 10.0 x 5.0 -> "10x5" (apc_geometry/README.md); "" for
// other families.
std::string ApcFileNameOfUiuc(const std::string& family, double d_in, double p_in);

// The bundled propeller families (rotor/family.h) derived from the data:
//   apc_e, apc_sf, apc_sport: the blades UIUC measured of APC's thin electric, slow-flyer and
//     sport families (uiuc_propdb/volume{1,2}_geom.csv, families apce, apcsf, apcsp);
//   multirotor: APC's multirotor (MR) blades from APC's own geometry (apc_geometry/geometry/*MR-PERF.PE0).
// `leave_out` names a blade to leave out of its family (the size-only check); "" = none.
std::vector<RotorFamily> DeriveBundledFamilies(const std::string& data_dir, const std::string& leave_out = "");
// The same in two steps, for callers that derive the families many times (the size-only check
// leaves each propeller out): the blades read once, then the shapes from them.
struct FamilyBlades {
  std::vector<FamilyBlade> uiuc;    // volumes 1-2, every family
  std::vector<FamilyBlade> apc_mr;  // APC's MR geometry files
};
FamilyBlades ReadFamilyBlades(const std::string& data_dir);
std::vector<RotorFamily> DeriveBundledFamilies(const FamilyBlades& blades, const std::string& leave_out = "");

// The measured propellers of catalog/uiuc_propdb.json whose blade has a UIUC geometry table
// (blade name from the id, importers/blade_geometry.h), as fit cases: every static point, and of
// each J sweep at most max_sweep_points (evenly spaced; positive thrust only).
std::vector<RotorFitCase> UiucCases(const std::vector<PropEntry>& props,
                                    const std::map<std::string, FamilyBlade>& blades,
                                    int max_sweep_points = 6);

// The blade name of a UIUC catalog entry id ("uiuc_v1_apce_10.0x5.0_2" -> "apce 10.0x5.0"),
// "" when the id is not a UIUC one.
std::string UiucBladeNameOfId(const std::string& id);

}  // namespace dynosize
