// Rule R15 (docs/search.md#r15) on its own: the least capacity a min_energy combination can
// have, from a lower bound of its energy. Used by the search's pair bounds (pair_bounds.h,
// through a BatteryOption) and by the evaluator's early exit (mission_eval_early_exits.cc).
// Internal to src/optimization (and its tests).
#pragma once

namespace dynosize {

// A feasible combination ends at or above the reserve, so its terminal energy E is at most its
// charge times the integral of OCV over [reserve, 1] (ocv_integral_v, OcvIntegralUpperBound):
// its capacity is at least E over that integral. With E at least `bound_wh` (a bound at the
// vehicle whose pack has capacity C_k, C_0 = capacity_lo_ah), the capacity is at least
// C_k+1 = bound/integral, so the vehicle weighs at least the one with C_k+1's pack and E is at
// least the bound there (M3 of docs/search.md): bound_at(C_k+1). Iterated while the bound stays
// below `cutoff_wh` (at or above it nothing more is needed) and the capacity grows by
// kCapacityStepMin, at most kCapacitySteps times. *over_range: C_k+1 above capacity_hi_ah,
// where no pack of the range holds the energy (reserve_soc); the bound is then left as it was.
// bound_at(capacity_ah) returns a bound in Wh at that capacity (+inf when nothing is feasible there).
inline constexpr int kCapacitySteps = 4;
inline constexpr double kCapacityStepMin = 1e-3;  // relative: a smaller step changes the bound by less
template <typename BoundAt>
double RaisedByNeededCapacity(double capacity_lo_ah, double capacity_hi_ah, double ocv_integral_v, double bound_wh,
                              double cutoff_wh, bool* over_range, BoundAt&& bound_at) {
  *over_range = false;
  if (!(capacity_hi_ah > capacity_lo_ah) || !(ocv_integral_v > 0)) return bound_wh;
  double capacity_ah = capacity_lo_ah;
  for (int k = 0; k < kCapacitySteps && bound_wh < cutoff_wh; ++k) {
    const double need_ah = bound_wh / ocv_integral_v;  // Wh over V
    if (need_ah > capacity_hi_ah) {
      *over_range = true;
      return bound_wh;
    }
    if (!(need_ah > capacity_ah * (1.0 + kCapacityStepMin))) break;
    capacity_ah = need_ah;
    const double raised = bound_at(capacity_ah);
    if (raised > bound_wh) bound_wh = raised;
  }
  return bound_wh;
}

}  // namespace dynosize
