// A documented physical prior for ESCs that have no dynamometer fit.
//
// Catalog ESCs (DriveCalc, FAST-UAV) give current ratings and sometimes a resistance, but never
// the eq (57) constants C1, C0 or the saturation knee of docs/model.md section 7. The prior fills
// them in, and every value it supplies is written as "assumed" in source.values, so results
// built on it say so:
//   c1 = (3/pi)*sqrt(27/20) ~= 1.1095, c0 = 0    the ideal ESC, eq (56): PDC = PAC, no
//                                                switching loss beyond RESC
//   tr_sat = 0.9, sat_slope = 0.61               the one measured knee we have: MultiStar 30 A,
//                                                docs/model.md section 7 (1230 -> 750 rpm per 10 %)
//   resc_ohm (when the data set has none)        a power law in the current rating fitted to
//                                                the DriveCalc ESCs that state R:
//      R [mOhm] = 79.18 * Imax[A]^-0.8467        (121 ESCs, log-residual sd 1.57, i.e. a
//                                                factor of 4.8 either way: a rough prior)
#pragma once

#include <cmath>

#include "common/units.h"

namespace dynosize {

// A LiPo cell's full-charge voltage, V: an ESC rated for N cells takes N*4.2 V.
inline constexpr double kLipoFullCellV = 4.2;

struct EscPrior {
  double c1 = kIdealIdcPerIrmsPerThrottle;  // eq (56)
  double c0 = 0.0;
  double tr_sat = 0.9;       // docs/model.md section 7
  double sat_slope = 0.61;   // 750/1230, docs/model.md section 7
  // R [mOhm] = resistance_coef_mohm * Imax^resistance_exp, from DriveCalc ESC.csv.
  double resistance_coef_mohm = 79.18;
  double resistance_exp = -0.8467;
  double resistance_log_sd = 1.57;  // scatter of ln(R) about the law
  // The voltage limit of an ESC that states none (no vdc_max_v, no cells_max): the p90 of the
  // 272 DriveCalc ESCs that state one (median 16.8 V, p10 12.6 V), i.e. 10S LiPo. Without it an
  // unrated 2000s hobby ESC ("Schulze 18.129F", 18 NiCd cells) was run on 24S packs.
  double unrated_vdc_max_v = 42.0;
};

inline const EscPrior& DefaultEscPrior() {
  static const EscPrior kPrior;
  return kPrior;
}

// Prior equivalent resistance for an ESC rated `max_current_a` (> 0), ohm.
inline double PriorEscResistanceOhm(double max_current_a, const EscPrior& prior = DefaultEscPrior()) {
  return MilliohmToOhm(prior.resistance_coef_mohm * std::pow(max_current_a, prior.resistance_exp));
}

}  // namespace dynosize
