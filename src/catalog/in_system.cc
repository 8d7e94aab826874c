#include "catalog/in_system.h"

#include <cmath>

#include "catalog/conventions.h"
#include "common/text_format.h"
#include "common/units.h"

namespace dynosize {

namespace {

// Fitted by `dynosize in-system-law` (stand/in_system_fit.h) on ../shared/data; the numbers
// and their check by leaving out are in docs/in-system-law.md. tests/catalog/in_system_test.cc
// refits them and fails when these drift from the data.
constexpr InSystemLaw kKdeLaw{
    /*r_scale=*/2.183, /*r_add_ohm=*/0.0, /*io_scale=*/3.283, /*io_speed=*/0.0,
    /*r_ratio_p10=*/0.838, /*r_ratio_p90=*/1.435, /*io_ratio_p10=*/0.7522, /*io_ratio_p90=*/1.28,
    /*motors=*/9, "KDE Direct stand sheets (9 motors with torque) against their datasheets"};
constexpr InSystemLaw kDriveCalcLaw{
    /*r_scale=*/1.094, /*r_add_ohm=*/0.01951, /*io_scale=*/0.995, /*io_speed=*/0.0,
    /*r_ratio_p10=*/0.7877, /*r_ratio_p90=*/1.78, /*io_ratio_p10=*/0.8005, /*io_ratio_p90=*/1.464,
    /*motors=*/1120, "DriveCalc database values against refits of DriveCalc's own measurements"};

// The throttle offset of KDE's stand ESC (KDE-UAS125UVC), the dead band fitted per motor on the
// same 9 sheets (docs/in-system-law.md, "Throttle offset of the sheets' ESC").
constexpr ThrottleOffsetPrior kKdeEscOffset{/*deadband_p10=*/-0.301, /*deadband_p50=*/-0.162,
                                            /*deadband_p90=*/0.013, /*motors=*/9,
                                            "KDE Direct stand sheets (9 motors with torque)"};

double JsonNumber(const Json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : 0.0;
}

}  // namespace

// An entry of DriveCalc's database (catalog/drivecalc.json: source.dataset "DriveCalc DB").
bool IsDriveCalcDatabaseEntry(const EntryBase& e) {
  if (!e.json.is_object()) return false;
  const auto src = e.json.find("source");
  if (src == e.json.end() || !src->is_object()) return false;
  const auto d = src->find("dataset");
  return d != src->end() && d->is_string() && d->get<std::string>() == "DriveCalc DB";
}

bool IsKdeDirectName(const std::string& name) {
  return name.size() > 3 && name.compare(0, 3, "KDE") == 0 && name[3] >= '0' && name[3] <= '9';
}

const InSystemLaw& KdeDatasheetLaw() { return kKdeLaw; }
const ThrottleOffsetPrior& KdeEscThrottleOffsetPrior() { return kKdeEscOffset; }
const InSystemLaw& DriveCalcDatabaseLaw() { return kDriveCalcLaw; }

const InSystemLaw* InSystemLawFor(const MotorEntry& motor) {
  if (motor.tier != DataTier::kManufacturerStated && motor.tier != DataTier::kUserContributed) return nullptr;
  if (IsKdeDirectName(motor.name)) return &kKdeLaw;
  return IsDriveCalcDatabaseEntry(motor) ? &kDriveCalcLaw : nullptr;
}

MotorParams InSystemMotorParams(const MotorParams& raw, const DatasheetMotor& ds,
                                const InSystemLaw& law, bool apply_r, bool apply_io,
                                double ratio_r, double ratio_io) {
  MotorParams p = raw;
  if (apply_r) {
    // (IS1), then conventions.h (1.): Rm = 0.7492*R_dc.
    p.rm_ohm = RmsCircuitResistanceFromDc(ratio_r * (law.r_scale * ds.r_dc_ohm + law.r_add_ohm));
  }
  if (apply_io) {
    // (IS2), then eq 56: Io = Io_dc/1.1095, the speed term in io1 (docs/model.md section 9).
    const double io_dc = ratio_io * ds.io_dc_a;
    p.io_a = RmsNoLoadCurrentFromDc(law.io_scale * io_dc);
    const double omega_test_rad_s = ds.kv_rpm_per_v * ds.io_test_voltage_v * kPi / 30.0;
    p.io1_a_s_per_rad = law.io_speed != 0.0 && omega_test_rad_s > 0.0
                            ? RmsNoLoadCurrentFromDc(law.io_speed * io_dc / omega_test_rad_s)
                            : raw.io1_a_s_per_rad;
  }
  return p;
}

InSystemApplicability InSystemApplicabilityOf(const MotorEntry& motor) {
  InSystemApplicability a;
  a.law = InSystemLawFor(motor);
  if (!motor.json.is_object()) return a;
  const Json& j = motor.json;
  const bool has_dc = j.contains("rm_dc_ohm");
  const std::string r_label = ValueMethod(motor, has_dc ? "rm_dc_ohm" : "rm_ohm");
  const std::string io_label = ValueMethod(motor, "io_a");
  a.r = r_label == "datasheet";
  a.io = io_label == "datasheet" || io_label == "derived";
  DatasheetMotor& d = a.datasheet;
  d.kv_rpm_per_v = motor.kv_rpm_per_v.value_or(0.0);
  // A brushed motor's rm_ohm is already the DC circuit's (conventions.h 1.).
  const bool bldc = motor.params.type == MotorType::kBldc;
  d.r_dc_ohm = has_dc ? JsonNumber(j, "rm_dc_ohm")
                      : (bldc ? JsonNumber(j, "rm_ohm") / kRmsPerDcResistance : JsonNumber(j, "rm_ohm"));
  d.io_dc_a = bldc ? JsonNumber(j, "io_a") * kIdealIdcPerIrmsPerThrottle : JsonNumber(j, "io_a");
  d.io_test_voltage_v = JsonNumber(j, "io_test_voltage_v");
  // The law is fitted on BLDC motors; a brushed motor's circuit is another machine.
  if (!bldc || !(d.r_dc_ohm > 0.0)) a.r = false;
  if (!bldc || !(d.io_dc_a > 0.0) || (a.law != nullptr && a.law->io_speed != 0.0 && !(d.io_test_voltage_v > 0.0 && d.kv_rpm_per_v > 0.0))) {
    a.io = false;
  }
  return a;
}

MotorParams InSystemSpreadParams(const MotorEntry& motor, bool high, bool* r_moved, bool* io_moved) {
  if (r_moved) *r_moved = false;
  if (io_moved) *io_moved = false;
  if (!motor.datasheet_params) return motor.params;
  const InSystemApplicability a = InSystemApplicabilityOf(motor);
  if (!a.any()) return motor.params;
  const InSystemLaw& l = *a.law;
  MotorParams p = InSystemMotorParams(*motor.datasheet_params, a.datasheet, l, a.r, a.io,
                                      high ? l.r_ratio_p90 : l.r_ratio_p10, high ? l.io_ratio_p90 : l.io_ratio_p10);
  p.max_current_a = motor.params.max_current_a;
  p.max_power_w = motor.params.max_power_w;
  if (r_moved) *r_moved = a.r;
  if (io_moved) *io_moved = a.io;
  return p;
}

double TierValueBand(DataTier tier) {
  switch (tier) {
    case DataTier::kMeasured: return 0.10;
    case DataTier::kManufacturerComputed:
    case DataTier::kManufacturerStated: return 0.25;
    case DataTier::kUserContributed: return 0.60;
    // Without the entry's own range (estimate_ranges), the width of the motor-constant law's
    // held-out R range (x0.38-2.07, docs/motor-estimate.md) rounded: a factor 2 either way.
    case DataTier::kEstimated: return 1.00;
    case DataTier::kAssumed: return 1.00;
  }
  return 1.0;
}

MotorParams MotorSpreadParams(const MotorEntry& motor, bool high) {
  bool r_law = false, io_law = false;
  const MotorParams spread = InSystemSpreadParams(motor, high, &r_law, &io_law);
  MotorParams p = motor.params;
  const double br = 1.0 + TierValueBand(ValueTier(motor, "rm_ohm"));
  const double bi = 1.0 + TierValueBand(ValueTier(motor, "io_a"));
  p.rm_ohm = r_law ? spread.rm_ohm : (high ? p.rm_ohm * br : p.rm_ohm / br);
  if (io_law) {
    p.io_a = spread.io_a;
    p.io1_a_s_per_rad = spread.io1_a_s_per_rad;
  } else {
    p.io_a = high ? p.io_a * bi : p.io_a / bi;
  }
  // An estimated entry's own p10-p90 (catalog/motor_estimate.h) replaces the tier's band.
  if (motor.rm_range_ohm) p.rm_ohm = high ? motor.rm_range_ohm->second : motor.rm_range_ohm->first;
  if (motor.io_range_a) p.io_a = high ? motor.io_range_a->second : motor.io_range_a->first;
  return p;
}

std::string InSystemSummary(const MotorEntry& motor) {
  const InSystemApplicability a = InSystemApplicabilityOf(motor);
  if (!a.any()) return "";
  const MotorParams& raw = motor.datasheet_params ? *motor.datasheet_params : motor.params;
  std::string s = std::string("in-system law (") + (a.law == &kKdeLaw ? "KDE Direct datasheets" : "DriveCalc database") + ", docs/in-system-law.md):";
  if (a.r) {
    s += " R_dc " + FixedText(raw.rm_ohm / kRmsPerDcResistance, 4) + " -> " +
         FixedText(motor.params.rm_ohm / kRmsPerDcResistance, 4) + " ohm";
  }
  if (a.io) {
    s += std::string(a.r ? "," : "") + " Io_dc " + FixedText(raw.io_a * kIdealIdcPerIrmsPerThrottle, 2) +
         " -> " + FixedText(motor.params.io_a * kIdealIdcPerIrmsPerThrottle, 2) + " A";
  }
  return s;
}

}  // namespace dynosize
