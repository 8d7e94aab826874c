#include "catalog/schema.h"

#include <sstream>

namespace dynosize {

namespace {

KeySpec Str(const std::string& key, bool required, const std::string& doc,
            std::vector<std::string> choices = {}) {
  KeySpec s;
  s.key = key;
  s.type = ValueType::kString;
  s.required = required;
  s.choices = std::move(choices);
  s.doc = doc;
  return s;
}

// A number in (min, max] when min_exclusive, else [min, max].
KeySpec Num(const std::string& key, bool required, double min, bool min_exclusive, double max,
            const std::string& doc) {
  KeySpec s;
  s.key = key;
  s.type = ValueType::kNumber;
  s.required = required;
  s.min = min;
  s.min_exclusive = min_exclusive;
  s.max = max;
  s.doc = doc;
  return s;
}

KeySpec Int(const std::string& key, bool required, double min, double max,
            const std::string& doc) {
  KeySpec s = Num(key, required, min, false, max, doc);
  s.type = ValueType::kInteger;
  return s;
}

std::vector<KeySpec> Common() {
  KeySpec source;
  source.key = "source";
  source.type = ValueType::kObject;
  source.required = true;
  source.doc = "where the numbers came from: {dataset, reference, values: {key: method}, note}";
  return {Str("id", true, "unique id across the catalog ([A-Za-z0-9_.+-], 1-120 characters)"),
          Str("name", true, "human-readable name"), source};
}

std::vector<KeySpec> Build(ComponentKind kind) {
  std::vector<KeySpec> s = Common();
  auto add = [&s](KeySpec k) { s.push_back(std::move(k)); };
  switch (kind) {
    case ComponentKind::kMotor:
      add(Str("type", true, "motor type", {"bldc", "brushed"}));
      add(Num("ke_v_s_per_rad", false, 0, true, 10,
              "back-EMF constant, V*s/rad (BLDC: line-line rms, eq 42); from kv_rpm_per_v by "
              "model.md section 8 when absent"));
      add(Num("kt_nm_per_a", false, 0, true, 20,
              "torque constant, N*m/A (BLDC: per rms ampere); sqrt(27/10)*ke when absent (BLDC), "
              "ke (brushed)"));
      add(Num("rm_ohm", true, 0, true, 100, "winding resistance of eq (42), ohm"));
      add(Num("io_a", true, 0, false, 200, "no-load current of eq (42), A"));
      add(Num("kv_rpm_per_v", false, 0, true, 1e5, "datasheet Kv, rpm per DC volt"));
      add(Num("mass_kg", false, 0, true, 1000, "mass, kg"));
      add(Num("max_current_a", false, 0, true, 1e4, "current rating, A"));
      add(Num("max_power_w", false, 0, true, 1e7, "power rating, W"));
      break;
    case ComponentKind::kEsc:
      add(Num("resc_ohm", true, 0, false, 10, "equivalent series resistance of eq (47), ohm"));
      add(Num("c1", true, 0, true, 5, "slope of IDC/Irms = c1*TR + c0 (eq 57); ideal 1.1095"));
      add(Num("c0", true, -1, false, 1, "offset of IDC/Irms = c1*TR + c0 (eq 57); ideal 0"));
      add(Num("tr_sat", true, 0, true, 1, "throttle above which the ESC saturates (section 7)"));
      add(Num("sat_slope", true, 0, true, 1,
              "fraction of the nominal voltage slope delivered above tr_sat (section 7)"));
      add(Num("max_current_a", false, 0, true, 1e4, "continuous current rating, A"));
      add(Num("vdc_max_v", false, 0, true, 2000, "maximum supply voltage, V"));
      add(Num("mass_kg", false, 0, true, 1000, "mass, kg"));
      break;
    case ComponentKind::kProp:
      add(Num("diameter_m", true, 0, true, 20, "diameter, m"));
      add(Num("pitch_m", false, 0, false, 20, "geometric pitch, m"));
      add(Int("blades", false, 1, 12, "number of blades"));
      add(Num("mass_kg", false, 0, true, 1000, "mass, kg"));
      break;
    case ComponentKind::kBattery:
      add(Num("mass_kg", false, 0, true, 1000, "mass, kg"));
      break;
  }
  return s;
}

}  // namespace

const std::vector<KeySpec>& SchemaFor(ComponentKind kind) {
  static const std::vector<KeySpec> kMotor = Build(ComponentKind::kMotor);
  static const std::vector<KeySpec> kEsc = Build(ComponentKind::kEsc);
  static const std::vector<KeySpec> kProp = Build(ComponentKind::kProp);
  static const std::vector<KeySpec> kBattery = Build(ComponentKind::kBattery);
  switch (kind) {
    case ComponentKind::kMotor: return kMotor;
    case ComponentKind::kEsc: return kEsc;
    case ComponentKind::kProp: return kProp;
    case ComponentKind::kBattery: return kBattery;
  }
  return kMotor;
}

std::string DescribeRule(const KeySpec& spec) {
  std::ostringstream out;
  switch (spec.type) {
    case ValueType::kString:
      out << "a string";
      if (!spec.choices.empty()) {
        out << ", one of ";
        for (std::size_t i = 0; i < spec.choices.size(); ++i) out << (i ? ", " : "") << spec.choices[i];
      }
      return out.str();
    case ValueType::kBool: return "true or false";
    case ValueType::kObject: return "an object";
    case ValueType::kArray: return "an array";
    case ValueType::kNumber:
    case ValueType::kInteger: break;
  }
  out << (spec.type == ValueType::kInteger ? "an integer" : "a finite number");
  const bool has_min = spec.min > -1e299, has_max = spec.max < 1e299;
  if (has_min) out << (spec.min_exclusive ? " > " : " >= ") << spec.min;
  if (has_min && has_max) out << " and";
  if (has_max) out << (spec.max_exclusive ? " < " : " <= ") << spec.max;
  return out.str();
}

const std::vector<std::string>& ProvenanceMethods() {
  static const std::vector<std::string> kMethods = {"datasheet", "measured", "fitted", "derived",
                                                    "assumed"};
  return kMethods;
}

}  // namespace dynosize
