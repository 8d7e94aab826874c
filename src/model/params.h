// The parameters of a drive (a motor and the ESC that feeds it) in the model of
// docs/model.md: the motor's constants and ratings, the ESC's constants and ratings, and the
// extensions of section 9 (0 = the first-order model). model/drive.h computes operating points
// from them, model/physics.h decides whether they can create energy (section 10).
#pragma once

#include <limits>

#include "common/units.h"

namespace dynosize {

enum class MotorType { kBldc, kBrushed };

struct MotorParams {
  MotorType type = MotorType::kBldc;
  double ke_v_s_per_rad = 0.0;  // back-EMF constant (BLDC: line-line rms volts per rad/s)
  double kt_nm_per_a = 0.0;     // torque constant (BLDC: per rms ampere)
  double rm_ohm = 0.0;          // winding resistance of the quasi-single-phase circuit
  double io_a = 0.0;            // no-load current (at omega = 0 when io1_a_s_per_rad != 0)
  // Extensions (docs/model.md section 9; 0 = the first-order model, see model/drive.h).
  double io1_a_s_per_rad = 0.0;  // Io(omega) = io_a + io1*omega
  double rth_k_per_w = 0.0;      // winding temperature rise per watt of copper loss
  double kt_droop_per_a = 0.0;   // KT(I) = kt/(1 + kt_droop*|I|)
  // Ratings; +inf when the catalog gives none.
  double max_current_a = std::numeric_limits<double>::infinity();
  double max_power_w = std::numeric_limits<double>::infinity();
};

struct EscParams {
  double resc_ohm = 0.0;  // equivalent series resistance (eq 47)
  // DC/AC current ratio IDC/Irms = c1*TR_eff + c0 (eq 57). Defaults: the ideal ESC (eq 56).
  double c1 = kIdealIdcPerIrmsPerThrottle;
  double c0 = 0.0;
  double tr_sat = 1.0;     // throttle above which the ESC saturates (section 7)
  double sat_slope = 1.0;  // fraction of the nominal voltage slope delivered above tr_sat
  double deadband = 0.0;   // command range that produces no voltage (-1 < deadband < 1;
                           // negative: a throttle offset)
  double rsupply_ohm = 0.0;  // wire/connector resistance between the VDC sense point and ESC
  double max_current_a = std::numeric_limits<double>::infinity();
  double vdc_max_v = std::numeric_limits<double>::infinity();
  // The least supply voltage it runs on (an eVTOL controller's undervoltage lockout); 0 = none stated.
  double vdc_min_v = 0.0;
};

}  // namespace dynosize
