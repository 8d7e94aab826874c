// Pieces shared by the catalog importers: the import report (what was kept, what was dropped
// and why), entry building with provenance, rounding and id slugs, and the deterministic
// catalog file layout.
#pragma once

#include <cstddef>
#include <map>
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
  Json Build() const;

 private:
  Json entry_;
  Json values_ = Json::object();
  std::string dataset_, reference_, note_;
};

// Writes a catalog document {"comment": ..., "motors": [...], ...} with one entry per line
// (compact JSON inside the entry), the kinds in the order motors, escs, props, batteries, and a
// final newline: small, diff-friendly and byte-for-byte reproducible. Empty kinds are omitted.
std::string FormatCatalogDocument(const std::string& comment, const Json& motors,
                                  const Json& escs, const Json& props, const Json& batteries);

}  // namespace dynosize
