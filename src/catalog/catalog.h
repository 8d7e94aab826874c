// The component catalog: a folder of JSON files, each an object with any of the arrays
// "motors", "escs", "props", "batteries", and "prop_families" (propeller families the search
// sizes; catalog/prop_families.h). Every entry has a unique "id" (across the whole
// catalog), a "name" and a "source" object saying where its numbers came from:
//
//   "source": {"dataset": "...",            required: the data set or document
//              "reference": "...",          optional: file, row, figure
//              "values": {"rm_ohm": "assumed", ...},  optional: how each value was obtained,
//                                           one of datasheet | measured | computed | fitted |
//                                           derived | assumed ("computed": a manufacturer's own
//                                           simulation, e.g. APC PER3 blade-element tables)
//              "note": "...",               optional
//              "tier": "measured"}          optional: the trust tier of the entry's data, one
//                                           of measured | manufacturer_computed |
//                                           manufacturer_stated | user_contributed | assumed
//                                           (best first; catalog/conventions.h); inferred from
//                                           "values" when absent
//
// Any entry may carry "exclude": "reason": it stays in the catalog for reference, but searches
// skip it by default (e.g. a motor with no rating and no mass to estimate one from).
//
// The reader is strict (schema.h lists every key, its type, unit and range): unknown keys,
// missing keys, wrong types, non-finite or out-of-range values and duplicate ids are errors that
// name the file, the entry (index and id), the key, the value and the rule. Physics at the door
// (docs/model.md section 10, model/physics.h, catalog/prop_credibility.h): an ESC or a motor whose
// constants create energy, or a propeller whose figure of merit exceeds 1 anywhere in its valid
// range, is a problem too. Load() refuses a catalog with any problem; Validate() returns every
// problem in the folder.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "catalog/catalog_path.h"
#include "common/json_file.h"
#include "catalog/entries.h"
#include "rotor/family.h"

namespace dynosize {

// The typed form of one propeller entry that already passed the schema (importers use it to
// audit what they write); no physics checks.
PropEntry PropEntryFromJson(const Json& entry);

class Catalog {
 public:
  // Reads every *.json below `dir` (sorted by path, so the result is deterministic). Throws
  // NoInputError when the folder is missing, DataError listing the problems (the first 20, and
  // how many more) when any file breaks a rule.
  // Motors whose resistance or no-load current is a datasheet value get the in-system law's
  // values (catalog/in_system.h; MotorEntry::datasheet_params keeps the file's) unless
  // `in_system_law` is false.
  static Catalog Load(const std::string& dir, bool in_system_law = true);
  // The base folder, then each added folder (CatalogFolders). A missing added folder is a
  // NoInputError, one without a .json file a DataError, as for the base.
  static Catalog Load(const CatalogFolders& folders, bool in_system_law = true);

  // Every problem in the folder, one line each ("file: motors[3] id=x: key 'rm_ohm' = -1: must
  // be > 0"); empty when the catalog is valid. Throws NoInputError when the folder is missing; a
  // folder without a .json file is a problem, as for Load.
  static std::vector<std::string> Validate(const std::string& dir);
  // Every problem of the folders read together (clashing ids included).
  static std::vector<std::string> Validate(const CatalogFolders& folders);

  // Adds the entries of one parsed catalog document; problems are appended to `problems`.
  void AddDocument(const Json& doc, const std::string& file, std::vector<std::string>* problems);

  const std::vector<MotorEntry>& motors() const { return motors_; }
  const std::vector<EscEntry>& escs() const { return escs_; }
  const std::vector<PropEntry>& props() const { return props_; }
  const std::vector<BatteryEntry>& batteries() const { return batteries_; }
  // Propeller families searched with their size free (catalog/prop_families.h; offered to a
  // mission's searched groups within their max_prop_diameter_m by api::MissionCatalog).
  const std::vector<PropSizing>& prop_families() const { return prop_families_; }

  // Lookup by id; UsageError naming the id, the kind and the closest ids when absent.
  const MotorEntry& motor(const std::string& id) const;
  const EscEntry& esc(const std::string& id) const;
  const PropEntry& prop(const std::string& id) const;
  const BatteryEntry& battery(const std::string& id) const;

  std::size_t size() const {
    return motors_.size() + escs_.size() + props_.size() + batteries_.size();
  }

 private:
  // Converts a valid entry to its typed form and adds it, unless it breaks a physical rule
  // (docs/model.md section 10): returns that rule's sentence then, "" when added.
  std::string AddEntry(ComponentKind kind, const Json& e, EntryBase base);

  struct IdOrigin;
  // Adds a converted entry, or replaces the entry of the same id and kind (an override).
  template <typename Entry>
  void Put(std::vector<Entry>* entries, ComponentKind kind, Entry entry);
  std::string ClashRule(const IdOrigin& prev, ComponentKind kind, const std::string& id) const;

  template <typename Entry>
  const Entry& Find(const std::vector<Entry>& entries, ComponentKind kind,
                    const std::string& id) const;

  // Reads every folder of `folders` (in order) into *this; problems are appended.
  void AddFolders(const CatalogFolders& folders, std::vector<std::string>* problems);

  bool in_system_law_ = false;  // Load's choice; AddDocument alone keeps the file's numbers
  // Which folder of CatalogFolders AddDocument is reading (0: the base) and whether an entry of
  // a later folder may replace one of an earlier folder with the same id.
  std::size_t folder_ = 0;
  bool override_ids_ = false;
  std::vector<MotorEntry> motors_;
  std::vector<EscEntry> escs_;
  std::vector<PropEntry> props_;
  std::vector<BatteryEntry> batteries_;
  std::vector<PropSizing> prop_families_;
  // id -> (kind, index); ids are unique across the catalog.
  std::unordered_map<std::string, std::pair<ComponentKind, std::size_t>> index_;
  // id -> where it was read ("file: motors[3] id=x") and from which folder.
  struct IdOrigin {
    std::string where;
    std::size_t folder = 0;
  };
  std::unordered_map<std::string, IdOrigin> id_file_;
};

}  // namespace dynosize
