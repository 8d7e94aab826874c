#include "battery/battery.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"

namespace dynosize {

namespace {

constexpr int kOcvPoints = 21;  // SOC 0, 0.05, ..., 1
using OcvTable = std::array<double, kOcvPoints>;

// Typical resting (open-circuit) voltage per cell vs SOC, ASSUMED curves:
// - LiPo (LiCoO2/graphite pouch): the resting-voltage table widely used in the RC community
//   (4.20 V full, 3.84 V at 50 %, 3.27 V empty), which matches the low-rate part of
//   shared/data/sjkim_mfr_motor_tables/battery/2.25Ah_Discharge_Profile.csv within ~30 mV.
// - Li-ion (NMC 18650/21700): typical manufacturer 0.2C curves (4.20 V full, 3.0 V empty).
// - LiFePO4: flat plateau near 3.3 V (3.60 V full, 2.50 V empty).
// - NiMH / NiCd: 1.42 V full, ~1.27 V plateau, 1.00 V empty.
constexpr OcvTable kLiPo = {3.27, 3.61, 3.69, 3.71, 3.73, 3.75, 3.77, 3.79, 3.80, 3.82, 3.84,
                            3.85, 3.87, 3.91, 3.95, 3.98, 4.02, 4.08, 4.11, 4.15, 4.20};
constexpr OcvTable kLiIon = {3.00, 3.30, 3.45, 3.53, 3.58, 3.62, 3.65, 3.68, 3.71, 3.73, 3.76,
                             3.79, 3.82, 3.86, 3.90, 3.94, 3.98, 4.03, 4.08, 4.13, 4.20};
constexpr OcvTable kLiFePo4 = {2.50, 3.00, 3.20, 3.22, 3.25, 3.26, 3.28, 3.29, 3.30, 3.30, 3.30,
                               3.30, 3.31, 3.31, 3.32, 3.32, 3.33, 3.34, 3.35, 3.40, 3.60};
constexpr OcvTable kNiMh = {1.00, 1.15, 1.20, 1.22, 1.23, 1.24, 1.25, 1.255, 1.26, 1.265, 1.27,
                            1.275, 1.28, 1.285, 1.29, 1.30, 1.31, 1.33, 1.35, 1.38, 1.42};

const OcvTable& Table(BatteryChemistry c) {
  switch (c) {
    case BatteryChemistry::kLiPo: return kLiPo;
    case BatteryChemistry::kLiIon: return kLiIon;
    case BatteryChemistry::kLiFePo4: return kLiFePo4;
    case BatteryChemistry::kNiMh:
    case BatteryChemistry::kNiCd: return kNiMh;
  }
  return kLiPo;
}

}  // namespace

double CellOcvV(BatteryChemistry chemistry, double soc) {
  const OcvTable& t = Table(chemistry);
  const double s = std::clamp(soc, 0.0, 1.0) * (kOcvPoints - 1);
  const int i = std::min(static_cast<int>(s), kOcvPoints - 2);
  const double f = s - i;
  return t[static_cast<std::size_t>(i)] * (1 - f) + t[static_cast<std::size_t>(i + 1)] * f;
}

double CellDefaultCutoffV(BatteryChemistry chemistry) {
  switch (chemistry) {
    case BatteryChemistry::kLiPo: return 3.0;
    case BatteryChemistry::kLiIon: return 2.75;
    case BatteryChemistry::kLiFePo4: return 2.5;
    case BatteryChemistry::kNiMh:
    case BatteryChemistry::kNiCd: return 1.0;
  }
  return 3.0;
}

const char* ChemistryName(BatteryChemistry chemistry) {
  switch (chemistry) {
    case BatteryChemistry::kLiPo: return "lipo";
    case BatteryChemistry::kLiIon: return "liion";
    case BatteryChemistry::kLiFePo4: return "lifepo4";
    case BatteryChemistry::kNiMh: return "nimh";
    case BatteryChemistry::kNiCd: return "nicd";
  }
  return "?";
}

double AssumedCellRiOhm(BatteryChemistry chemistry, double cell_capacity_ah) {
  const bool nickel =
      chemistry == BatteryChemistry::kNiMh || chemistry == BatteryChemistry::kNiCd;
  return (nickel ? 0.010 : 0.015) / cell_capacity_ah;
}

bool BatteryPackParams::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (n_series < 1) return fail("n_series = " + std::to_string(n_series) + ": must be >= 1");
  if (n_parallel < 1) return fail("n_parallel = " + std::to_string(n_parallel) + ": must be >= 1");
  if (!(cell_capacity_ah > 0) || !std::isfinite(cell_capacity_ah)) {
    return fail("cell_capacity_ah = " + SignificantText(cell_capacity_ah) + ": must be a finite number > 0");
  }
  if (!(cell_ri_ohm >= 0) || !std::isfinite(cell_ri_ohm)) {
    return fail("cell_ri_ohm = " + SignificantText(cell_ri_ohm) + ": must be a finite number >= 0");
  }
  if (!(cell_mass_kg >= 0)) return fail("cell_mass_kg = " + SignificantText(cell_mass_kg) + ": must be >= 0");
  if (!(mass_factor >= 1.0) || !std::isfinite(mass_factor)) {
    return fail("mass_factor = " + SignificantText(mass_factor) + ": must be a finite number >= 1");
  }
  if (!(cell_max_current_a > 0)) {
    return fail("cell_max_current_a = " + SignificantText(cell_max_current_a) + ": must be > 0");
  }
  return true;
}

BatteryPackParams PackFromEntry(const BatteryEntry& e, int units_series, int units_parallel) {
  if (units_series < 1 || units_parallel < 1) {
    throw UsageError("battery '" + e.id + "': a pack needs at least 1 unit in series and 1 in "
                     "parallel, got " + std::to_string(units_series) + "S" +
                     std::to_string(units_parallel) + "P");
  }
  BatteryPackParams p;
  p.chemistry = e.chemistry;
  const int s0 = e.cells_series, p0 = e.cells_parallel;
  p.n_series = s0 * units_series;
  p.n_parallel = p0 * units_parallel;
  p.cell_capacity_ah = e.capacity_ah / p0;
  if (e.ri_ohm) {
    p.cell_ri_ohm = *e.ri_ohm * p0 / s0;
  } else {
    p.cell_ri_ohm = AssumedCellRiOhm(e.chemistry, p.cell_capacity_ah);
    p.assumed.push_back("ri_ohm");
  }
  if (e.mass_kg) p.cell_mass_kg = *e.mass_kg / (s0 * p0);
  else p.assumed.push_back("mass_kg");
  if (e.max_current_a) p.cell_max_current_a = *e.max_current_a / p0;
  if (e.peak_current_a) p.cell_peak_current_a = *e.peak_current_a / p0;
  for (const auto& k : e.assumed_keys) p.assumed.push_back(k);
  return p;
}

BatteryPack::BatteryPack(const BatteryPackParams& params) : p_(params) {
  std::string error;
  if (!p_.IsValid(&error)) throw UsageError("battery pack: " + error);
}

double BatteryPack::cutoff_v(const DischargeOptions& o) const {
  const double cell = std::isnan(o.cutoff_cell_v) ? CellDefaultCutoffV(p_.chemistry) : o.cutoff_cell_v;
  return cell * p_.n_series;
}

double BatteryPack::OcvV(double soc) const { return p_.n_series * CellOcvV(p_.chemistry, soc); }

double BatteryPack::TerminalVoltageV(double soc, double current_a) const {
  return OcvV(soc) - current_a * ri_ohm();
}

bool BatteryPack::CurrentForPower(double soc, double power_w, double* current_a) const {
  const double v = OcvV(soc), r = ri_ohm();
  if (r == 0.0) {
    *current_a = power_w / v;
    return true;
  }
  const double disc = v * v - 4 * r * power_w;
  if (disc < 0) return false;
  // The smaller root of R*I^2 - V*I + P = 0, written to avoid cancellation.
  *current_a = 2 * power_w / (v + std::sqrt(disc));
  return true;
}

double BatteryPack::StoredEnergyJ() const {
  return p_.n_series * CellOcvIntegral(p_.chemistry, 0.0) * AhToCoulomb(capacity_ah());
}

template <typename CurrentAt>
DischargeResult BatteryPack::Discharge(CurrentAt current_at, const DischargeOptions& o) const {
  if (!(o.soc_step > 0 && o.soc_step <= 0.1)) {
    throw UsageError("DischargeOptions.soc_step = " + SignificantText(o.soc_step) + ": must be in (0, 0.1]");
  }
  if (!(o.initial_soc > 0 && o.initial_soc <= 1)) {
    throw UsageError("DischargeOptions.initial_soc = " + SignificantText(o.initial_soc) + ": must be in (0, 1]");
  }
  const double cutoff = cutoff_v(o);
  const double q_c = AhToCoulomb(capacity_ah());
  DischargeResult r;
  double soc = o.initial_soc;
  double i0 = 0;
  if (!current_at(soc, &i0)) {
    r.status = DischargeStatus::kPowerUnreachable;
    r.final_soc = soc;
    r.message = "the pack cannot deliver this power even when full";
    return r;
  }
  double v0 = TerminalVoltageV(soc, i0);
  if (v0 <= cutoff) {
    r.status = DischargeStatus::kReachedCutoff;
    r.final_soc = soc;
    r.final_voltage_v = v0;
    r.max_current_a = i0;
    r.message = "terminal voltage at the start is already below the cut-off";
    return r;
  }
  r.max_current_a = i0;
  while (soc > 0) {
    const double ds = std::min(o.soc_step, soc);
    const double mid = soc - ds / 2, end = soc - ds;
    double im = 0, i1 = 0;
    if (!current_at(mid, &im) || !current_at(end, &i1)) {
      r.status = DischargeStatus::kPowerUnreachable;
      r.message = "the pack can no longer deliver the power at SOC " + SignificantText(end);
      break;
    }
    const double v1 = TerminalVoltageV(end, i1);
    const double vm = TerminalVoltageV(mid, im);
    double frac = 1.0;  // fraction of the step taken before the cut-off
    if (v1 <= cutoff) frac = std::clamp((v0 - cutoff) / (v0 - v1), 0.0, 1.0);
    const double dq = ds * frac * q_c;  // coulombs
    const double dt = dq / im;          // midpoint current
    r.time_s += dt;
    r.energy_j += vm * im * dt;
    r.charge_ah += dq / 3600.0;
    r.max_current_a = std::max(r.max_current_a, i1);
    soc -= ds * frac;
    if (v1 <= cutoff) {
      r.status = DischargeStatus::kReachedCutoff;
      r.final_voltage_v = cutoff;
      break;
    }
    v0 = v1;
    r.final_voltage_v = v1;
    if (soc <= 0) r.status = DischargeStatus::kEmpty;
  }
  r.final_soc = std::max(soc, 0.0);
  if (r.max_current_a > max_current_a()) {
    r.over_current = true;
    r.message += std::string(r.message.empty() ? "" : "; ") + "current " + SignificantText(r.max_current_a) +
                 " A above the continuous rating " + SignificantText(max_current_a()) + " A";
  }
  return r;
}

DischargeResult BatteryPack::DischargeAtPower(double power_w, const DischargeOptions& o) const {
  if (!(power_w > 0) || !std::isfinite(power_w)) {
    throw UsageError("DischargeAtPower: power_w = " + SignificantText(power_w) + ": must be a finite number > 0");
  }
  return Discharge([&](double soc, double* i) { return CurrentForPower(soc, power_w, i); }, o);
}

DischargeResult BatteryPack::DischargeAtCurrent(double current_a, const DischargeOptions& o) const {
  if (!(current_a > 0) || !std::isfinite(current_a)) {
    throw UsageError("DischargeAtCurrent: current_a = " + SignificantText(current_a) + ": must be a finite number > 0");
  }
  return Discharge(
      [&](double, double* i) {
        *i = current_a;
        return true;
      },
      o);
}

double CellOcvIntegral(BatteryChemistry chemistry, double from_soc) {
  const OcvTable& t = Table(chemistry);
  constexpr double kStep = 1.0 / (kOcvPoints - 1);
  const double from = std::clamp(from_soc, 0.0, 1.0);
  const int i = std::min(static_cast<int>(from / kStep), kOcvPoints - 2);
  // The part of table interval i above `from`, then whole intervals: trapezoids, exact for
  // the piecewise-linear curve CellOcvV interpolates.
  double sum = 0.5 * (CellOcvV(chemistry, from) + t[static_cast<std::size_t>(i + 1)]) * ((i + 1) * kStep - from);
  for (int k = i + 1; k < kOcvPoints - 1; ++k) {
    sum += 0.5 * (t[static_cast<std::size_t>(k)] + t[static_cast<std::size_t>(k + 1)]) * kStep;
  }
  return sum;
}

double OcvIntegralUpperBound(const BatteryPack& pack, double reserve_soc) {
  constexpr double kRounding = 1e-12;  // relative: the sum's rounding, kept on the upper side
  return pack.params().n_series * CellOcvIntegral(pack.params().chemistry, reserve_soc) * (1.0 + kRounding);
}

}  // namespace dynosize
