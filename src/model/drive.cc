#include "model/drive.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

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
  // Eigen array expressions: each line is one SIMD pass with no branches. The selects of the
  // scalar path become min/max, which is exact for non-negative load laws (a, b, c >= 0):
  //  - TR_eff = min(TR, tr_sat) + sat_slope*max(TR - tr_sat, 0)                  (section 7)
  //  - a stalled drive has omega = max(root, 0) = 0, and then I = U/R >= 0 follows from (48)
  //    with omega = 0, so the same current formula serves both cases;
  //  - when running, Q = a + b*w + c*w^2 >= 0, so Q = max(KT*(I - Io), 0) in both cases.
  using Arr = Eigen::ArrayXd;
  using In = Eigen::Map<const Arr>;
  using Out = Eigen::Map<Arr>;
  out->Resize(n);
  const Eigen::Index m = static_cast<Eigen::Index>(n);
  const In vdc(vdc_v, m), tr(throttle, m), a(a_nm, m);
  const double kt = motor_.kt_nm_per_a, ke = motor_.ke_v_s_per_rad, io = motor_.io_a;
  const double inv_r = 1.0 / r_total_ohm_;
  Out tre(out->throttle_effective.data(), m), w(out->omega_rad_s.data(), m),
      cur(out->irms_a.data(), m), q(out->torque_nm.data(), m), vll(out->vll_rms_v.data(), m),
      pac(out->pac_w.data(), m), idc(out->idc_a.data(), m), pdc(out->pdc_w.data(), m),
      pesc(out->pesc_w.data(), m), pm(out->pmech_w.data(), m), em(out->eta_motor.data(), m),
      ee(out->eta_esc.data(), m), es(out->eta_system.data(), m);
  tre = tr.min(esc_.tr_sat) + esc_.sat_slope * (tr - esc_.tr_sat).max(0.0);
  vll = volt_factor_ * vdc * tre;  // U of (48), kept in vll until (47) below
  // c*w^2 + B*w + C = 0 with B = b + KT*KE/R, C = a + KT*Io - KT*U/R (as AtLoad); pac and
  // idc serve as scratch for B and C.
  pac.setConstant(kt * ke * inv_r);
  if (b_nm_s_per_rad) pac += In(b_nm_s_per_rad, m);
  idc = a + kt * io - kt * inv_r * vll;
  if (c_nm_s2_per_rad2) {
    const In c(c_nm_s2_per_rad2, m);
    // |disc| < 0 only when C > 0, where the motor stalls whatever the root (see AtLoad).
    w = (-2.0 * idc / (pac + (pac.square() - 4.0 * c * idc).abs().sqrt())).max(0.0);
  } else {
    w = (-idc / pac).max(0.0);
  }
  cur = (vll - ke * w) * inv_r;                            // (48)
  q = (kt * (cur - io)).max(0.0);                          // (42)
  vll = vll - esc_.resc_ohm * cur;                         // (47)
  pac = power_factor_ * vll * cur;                         // (41), (51)
  idc = (esc_.c1 * tre + esc_.c0) * cur;                   // (57)
  pdc = vdc * idc;                                         // (59)
  pesc = pdc - pac;                                        // (52)
  pm = q * w;                                              // (50)
  // Efficiencies: 0 where the numerator or denominator is not positive, as Ratio() does.
  em = (pac > 0.0 && pm > 0.0).select(pm / pac.max(1e-300), 0.0);
  ee = (pdc > 0.0 && pac > 0.0).select(pac / pdc.max(1e-300), 0.0);
  es = (pdc > 0.0 && pm > 0.0).select(pm / pdc.max(1e-300), 0.0);
}

}  // namespace dynosize
