// Calibration results as catalog entries (catalog/README.md, src/catalog/schema.h), and writing
// them into a catalog file without losing what is already there.
//
// Provenance: a value the fit determined is "fitted"; one held at a prior or default because
// the data cannot identify it is "assumed" (so results built on it say so); kv_rpm_per_v is
// "derived" from the fitted KE by docs/model.md section 8, KT tied to KE is "derived".
#pragma once

#include <string>
#include <vector>

#include <optional>

#include "calibration/calibrate.h"
#include "calibration/prop_static.h"
#include "common/json_file.h"
#include "identification/verdict.h"

namespace dynosize::calibration {

struct EntryProvenance {
  std::string dataset;    // e.g. the log file names
  std::string reference;  // e.g. "dynosize calibrate (dc), 42 points"
  std::string note;       // appended to the automatic note (unidentifiable parameters)
};

// Datasheet values stored in a written entry (sizing needs mass and ratings; --kv-label is kept
// beside the fitted KE). Each is recorded as "datasheet" in source.values.
struct EntryRatings {
  std::optional<double> mass_kg, max_current_a, max_power_w, kv_label_rpm_per_v, vdc_max_v;
};
// Sets the given keys of `entry` (mass_kg, max_current_a, max_power_w, kv_rpm_per_v, vdc_max_v).
void AddRatings(Json* entry, const EntryRatings& ratings);

// {"status", "summary", "advice", "checks": [{name, passed, value, limit, detail}]}.
Json VerdictJson(const identification::Verdict& v);

// A propeller entry {"id", "name", "diameter_m", ["pitch_m",] "static_table": {rpm, ct, cp},
// "source"} from FitPropStatic.
Json PropEntryJson(const std::string& id, const std::string& name, const PropStaticTable& table,
                   const PropStaticOptions& options, const EntryProvenance& p);

// One value of a catalog entry and how it was obtained ("fitted", "assumed", "derived",
// "datasheet", "measured"): a number (rounded to 6 significant digits) or, when text is not
// empty, a string.
struct EntryValue {
  std::string key;
  double value = 0.0;
  std::string method;
  std::string text;
};
// The one writer of catalog entries from identified parameters (calibrate and diagnose):
// {"id", "name", <values>, "source": {"dataset", "reference", "values": {key: method}, "note"}}.
// Throws DataError naming the entry when a value is not finite.
Json ComponentEntryJson(const std::string& id, const std::string& name, const std::vector<EntryValue>& values,
                        const EntryProvenance& p, const std::string& auto_note, const std::string& kind);

// {"id", "name", "type": "bldc", "ke_v_s_per_rad", "kt_nm_per_a", "rm_ohm", "io_a",
//  "kv_rpm_per_v", "source"}.
Json MotorEntryJson(const std::string& id, const std::string& name, const CalibrationResult& r,
                    const EntryProvenance& p);
// {"id", "name", "resc_ohm", "c1", "c0", "tr_sat", "sat_slope", "source"}.
Json EscEntryJson(const std::string& id, const std::string& name, const CalibrationResult& r,
                  const EntryProvenance& p);

// Adds the entries to the catalog document in `path` (created when missing, with `comment`)
// and writes it atomically. An entry whose id is already in the file is replaced only with
// `force`; otherwise UsageError naming the id and the file, and the file is left untouched.
// The new document is checked with the catalog reader before it is written (DataError listing
// the problems if not). Throws CantCreateError when the file cannot be written.
void WriteCatalogEntries(const std::string& path, const std::vector<Json>& motors,
                         const std::vector<Json>& escs, bool force, const std::string& comment,
                         const std::vector<Json>& props = {});

// Parameters as {name: value} and {name: standard error | null} / {name: bool} objects.
Json StandardErrorsJson(const CalibrationResult& r);
Json IdentifiableJson(const CalibrationResult& r);
// {"mode", "converged", "message", "points_used", "points_dropped", "dropped": [..],
//  "condition_number", "r_total_ohm", "r_total_stderr", "columns": {name: {rmse, rmse_percent,
//  median_abs_percent, points}}, "unidentifiable_directions": [..]}.
Json FitJson(const CalibrationResult& r);

}  // namespace dynosize::calibration
