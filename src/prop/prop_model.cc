#include "prop/prop_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"

namespace dynosize {

namespace {

struct Interp {
  double value = 0.0;
  bool outside = false;
};

// Linear interpolation of y(x) on increasing x; outside the range the end value is held and
// `outside` is set (no silent extrapolation).
Interp Lerp(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  if (x.size() == 1) return {y[0], xq != x[0]};
  if (xq <= x.front()) return {y.front(), xq < x.front()};
  if (xq >= x.back()) return {y.back(), xq > x.back()};
  const auto it = std::upper_bound(x.begin(), x.end(), xq);
  const std::size_t i = static_cast<std::size_t>(it - x.begin());
  const double t = (xq - x[i - 1]) / (x[i] - x[i - 1]);
  return {y[i - 1] + t * (y[i] - y[i - 1]), false};
}

// The catalog reader enforces these rules for entries from files; a PropEntry built in code
// is checked here so that interpolation never reads outside an array.
void CheckTable(const std::string& id, const std::string& what, const std::vector<double>& x,
                const std::vector<double>& ct, const std::vector<double>& cp) {
  if (x.empty() || x.size() != ct.size() || x.size() != cp.size()) {
    throw UsageError("propeller '" + id + "': " + what +
                     " needs non-empty axis, ct and cp arrays of equal length");
  }
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (!(x[i] > x[i - 1])) {
      throw UsageError("propeller '" + id + "': " + what + " axis must be strictly increasing");
    }
  }
}

// The UsageError of an argument that breaks its rule: "<who>: <name> = <value> must be <rule>".
[[noreturn]] void ThrowBadArgument(const std::string& who, const char* name, double value, const char* rule) {
  throw UsageError(who + ": " + name + " = " + SignificantText(value, 4) + " must be " + rule);
}

}  // namespace

PropModel::PropModel(const PropEntry& entry) : entry_(entry) {
  if (!entry_.static_table.rpm.empty()) {
    CheckTable(entry_.id, "static_table", entry_.static_table.rpm, entry_.static_table.ct,
               entry_.static_table.cp);
  }
  for (std::size_t k = 0; k < entry_.j_tables.size(); ++k) {
    const PropSweep& s = entry_.j_tables[k];
    CheckTable(entry_.id, "j_tables[" + std::to_string(k) + "]", s.j, s.ct, s.cp);
    if (k > 0 && !(s.rpm > entry_.j_tables[k - 1].rpm)) {
      throw UsageError("propeller '" + entry_.id + "': j_tables must be sorted by increasing rpm");
    }
  }
  if (!entry_.static_table.rpm.empty() || !entry_.j_tables.empty()) {
    kind_ = PropDataKind::kTables;
  } else if (entry_.ct_static && entry_.cp_static) {
    kind_ = PropDataKind::kCoefficients;
  } else if (entry_.power_law) {
    kind_ = PropDataKind::kPowerLaw;
  } else {
    throw UsageError("propeller '" + entry_.id + "' has no performance data (tables, "
                     "ct_static/cp_static or power laws)");
  }
  const PropStaticTable& st = entry_.static_table;
  for (const PropSweep& s : entry_.j_tables) {
    PropSweep a = s;
    if (!st.rpm.empty() && !a.j.empty() && a.j.front() > 0.0) {
      // Join the sweep to the static table at this sweep's rpm (J = 0).
      a.j.insert(a.j.begin(), 0.0);
      a.ct.insert(a.ct.begin(), Lerp(st.rpm, st.ct, s.rpm).value);
      a.cp.insert(a.cp.begin(), Lerp(st.rpm, st.cp, s.rpm).value);
    }
    sweeps_.push_back(std::move(a));
  }
  if (!(entry_.diameter_m > 0)) {
    throw UsageError("propeller '" + entry_.id + "': diameter_m must be > 0");
  }
  range_ = ValidRange(entry_);
  ct_max_ = MaxThrustCoefficient();
}

double PropModel::MaxThrustCoefficient() const {
  double ct = -std::numeric_limits<double>::infinity();
  switch (kind_) {
    case PropDataKind::kTables:
      for (double c : entry_.static_table.ct) ct = std::max(ct, c);
      for (const PropSweep& s : sweeps_) {
        for (double c : s.ct) ct = std::max(ct, c);
      }
      break;
    case PropDataKind::kCoefficients:
      ct = *entry_.ct_static;
      break;
    case PropDataKind::kPowerLaw:
      // Inside the range CT is a power of the speed (Evaluate: a*(rpm/1000)^b/(rho_law*n^2*D^4),
      // independent of rho): its largest is at an end; outside it the ends' are held (below, the
      // Reynolds correction only lowers them).
      for (double rpm : {range_.rpm_lo, range_.rpm_hi}) {
        if (rpm > 0) ct = std::max(ct, Evaluate(RpmToRadPerSec(rpm), entry_.power_law->rho_kg_m3).ct);
      }
      break;
  }
  return ct;
}

void PropModel::TableCoefficients(double rpm, double j, PropEvaluation* ev) const {
  const PropStaticTable& st = entry_.static_table;
  if (!st.rpm.empty() && (j == 0.0 || entry_.j_tables.empty())) {
    const Interp ct = Lerp(st.rpm, st.ct, rpm), cp = Lerp(st.rpm, st.cp, rpm);
    ev->ct = ct.value;
    ev->cp = cp.value;
    ev->data_rpm_lo = st.rpm.front();
    ev->data_rpm_hi = st.rpm.back();
    ev->rpm_outside_data = ct.outside;
    ev->no_forward_flight_data = j > 0.0;
    return;
  }
  // Forward flight (or static without a static table): interpolate each sweep at J, then
  // between the two sweeps that bracket rpm.
  const auto& sweeps = sweeps_;
  ev->from_sweeps = true;
  ev->data_rpm_lo = sweeps.front().rpm;
  ev->data_rpm_hi = sweeps.back().rpm;
  auto sweep_at = [&](const PropSweep& s, double* ct, double* cp) {
    const Interp a = Lerp(s.j, s.ct, j), b = Lerp(s.j, s.cp, j);
    *ct = a.value;
    *cp = b.value;
    return a.outside;
  };
  std::size_t hi = 0;
  while (hi < sweeps.size() && sweeps[hi].rpm < rpm) ++hi;
  double ct = 0, cp = 0;
  bool j_out = false;
  if (hi == 0 || hi == sweeps.size()) {
    const PropSweep& s = sweeps[hi == 0 ? 0 : sweeps.size() - 1];
    j_out = sweep_at(s, &ct, &cp);
    ev->rpm_outside_data = rpm < sweeps.front().rpm || rpm > sweeps.back().rpm;
  } else {
    const PropSweep& a = sweeps[hi - 1];
    const PropSweep& b = sweeps[hi];
    double cta, cpa, ctb, cpb;
    const bool oa = sweep_at(a, &cta, &cpa);
    const bool ob = sweep_at(b, &ctb, &cpb);
    const double t = (rpm - a.rpm) / (b.rpm - a.rpm);
    ct = cta + t * (ctb - cta);
    cp = cpa + t * (cpb - cpa);
    j_out = oa || ob;
  }
  ev->j_outside_data = j_out;
  ev->ct = ct;
  ev->cp = cp;
}

std::string PropEvaluation::Message() const {
  if (at_rest_in_flow) return "shaft at rest in a flow: windmilling is not modelled";
  std::vector<std::string> parts;
  if (rpm_outside_data) {
    if (data != PropDataKind::kTables) {
      auto whole = [](double x) { return std::to_string(std::lround(x)); };
      parts.push_back("rpm " + whole(rpm) + " outside the valid range " + whole(data_rpm_lo) + "-" +
                      whole(data_rpm_hi) + " of the propeller's data; " +
                      (reynolds_ratio < 1.0 ? "edge coefficients corrected" : "edge coefficients held"));
    } else {
      parts.push_back("rpm " + SignificantText(rpm, 4) +
                      (from_sweeps ? " outside the forward-flight sweeps " : " outside the static data ") +
                      SignificantText(data_rpm_lo, 4) + "-" + SignificantText(data_rpm_hi, 4));
    }
    if (reynolds_ratio < 1.0) {
      parts.push_back(
          "at " + SignificantText(reynolds_ratio, 4) +
          "x its lowest speed: CT and CP corrected for the lower Reynolds number (catalog/prop_reynolds.h)");
    }
  }
  if (no_forward_flight_data) {
    const char* what = data == PropDataKind::kTables         ? "static data: static coefficients used"
                       : data == PropDataKind::kCoefficients ? "static coefficients: static values used"
                                                             : "static power laws: static values used";
    parts.push_back("J = " + SignificantText(j, 4) + " but only " + what);
  }
  if (j_outside_data)
    parts.push_back("J = " + SignificantText(j, 4) + " outside the measured advance ratios; edge coefficients held");
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

PropEvaluation PropModel::Evaluate(double omega_rad_s, double rho_kg_m3,
                                   double airspeed_m_s) const {
  if (!std::isfinite(omega_rad_s) || omega_rad_s < 0) {
    ThrowBadArgument("propeller '" + entry_.id + "'", "omega_rad_s", omega_rad_s, "a finite number >= 0");
  }
  if (!std::isfinite(rho_kg_m3) || !(rho_kg_m3 > 0)) {
    ThrowBadArgument("propeller '" + entry_.id + "'", "rho_kg_m3", rho_kg_m3, "a finite number > 0");
  }
  if (!std::isfinite(airspeed_m_s) || airspeed_m_s < 0) {
    ThrowBadArgument("propeller '" + entry_.id + "'", "airspeed_m_s", airspeed_m_s, "a finite number >= 0");
  }
  PropEvaluation ev;
  ev.omega_rad_s = omega_rad_s;
  ev.rpm = RadPerSecToRpm(omega_rad_s);
  ev.rho_kg_m3 = rho_kg_m3;
  ev.airspeed_m_s = airspeed_m_s;
  ev.data = kind_;
  const double d = entry_.diameter_m;
  const double d4 = d * d * d * d, d5 = d4 * d;
  const double n = omega_rad_s / (2.0 * kPi);  // rev/s
  if (n == 0.0) {
    ev.at_rest_in_flow = airspeed_m_s > 0;
    return ev;
  }
  ev.j = airspeed_m_s / (n * d);
  switch (kind_) {
    case PropDataKind::kTables:
      TableCoefficients(ev.rpm, ev.j, &ev);
      CorrectBelowData(ev.data_rpm_lo, &ev);  // the lowest rpm of the table read
      break;
    case PropDataKind::kCoefficients:
      ev.ct = *entry_.ct_static;
      ev.cp = *entry_.cp_static;
      ev.no_forward_flight_data = ev.j > 0;
      if (!range_.rpm_assumed) {  // a stated range: say when the speed leaves it
        ev.data_rpm_lo = range_.rpm_lo;
        ev.data_rpm_hi = range_.rpm_hi;
        ev.rpm_outside_data = ev.rpm < range_.rpm_lo || ev.rpm > range_.rpm_hi;
      }
      CorrectBelowData(range_.rpm_lo, &ev);  // the assumed band's low edge too
      break;
    case PropDataKind::kPowerLaw: {
      // DriveCalc: T [N] = a*(rpm/1000)^b, P [W] = c*(rpm/1000)^d at law rho, linear in rho;
      // expressed as CT, CP through the UIUC definitions. Outside the valid range
      // (catalog/prop_credibility.h) the coefficients are held at the edge, not extrapolated:
      // the laws' figure of merit drifts with rpm and beats momentum theory far from the data.
      const PropPowerLaw& law = *entry_.power_law;
      const double rpm_eval = std::clamp(ev.rpm, range_.rpm_lo, range_.rpm_hi);
      const double n_eval = rpm_eval / 60.0;
      const double k = rpm_eval / 1000.0;
      const double t = law.thrust_law_n * std::pow(k, law.thrust_law_exp) * rho_kg_m3 / law.rho_kg_m3;
      const double p = law.power_law_w * std::pow(k, law.power_law_exp) * rho_kg_m3 / law.rho_kg_m3;
      ev.ct = t / (rho_kg_m3 * n_eval * n_eval * d4);
      ev.cp = p / (rho_kg_m3 * n_eval * n_eval * n_eval * d5);
      ev.data_rpm_lo = range_.rpm_lo;
      ev.data_rpm_hi = range_.rpm_hi;
      ev.rpm_outside_data = rpm_eval != ev.rpm;
      ev.no_forward_flight_data = ev.j > 0;
      CorrectBelowData(range_.rpm_lo, &ev);
      break;
    }
  }
  // UIUC definitions: T = CT*rho*n^2*D^4, P = CP*rho*n^3*D^5, Q = P/omega.
  ev.thrust_n = ev.ct * rho_kg_m3 * n * n * d4;
  ev.power_w = ev.cp * rho_kg_m3 * n * n * n * d5;
  ev.torque_nm = ev.power_w / omega_rad_s;
  return ev;
}

void PropModel::CorrectBelowData(double rpm_lo, PropEvaluation* ev) const {
  const ReynoldsFactors f = ReynoldsCorrection(DefaultReynoldsLaw(), ev->rpm, rpm_lo);
  ev->reynolds_ratio = f.ratio;
  ev->ct *= f.ct;
  ev->cp *= f.cp;
}

bool PropModel::StaticSpeedForThrust(double thrust_n, double rho_kg_m3, double* omega_rad_s) const {
  if (!(thrust_n > 0) || !(rho_kg_m3 > 0)) return false;
  const double d = entry_.diameter_m;
  const double d4 = d * d * d * d;
  double rpm = 0.0;
  if (kind_ == PropDataKind::kCoefficients) {
    const double ct = *entry_.ct_static;
    if (!(ct > 0)) return false;
    rpm = 60.0 * std::sqrt(thrust_n / (ct * rho_kg_m3 * d4));  // T = CT*rho*n^2*D^4
    if (rpm < range_.rpm_lo) {
      // Below the range CT falls as (rpm/rpm_lo)^a (CorrectBelowData): T = T_lo*(rpm/rpm_lo)^(2 + a).
      const double n_lo = range_.rpm_lo / 60.0;
      const double t_lo = ct * rho_kg_m3 * n_lo * n_lo * d4;
      rpm = range_.rpm_lo * std::pow(thrust_n / t_lo, 1.0 / (2.0 + DefaultReynoldsLaw().ct_exp()));
    }
  } else if (kind_ == PropDataKind::kPowerLaw) {
    const PropPowerLaw& law = *entry_.power_law;
    if (!(law.thrust_law_n > 0) || !(law.thrust_law_exp > 0)) return false;
    // The law's thrust at rpm r (Evaluate's expression, inside the range).
    auto thrust_at = [&](double r) {
      return law.thrust_law_n * std::pow(r / 1000.0, law.thrust_law_exp) * rho_kg_m3 / law.rho_kg_m3;
    };
    const double t_lo = thrust_at(range_.rpm_lo), t_hi = thrust_at(range_.rpm_hi);
    if (thrust_n <= t_lo) {
      // CT at rpm_lo times the Reynolds correction (rpm/rpm_lo)^a: T ~ n^(2 + a).
      rpm = range_.rpm_lo * std::pow(thrust_n / t_lo, 1.0 / (2.0 + DefaultReynoldsLaw().ct_exp()));
    } else if (thrust_n >= t_hi) {
      rpm = range_.rpm_hi * std::sqrt(thrust_n / t_hi);  // CT held at rpm_hi
    } else {
      rpm = 1000.0 * std::pow(thrust_n * law.rho_kg_m3 / (law.thrust_law_n * rho_kg_m3), 1.0 / law.thrust_law_exp);
    }
  } else {
    return false;
  }
  if (!std::isfinite(rpm) || !(rpm > 0)) return false;
  *omega_rad_s = RpmToRadPerSec(rpm);
  return true;
}

PropEvaluation PropModel::EvaluateAtAdvanceRatio(double omega_rad_s, double rho_kg_m3,
                                                 double j) const {
  if (!std::isfinite(j) || j < 0) {
    ThrowBadArgument("propeller '" + entry_.id + "'", "advance ratio J", j, "a finite number >= 0");
  }
  // J = V/(n*D) with n = omega/(2*pi) rev/s.
  const double v = j * (omega_rad_s / (2.0 * kPi)) * entry_.diameter_m;
  return Evaluate(omega_rad_s, rho_kg_m3, std::isfinite(v) ? v : 0.0);
}

LocalTorqueFit PropModel::FitTorqueLaw(double omega0_rad_s, double rho_kg_m3, double airspeed_m_s,
                                       double rel_step) const {
  if (!std::isfinite(omega0_rad_s) || !(omega0_rad_s > 0)) {
    ThrowBadArgument("FitTorqueLaw", "omega0_rad_s", omega0_rad_s, "> 0");
  }
  if (!(rel_step > 0 && rel_step <= 0.5)) {
    ThrowBadArgument("FitTorqueLaw", "rel_step", rel_step, "in (0, 0.5]");
  }
  const double w[3] = {omega0_rad_s * (1 - rel_step), omega0_rad_s, omega0_rad_s * (1 + rel_step)};
  double q[3];
  LocalTorqueFit fit;
  fit.omega0_rad_s = omega0_rad_s;
  fit.rel_step = rel_step;
  for (int i = 0; i < 3; ++i) {
    const PropEvaluation ev = Evaluate(w[i], rho_kg_m3, airspeed_m_s);
    q[i] = ev.torque_nm;
    if (!ev.InData()) {
      fit.in_data = false;
      if (fit.message.empty()) fit.message = ev.Message();
    }
  }
  // Newton divided differences of the three points, expanded to a + b*w + c*w^2.
  const double f01 = (q[1] - q[0]) / (w[1] - w[0]);
  const double f12 = (q[2] - q[1]) / (w[2] - w[1]);
  const double c = (f12 - f01) / (w[2] - w[0]);
  const double b = f01 - c * (w[0] + w[1]);
  const double a = q[0] - b * w[0] - c * w[0] * w[0];
  fit.law.a_nm = a;
  fit.law.b_nm_s_per_rad = b;
  fit.law.c_nm_s2_per_rad2 = c;
  return fit;
}

}  // namespace dynosize
