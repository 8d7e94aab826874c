// Propeller model: thrust and torque of a catalog propeller as functions of shaft speed, air
// density and airspeed (advance ratio), and the local quadratic load law that the closed-form
// motor+ESC operating point (model/drive.h, TorqueLaw) needs.
//
// Definitions (UIUC Propeller Data Site, Brandt & Selig; n in rev/s, D in m):
//   J = V/(n*D),   T = CT*rho*n^2*D^4,   P = CP*rho*n^3*D^5,   Q = P/(2*pi*n) = CP*rho*n^2*D^5/(2*pi)
// Data, in the order the model prefers them:
//   1. measured tables (PropEntry::static_table: CT, CP vs rpm at J = 0; PropEntry::j_tables:
//      CT, CP vs J at several rpm). Linear interpolation in J within a sweep and in rpm between
//      sweeps, so the Reynolds-number (rpm) dependence of the data is kept. A sweep that starts
//      above J = 0 is joined to the static table at its rpm.
//   2. constant coefficients ct_static, cp_static (static only, no rpm dependence).
//   3. DriveCalc power laws T = a*(rpm/1000)^b, P = c*(rpm/1000)^d at law_rho, scaled by rho
//      (static only), within the entry's valid rpm range (catalog/prop_credibility.h).
// Outside the data the model does not extrapolate silently. Below the lowest speed of the data
// (the valid range's low edge, catalog/prop_credibility.h; for tables the lowest rpm of the table
// read) the coefficients at that edge are corrected for the lower Reynolds number
// (catalog/prop_reynolds.h: CT x (rpm/rpm_lo)^a, CP x (rpm/rpm_lo)^b, a >= 0 >= b, fitted on
// UIUC's measured static tables; the figure of merit only falls), for every kind of data. Above
// the highest speed and beyond the measured advance ratios the edge coefficients are held (a
// higher Reynolds number changes little, and compressibility is not in the data). Either way
// PropEvaluation says so (rpm_outside_data, j_outside_data, no_forward_flight_data,
// reynolds_ratio).
#pragma once

#include <string>

#include "catalog/catalog.h"
#include "catalog/prop_credibility.h"
#include "catalog/prop_reynolds.h"
#include "model/drive.h"

namespace dynosize {

enum class PropDataKind { kTables, kCoefficients, kPowerLaw };

struct PropEvaluation {
  double omega_rad_s = 0.0;
  double rpm = 0.0;
  double rho_kg_m3 = 0.0;
  double airspeed_m_s = 0.0;
  double j = 0.0;  // advance ratio V/(n*D); 0 when n = 0
  double ct = 0.0;
  double cp = 0.0;
  double thrust_n = 0.0;
  double torque_nm = 0.0;
  double power_w = 0.0;
  PropDataKind data = PropDataKind::kTables;
  // The flags: when any is set the numbers rest on coefficients held at the edge of the data.
  bool rpm_outside_data = false;        // below the lowest / above the highest measured rpm
  bool j_outside_data = false;          // advance ratio beyond the measured sweep(s)
  bool no_forward_flight_data = false;  // airspeed > 0 but only static data exist
  bool InData() const { return !rpm_outside_data && !j_outside_data && !no_forward_flight_data; }
  // What the flags refer to, kept as numbers so that evaluations in a solver's inner loop do
  // not format text; Message() writes the sentence when someone reads it.
  bool at_rest_in_flow = false;  // n = 0 with airspeed > 0 (windmilling is not modelled)
  bool from_sweeps = false;      // kTables: the forward-flight sweeps were used, not the static table
  double data_rpm_lo = 0.0, data_rpm_hi = 0.0;  // the rpm range of that data (power law: max_rpm)
  // rpm over the low edge of the data when below it (the Reynolds correction was applied at
  // this ratio, catalog/prop_reynolds.h), else 1.
  double reynolds_ratio = 1.0;
  // "" when in the data, else one sentence naming the limit ("rpm 1200 outside the static data
  // 2484-6804").
  std::string Message() const;
};

// The load law Q(omega) = a + b*omega + c*omega^2 of model/drive.h, a quadratic through the
// exact torque at omega0*(1 - rel_step), omega0, omega0*(1 + rel_step) at fixed density and
// airspeed. Valid near omega0 only; `in_data` and `message` carry the flags of the three points.
struct LocalTorqueFit {
  TorqueLaw law;
  double omega0_rad_s = 0.0;
  double rel_step = 0.0;
  bool in_data = true;
  std::string message;
};

class PropModel {
 public:
  // Copies what it needs from the entry. Throws UsageError when the entry has no performance
  // data (the catalog reader already refuses such entries).
  explicit PropModel(const PropEntry& entry);

  // Exact evaluation. Throws UsageError for omega < 0, rho <= 0 or airspeed < 0 (not finite).
  PropEvaluation Evaluate(double omega_rad_s, double rho_kg_m3, double airspeed_m_s = 0.0) const;

  // Same at a given advance ratio J = V/(n*D) (>= 0) instead of an airspeed.
  PropEvaluation EvaluateAtAdvanceRatio(double omega_rad_s, double rho_kg_m3, double j) const;

  // Local quadratic fit of the torque around omega0 (> 0), rel_step in (0, 0.5].
  LocalTorqueFit FitTorqueLaw(double omega0_rad_s, double rho_kg_m3, double airspeed_m_s = 0.0,
                              double rel_step = 0.05) const;

  // The speed whose static thrust is thrust_n (> 0) at rho, in closed form where the data
  // allow one: constant coefficients (T = CT*rho*n^2*D^4) and power laws (T = a*(rpm/1000)^b
  // at the law's density, linear in rho; held at the edges of the valid range as Evaluate
  // holds them, so T grows as n^2 outside it). Evaluate(*omega) gives thrust_n to rounding
  // (a few ulps); below the valid range the Reynolds correction makes T ~ n^(2 + a). False for tables and for a law whose thrust does not rise with the speed
  // (the caller then finds the root numerically).
  bool StaticSpeedForThrust(double thrust_n, double rho_kg_m3, double* omega_rad_s) const;

  const PropEntry& entry() const { return entry_; }
  PropDataKind data_kind() const { return kind_; }
  double diameter_m() const { return entry_.diameter_m; }
  // The data's valid range (catalog/prop_credibility.h, ValidRange of the entry).
  const PropValidRange& valid_range() const { return range_; }
  // The largest CT any evaluation returns (at any speed, density and airspeed): the tables'
  // largest (interpolation stays between the points, the edges are held), the constant CT, or
  // the power law's CT at the ends of its range (a power of the speed between them); the
  // Reynolds correction below the data only lowers CT (a >= 0). So at every speed
  // T <= max_thrust_coefficient()*rho*n^2*D^4.
  double max_thrust_coefficient() const { return ct_max_; }

 private:
  // CT, CP at (rpm, J) from the tables; sets the flags of `ev`.
  void TableCoefficients(double rpm, double j, PropEvaluation* ev) const;

  PropEntry entry_;
  PropDataKind kind_ = PropDataKind::kTables;
  // j_tables with the static point (J = 0, from static_table at the sweep's rpm) prepended
  // when the sweep starts above J = 0; built once in the constructor.
  std::vector<PropSweep> sweeps_;
  // The data's valid range (power laws: rpm_min/rpm_max or the assumed tip-speed band).
  PropValidRange range_;
  double ct_max_ = 0.0;  // max_thrust_coefficient()
  double MaxThrustCoefficient() const;  // for ct_max_, once
  // Applies the Reynolds correction below rpm_lo to ev's coefficients.
  void CorrectBelowData(double rpm_lo, PropEvaluation* ev) const;
};

}  // namespace dynosize
