// Readers of blade geometry for the blade-element model (rotor/blade.h):
//   - UIUC's geometry tables (shared/data/uiuc_propdb/volume{1,2,3}_geom.csv: BladeName, Family,
//     D [in], P [in], c/R, r/R, beta [deg], one row per station);
//   - APC's PE0 files (shared/data/apc_geometry/geometry/<prop>-PERF.PE0 and
//     large_props_apc/geometry/): per station the radius [in], chord [in], thickness ratio and
//     TWIST [deg] (the angle of the line from leading to trailing edge, APC's "LE-TE" datum),
//     then "RADIUS:", "HUBTRA:" (hub transition) and "BLADES:" lines.
// Errors: DataError naming the file, line and rule; NoInputError for a missing file.
#pragma once

#include <string>
#include <vector>

#include "rotor/blade.h"

namespace dynosize {

// One UIUC blade: its geometry (blades = 2; the measured propellers name their blade count,
// catalog/uiuc_propdb.json) and the family and nominal size it was filed under.
struct UiucBlade {
  BladeGeometry geometry;
  std::string family;     // e.g. "apce"
  double diameter_in = 0.0, pitch_in = 0.0;
};

// Every blade of one volume's geometry CSV, in file order. The lifting blade starts at the first
// station (UIUC measured from r/R 0.15, or 0.30 for volume 3's small propellers).
std::vector<UiucBlade> ReadUiucGeometry(const std::string& csv_path);

// One APC PE0 file. name = the file name without "-PERF.PE0" (e.g. "10x5E").
BladeGeometry ReadApcPe0(const std::string& path);

// The blade name of a UIUC catalog entry id ("uiuc_v1_apce_10.0x5.0_2" -> "apce 10.0x5.0"),
// "" when the id is not a UIUC one.
std::string UiucBladeNameOfId(const std::string& id);

}  // namespace dynosize
