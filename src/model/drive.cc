#include "model/drive.h"

#include <algorithm>
#include <cmath>

#include "common/units.h"

namespace dynosize {

namespace {

// Positive root of c*w^2 + B*w + C = 0 written as w = -2C / (B + sqrt(B^2 - 4cC)): no
// cancellation for B > 0, C < 0, and it reduces to -C/B when c = 0. Returns -1 when there is no
// non-negative root (the load exceeds the stall torque, or a non-physical c < 0 law has no
// crossing).
inline double PositiveRoot(double c, double b_total, double c_total) {
  const double disc = b_total * b_total - 4.0 * c * c_total;
  const double q = b_total + std::sqrt(std::max(disc, 0.0));
  const bool ok = disc >= 0.0 && q > 0.0 && c_total <= 0.0;
  return ok ? -2.0 * c_total / q : -1.0;
}

inline double Ratio(double num, double den) { return (den > 0.0 && num > 0.0) ? num / den : 0.0; }

}  // namespace

std::vector<std::string> LimitNames(std::uint32_t limits) {
  static const char* const kNames[] = {"throttle_above_one", "throttle_below_zero",
                                       "motor_current",      "esc_current",
                                       "motor_power",        "esc_voltage",
                                       "stalled",            "overrunning"};
  std::vector<std::string> names;
  for (std::uint32_t bit = 0; bit < sizeof(kNames) / sizeof(kNames[0]); ++bit) {
    if (limits & (1u << bit)) names.emplace_back(kNames[bit]);
  }
  return names;
}

void OperatingPointBatch::Resize(std::size_t n) {
  for (auto* v : {&omega_rad_s, &torque_nm, &irms_a, &vll_rms_v, &pac_w, &idc_a, &pdc_w, &pesc_w,
                  &pmech_w, &eta_motor, &eta_esc, &eta_system, &throttle_effective}) {
    v->resize(n);
  }
}

Drive::Drive(const MotorParams& motor, const EscParams& esc)
    : motor_(motor),
      esc_(esc),
      r_total_ohm_(motor.rm_ohm + esc.resc_ohm),
      volt_factor_(motor.type == MotorType::kBldc ? kVllRmsPerVdc : 1.0),
      power_factor_(motor.type == MotorType::kBldc ? kPacPerVllIrms : 1.0) {}

double Drive::EffectiveThrottle(double throttle) const {
  return throttle <= esc_.tr_sat ? throttle
                                  : esc_.tr_sat + esc_.sat_slope * (throttle - esc_.tr_sat);
}

double Drive::ThrottleFromEffective(double throttle_effective) const {
  return throttle_effective <= esc_.tr_sat
             ? throttle_effective
             : esc_.tr_sat + (throttle_effective - esc_.tr_sat) / esc_.sat_slope;
}

OperatingPoint Drive::Complete(double vdc_v, double throttle, double omega_rad_s,
                               double current_a, std::uint32_t limits) const {
  OperatingPoint p;
  p.vdc_v = vdc_v;
  p.throttle = throttle;
  p.throttle_effective = EffectiveThrottle(throttle);
  p.saturated = throttle > esc_.tr_sat;
  p.omega_rad_s = omega_rad_s;
  p.rpm = RadPerSecToRpm(omega_rad_s);
  p.irms_a = current_a;
  p.torque_nm = motor_.kt_nm_per_a * (current_a - motor_.io_a);                 // (42)
  if (limits & kLimitStalled) p.torque_nm = std::max(p.torque_nm, 0.0);
  p.vll_rms_v = volt_factor_ * vdc_v * p.throttle_effective - esc_.resc_ohm * current_a;  // (47)
  p.pac_w = power_factor_ * p.vll_rms_v * current_a;                            // (41), (51)
  p.idc_a = (esc_.c1 * p.throttle_effective + esc_.c0) * current_a;             // (57)
  p.pdc_w = vdc_v * p.idc_a;                                                    // (59)
  p.pesc_w = p.pdc_w - p.pac_w;                                                 // (52)
  p.pmech_w = p.torque_nm * omega_rad_s;                                        // (50)
  p.eta_motor = Ratio(p.pmech_w, p.pac_w);
  p.eta_esc = Ratio(p.pac_w, p.pdc_w);                                          // (53)
  p.eta_system = Ratio(p.pmech_w, p.pdc_w);                                     // (13)

  if (throttle > 1.0) limits |= kLimitThrottleAboveOne;
  if (throttle < 0.0) limits |= kLimitThrottleBelowZero;
  const double i_max = std::max(std::fabs(p.idc_a), std::fabs(p.irms_a));
  if (i_max > motor_.max_current_a) limits |= kLimitMotorCurrent;
  if (i_max > esc_.max_current_a) limits |= kLimitEscCurrent;
  if (p.pac_w > motor_.max_power_w) limits |= kLimitMotorPower;
  if (vdc_v > esc_.vdc_max_v) limits |= kLimitEscVoltage;
  p.limits = limits;
  return p;
}

OperatingPoint Drive::AtLoad(double vdc_v, double throttle, const TorqueLaw& load) const {
  const double kt = motor_.kt_nm_per_a;
  const double u = volt_factor_ * vdc_v * EffectiveThrottle(throttle);  // (48) left side
  // Substituting I = (U - KE*w)/R (48) into KT*(I - Io) = a + b*w + c*w^2 gives
  // c*w^2 + (b + KT*KE/R)*w + (a + KT*Io - KT*U/R) = 0.
  const double b_total = load.b_nm_s_per_rad + kt * motor_.ke_v_s_per_rad / r_total_ohm_;
  const double c_total = load.a_nm + kt * motor_.io_a - kt * u / r_total_ohm_;
  const double omega = PositiveRoot(load.c_nm_s2_per_rad2, b_total, c_total);
  if (omega < 0.0) {
    // The load at standstill exceeds what the motor can deliver: it stalls.
    return Complete(vdc_v, throttle, 0.0, std::max(u / r_total_ohm_, 0.0), kLimitStalled);
  }
  const double current = (u - motor_.ke_v_s_per_rad * omega) / r_total_ohm_;
  return Complete(vdc_v, throttle, omega, current, kLimitNone);
}

OperatingPoint Drive::AtTorque(double vdc_v, double throttle, double torque_nm) const {
  return AtLoad(vdc_v, throttle, TorqueLaw{torque_nm, 0.0, 0.0});
}

OperatingPoint Drive::AtSpeed(double vdc_v, double throttle, double omega_rad_s) const {
  const double u = volt_factor_ * vdc_v * EffectiveThrottle(throttle);
  const double current = (u - motor_.ke_v_s_per_rad * omega_rad_s) / r_total_ohm_;  // (48)
  const std::uint32_t limits = current < motor_.io_a ? kLimitOverrunning : kLimitNone;
  return Complete(vdc_v, throttle, omega_rad_s, current, limits);
}

OperatingPoint Drive::Inverse(double vdc_v, double torque_nm, double omega_rad_s) const {
  const double current = torque_nm / motor_.kt_nm_per_a + motor_.io_a;                 // (42)
  const double u = r_total_ohm_ * current + motor_.ke_v_s_per_rad * omega_rad_s;       // (48)
  const double throttle = ThrottleFromEffective(u / (volt_factor_ * vdc_v));
  return Complete(vdc_v, throttle, omega_rad_s, current, kLimitNone);
}

double Drive::NoLoadSpeed(double vdc_v, double throttle) const {
  const double u = volt_factor_ * vdc_v * EffectiveThrottle(throttle);
  return (u - motor_.io_a * r_total_ohm_) / motor_.ke_v_s_per_rad;
}

double Drive::StallTorque(double vdc_v, double throttle) const {
  const double u = volt_factor_ * vdc_v * EffectiveThrottle(throttle);
  return motor_.kt_nm_per_a * (u / r_total_ohm_ - motor_.io_a);
}

double Drive::MaxPowerSpeed(double vdc_v, double throttle) const {
  return 0.5 * NoLoadSpeed(vdc_v, throttle);  // (12)
}

double Drive::MaxEfficiencySpeed(double vdc_v, double throttle) const {
  const double u = volt_factor_ * vdc_v * EffectiveThrottle(throttle);
  return (u - std::sqrt(motor_.io_a * r_total_ohm_ * u)) / motor_.ke_v_s_per_rad;  // (14)
}

double Drive::EscTimingFigure(double throttle) const {
  return (esc_.c1 - kIdealIdcPerIrmsPerThrottle) * EffectiveThrottle(throttle) + esc_.c0;  // (62)
}

void Drive::AtLoadBatch(std::size_t n, const double* vdc_v, const double* throttle,
                        const double* a_nm, const double* b_nm_s_per_rad,
                        const double* c_nm_s2_per_rad2, OperatingPointBatch* out) const {
  out->Resize(n);
  // Hoisted constants; the loop body mirrors AtLoad + Complete without the limit checks and
  // with selects instead of branches.
  const double kt = motor_.kt_nm_per_a, ke = motor_.ke_v_s_per_rad, io = motor_.io_a;
  const double r = r_total_ohm_, resc = esc_.resc_ohm, c1 = esc_.c1, c0 = esc_.c0;
  const double tr_sat = esc_.tr_sat, slope = esc_.sat_slope;
  const double kv = volt_factor_, kp = power_factor_, kt_ke_over_r = kt * ke / r;
  double* __restrict w_out = out->omega_rad_s.data();
  double* __restrict q_out = out->torque_nm.data();
  double* __restrict i_out = out->irms_a.data();
  double* __restrict v_out = out->vll_rms_v.data();
  double* __restrict pac_out = out->pac_w.data();
  double* __restrict idc_out = out->idc_a.data();
  double* __restrict pdc_out = out->pdc_w.data();
  double* __restrict pesc_out = out->pesc_w.data();
  double* __restrict pm_out = out->pmech_w.data();
  double* __restrict em_out = out->eta_motor.data();
  double* __restrict ee_out = out->eta_esc.data();
  double* __restrict es_out = out->eta_system.data();
  double* __restrict tre_out = out->throttle_effective.data();
  for (std::size_t i = 0; i < n; ++i) {
    const double tr = throttle[i];
    const double tre = tr <= tr_sat ? tr : tr_sat + slope * (tr - tr_sat);
    const double u = kv * vdc_v[i] * tre;
    const double b = b_nm_s_per_rad ? b_nm_s_per_rad[i] : 0.0;
    const double c = c_nm_s2_per_rad2 ? c_nm_s2_per_rad2[i] : 0.0;
    const double b_total = b + kt_ke_over_r;
    const double c_total = a_nm[i] + kt * io - kt * u / r;
    const double disc = std::max(b_total * b_total - 4.0 * c * c_total, 0.0);
    const double w_root = -2.0 * c_total / (b_total + std::sqrt(disc));
    const bool stalled = !(w_root >= 0.0);
    const double w = stalled ? 0.0 : w_root;
    const double cur = stalled ? std::max(u / r, 0.0) : (u - ke * w) / r;
    const double q_raw = kt * (cur - io);
    const double q = stalled ? std::max(q_raw, 0.0) : q_raw;
    const double vll = u - resc * cur;
    const double pac = kp * vll * cur;
    const double idc = (c1 * tre + c0) * cur;
    const double pdc = vdc_v[i] * idc;
    const double pm = q * w;
    tre_out[i] = tre;
    w_out[i] = w;
    q_out[i] = q;
    i_out[i] = cur;
    v_out[i] = vll;
    pac_out[i] = pac;
    idc_out[i] = idc;
    pdc_out[i] = pdc;
    pesc_out[i] = pdc - pac;
    pm_out[i] = pm;
    em_out[i] = (pac > 0.0 && pm > 0.0) ? pm / pac : 0.0;
    ee_out[i] = (pdc > 0.0 && pac > 0.0) ? pac / pdc : 0.0;
    es_out[i] = (pdc > 0.0 && pm > 0.0) ? pm / pdc : 0.0;
  }
}

}  // namespace dynosize
