#include "identification/verdict.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/text_format.h"
#include "identification/parameters.h"

namespace dynosize::identification {

namespace {

std::string Num(double v) { return SignificantText(v, 3); }

void Add(Verdict* v, const std::string& name, bool passed, double value, double limit, const std::string& detail) {
  Check c;
  c.name = name;
  c.passed = passed;
  c.value = value;
  c.limit = limit;
  c.detail = detail;
  v->checks.push_back(c);
}

// A saturation the data cannot pin down. A flat top (sat_slope near 0: the speed stops rising
// above the knee) is most often the ESC's end point below the pulse width taken as full throttle:
// the fix is the end point, named with its value (the knee's pulse width, to 10 us).
std::string SaturationAdvice(const VerdictInputs& in) {
  double knee = 1.0, slope = 1.0;
  for (const auto& p : in.params) {
    if (p.name == "tr_sat") knee = p.value;
    if (p.name == "sat_slope") slope = p.value;
  }
  constexpr double kFlatSlope = 0.1;  // below this the output barely rises above the knee
  if (slope < kFlatSlope && knee < 1.0) {
    if (in.pulse_max_us > in.pulse_min_us && in.pulse_min_us > 0.0) {
      const std::string us = std::to_string(
          10 * std::llround((in.pulse_min_us + knee * (in.pulse_max_us - in.pulse_min_us)) / 10.0));
      return "saturation: the speed stops rising above throttle " + Num(knee) + " (" + us +
             " us): if that is the ESC's end point, give --esc-max-us " + us;
    }
    return "saturation: the speed stops rising above throttle " + Num(knee) +
           ": if that is the ESC's end point, map the command to it (--esc-max-us for pulse widths)";
  }
  return "saturation: log more throttle levels above 80 %";
}

// Which measurement would identify the parameters the checks complain about.
std::string Advice(const VerdictInputs& in, const std::vector<std::string>& weak) {
  std::string a;
  auto add = [&](const std::string& s) {
    if (a.find(s) == std::string::npos) a += (a.empty() ? "" : "; ") + s;
  };
  // The log's own inconsistency first: the parameters' complaints follow from it.
  if (std::find(weak.begin(), weak.end(), "torque_per_ampere") != weak.end()) {
    add("the log: check the torque sensor's calibration (lever arm, zero) against the current sensor's, "
        "or the label Kv (a no-load run at full command gives rpm/V directly)");
  }
  for (const auto& n : weak) {
    if (n == "ke_v_s_per_rad" || n == "deadband") {
      add(in.kv_label_rpm_per_v ? "KE: check the throttle range (--esc-min-us/--esc-max-us) or log no-load points"
                                : "KE: give the motor's label with --kv-label, or log no-load points");
    } else if (n == "io_a") {
      add(in.has_torque ? "Io: give the datasheet's no-load current and its test voltage (--io-label A "
                          "--io-label-v V), or log points at low load (no-load or light propeller)"
                        : "Io: give --io-label A --io-label-v V (the datasheet's no-load current and its test "
                          "voltage), or log torque or no-load points");
    } else if (n == "rm_ohm" || n == "resc_ohm") {
      add(in.has_ac ? "Rm: log more points at high current"
                    : in.has_torque
                        ? "Rm vs RESC: log the AC columns (vll_rms_v, irms_a) or give --rm-label"
                        // Without torque R is seen only through the speed drop at the top steps:
                        // sweeps with other propellers load the same steps differently
                        // (docs/validation.md, one entry per motor: 12 of 13 Strawson motors ok).
                        : "Rm: give --rm-label, log torque, or calibrate this motor's sweeps with other "
                          "propellers or supply voltages together (calibrate LOG1 LOG2 ...)");
    } else if (n == "c1" || n == "c0") {
      add(in.has_torque || in.has_ac ? "C1, C0: log two or more throttle levels over a wider current range"
                                     : "C1, C0: log torque or the AC columns, or give --prior-esc");
    } else if (n == "kt_nm_per_a") {
      add("KT: log torque and the AC columns");
    } else if (n == "tr_sat" || n == "sat_slope") {
      add(SaturationAdvice(in));
    } else if (n == "first_order_better") {
      add("the first-order model predicts this log better: make the entry with calibrate (its own checks "
          "apply), or log torque and the AC columns so that the extension's ESC can be identified");
    }
  }
  return a;
}

}  // namespace

const char* StatusName(Status s) {
  switch (s) {
    case Status::kOk: return "ok";
    case Status::kUnidentifiable: return "unidentifiable";
    case Status::kFailed: return "failed";
  }
  return "failed";
}

const Check* Verdict::FirstFailed() const {
  for (const auto& c : checks) {
    if (!c.passed) return &c;
  }
  return nullptr;
}

void MaxEfficiencies(const MotorParams& motor, const EscParams& esc, const Envelope& env, double* max_eta_esc,
                     double* max_eta_motor) {
  *max_eta_esc = 0.0;
  *max_eta_motor = 0.0;
  if (!(motor.ke_v_s_per_rad > 0.0) || !(motor.rm_ohm + esc.resc_ohm > 0.0)) return;
  const Drive drive(motor, esc);
  const double vmin = env.vdc_min_v > 0.0 ? env.vdc_min_v : 10.0;
  const double vmax = env.vdc_max_v > vmin ? env.vdc_max_v : vmin;
  for (double vdc : {vmin, vmax}) {
    for (int it = 1; it <= 20; ++it) {
      const double tr = 0.05 * it;
      const double wnl = drive.NoLoadSpeed(vdc, tr);
      if (!(wnl > 0.0) || !std::isfinite(wnl)) continue;
      for (int iw = 0; iw < 25; ++iw) {
        const double w = wnl * (0.02 + 0.98 * iw / 24.0);
        const OperatingPoint p = drive.AtSpeed(vdc, tr, w);
        if (!(p.pdc_w > 0.0) || !(p.pac_w > 0.0)) continue;
        if (std::isfinite(p.eta_esc)) *max_eta_esc = std::max(*max_eta_esc, p.eta_esc);
        if (std::isfinite(p.eta_motor)) *max_eta_motor = std::max(*max_eta_motor, p.eta_motor);
      }
    }
  }
}

Verdict Judge(const VerdictInputs& in) {
  Verdict v;
  bool unident = false, failed = false;
  Add(&v, "converged", in.converged, in.converged ? 1.0 : 0.0, 1.0,
      in.converged ? "the solver met a tolerance test" : "the solver stopped before a tolerance test was met");
  failed = failed || !in.converged;

  std::vector<std::string> weak;
  if (std::isfinite(in.torque_per_ampere_vs_label)) {
    const double excess = 100.0 * (in.torque_per_ampere_vs_label - 1.0);
    const bool ok = excess <= 100.0 * kKvLabelMaxRelDeviation;
    Add(&v, "torque_per_ampere_vs_label", ok, excess, 100.0 * kKvLabelMaxRelDeviation,
        "the log's torque per DC ampere at full command against a motor of the label Kv at full duty "
        "(Q <= KT_dc*IDC, eqs 41, 57; model.md sections 8, 10)" +
            std::string(ok ? "" : ": no motor within the label's tolerance gives this torque for this current"));
    failed = failed || !ok;
    if (!ok) weak.push_back("torque_per_ampere");
  }
  std::string on_bound, flat, worst_name;
  int n_bound = 0, n_flat = 0;
  double worst_rel = 0.0;
  for (const auto& p : in.params) {
    if (!p.fitted) continue;
    if (p.at_bound) {
      ++n_bound;
      on_bound += (on_bound.empty() ? "" : ", ") + p.name + " = " + Num(p.value);
      weak.push_back(p.name);
      continue;
    }
    if (!p.identifiable) {
      ++n_flat;
      flat += (flat.empty() ? "" : ", ") + p.name;
      weak.push_back(p.name);
      continue;
    }
    const double rel = std::isfinite(p.standard_error) && p.value != 0.0
                           ? 100.0 * std::fabs(p.standard_error / p.value)
                           : (std::isfinite(p.standard_error) ? std::numeric_limits<double>::infinity() : 0.0);
    if (rel > kMaxRelStdErrorPercent) weak.push_back(p.name);
    if (rel > worst_rel || worst_name.empty()) {
      worst_rel = rel;
      worst_name = p.name;
    }
  }
  Add(&v, "no_parameter_on_bound", n_bound == 0, n_bound, 0.0,
      n_bound == 0 ? "every fitted parameter is inside its physical range"
                   : "on a bound of the physical range (the data push it outside): " + on_bound);
  Add(&v, "identifiable", n_flat == 0, n_flat, 0.0,
      n_flat == 0 ? "no direction of the fitted parameters is flat" : "the data do not determine " + flat);
  Add(&v, "rel_std_error", worst_rel <= kMaxRelStdErrorPercent, worst_rel, kMaxRelStdErrorPercent,
      worst_name.empty() ? "no identified parameter" : "largest: " + worst_name);
  unident = n_bound > 0 || n_flat > 0 || worst_rel > kMaxRelStdErrorPercent;

  if (in.kv_label_rpm_per_v) {
    const double kv = KvFromKe(in.motor.ke_v_s_per_rad, in.motor.type);
    const double dev = 100.0 * std::fabs(kv / *in.kv_label_rpm_per_v - 1.0);
    const bool ok = std::isfinite(dev) && dev <= 100.0 * kKvLabelMaxRelDeviation;
    Add(&v, "kv_vs_label", ok, dev, 100.0 * kKvLabelMaxRelDeviation,
        "fitted Kv " + Num(kv) + " rpm/V vs label " + Num(*in.kv_label_rpm_per_v));
    failed = failed || !ok;
    if (!ok) weak.push_back("ke_v_s_per_rad");
  }

  double eta_esc = 0.0, eta_motor = 0.0;
  MaxEfficiencies(in.motor, in.esc, in.envelope, &eta_esc, &eta_motor);
  const std::string esc_rule = EscEnergyViolation(in.esc, in.motor.type);
  const std::string motor_rule = MotorEnergyViolation(in.motor);
  const double tol = 1.0 + kPhysicsRelTol;
  Add(&v, "esc_efficiency", eta_esc <= tol && esc_rule.empty(), eta_esc, 1.0,
      esc_rule.empty() ? "PESC >= 0 at every throttle and current (model.md section 10)" : esc_rule);
  Add(&v, "motor_efficiency", eta_motor <= tol && motor_rule.empty(), eta_motor, 1.0,
      motor_rule.empty() ? "KT <= sqrt(27/10)*KE, Rm > 0, Io >= 0 (model.md section 10)" : motor_rule);
  failed = failed || !(eta_esc <= tol && esc_rule.empty()) || !(eta_motor <= tol && motor_rule.empty());

  if (in.held_out) {
    const HeldOut& h = *in.held_out;
    const std::size_t fitted = h.folds - h.failed_folds;
    const bool folds_ok = h.folds >= 2 && h.failed_folds == 0;
    Add(&v, "cross_validation_folds", folds_ok, static_cast<double>(fitted), static_cast<double>(h.folds),
        h.folds < 2 ? "too few points to cross-validate: " + std::to_string(h.folds)
        : h.failed_folds > 0
            ? std::to_string(h.failed_folds) + " of " + std::to_string(h.folds) +
                  " folds could not be fitted (too few points left to cross-validate)"
            : std::string(h.leave_one_out ? "leave-one-out, " : "") + std::to_string(h.folds) + " folds fitted");
    unident = unident || !folds_ok;
    const double e = h.median_abs_current_percent;
    const bool err_ok = std::isfinite(e) && e <= kMaxHeldOutCurrentPercent;
    std::string d = "median |error| of the held-out " +
                    (h.primary_quantity.empty() ? std::string("DC current") : h.primary_quantity);
    if (h.primary_quantity.empty() && std::isfinite(h.median_abs_speed_percent)) {
      d += "; speed " + Num(h.median_abs_speed_percent) + " %";
    }
    if (!std::isfinite(e)) d = "no held-out prediction could be made";
    Add(&v, "held_out_error", err_ok, e, kMaxHeldOutCurrentPercent, d);
    failed = failed || (!err_ok && folds_ok);
    unident = unident || (!err_ok && !folds_ok);
    if (h.primary_quantity.empty() && std::isfinite(h.median_abs_speed_percent)) {
      const double es = h.median_abs_speed_percent;
      const bool speed_ok = es <= kMaxHeldOutSpeedPercent;
      Add(&v, "held_out_speed_error", speed_ok, es, kMaxHeldOutSpeedPercent,
          "median |error| of the held-out speed" +
              std::string(speed_ok ? "" : ": the fit predicts the current but not the speed (check the speed "
                                          "readings, the throttle range --esc-min-us/--esc-max-us, or the label Kv)"));
      failed = failed || (!speed_ok && folds_ok);
      unident = unident || (!speed_ok && !folds_ok);
    }
    if (std::isfinite(h.rms_percent) && std::isfinite(h.first_order_rms_percent)) {
      const double limit = h.first_order_rms_percent + kMaxHeldOutLossPoints;
      const bool no_worse = h.rms_percent <= limit;
      Add(&v, "held_out_vs_first_order", no_worse, h.rms_percent, limit,
          "rms held-out error of this model against the first-order model's " + Num(h.first_order_rms_percent) +
              " % (+" + Num(kMaxHeldOutLossPoints) + " point)" +
              (no_worse ? std::string() : ": the extension predicts unseen rows worse than the model it extends"));
      failed = failed || !no_worse;
      if (!no_worse) weak.push_back("first_order_better");
    }
  }

  v.status = failed ? Status::kFailed : (unident ? Status::kUnidentifiable : Status::kOk);
  std::sort(weak.begin(), weak.end());
  weak.erase(std::unique(weak.begin(), weak.end()), weak.end());
  v.advice = v.status == Status::kOk ? "" : Advice(in, weak);
  std::ostringstream s;
  s << "status " << StatusName(v.status);
  if (const Check* c = v.FirstFailed()) {
    s << ": check " << c->name << " failed (" << Num(c->value) << " vs limit " << Num(c->limit) << "): " << c->detail;
  } else {
    s << ": all " << v.checks.size() << " checks passed";
  }
  v.summary = s.str();
  return v;
}

}  // namespace dynosize::identification
