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
  source.doc = "where the numbers came from: {dataset, reference, values: {key: method}, note, "
               "tier: measured | manufacturer_computed | manufacturer_stated | user_contributed | "
               "assumed}";
  return {Str("id", true, "unique id across the catalog ([A-Za-z0-9_.+-], 1-120 characters)"),
          Str("name", true, "human-readable name"), source,
          Str("exclude", false,
              "why searches skip this entry by default (kept for reference), e.g. no rating")};
}

// The motor's keys (after the common ones).
void AddMotorKeys(std::vector<KeySpec>& s) {
  auto add = [&s](KeySpec k) { s.push_back(std::move(k)); };
  add(Str("type", true, "motor type", {"bldc", "brushed"}));
  add(Num("ke_v_s_per_rad", false, 0, true, 10,
          "back-EMF constant, V*s/rad (BLDC: line-line rms, eq 42); from kv_rpm_per_v by "
          "model.md section 8 when absent"));
  add(Num("kt_nm_per_a", false, 0, true, 20,
          "torque constant, N*m/A (BLDC: per rms ampere); sqrt(27/10)*ke when absent (BLDC), "
          "ke (brushed)"));
  add(Num("rm_ohm", true, 0, true, 100,
          "resistance of the rms circuit of eq (42)/(48), ohm; = 0.7492 x rm_dc_ohm "
          "(catalog/conventions.h)"));
  add(Num("rm_dc_ohm", false, 0, true, 100,
          "the source's resistance of the DC equivalent circuit VDC = R*IDC + n/Kv "
          "(datasheet, DriveCalc, stand-table fit), ohm; kept for provenance"));
  add(Num("io_a", true, 0, false, 200, "no-load current of eq (42), A"));
  add(Num("kv_rpm_per_v", false, 0, true, 1e5, "datasheet Kv, rpm per DC volt"));
  add(Num("mass_kg", false, 0, true, 1000, "mass, kg"));
  add(Num("max_current_a", false, 0, true, 1e4, "current rating, A"));
  add(Num("max_power_w", false, 0, true, 1e7, "power rating, W"));
  add(Num("io_test_voltage_v", false, 0, true, 2000,
          "DC supply voltage at which io_a was stated or evaluated, V"));
  add(Num("vdc_nominal_v", false, 0, true, 2000, "nominal (datasheet test) supply voltage, V"));
  add(Int("cells_min", false, 1, 250, "smallest recommended LiPo cell count in series"));
  add(Int("cells_max", false, 1, 250, "largest recommended LiPo cell count in series"));
  add(Int("poles", false, 2, 200, "number of magnet poles"));
  add(Num("loss_torque_nm", false, 0, false, 100,
          "constant loss torque (DriveCalc MvK), N*m; with loss_torque_per_omega it is "
          "the no-load current law Io(omega) = (loss_torque + loss_torque_per_omega*omega)/kt "
          "of model.md section 9"));
  add(Num("loss_torque_per_omega_nm_s_per_rad", false, 0, false, 1,
          "speed-proportional loss torque (DriveCalc kL), N*m per rad/s"));
  add(Num("rm_per_omega_ohm_s_per_rad", false, 0, false, 1,
          "speed-dependent impedance term (DriveCalc K): R(omega) = rm + K*omega, ohm per rad/s"));
  add(Num("max_torque_nm", false, 0, true, 1e4, "peak torque rating, N*m"));
  // Ratings at eVTOL scale (docs/catalog.md "Ratings"): max_current_a and max_power_w stay
  // the continuous ratings; the peak ones hold for peak_duration_s at most.
  add(Num("peak_current_a", false, 0, true, 1e5,
          "peak current rating (the DC or phase basis of max_current_a), A"));
  add(Num("peak_power_w", false, 0, true, 1e8, "peak power rating, W"));
  add(Num("peak_duration_s", false, 0, true, 3600,
          "how long the peak ratings may be held, s (absent: not stated)"));
  add(Num("continuous_torque_nm", false, 0, true, 1e5, "continuous torque rating, N*m"));
  add(Num("max_rpm", false, 0, true, 1e6, "maker's speed limit, rpm"));
  add(Num("vdc_max_v", false, 0, true, 2000, "largest DC supply voltage stated, V"));
  // A gearbox between the motor and the propeller (model/gear.h); absent = direct drive.
  add(Num("gear_ratio", false, 1, false, 100,
          "motor turns per propeller turn (>= 1; 1 = direct drive, the default); kv, ke, "
          "rm and the loss terms stay the motor's own: omega_motor = ratio*omega_prop"));
  add(Num("gear_efficiency", false, 0, true, 1,
          "gearbox efficiency (0 < eta <= 1; 1 when direct drive): Q_motor = "
          "Q_prop/(gear_ratio*eta); required with a gear_ratio above 1"));
  // Model extensions of docs/model.md section 9 (src/model/drive.h); absent = 0 = first order.
  add(Num("io1_a_s_per_rad", false, 0, false, 1,
          "speed-dependent no-load current Io(omega) = io_a + io1*omega, A per rad/s"));
  add(Num("rth_k_per_w", false, 0, false, 1000,
          "winding temperature rise per watt of copper loss, K/W: Rm = rm_ohm*(1 + "
          "0.00393*rise), rise = rth*P_cu"));
  add(Num("kt_droop_per_a", false, 0, false, 10,
          "torque constant droop at high current, KT(I) = kt/(1 + kt_droop*I), 1/A"));
  {
    KeySpec er;
    er.key = "estimate_ranges";
    er.type = ValueType::kObject;
    er.doc = "p10-p90 of values a law estimated (catalog/motor_estimate.h): {\"rm_ohm\", "
             "\"io_a\", \"kv_rpm_per_v\": [p10, p90]}; the sizing's spread for them";
    add(er);
  }
  {
    KeySpec tp;
    tp.key = "test_points";
    tp.type = ValueType::kArray;
    tp.doc = "published operating points (manufacturer or stand tables): [{\"vdc_v\", "
             "\"idc_a\" (required), \"throttle\" (0-1), \"rpm\", \"torque_nm\", "
             "\"thrust_n\", \"prop\" (string)}]";
    add(tp);
  }
}

std::vector<KeySpec> Build(ComponentKind kind) {
  std::vector<KeySpec> s = Common();
  auto add = [&s](KeySpec k) { s.push_back(std::move(k)); };
  switch (kind) {
    case ComponentKind::kMotor:
      AddMotorKeys(s);
      break;
    case ComponentKind::kEsc:
      add(Num("resc_ohm", true, 0, false, 10, "equivalent series resistance of eq (47), ohm"));
      add(Num("c1", true, 0, true, 5, "slope of IDC/Irms = c1*TR + c0 (eq 57); ideal 1.1095"));
      add(Num("c0", true, -1, false, 1, "offset of IDC/Irms = c1*TR + c0 (eq 57); ideal 0"));
      add(Num("tr_sat", true, 0, true, 1, "throttle above which the ESC saturates (section 7)"));
      add(Num("sat_slope", true, 0, true, 1,
              "fraction of the nominal voltage slope delivered above tr_sat (section 7)"));
      {
        KeySpec db = Num("deadband", false, -0.5, false, 0.5,
                         "throttle dead band: TR_eff = (TR - deadband)/(1 - deadband), clamped "
                         "at 0, before the saturation knee; negative = a throttle offset");
        db.max_exclusive = true;
        add(db);
      }
      add(Num("rsupply_ohm", false, 0, false, 10,
              "resistance between the VDC sense point and the ESC (wires, connectors), ohm"));
      add(Num("max_current_a", false, 0, true, 1e4, "continuous current rating, A"));
      add(Num("vdc_max_v", false, 0, true, 2000, "maximum supply voltage, V"));
      add(Num("mass_kg", false, 0, true, 1000, "mass, kg"));
      add(Num("ipeak_a", false, 0, true, 1e4, "peak (burst, a few seconds) current rating, A"));
      add(Num("peak_duration_s", false, 0, true, 3600,
              "how long ipeak_a may be held, s (absent: not stated)"));
      add(Num("vdc_min_v", false, 0, true, 2000, "smallest supply voltage, V"));
      add(Num("max_power_w", false, 0, true, 1e7, "power rating, W"));
      add(Int("cells_min", false, 1, 250, "smallest LiPo cell count in series it accepts"));
      add(Int("cells_max", false, 1, 250, "largest LiPo cell count in series it accepts"));
      break;
    case ComponentKind::kProp: {
      add(Num("diameter_m", true, 0, true, 20, "diameter, m"));
      add(Num("pitch_m", false, 0, false, 20, "geometric pitch, m"));
      add(Int("blades", false, 1, 12, "number of blades"));
      add(Num("mass_kg", false, 0, true, 1000, "mass, kg"));
      add(Num("max_rpm", false, 0, true, 1e6, "manufacturer's speed limit, rpm"));
      add(Num("rpm_min", false, 0, true, 1e6,
              "lowest speed at which the power laws / coefficients hold, rpm (tables: their data)"));
      add(Num("rpm_max", false, 0, true, 1e6,
              "highest speed at which the power laws / coefficients hold, rpm"));
      {
        KeySpec f;
        f.key = "folding";
        f.type = ValueType::kBool;
        f.doc = "the blades fold (glider propeller): not for multirotor lift by default";
        add(f);
      }
      add(Num("power_derate_factor", false, 1, false, 10,
              "factor applied by the importer to the power data (power_law_w, cp) to bring the "
              "figure of merit to the envelope of measured propellers (prop_credibility.h)"));
      add(Num("thrust_law_n", false, 0, true, 1e6,
              "power law T = thrust_law_n*(rpm/1000)^thrust_law_exp at law_rho_kg_m3, static "
              "thrust in N at 1000 rpm (DriveCalc a, converted from g)"));
      add(Num("thrust_law_exp", false, 0, true, 6, "exponent of the thrust power law"));
      add(Num("power_law_w", false, 0, true, 1e7,
              "power law P = power_law_w*(rpm/1000)^power_law_exp at law_rho_kg_m3, static shaft "
              "power in W at 1000 rpm (DriveCalc c)"));
      add(Num("power_law_exp", false, 0, true, 8, "exponent of the power power law"));
      add(Num("law_rho_kg_m3", false, 0.5, false, 1.5,
              "air density at which the power laws hold, kg/m^3 (they scale with rho)"));
      add(Num("ct_static", false, 0, true, 1,
              "static thrust coefficient, T = ct*rho*n^2*D^4 with n in rev/s (UIUC definition)"));
      add(Num("cp_static", false, 0, true, 1,
              "static power coefficient, P = cp*rho*n^3*D^5 with n in rev/s (UIUC definition)"));
      KeySpec st;
      st.key = "static_table";
      st.type = ValueType::kObject;
      st.doc = "static (J = 0) coefficients vs speed: {\"rpm\": [increasing], \"ct\": [...], "
               "\"cp\": [...]}, arrays of equal length";
      add(st);
      KeySpec jt;
      jt.key = "j_tables";
      jt.type = ValueType::kArray;
      jt.doc = "forward-flight coefficients: [{\"rpm\": speed of the sweep, \"j\": [increasing "
               "advance ratios V/(n*D)], \"ct\": [...], \"cp\": [...]}], sweeps by increasing rpm";
      add(jt);
      break;
    }
    case ComponentKind::kBattery:
      add(Str("chemistry", true, "cell chemistry (selects the open-circuit-voltage curve)",
              {"lipo", "liion", "lifepo4", "nimh", "nicd"}));
      add(Int("cells_series", true, 1, 250, "cells in series in this unit (1 for a single cell)"));
      add(Int("cells_parallel", false, 1, 250, "cells in parallel in this unit (default 1)"));
      add(Num("capacity_ah", true, 0, true, 1e4, "rated capacity of the unit, A*h"));
      add(Num("voltage_nominal_v", true, 0, true, 2000, "nominal voltage of the unit, V"));
      add(Num("ri_ohm", false, 0, true, 100, "internal (DC) resistance of the unit, ohm"));
      add(Num("max_current_a", false, 0, true, 1e5, "continuous discharge current rating, A"));
      add(Num("peak_current_a", false, 0, true, 1e5, "burst discharge current rating, A"));
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
  static const std::vector<std::string> kMethods = {"datasheet", "measured", "computed",
                                                    "fitted", "derived", "estimated", "assumed"};
  return kMethods;
}

}  // namespace dynosize
