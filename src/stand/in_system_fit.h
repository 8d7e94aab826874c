// Fitting and checking the in-system law of catalog/in_system.h on measured systems.
//
// Stand data with measured torque (KDE Direct's sheets): at each measured point (VDC, command,
// speed, torque) the model gives the DC current of a motor whose parameters come from its
// datasheet through the law, with the ideal ESC of eq (56) (Drive::Inverse, eqs 42, 48, 57).
// With the ideal ESC the rms model and the plain first-order DC model of the same numbers are
// one machine (catalog/conventions.h 1.), so the "datasheet" column of every check is also the
// plain DC model's.
//
// The law's coefficients minimise  sum_m w_m sum_i (IDC_pred/IDC_meas - 1)^2,  w_m = 1/n_m
// (every motor counts alike, whatever its number of points), by Levenberg-Marquardt
// (fit/nonlinear_least_squares.h). Checked by leaving out: for each motor the law is fitted
// without it and predicts its sheet.
//
// Databases of refits (DriveCalc: datasheet R and Io against fits of the same motor's measured
// points) give the law from pairs directly.
#pragma once

#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "catalog/in_system.h"

namespace dynosize::stand {

struct LawPoint {
  double vdc_v = 0.0, throttle = 0.0, idc_a = 0.0, omega_rad_s = 0.0, torque_nm = 0.0;
  int sweep = 0;
};

struct LawMotor {
  std::string name;
  DatasheetMotor datasheet;
  std::vector<LawPoint> points;
};

// Which coefficients of (IS1), (IS2) are free; the others stay at the identity (1 or 0).
struct LawForm {
  bool r_add = true;
  bool io_speed = false;
  std::string Describe() const;
};

// The DC current at a measured point (VDC, speed, torque) of the motor through the law, with
// the ideal ESC and ratio_r/ratio_io scaling the law's R and Io (1: the law itself).
double PredictIdc(const LawMotor& motor, const InSystemLaw& law, const LawPoint& p,
                  double ratio_r = 1.0, double ratio_io = 1.0);

// The law fitted on `motors` except the one at index `leave_out` (-1: none). Only the
// coefficients are set (the spreads are the caller's).
InSystemLaw FitLaw(const std::vector<LawMotor>& motors, const LawForm& form, int leave_out = -1);

// One motor's own in-system values (R_dc and Io_dc, constant Io) fitted to its points, as
// factors over what `law` gives it: the motor's scatter about the law.
struct MotorRatios {
  double r_ratio = 1.0, io_ratio = 1.0;
};
MotorRatios FitMotorRatios(const LawMotor& motor, const InSystemLaw& law);

// Per sweep, the median relative DC-current error (pred/meas - 1) and its median |.|.
struct SweepErrors {
  std::vector<double> median_abs, median_signed;
};
SweepErrors CurrentErrorsBySweep(const LawMotor& motor, const InSystemLaw& law);

// The dead band (EscParams::deadband, negative: an offset) that maps the command onto the
// effective throttle the motor needs at each point (ideal ESC otherwise): the median over the
// points of the motor, its own in-system values fitted (FitMotorRatios).
double FitMotorDeadband(const LawMotor& motor, const InSystemLaw& law);

// Median over sweeps of the median relative speed error forward from the command at the
// measured torque (Drive::AtTorque) with the law's values and the ESC dead band `deadband`.
double ForwardSpeedError(const LawMotor& motor, const InSystemLaw& law, double deadband);

// The check of one motor left out of everything (law, spreads, throttle prior).
struct LeftOutCheck {
  std::string name;
  int points = 0, sweeps = 0;
  InSystemLaw law;  // fitted without this motor, spreads from the others' ratios
  double datasheet_error = 0.0, datasheet_bias = 0.0;  // median over sweeps (the plain DC model)
  double law_error = 0.0, law_bias = 0.0;              // the same through the law
  double coverage = 0.0;      // share of points with IDC inside the p10-p90 range
  double deadband_prior = 0.0;  // median of the other motors' fitted dead bands
  double rpm_error_forward = 0.0;  // ForwardSpeedError with that prior
  MotorRatios own;                 // this motor's ratios over the law without it
};

struct LawReport {
  LawForm form;
  InSystemLaw law;  // on every motor, with the spreads of every motor's ratios
  ThrottleOffsetPrior throttle;  // from every motor's fitted dead band
  std::vector<LeftOutCheck> left_out;
  // Medians over every sweep of every left-out motor, and the share of all points covered.
  double datasheet_error = 0.0, datasheet_bias = 0.0, law_error = 0.0, law_bias = 0.0;
  double coverage = 0.0, rpm_error_forward = 0.0;
  int points = 0, sweeps = 0;
};
LawReport LeaveOneMotorOut(const std::vector<LawMotor>& motors, const LawForm& form);

// A database pair: a motor's datasheet values and its refit from measured points (DC circuit).
struct RefitPair {
  std::string id;
  double r_dc_datasheet_ohm = 0.0, io_dc_datasheet_a = 0.0;
  double r_dc_refit_ohm = 0.0, io_dc_refit_a = 0.0;
};
// The law (r_scale, r_add_ohm by least squares of the relative R error; io_scale the median Io
// ratio; io_speed 0: the refits hold Io at the database's own test speed) with the spreads
// (p10/p90 of the pairs' ratios over the law) and, in *held_out (optional), the median
// |relative R error| and the p10-p90 coverage of R with each tenth of the pairs left out.
struct RefitLawCheck {
  double r_error_law = 0.0, r_error_datasheet = 0.0;  // median |R_pred/R_refit - 1|
  double r_bias_law = 0.0, r_bias_datasheet = 0.0;
  double coverage_r = 0.0, coverage_io = 0.0;
  int pairs = 0;
};
InSystemLaw FitLawFromRefits(const std::vector<RefitPair>& pairs, RefitLawCheck* held_out = nullptr);

// A law (fitted elsewhere) against refit pairs it was not fitted on: median |pred/refit - 1|
// and median signed error of R and Io, and the share of refits inside the law's p10-p90.
struct RefitErrors {
  double r_error = 0.0, r_bias = 0.0, io_error = 0.0, io_bias = 0.0;
  double coverage_r = 0.0, coverage_io = 0.0;
  int pairs = 0;
};
RefitErrors EvaluateOnRefits(const std::vector<RefitPair>& pairs, const InSystemLaw& law);

// DriveCalc's database motors (catalog/drivecalc.json "dc_m_N") beside their refits
// (drivecalc_fitted.json "dc_m_N_fit"), from a catalog loaded without the law (both as the files
// state them), DC circuit.
std::vector<RefitPair> DriveCalcRefitPairs(const Catalog& raw);
// Manufacturer-stated motors of another maker than KDE that DriveCalc measured (the same name up
// to punctuation and "Gold Line", or contained in DriveCalc's, and Kv within 5 %): their datasheet
// values beside `drivecalc`'s refit of the same motor.
std::vector<RefitPair> ManufacturerRefitPairs(const Catalog& raw, const std::vector<RefitPair>& drivecalc);

}  // namespace dynosize::stand
