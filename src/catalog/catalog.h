// The component catalog: a folder of JSON files, each an object with any of the arrays
// "motors", "escs", "props", "batteries". Every entry has a unique "id" (across the whole
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
#include "model/drive.h"
#include "model/gear.h"

namespace dynosize {

enum class ComponentKind { kMotor, kEsc, kProp, kBattery };

// Trust tier of an entry's data, best first (catalog/conventions.h).
enum class DataTier {
  kMeasured = 0,
  kManufacturerComputed = 1,
  kManufacturerStated = 2,
  kUserContributed = 3,
  kAssumed = 4,
};
// "measured", "manufacturer_computed", "manufacturer_stated", "user_contributed", "assumed".
const char* TierName(DataTier tier);
// All tier names, best first (the schema's choices).
const std::vector<std::string>& TierNames();

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
  // source.tier, or inferred from source.values when the file does not state it.
  DataTier tier = DataTier::kAssumed;
  bool tier_stated = false;
  // "exclude" of the file: why searches skip this entry by default ("" = usable).
  std::string exclude_reason;
};

// The tier of one value of an entry: from its source.values label (as the tier inference reads
// it), never better than the entry's tier; the entry's tier when the value has no label.
DataTier ValueTier(const EntryBase& entry, const std::string& key);
// The source.values label of one value ("datasheet", "fitted", ...); "" when it has none.
std::string ValueMethod(const EntryBase& entry, const std::string& key);

struct MotorEntry : EntryBase {
  MotorParams params;
  std::optional<double> kv_rpm_per_v;
  std::optional<double> mass_kg;
  // DriveCalc's loss terms (docs/model.md section 9): Io(omega) = (loss_torque_nm +
  // loss_torque_per_omega_nm_s_per_rad*omega)/kt; absent for other data sets.
  std::optional<double> loss_torque_nm;
  std::optional<double> loss_torque_per_omega_nm_s_per_rad;
  // The entry's own numbers when the in-system law (catalog/in_system.h) replaced params' rm_ohm,
  // io_a or io1 by the values the motor shows in a system; empty when params are the file's.
  std::optional<MotorParams> datasheet_params;
  // Keys gear_ratio, gear_efficiency (model/gear.h); direct drive when absent. params and
  // kv_rpm_per_v are the motor's own (at its shaft, before the gearbox).
  Gear gear;
};

struct EscEntry : EntryBase {
  EscParams params;
  std::optional<double> mass_kg;
  std::optional<double> ipeak_a;
};

// Static thrust and shaft power as power laws in speed (DriveCalc):
//   T [N] = thrust_law_n * (rpm/1000)^thrust_law_exp,  P [W] = power_law_w * (rpm/1000)^power_law_exp
// at air density rho_kg_m3 (both scale linearly with density).
struct PropPowerLaw {
  double thrust_law_n = 0.0;
  double thrust_law_exp = 2.0;
  double power_law_w = 0.0;
  double power_law_exp = 3.0;
  double rho_kg_m3 = 1.225;
};

// Coefficients at one speed: CT and CP vs advance ratio J = V/(n*D) (UIUC definitions,
// T = CT*rho*n^2*D^4, P = CP*rho*n^3*D^5, n in rev/s). For the static table `j` is empty and
// the arrays run over `rpm` instead.
struct PropSweep {
  double rpm = 0.0;
  std::vector<double> j;
  std::vector<double> ct;
  std::vector<double> cp;
};

struct PropStaticTable {
  std::vector<double> rpm;  // increasing
  std::vector<double> ct;
  std::vector<double> cp;
};

struct PropEntry : EntryBase {
  double diameter_m = 0.0;
  std::optional<double> pitch_m;
  std::optional<double> mass_kg;
  std::optional<int> blades;
  std::optional<double> max_rpm;
  // Valid rpm range stated for power laws and constant coefficients (tables carry their own);
  // catalog/prop_credibility.h ValidRange() gives the range of every entry.
  std::optional<double> rpm_min;
  std::optional<double> rpm_max;
  // The blades fold (glider propeller): not for multirotor lift unless a mission allows it.
  bool folding = false;
  // Factor (>= 1) by which the importer raised the power data (power_law_w, cp) to bring the
  // entry's figure of merit down to the envelope of measured propellers; 1 = not derated.
  double power_derate_factor = 1.0;
  std::optional<PropPowerLaw> power_law;
  std::optional<double> ct_static;
  std::optional<double> cp_static;
  PropStaticTable static_table;     // empty when absent
  std::vector<PropSweep> j_tables;  // by increasing rpm; empty when absent
};

enum class BatteryChemistry { kLiPo, kLiIon, kLiFePo4, kNiMh, kNiCd };

struct BatteryEntry : EntryBase {
  BatteryChemistry chemistry = BatteryChemistry::kLiPo;
  int cells_series = 1;
  int cells_parallel = 1;
  double capacity_ah = 0.0;
  double voltage_nominal_v = 0.0;
  std::optional<double> ri_ohm;
  std::optional<double> max_current_a;
  std::optional<double> peak_current_a;
  std::optional<double> mass_kg;
};

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
