// Pieces shared by the catalog importers: the import report (what was kept, what was dropped
// and why), entry building with provenance, rounding and id slugs, and the deterministic
// catalog file layout.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/json_file.h"

namespace dynosize {

// Rows dropped for one reason.
struct DropCount {
  std::string kind;    // "motors", "escs", "props", "batteries"
  std::string reason;  // e.g. "Rm = 0 placeholder"
  std::size_t count = 0;
  std::vector<std::string> examples;  // the first few "file:line name"
};

// What one data set's importer did.
struct DatasetReport {
  std::string dataset;      // folder name in shared/data, e.g. "drivecalc"
  std::string output_file;  // catalog file written, e.g. "drivecalc.json"
  std::map<std::string, std::size_t> kept;  // kind -> entries written
  std::vector<DropCount> dropped;           // in the order first seen
  std::vector<std::string> notes;           // cleaning done without dropping (unit fixes, ...)
  // Propellers whose power data were raised to the envelope of measured propellers (AuditProp),
  // with the first few "id xfactor" as examples.
  std::size_t props_derated = 0;
  std::vector<std::string> derated_examples;

  void Keep(const std::string& kind) { ++kept[kind]; }
  void Drop(const std::string& kind, const std::string& reason, const std::string& example);
  std::size_t DroppedCount(const std::string& kind) const;
};

struct ImportReport {
  std::vector<DatasetReport> datasets;
  // Kept entries per kind over all data sets.
  std::map<std::string, std::size_t> TotalKept() const;
  // One line: "1807 motors, ... written to 8 files; 123 rows dropped".
  std::string BriefReport() const;
  // A table per data set with every drop reason, its count and examples.
  std::string FullReport() const;
  Json ToJson() const;
};

// Rounds to `digits` significant digits (through the shortest decimal text, so the JSON shows
// the rounded number); keeps derived numbers from carrying float noise into the catalog.
double RoundSig(double x, int digits = 6);

// Lowercase ASCII slug: letters and digits kept, German umlauts and sharp s transliterated
// (ae, oe, ue, ss), runs of anything else become one '_'; no leading or trailing '_'.
std::string Slug(const std::string& text);

// Collapses runs of white space to one space and trims.
std::string CleanName(const std::string& text);

// Builds one catalog entry with its provenance: keys in insertion order, then "source".
class EntryBuilder {
 public:
  EntryBuilder(const std::string& id, const std::string& name);
  // Sets a value and records how it was obtained (datasheet|measured|computed|fitted|derived|
  // assumed); method "" records nothing (for id-like keys such as "type" when obvious).
  EntryBuilder& Set(const std::string& key, const Json& value, const std::string& method);
  // The number rounded to 6 significant digits.
  EntryBuilder& SetNum(const std::string& key, double value, const std::string& method,
                       int digits = 6);
  EntryBuilder& Source(const std::string& dataset, const std::string& reference,
                       const std::string& note);
  // source.tier: measured | manufacturer_computed | manufacturer_stated | user_contributed |
  // assumed (catalog/conventions.h).
  EntryBuilder& Tier(const std::string& tier);
  Json Build() const;

 private:
  Json entry_;
  Json values_ = Json::object();
  std::string dataset_, reference_, note_, tier_;
};

// The figure-of-merit audit of a propeller entry that is not measured (catalog/
// prop_credibility.h): an entry whose static FM exceeds 1 anywhere in its valid range is
// refused (returns false, reason in *why); one above the envelope of measured propellers of
// its size class gets its power data (power_law_w, cp_static, static_table.cp, j_tables.cp)
// multiplied by fm_max/envelope_max, "power_derate_factor" set and a note appended. Counts go
// to report->notes through the caller.
struct PropAudit {
  bool refused = false;
  bool derated = false;
  double fm_max = 0.0;        // before derating
  double envelope_max = 0.0;  // of the size class
  double factor = 1.0;
  std::string why;
};
PropAudit AuditProp(Json* entry);

// Motor ratings (catalog/conventions.h): with a rating, nothing; without one, a BLDC motor
// with a mass gets max_power_w from the outrunner specific-power law ("assumed"), any other
// gets "exclude". Returns the text to append to source.note ("" or "; ...").
std::string SetRatingOrExclude(EntryBuilder* b, bool has_rating, std::optional<double> mass_kg,
                               bool brushed);

// Resistance convention (catalog/conventions.h): sets rm_dc_ohm (the source's DC-circuit
// resistance, with its method) and rm_ohm = 0.7492*rm_dc_ohm ("derived").
void SetResistanceFromDc(EntryBuilder* b, double r_dc_ohm, const std::string& method, int digits = 6);

// A rating's duration printed in text, s: the first number followed by "s" or "min" ("10 s
// burst" -> 10, "S2 2 min" -> 120, "periodic 30 s at 100 % + 90 s at 50 %" -> 30); nullopt for
// text without one ("take-off", "short duration").
std::optional<double> DurationTextS(const std::string& text);

// Writes a catalog document {"comment": ..., "motors": [...], ...} with one entry per line
// (compact JSON inside the entry), the kinds in the order motors, escs, props, batteries, and a
// final newline: small, diff-friendly and byte-for-byte reproducible. Empty kinds are omitted.
std::string FormatCatalogDocument(const std::string& comment, const Json& motors,
                                  const Json& escs, const Json& props, const Json& batteries);

}  // namespace dynosize
