// Motor constants from what eVTOL motor makers state: Kv [rpm/V], the resistance R_dc [ohm] of
// the DC equivalent circuit and the no-load current Io_dc [A] at a test voltage (the circuit
// VDC = R_dc*IDC + n/Kv of catalog/conventions.h, 1.), estimated from a motor's mass, speed
// limits and voltage, with the range that leaving each maker out of the fit gives them.
// docs/motor-estimate.md has the fitted numbers and the leave-one-maker-out table.
//
// The law (Kv_SI = Kv*pi/30 [rad/s/V]; Kt = 1/Kv_SI [N m/A] in the DC circuit, docs/model.md
// section 8):
//
//   Kv  = c_max   * rpm_max   / V     when rpm_max is stated, else                       (E1)
//   Kv  = c_rated * rpm_rated / V     V = v_nom, else v_max (no-load speed at the voltage
//                                     is above the limiting speed: c > 1 expected)
//   Km  = Kt/sqrt(R_dc) = km_1kg * (m/1 kg)^km_exp  [N m/sqrt(W)]                          (E2)
//   R_dc = 1/(Kv_SI^2 * Km^2)                           (E2 solved for R, with Kt from Kv)
//   T0  = Io_dc/Kv_SI   = t0_1kg * (m/1 kg)^t0_exp  [N m]                                  (E3)
//   Io_dc = T0 * Kv_SI
//
// Km (the torque per square root of copper loss) is a property of the frame, not of its
// winding, and grows with the active mass. T0 is the no-load drag torque (hysteresis and
// bearings, docs/model.md section 9: Io(omega) = Io0 + Io1*omega); the references state Io at
// 10 V (a few hundred rpm), where the drag torque hardly depends on speed, so Io_dc at the test
// voltage is T0*Kv_SI whatever the voltage, and the estimate says it is Io at 10 V, cold.
//
// Fitting (Fit): (E1) as weighted means of ln(Kv*V/rpm), (E2) and (E3) as weighted least squares
// of ln Km and ln T0 on ln m (fit/linear_least_squares.h). Each row weighs 1/(rows of its maker
// and model): the windings of one frame are one observation of Km and T0.
// Ranges (LeaveOneMakerOut): every maker is left out in turn, the law refitted on the others and
// the left-out maker's constants estimated (R and Io from its true Kv); the p10 and p90 of the
// ratio true/estimate over all held-out motors, every maker weighing alike, are the range.
// Where Kv is itself estimated, the ranges of R and Io widen by the Kv range in quadrature of
// logs (R ~ Kv^-2, Io ~ Kv; the two errors taken as independent).
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace dynosize {

inline constexpr double kNotStated = std::numeric_limits<double>::quiet_NaN();

// What a maker states of one motor (SI except Kv and speeds, which stay in the datasheet units
// rpm/V and rpm). NaN = not stated; a stated value must be finite and > 0.
struct StatedMotor {
  std::string maker;  // leave-one-maker-out groups by this
  std::string model;  // frame (windings of one model share it); weights in the fit
  double mass_kg = kNotStated;
  double p_cont_w = kNotStated, p_peak_w = kNotStated;
  double t_cont_nm = kNotStated, t_peak_nm = kNotStated;
  double rpm_max = kNotStated;    // limiting / maximum speed
  double rpm_rated = kNotStated;  // speed tied to the rating (base, nominal, working)
  double v_nom_v = kNotStated, v_max_v = kNotStated;  // DC voltage
  double kv_rpm_per_v = kNotStated;
};

// A motor that states its constants too: `stated` without them (stated.kv_rpm_per_v NaN), the
// constants in the fields below (NaN where the source does not state one).
struct ReferenceMotor {
  StatedMotor stated;
  double kv_rpm_per_v = kNotStated;
  double r_dc_ohm = kNotStated;   // DC equivalent circuit (line-to-line ohmmeter value)
  double io_dc_a = kNotStated;    // no-load DC current at io_test_v
  double io_test_v = kNotStated;
  std::string where;              // "file:line" of the row, for messages
};

// One estimated constant.
struct EstimatedValue {
  bool known = false;  // false: not estimated (why in `how`)
  bool stated = false;  // the maker's own value (p10 = p90 = value)
  double value = kNotStated, p10 = kNotStated, p90 = kNotStated;
  // One line: "Kv = 1.32*rpm_max/v_nom (law fitted on 55 motors of 3 makers,
  // leave-one-maker-out p10-p90 x0.80-1.21)", or why it could not be estimated.
  std::string how;
};

struct MotorConstantsEstimate {
  EstimatedValue kv_rpm_per_v;
  EstimatedValue r_dc_ohm;
  EstimatedValue io_dc_a;
  double io_test_v = 10.0;  // Io_dc is the no-load current at this voltage
  // "R_dc: needs the mass (not stated)" per value not estimated; empty when all three are known.
  std::vector<std::string> not_estimated;
  bool AllKnown() const { return not_estimated.empty(); }
  std::string FullReport() const;  // one line per value
};

// The coefficients of (E1)-(E3) and the leave-one-maker-out ranges (ratio true/estimate).
struct MotorEstimateCoefficients {
  double kv_factor_rpm_max = kNotStated, kv_factor_rpm_rated = kNotStated;
  double km_1kg_nm_per_sqrt_w = kNotStated, km_mass_exponent = kNotStated;
  double t0_1kg_nm = kNotStated, t0_mass_exponent = kNotStated;
};

// Range and support of one law: p10/p90 of true/estimate on held-out makers, motors and makers
// it was fitted on, and the fitted mass range (for the extrapolation note).
struct LawSupport {
  double ratio_p10 = kNotStated, ratio_p90 = kNotStated;
  int motors = 0, makers = 0;
  double mass_min_kg = kNotStated, mass_max_kg = kNotStated;
};

// One held-out maker's row of the table (errors are |estimate/true - 1|).
struct MakerHoldOut {
  std::string maker;
  int kv_max_n = 0, kv_rated_n = 0, r_n = 0, io_n = 0;  // held-out motors per law
  double kv_max_median_abs_error = kNotStated, kv_rated_median_abs_error = kNotStated;
  double r_median_abs_error = kNotStated, io_median_abs_error = kNotStated;
  // Median ratio true/estimate (bias) and the share of the maker's motors inside the pooled
  // p10-p90 range.
  double kv_max_median_ratio = kNotStated, kv_rated_median_ratio = kNotStated;
  double r_median_ratio = kNotStated, io_median_ratio = kNotStated;
  double kv_max_coverage = kNotStated, kv_rated_coverage = kNotStated;
  double r_coverage = kNotStated, io_coverage = kNotStated;
};

struct LeaveOneMakerOutTable {
  std::vector<MakerHoldOut> makers;  // sorted by name
  LawSupport kv_max, kv_rated, r, io;  // pooled ranges (motors/makers: held-out counts)
  // Share of all held-out motors (each counting once) inside the pooled p10-p90.
  double kv_max_coverage = kNotStated, kv_rated_coverage = kNotStated;
  double r_coverage = kNotStated, io_coverage = kNotStated;
  std::string FullReport() const;  // a Markdown table, as in docs/motor-estimate.md
};

class MotorEstimateLaw {
 public:
  // Fits (E1)-(E3) on `refs` and takes the ranges from LeaveOneMakerOut(refs). A law without
  // rows (or with rows of fewer than two makers, so no range) stays unknown: Estimate then says
  // so. Throws UsageError on a stated value that is not NaN and not finite > 0.
  static MotorEstimateLaw Fit(const std::vector<ReferenceMotor>& refs);

  // The constants of `motor`: its Kv if stated (else (E1)), R_dc and Io_dc from its mass and Kv.
  // Io_dc is at 10 V (the references' test voltage). Throws UsageError on a bad stated value.
  MotorConstantsEstimate Estimate(const StatedMotor& motor) const;

  const MotorEstimateCoefficients& coefficients() const { return coef_; }
  const LawSupport& kv_max_support() const { return kv_max_; }
  const LawSupport& kv_rated_support() const { return kv_rated_; }
  const LawSupport& r_support() const { return r_; }
  const LawSupport& io_support() const { return io_; }
  // One line per law with its coefficients and range.
  std::string Describe() const;

 private:
  MotorEstimateCoefficients coef_;
  LawSupport kv_max_, kv_rated_, r_, io_;
};

// Coefficients only (no ranges): what Fit and LeaveOneMakerOut refit on each subset.
MotorEstimateCoefficients FitMotorEstimateCoefficients(const std::vector<ReferenceMotor>& refs);

// Leaves each maker out in turn (makers with at least one usable reference).
LeaveOneMakerOutTable LeaveOneMakerOut(const std::vector<ReferenceMotor>& refs);

}  // namespace dynosize
