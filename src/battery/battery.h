// Battery model: a pack of n_series x n_parallel catalog units (cells or packs) as an
// open-circuit voltage that depends on state of charge, in series with an internal resistance
// (the zeroth-order Thevenin / "Rint" model, e.g. Plett, Battery Management Systems vol. 1,
// ch. 2):
//   V_terminal = N_s*OCV_cell(SOC) - I*R_pack,   R_pack = R_cell*N_s/N_p,   Q_pack = Q_cell*N_p
//   dSOC/dt = -I/Q_pack                           (coulomb counting, Q in A*s)
// At constant power P the current solves P = V_terminal*I:
//   I = (V_oc - sqrt(V_oc^2 - 4*R*P)) / (2*R)    (the smaller root; none when V_oc^2 < 4*R*P,
//                                                  the pack cannot deliver P)
// OCV_cell(SOC) is a typical resting-voltage curve per chemistry (battery.cc gives the tables
// and their sources); it is an ASSUMED curve, not a per-product measurement. No RC polarisation,
// temperature or rate-dependent capacity: under heavy load the model is optimistic at the end of
// discharge (tests/battery quantify this against real discharge logs).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/numbers.h"

namespace dynosize {

// Open-circuit voltage of one cell at state of charge soc in [0, 1] (clamped), V.
double CellOcvV(BatteryChemistry chemistry, double soc);
// Usual discharge cut-off of one cell under load, V (LiPo 3.0, Li-ion 2.75, LiFePO4 2.5,
// NiMH/NiCd 1.0).
double CellDefaultCutoffV(BatteryChemistry chemistry);
const char* ChemistryName(BatteryChemistry chemistry);

struct BatteryPackParams {
  BatteryChemistry chemistry = BatteryChemistry::kLiPo;
  int n_series = 1;    // cells in series
  int n_parallel = 1;  // cells in parallel
  double cell_capacity_ah = 0.0;
  double cell_ri_ohm = 0.0;
  double cell_mass_kg = 0.0;
  double cell_max_current_a = std::numeric_limits<double>::infinity();
  double cell_peak_current_a = std::numeric_limits<double>::infinity();
  // The pack's mass over its cells' (structure, BMS, wiring, cooling; >= 1, 1 = as the units).
  double mass_factor = 1.0;
  // Keys whose value is assumed rather than from the entry ("ri_ohm" when the entry has none).
  std::vector<std::string> assumed;
  // Returns false and names the field, value and rule when a value is out of range.
  bool IsValid(std::string* error) const;
};

// Cell internal resistance assumed when the catalog gives none: r = k/capacity with
// k = 0.015 ohm*A*h for lithium cells (a 2.2 A*h LiPo gets 6.8 mOhm; the DriveCalc LiPo cells
// have a median of ~7 mOhm at 2.2 A*h) and 0.010 ohm*A*h for NiMH/NiCd.
double AssumedCellRiOhm(BatteryChemistry chemistry, double cell_capacity_ah);

// A pack of units_series x units_parallel copies of a catalog entry (an entry is itself
// cells_series x cells_parallel cells). Per-cell values are the entry's divided accordingly.
// Throws UsageError for counts < 1.
BatteryPackParams PackFromEntry(const BatteryEntry& entry, int units_series, int units_parallel = 1);

enum class DischargeStatus {
  kReachedCutoff,     // ran until the terminal voltage fell to the cut-off
  kEmpty,             // reached SOC = 0 above the cut-off
  kPowerUnreachable,  // at some SOC the pack cannot deliver the power (V_oc^2 < 4*R*P)
};

struct DischargeOptions {
  double initial_soc = 1.0;
  // Cut-off per cell under load, V; NaN = CellDefaultCutoffV(chemistry).
  double cutoff_cell_v = kNaN;
  double soc_step = 1e-3;  // integration step in SOC (midpoint rule)
};

struct DischargeResult {
  DischargeStatus status = DischargeStatus::kEmpty;
  bool over_current = false;  // the current exceeded the continuous rating at some point
  double time_s = 0.0;        // time to the cut-off (or to empty / to the unreachable point)
  double energy_j = 0.0;      // energy delivered at the terminals
  double charge_ah = 0.0;
  double final_soc = 0.0;
  double final_voltage_v = 0.0;
  double max_current_a = 0.0;
  std::string message;
};

class BatteryPack {
 public:
  // Throws UsageError naming the field when params.IsValid fails.
  explicit BatteryPack(const BatteryPackParams& params);

  const BatteryPackParams& params() const { return p_; }
  double capacity_ah() const { return p_.cell_capacity_ah * p_.n_parallel; }
  double ri_ohm() const { return p_.cell_ri_ohm * p_.n_series / p_.n_parallel; }
  double mass_kg() const { return p_.cell_mass_kg * p_.n_series * p_.n_parallel * p_.mass_factor; }
  double max_current_a() const { return p_.cell_max_current_a * p_.n_parallel; }
  double peak_current_a() const { return p_.cell_peak_current_a * p_.n_parallel; }
  double cutoff_v(const DischargeOptions& o = {}) const;

  double OcvV(double soc) const;
  // OCV - I*R; I > 0 discharging.
  double TerminalVoltageV(double soc, double current_a) const;
  // The current that delivers `power_w` at the terminals at `soc`; false when impossible.
  bool CurrentForPower(double soc, double power_w, double* current_a) const;
  // Nominal energy: integral of OCV over the capacity, J (what the pack holds at zero current).
  double StoredEnergyJ() const;

  // Constant-power discharge from initial_soc to the cut-off: time to empty and usable energy.
  DischargeResult DischargeAtPower(double power_w, const DischargeOptions& options = {}) const;
  // Constant-current discharge.
  DischargeResult DischargeAtCurrent(double current_a, const DischargeOptions& options = {}) const;

 private:
  template <typename CurrentAt>
  DischargeResult Discharge(CurrentAt current_at, const DischargeOptions& options) const;

  BatteryPackParams p_;
};

// The integral of CellOcvV(chemistry, soc) d(soc) over [from_soc, 1], V, in closed form (the
// curve is piecewise linear in its table).
double CellOcvIntegral(BatteryChemistry chemistry, double from_soc);
// An upper bound of the integral of OCV(soc) d(soc) over [reserve_soc, 1], V: the terminal
// energy a pack can give above the reserve is at most this times its charge (V <= OCV while
// discharging, coulomb counting). The closed form, raised by 1e-12 against rounding. The OCV
// curve per SOC does not depend on the capacity.
double OcvIntegralUpperBound(const BatteryPack& pack, double reserve_soc);

}  // namespace dynosize
