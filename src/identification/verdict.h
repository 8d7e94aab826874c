// The status contract of an identified motor + ESC pair: one verdict that `calibrate`
// and `diagnose` both report in --json ("status", "checks") and in one line of text, and that
// decides whether --out may write the entry.
//
//   status "ok"              every check passed: the entry may be written and used for sizing;
//          "unidentifiable"  the log cannot pin the parameters down (a parameter on a bound of its
//                            physical range, a relative standard error above 50 %, a direction the
//                            data do not determine, too few points to cross-validate);
//          "failed"          the fit did not converge, or its result breaks physics or the label
//                            (energy created, Kv beyond 25 % of the label, held-out error too large).
//
// Checks (name: value vs limit):
//   converged                     1 when the solver met a tolerance test        (limit 1)
//   torque_per_ampere_vs_label    the log itself, with torque and a label: percent by which its
//                                 torque per DC ampere at full command exceeds a motor of the
//                                 label Kv at full duty, Q <= KT_dc*IDC (fit_rows.h) (limit 25,
//                                 the label tolerance of kv_vs_label)
//   no_parameter_on_bound         number of fitted parameters on a bound          (limit 0)
//   identifiable                  number of fitted parameters in a flat direction (limit 0)
//   rel_std_error                 largest standard error / |value| of the fitted,
//                                 identifiable parameters, percent               (limit 50)
//   kv_vs_label                   |Kv_fit/Kv_label - 1|, percent (with a label)   (limit 25)
//   esc_efficiency                largest eta_esc over the fitted envelope        (limit 1)
//   motor_efficiency              largest eta_motor over the fitted envelope      (limit 1)
//   held_out_error                median |error| of the held-out current (or, for logs without
//                                 torque and AC columns, of the speed predicted from the
//                                 measured current), percent                     (limit 10)
//   held_out_speed_error          median |error| of the held-out speed at the measured torque (or
//                                 from the measured current), where the primary held-out
//                                 quantity is the DC current: a fit that predicts the current
//                                 but not the speed is not an entry for sizing   (limit 10)
//   cross_validation_folds        folds that could be fitted (small tables: each point left out
//                                 in turn; a fold that cannot be fitted fails it) (limit: all)
//   held_out_vs_first_order       diagnose only: rms held-out error of the extended model, percent,
//                                 against the first-order model's plus kMaxHeldOutLossPoints (an
//                                 extension must not predict unseen rows worse than the model it
//                                 extends; the search's own gain threshold is 1 point)
// The efficiency checks evaluate model::Drive over the envelope (VDC range of the log, throttle
// 0.05..1, speeds from 2 % to 100 % of no-load), independently of the fit's own bounds.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "model/drive.h"

namespace dynosize::identification {

enum class Status { kOk, kUnidentifiable, kFailed };
const char* StatusName(Status s);  // "ok", "unidentifiable", "failed"

struct Check {
  std::string name;
  bool passed = false;
  double value = std::numeric_limits<double>::quiet_NaN();
  double limit = std::numeric_limits<double>::quiet_NaN();
  std::string detail;  // what the value is made of, and what would fix a failure
};

// A fitted parameter as the verdict sees it.
struct ParamState {
  std::string name;
  double value = 0.0;
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  bool fitted = false;
  bool identifiable = false;
  bool at_bound = false;
};

// The operating range the entry was fitted on.
struct Envelope {
  double vdc_min_v = 0.0;
  double vdc_max_v = 0.0;
};

// Held-out prediction errors (src/calibration LeaveOneOut, or diagnose's folds).
struct HeldOut {
  std::size_t folds = 0;
  std::size_t failed_folds = 0;
  double median_abs_current_percent = std::numeric_limits<double>::quiet_NaN();
  double median_abs_speed_percent = std::numeric_limits<double>::quiet_NaN();
  bool leave_one_out = false;  // each point (or throttle level) left out in turn
  // What median_abs_current_percent measures when it is not the DC current (logs without torque
  // or AC columns predict the speed from the measured current); "" = the DC current.
  std::string primary_quantity;
  // diagnose: rms of the held-out percent errors of this (extended) model and of the first-order
  // model it extends, on the same folds; NaN where not computed (calibrate).
  double rms_percent = std::numeric_limits<double>::quiet_NaN();
  double first_order_rms_percent = std::numeric_limits<double>::quiet_NaN();
};

struct VerdictInputs {
  bool converged = false;
  std::vector<ParamState> params;
  MotorParams motor;
  EscParams esc;
  Envelope envelope;
  std::optional<double> kv_label_rpm_per_v;
  std::optional<HeldOut> held_out;  // absent: not computed (the check is then not listed)
  // TorquePerAmpereVsLabel of the log (fit_rows.h); NaN = not computed (the check is then not
  // listed).
  double torque_per_ampere_vs_label = std::numeric_limits<double>::quiet_NaN();
  bool has_torque = false;          // for the advice: what measurement would help
  bool has_ac = false;
  bool has_throttle = false;
  // The throttle came from ESC pulse widths with these end points (logs::SteadyTable; 0 = not a
  // pulse width): the advice then names the pulse width where the speed stops rising.
  double pulse_min_us = 0.0;
  double pulse_max_us = 0.0;
};

struct Verdict {
  Status status = Status::kFailed;
  std::vector<Check> checks;
  // One line: "status ok: all 8 checks passed" or "status unidentifiable: <check> (<value> vs
  // <limit>): <detail>".
  std::string summary;
  std::string advice;  // which measurement would identify what ("" when ok)
  const Check* FirstFailed() const;
};

// Limits of the checks (see the header comment).
inline constexpr double kMaxRelStdErrorPercent = 50.0;
inline constexpr double kMaxHeldOutCurrentPercent = 10.0;
// The same limit on the held-out speed (docs/validation.md: the largest median held-out speed
// error of an ok log was 7.0 % before this check existed).
inline constexpr double kMaxHeldOutSpeedPercent = 10.0;
// An extended model may be this much worse (rms held-out error, percentage points) than the
// first-order model before it is refused: diagnose's smallest cross-validated gain that counts.
inline constexpr double kMaxHeldOutLossPoints = 1.0;

Verdict Judge(const VerdictInputs& in);

// Largest eta_esc and eta_motor of model::Drive(motor, esc) over the envelope (throttle 0.05..1
// in steps of 0.05, speeds 2..100 % of no-load in 25 steps, VDC at both ends of the range).
void MaxEfficiencies(const MotorParams& motor, const EscParams& esc, const Envelope& env,
                     double* max_eta_esc, double* max_eta_motor);

}  // namespace dynosize::identification
