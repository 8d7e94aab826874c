// The typed entries of the catalog (catalog/catalog.h reads them from its JSON files): the
// common part of every entry (id, name, file, trust tier, excluded or not) and the motor, ESC,
// propeller and battery entries, with the tier rules that read an entry's source.values.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/json_file.h"
#include "model/gear.h"
#include "model/params.h"

namespace dynosize {

enum class ComponentKind { kMotor, kEsc, kProp, kBattery };

// Trust tier of an entry's data, best first (catalog/conventions.h).
enum class DataTier {
  kMeasured = 0,
  kManufacturerComputed = 1,
  kManufacturerStated = 2,
  kUserContributed = 3,
  // Values a law estimated from other stated values (catalog/motor_estimate.h): the law's
  // check by leaving makers out is their range.
  kEstimated = 4,
  kAssumed = 5,
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
// The tier of a value obtained by `method` (a source.values label): measured/fitted -> measured,
// computed -> manufacturer_computed, datasheet/derived -> manufacturer_stated, else assumed.
DataTier MethodTier(const std::string& method);

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
  // Estimated values' p10-p90 (key "estimate_ranges": {"rm_ohm": [p10, p90], "io_a": [...],
  // "kv_rpm_per_v": [...]}, catalog/motor_estimate.h): the sizing's spread for these values
  // instead of the tier's band (MotorSpreadParams).
  std::optional<std::pair<double, double>> rm_range_ohm, io_range_a, kv_range_rpm_per_v;
  // Keys gear_ratio, gear_efficiency (model/gear.h); direct drive when absent. params and
  // kv_rpm_per_v are the motor's own (at its shaft, before the gearbox).
  Gear gear;
};

struct EscEntry : EntryBase {
  EscParams params;
  std::optional<double> mass_kg;
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

}  // namespace dynosize
