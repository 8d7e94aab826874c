// The parameters of a drive (a motor and the ESC that feeds it) in the model of
// docs/model.md: the motor's constants and ratings, the ESC's constants and ratings, and the
// extensions of section 9 (0 = the first-order model). model/drive.h computes operating points
// from them, model/physics.h decides whether they can create energy (section 10).
#pragma once

#include <algorithm>
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
  // Ratings; +inf when the catalog gives none. A point may reach max_current_a and max_power_w;
  // a point of a segment longer than peak_duration_s is held to the continuous ones (issue 51:
  // a peak rating above the continuous one holds for its stated duration only; SegmentRating).
  double max_current_a = std::numeric_limits<double>::infinity();
  double max_power_w = std::numeric_limits<double>::infinity();
  double continuous_current_a = std::numeric_limits<double>::infinity();
  double continuous_power_w = std::numeric_limits<double>::infinity();
  double peak_duration_s = 0.0;  // 0: no peak rating stated
  // The catalog's peak ratings (0: none stated), which the mission's ratings read
  // (optimization/credibility.h ScenarioMotorParams).
  double peak_current_a = 0.0, peak_power_w = 0.0;
};

// The ratings a mission reads (issue 51): the continuous ones kept as continuous_*, max_* raised
// to the stated peak ones where a peak duration is stated (optimization/credibility.h's
// ScenarioMotorParams and ScenarioEscParams, the one place a mission takes a part's ratings).
inline void ApplyPeakRatings(MotorParams* p) {
  p->continuous_current_a = p->max_current_a;
  p->continuous_power_w = p->max_power_w;
  if (!(p->peak_duration_s > 0.0)) return;
  p->max_current_a = std::max(p->max_current_a, p->peak_current_a);
  p->max_power_w = std::max(p->max_power_w, p->peak_power_w);
}

// The rating a point of a segment of segment_s seconds is held to: `reach` (the most any point
// may reach) for a segment no longer than peak_duration_s, else `continuous` (issue 51).
inline double SegmentRating(double reach, double continuous, double peak_duration_s, double segment_s) {
  return segment_s > peak_duration_s ? std::min(reach, continuous) : reach;
}

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
  double max_current_a = std::numeric_limits<double>::infinity();  // what a point may reach, as MotorParams'
  double continuous_current_a = std::numeric_limits<double>::infinity();
  double peak_duration_s = 0.0;  // 0: no peak rating stated
  double peak_current_a = 0.0;  // the catalog's ipeak_a with its peak_duration_s (0: none)
  double vdc_max_v = std::numeric_limits<double>::infinity();
  // The least supply voltage it runs on (an eVTOL controller's undervoltage lockout); 0 = none stated.
  double vdc_min_v = 0.0;
};

inline void ApplyPeakRatings(EscParams* p) {
  p->continuous_current_a = p->max_current_a;
  if (p->peak_duration_s > 0.0) p->max_current_a = std::max(p->max_current_a, p->peak_current_a);
}

}  // namespace dynosize
