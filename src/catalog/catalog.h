// The component catalog: a folder of JSON files, each an object with any of the arrays
// "motors", "escs", "props", "batteries". Every entry has a unique "id" (across the whole
// catalog), a "name" and a "source" object saying where its numbers came from:
//
//   "source": {"dataset": "...",            required: the data set or document
//              "reference": "...",          optional: file, row, figure
//              "values": {"rm_ohm": "assumed", ...},  optional: how each value was obtained,
//                                           one of datasheet | measured | fitted | derived | assumed
//              "note": "..."}               optional
//
// The reader is strict (schema.h lists every key, its type, unit and range): unknown keys,
// missing keys, wrong types, non-finite or out-of-range values and duplicate ids are errors that
// name the file, the entry (index and id), the key, the value and the rule. Load() refuses a
// catalog with any problem; Validate() returns every problem in the folder.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/json_file.h"
#include "model/drive.h"

namespace dynosize {

enum class ComponentKind { kMotor, kEsc, kProp, kBattery };

// "motors", "escs", "props", "batteries".
const char* KindArrayName(ComponentKind kind);
// "motor", "ESC", "propeller", "battery".
const char* KindNoun(ComponentKind kind);

struct EntryBase {
  std::string id;
  std::string name;
  std::string file;  // the catalog file it came from
  Json json;         // the entry exactly as in the file
  // Keys whose source.values says "assumed" (results built on them must say so).
  std::vector<std::string> assumed_keys;
};

struct MotorEntry : EntryBase {
  MotorParams params;
  std::optional<double> kv_rpm_per_v;
  std::optional<double> mass_kg;
};

struct EscEntry : EntryBase {
  EscParams params;
  std::optional<double> mass_kg;
};

struct PropEntry : EntryBase {
  double diameter_m = 0.0;
  std::optional<double> pitch_m;
  std::optional<double> mass_kg;
};

struct BatteryEntry : EntryBase {
  std::optional<double> mass_kg;
};

class Catalog {
 public:
  // Reads every *.json below `dir` (sorted by path, so the result is deterministic). Throws
  // NoInputError when the folder is missing, DataError listing the problems (the first 20, and
  // how many more) when any file breaks a rule.
  static Catalog Load(const std::string& dir);

  // Every problem in the folder, one line each ("file: motors[3] id=x: key 'rm_ohm' = -1: must
  // be > 0"); empty when the catalog is valid. Throws NoInputError when the folder is missing.
  static std::vector<std::string> Validate(const std::string& dir);

  // Adds the entries of one parsed catalog document; problems are appended to `problems`.
  void AddDocument(const Json& doc, const std::string& file, std::vector<std::string>* problems);

  const std::vector<MotorEntry>& motors() const { return motors_; }
  const std::vector<EscEntry>& escs() const { return escs_; }
  const std::vector<PropEntry>& props() const { return props_; }
  const std::vector<BatteryEntry>& batteries() const { return batteries_; }

  // Lookup by id; UsageError naming the id, the kind and the closest ids when absent.
  const MotorEntry& motor(const std::string& id) const;
  const EscEntry& esc(const std::string& id) const;
  const PropEntry& prop(const std::string& id) const;
  const BatteryEntry& battery(const std::string& id) const;

  std::size_t size() const {
    return motors_.size() + escs_.size() + props_.size() + batteries_.size();
  }

 private:
  template <typename Entry>
  const Entry& Find(const std::vector<Entry>& entries, ComponentKind kind,
                    const std::string& id) const;

  std::vector<MotorEntry> motors_;
  std::vector<EscEntry> escs_;
  std::vector<PropEntry> props_;
  std::vector<BatteryEntry> batteries_;
  // id -> (kind, index); ids are unique across the catalog.
  std::unordered_map<std::string, std::pair<ComponentKind, std::size_t>> index_;
  std::unordered_map<std::string, std::string> id_file_;
};

}  // namespace dynosize
