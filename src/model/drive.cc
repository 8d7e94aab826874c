#include "model/drive.h"
#include "model/physics.h"
#include "model/circuit.h"

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

// The powers and efficiencies of a point whose currents, voltages and torque are set:
// PDC (59), PESC (52), Pmech (50) and the efficiencies (53), (13).
inline void FillPowers(double vdc_v, double omega_rad_s, OperatingPoint* p) {
  p->pdc_w = vdc_v * p->idc_a;
  p->pesc_w = p->pdc_w - p->pac_w;
  p->pmech_w = p->torque_nm * omega_rad_s;
  p->eta_motor = Ratio(p->pmech_w, p->pac_w);
  p->eta_esc = Ratio(p->pac_w, p->pdc_w);
  p->eta_system = Ratio(p->pmech_w, p->pdc_w);
}

}  // namespace

Drive::Drive(const MotorParams& motor, const EscParams& esc)
    : motor_(motor),
      esc_(esc),
      r_total_ohm_(motor.rm_ohm + esc.resc_ohm),
      volt_factor_(motor.type == MotorType::kBldc ? kVllRmsPerVdc : 1.0),
      power_factor_(motor.type == MotorType::kBldc ? kPacPerVllIrms : 1.0),
      nonlinear_(motor.rth_k_per_w != 0.0 || motor.kt_droop_per_a != 0.0),
      extended_(nonlinear_ || motor.io1_a_s_per_rad != 0.0 || esc.deadband != 0.0 ||
                esc.rsupply_ohm != 0.0),
      thermal_k_per_a2_(kAlphaCopperPerK * motor.rth_k_per_w * power_factor_ * motor.rm_ohm) {}

namespace {

// Root of a function that changes sign on [lo, hi] (f(lo) <= 0 <= f(hi)) by the Illinois
// variant of regula falsi (superlinear, never leaves the bracket); no allocation.
template <typename F>
double RootInBracket(const F& f, double lo, double hi, double f_lo, double f_hi) {
  if (f_lo == 0.0) return lo;
  if (f_hi == 0.0) return hi;
  int side = 0;
  double x = lo;
  for (int it = 0; it < 200; ++it) {
    x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);  // degenerate secant: bisect
    const double fx = f(x);
    if (fx == 0.0 || std::fabs(hi - lo) <= 1e-14 * std::max(std::fabs(x), 1e-12)) return x;
    if (fx < 0.0) {
      lo = x;
      f_lo = fx;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = x;
      f_hi = fx;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return x;
}

}  // namespace

double Drive::WindingResistance(double current_a) const {
  if (thermal_k_per_a2_ == 0.0) return motor_.rm_ohm;
  const double s = 1.0 - thermal_k_per_a2_ * current_a * current_a;
  return s > 0.0 ? motor_.rm_ohm / s : std::numeric_limits<double>::infinity();
}

double Drive::TorqueConstant(double current_a) const {
  if (motor_.kt_droop_per_a == 0.0) return motor_.kt_nm_per_a;
  return motor_.kt_nm_per_a / (1.0 + motor_.kt_droop_per_a * std::fabs(current_a));
}

double Drive::SeriesResistance(double throttle_effective) const {
  if (esc_.rsupply_ohm == 0.0) return r_total_ohm_;
  return r_total_ohm_ + volt_factor_ * esc_.rsupply_ohm * (esc_.c1 * throttle_effective + esc_.c0) *
                            throttle_effective;
}

double Drive::CircuitCurrent(double x_v, double r_series_ohm) const {
  if (thermal_k_per_a2_ == 0.0) return x_v / r_series_ohm;
  if (x_v < 0.0) return -CircuitCurrent(-x_v, r_series_ohm);
  // h(I) = (r_series + Rm(I) - Rm0)*I - x is increasing in I on [0, 1/sqrt(k)).
  const double i_runaway = 1.0 / std::sqrt(thermal_k_per_a2_);
  const double hi = std::min(x_v / r_series_ohm, i_runaway * (1.0 - 1e-12));
  const auto h = [&](double i) {
    return (r_series_ohm + WindingResistance(i) - motor_.rm_ohm) * i - x_v;
  };
  return RootInBracket(h, 0.0, hi, -x_v, h(hi));
}

double Drive::EffectiveThrottle(double throttle) const {
  return circuit::EffectiveThrottle(throttle, esc_.tr_sat, esc_.sat_slope, esc_.deadband);
}

double Drive::ThrottleFromEffective(double throttle_effective) const {
  return circuit::ThrottleFromEffective(throttle_effective, esc_.tr_sat, esc_.sat_slope, esc_.deadband);
}

OperatingPoint Drive::Complete(double vdc_v, double throttle, double omega_rad_s,
                               double current_a, std::uint32_t limits) const {
  // One object and one return (copy elision); the extensions fill it in CompleteExtended so
  // that the first-order path stays as short as before.
  OperatingPoint p;
  if (extended_) {
    CompleteExtended(vdc_v, throttle, omega_rad_s, current_a, &p, &limits);
  } else {
    p.vdc_v = vdc_v;
    p.throttle = throttle;
    p.throttle_effective = EffectiveThrottle(throttle);
    p.saturated = throttle > esc_.tr_sat;
    p.omega_rad_s = omega_rad_s;
    p.rpm = RadPerSecToRpm(omega_rad_s);
    p.irms_a = current_a;
    p.torque_nm = circuit::ShaftTorque(motor_.kt_nm_per_a, current_a, motor_.io_a);
    if (limits & kLimitStalled) p.torque_nm = std::max(p.torque_nm, 0.0);
    p.vll_rms_v = circuit::LineVoltage(circuit::AppliedVoltage(volt_factor_, vdc_v, p.throttle_effective),
                                       esc_.resc_ohm, current_a);
    p.pac_w = circuit::AcPower(power_factor_, p.vll_rms_v, current_a);
    p.idc_a = circuit::DcCurrent(esc_.c1, p.throttle_effective, esc_.c0, current_a);
    FillPowers(vdc_v, omega_rad_s, &p);
  }
  Flag(&p, limits);
  return p;
}

void Drive::Flag(OperatingPoint* p, std::uint32_t limits) const {
  // docs/model.md section 10 and the ratings (model/physics.h).
  p->limits = limits | RatingLimits(motor_, esc_, p->vdc_v, p->throttle, p->irms_a, p->idc_a, p->pac_w,
                                    p->pdc_w, p->pesc_w, p->pmech_w);
}

[[gnu::noinline]] void Drive::CompleteExtended(double vdc_v, double throttle, double omega_rad_s,
                                               double current_a, OperatingPoint* out,
                                               std::uint32_t* limits) const {
  OperatingPoint& p = *out;
  p.vdc_v = vdc_v;
  p.throttle = throttle;
  p.throttle_effective = EffectiveThrottle(throttle);
  p.saturated = (esc_.deadband != 0.0 ? esc_.deadband + esc_.tr_sat * (1.0 - esc_.deadband)
                                      : esc_.tr_sat) < throttle;
  p.omega_rad_s = omega_rad_s;
  p.rpm = RadPerSecToRpm(omega_rad_s);
  p.irms_a = current_a;
  const double io = motor_.io_a + motor_.io1_a_s_per_rad * omega_rad_s;          // section 9
  p.torque_nm = circuit::ShaftTorque(TorqueConstant(current_a), current_a, io);
  if (*limits & kLimitStalled) p.torque_nm = std::max(p.torque_nm, 0.0);
  p.idc_a = circuit::DcCurrent(esc_.c1, p.throttle_effective, esc_.c0, current_a);
  const double vdc_esc = vdc_v - esc_.rsupply_ohm * p.idc_a;                    // supply drop
  p.vll_rms_v = circuit::LineVoltage(circuit::AppliedVoltage(volt_factor_, vdc_esc, p.throttle_effective),
                                     esc_.resc_ohm, current_a);
  p.pac_w = circuit::AcPower(power_factor_, p.vll_rms_v, current_a);
  FillPowers(vdc_v, omega_rad_s, &p);
  if (motor_.rth_k_per_w != 0.0) {
    const double rm_hot = WindingResistance(current_a);
    p.winding_rise_k = motor_.rth_k_per_w * power_factor_ * rm_hot * current_a * current_a;
    if (!std::isfinite(rm_hot)) *limits |= kLimitThermalRunaway;
  }
}

OperatingPoint Drive::AtLoad(double vdc_v, double throttle, const TorqueLaw& load) const {
  if (extended_) return AtLoadExtended(vdc_v, throttle, load);
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
  // Below the no-load current the shaft torque is negative: the load drives the motor. (1 nA of
  // slack: a zero load must not be flagged through round-off.)
  return Complete(vdc_v, throttle, omega, current,
                  current < motor_.io_a - 1e-9 ? kLimitOverrunning : kLimitNone);
}

[[gnu::noinline]] OperatingPoint Drive::AtLoadExtended(double vdc_v, double throttle, const TorqueLaw& load) const {
  if (nonlinear_) return AtLoadNonlinear(vdc_v, throttle, load);
  const double kt = motor_.kt_nm_per_a;
  const double tre = EffectiveThrottle(throttle);
  const double u = volt_factor_ * vdc_v * tre;  // (48) left side
  const double r = SeriesResistance(tre);
  // Substituting I = (U - KE*w)/R (48) into KT*(I - Io - io1*w) = a + b*w + c*w^2 gives
  // c*w^2 + (b + KT*KE/R + KT*io1)*w + (a + KT*Io - KT*U/R) = 0.
  double b_total = load.b_nm_s_per_rad + kt * motor_.ke_v_s_per_rad / r;
  if (motor_.io1_a_s_per_rad != 0.0) b_total += kt * motor_.io1_a_s_per_rad;
  const double c_total = load.a_nm + kt * motor_.io_a - kt * u / r;
  const double omega = PositiveRoot(load.c_nm_s2_per_rad2, b_total, c_total);
  if (omega < 0.0) {
    // The load at standstill exceeds what the motor can deliver: it stalls.
    return Complete(vdc_v, throttle, 0.0, std::max(u / r, 0.0), kLimitStalled);
  }
  const double current = (u - motor_.ke_v_s_per_rad * omega) / r;
  const double io = motor_.io_a + motor_.io1_a_s_per_rad * omega;
  return Complete(vdc_v, throttle, omega, current, current < io - 1e-9 ? kLimitOverrunning : kLimitNone);
}

OperatingPoint Drive::AtLoadNonlinear(double vdc_v, double throttle, const TorqueLaw& load) const {
  const double tre = EffectiveThrottle(throttle);
  const double u = volt_factor_ * vdc_v * tre;
  const double r = SeriesResistance(tre);
  const double ke = motor_.ke_v_s_per_rad;
  if (!(u > 0.0)) return Complete(vdc_v, throttle, 0.0, 0.0, kLimitStalled);
  const double i_stall = CircuitCurrent(u, r);  // omega = 0 in (48)
  // With I the unknown, omega(I) = (U - (R + Rm(I) - Rm0)*I)/KE from (48), and the torque
  // balance f(I) = KT(I)*(I - Io - io1*omega(I)) - (a + b*omega + c*omega^2) is increasing in I
  // (omega falls as I rises; the load law is non-decreasing in omega).
  const auto omega_of = [&](double i) {
    return std::max(0.0, (u - (r + WindingResistance(i) - motor_.rm_ohm) * i) / ke);
  };
  const auto f = [&](double i) {
    const double w = omega_of(i);
    const double io = motor_.io_a + motor_.io1_a_s_per_rad * w;
    return TorqueConstant(i) * (i - io) -
           (load.a_nm + load.b_nm_s_per_rad * w + load.c_nm_s2_per_rad2 * w * w);
  };
  const double f_hi = f(i_stall);
  if (f_hi < 0.0) return Complete(vdc_v, throttle, 0.0, i_stall, kLimitStalled);
  const double f_lo = f(0.0);
  if (f_lo > 0.0) {
    // Only a negative load (driving the motor) gives f(0) > 0: the motor overruns.
    return Complete(vdc_v, throttle, omega_of(0.0), 0.0, kLimitOverrunning);
  }
  const double current = RootInBracket(f, 0.0, i_stall, f_lo, f_hi);
  return Complete(vdc_v, throttle, omega_of(current), current, kLimitNone);
}

OperatingPoint Drive::AtTorque(double vdc_v, double throttle, double torque_nm) const {
  return AtLoad(vdc_v, throttle, TorqueLaw{torque_nm, 0.0, 0.0});
}

OperatingPoint Drive::AtSpeed(double vdc_v, double throttle, double omega_rad_s) const {
  const double tre = EffectiveThrottle(throttle);
  const double u = volt_factor_ * vdc_v * tre;
  const double r = SeriesResistance(tre);
  const double current = nonlinear_ ? CircuitCurrent(u - motor_.ke_v_s_per_rad * omega_rad_s, r)
                                    : (u - motor_.ke_v_s_per_rad * omega_rad_s) / r;  // (48)
  const double io = motor_.io_a + motor_.io1_a_s_per_rad * omega_rad_s;
  const std::uint32_t limits = current < io ? kLimitOverrunning : kLimitNone;
  return Complete(vdc_v, throttle, omega_rad_s, current, limits);
}

OperatingPoint Drive::Inverse(double vdc_v, double torque_nm, double omega_rad_s) const {
  if (extended_) return InverseExtended(vdc_v, torque_nm, omega_rad_s);
  const double current = circuit::CurrentAtTorque(torque_nm, motor_.kt_nm_per_a, motor_.io_a);
  const double u = circuit::VoltageAtPoint(r_total_ohm_, current, motor_.ke_v_s_per_rad, omega_rad_s);
  const double throttle = ThrottleFromEffective(u / (volt_factor_ * vdc_v));
  return Complete(vdc_v, throttle, omega_rad_s, current, kLimitNone);
}

Drive::InverseCurrents Drive::InverseLight(double vdc_v, double torque_nm, double omega_rad_s) const {
  if (extended_) {
    const OperatingPoint p = InverseExtended(vdc_v, torque_nm, omega_rad_s);
    return {p.throttle, p.idc_a, p.irms_a};
  }
  // Inverse and Complete's expressions, in their order (the same rounding).
  const double current = torque_nm / motor_.kt_nm_per_a + motor_.io_a;                 // (42)
  const double u = r_total_ohm_ * current + motor_.ke_v_s_per_rad * omega_rad_s;       // (48)
  const double throttle = ThrottleFromEffective(u / (volt_factor_ * vdc_v));
  return {throttle, (esc_.c1 * EffectiveThrottle(throttle) + esc_.c0) * current, current};  // (57)
}

double Drive::InverseAcPower(double vdc_v, const InverseCurrents& c, double torque_nm, double omega_rad_s) const {
  if (extended_) return InverseExtended(vdc_v, torque_nm, omega_rad_s).pac_w;
  // Complete's expressions (the same rounding).
  const double vll = circuit::LineVoltage(circuit::AppliedVoltage(volt_factor_, vdc_v, EffectiveThrottle(c.throttle)),
                                          esc_.resc_ohm, c.irms_a);
  return circuit::AcPower(power_factor_, vll, c.irms_a);
}

[[gnu::noinline]] OperatingPoint Drive::InverseExtended(double vdc_v, double torque_nm, double omega_rad_s) const {
  const double kt = motor_.kt_nm_per_a;
  const double io = motor_.io1_a_s_per_rad == 0.0
                        ? motor_.io_a
                        : motor_.io_a + motor_.io1_a_s_per_rad * omega_rad_s;
  std::uint32_t limits = kLimitNone;
  double current = torque_nm / kt + io;                                                // (42)
  if (motor_.kt_droop_per_a != 0.0) {
    // Q*(1 + droop*I) = KT0*(I - Io)  =>  I = (Q + KT0*Io)/(KT0 - Q*droop), I > 0.
    const double den = kt - torque_nm * motor_.kt_droop_per_a;
    if (den > 0.0) {
      current = (torque_nm + kt * io) / den;
    } else {
      current = std::numeric_limits<double>::infinity();  // beyond the droop's torque asymptote
      limits |= kLimitMotorCurrent;
    }
  }
  const double r_motor = motor_.rm_ohm == WindingResistance(current)
                             ? r_total_ohm_
                             : WindingResistance(current) + esc_.resc_ohm;
  const double u = r_motor * current + motor_.ke_v_s_per_rad * omega_rad_s;            // (48)
  double tre = u / (volt_factor_ * vdc_v);
  if (esc_.rsupply_ohm != 0.0) {
    // kv*VDC*t - kv*rsupply*(C1*t + C0)*I*t = U: a*t^2 + b*t + c = 0, the smaller root.
    const double a = volt_factor_ * esc_.rsupply_ohm * current * esc_.c1;
    const double b = volt_factor_ * esc_.rsupply_ohm * current * esc_.c0 - volt_factor_ * vdc_v;
    const double disc = b * b - 4.0 * a * u;
    if (disc >= 0.0 && b < 0.0) {
      tre = 2.0 * u / (-b + std::sqrt(disc));
    } else {
      // No throttle reaches U: the ESC's output -a*t^2 - b*t peaks below it. The point is
      // reported at the least throttle it would need, which the supply drop only raises (the
      // lossless supply's U/(kv*VDC)), and at least full throttle, flagged; an infinite
      // throttle would leave VLL and PAC without a value.
      tre = std::max(1.0, u / (volt_factor_ * vdc_v));
      limits |= kLimitThrottleAboveOne;
    }
  }
  const double throttle = ThrottleFromEffective(tre);
  return Complete(vdc_v, throttle, omega_rad_s, current, limits);
}

double Drive::NoLoadSpeed(double vdc_v, double throttle) const {
  if (nonlinear_) return AtLoad(vdc_v, throttle, TorqueLaw{}).omega_rad_s;
  const double tre = EffectiveThrottle(throttle);
  const double u = volt_factor_ * vdc_v * tre;
  const double r = SeriesResistance(tre);
  // KT*(I - Io - io1*w) = 0 with I = (U - KE*w)/R.
  return (u - motor_.io_a * r) / (motor_.ke_v_s_per_rad + motor_.io1_a_s_per_rad * r);
}

double Drive::StallTorque(double vdc_v, double throttle) const {
  const double tre = EffectiveThrottle(throttle);
  const double u = volt_factor_ * vdc_v * tre;
  const double r = SeriesResistance(tre);
  if (nonlinear_) {
    const double i = CircuitCurrent(u, r);
    return TorqueConstant(i) * (i - motor_.io_a);
  }
  return motor_.kt_nm_per_a * (u / r - motor_.io_a);
}

double Drive::MaxPowerSpeed(double vdc_v, double throttle) const {
  return 0.5 * NoLoadSpeed(vdc_v, throttle);  // (12)
}

double Drive::MaxEfficiencySpeed(double vdc_v, double throttle) const {
  if (nonlinear_) {
    // No closed form: golden-section search of Pmech/PDC over [0, omega_NL] (unimodal).
    double lo = 0.0, hi = std::max(NoLoadSpeed(vdc_v, throttle), 0.0);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    const auto eta = [&](double w) { return AtSpeed(vdc_v, throttle, w).eta_system; };
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = eta(x1), f2 = eta(x2);
    for (int it = 0; it < 80 && hi - lo > 1e-9 * std::max(hi, 1.0); ++it) {
      if (f1 < f2) {
        lo = x1; x1 = x2; f1 = f2; x2 = lo + g * (hi - lo); f2 = eta(x2);
      } else {
        hi = x2; x2 = x1; f2 = f1; x1 = hi - g * (hi - lo); f1 = eta(x1);
      }
    }
    return 0.5 * (lo + hi);
  }
  const double tre = EffectiveThrottle(throttle);
  const double u = volt_factor_ * vdc_v * tre;
  const double r = SeriesResistance(tre);
  const double ke = motor_.ke_v_s_per_rad;
  if (motor_.io1_a_s_per_rad == 0.0) return (u - std::sqrt(motor_.io_a * r * u)) / ke;  // (14)
  // With Io = Io0 + io1*w and w = (U - R*I)/KE: eta ~ (U - R*I)*(a - b/I), a = 1 + io1*R/KE,
  // b = Io0 + io1*U/KE, maximal at I = sqrt(U*b/(R*a)) (eq 14 is the case io1 = 0).
  const double a = 1.0 + motor_.io1_a_s_per_rad * r / ke;
  const double b = motor_.io_a + motor_.io1_a_s_per_rad * u / ke;
  return (u - r * std::sqrt(u * b / (r * a))) / ke;
}

double Drive::EscTimingFigure(double throttle) const {
  return (esc_.c1 - kIdealIdcPerIrmsPerThrottle) * EffectiveThrottle(throttle) + esc_.c0;  // (62)
}

}  // namespace dynosize
