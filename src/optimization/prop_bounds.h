// Bounds read from a propeller's data that the search's pruning rules (docs/search.md) and the
// evaluator's early exits (mission_eval.cc) both use: a speed from below for a thrust, and the
// least energy of a wing-borne cruise whose airspeed is free, cell by cell over its range.
#pragma once
#include <array>
#include <limits>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "model/drive.h"
#include "model/physics.h"
#include "optimization/credibility.h"
#include "prop/prop_model.h"

namespace dynosize {

// The highest rotor speed any bound reads a propeller at (rad/s; 57,000 rpm).
inline constexpr double kPropSpeedCeilingRadS = 6000.0;

// A speed at or below the root of thrust(omega) = T in axial inflow v on [lo, hi] (thrust
// rising with speed, docs/search.md#m1, and thrust(lo) <= T): at most `steps` bracketing steps
// (regula falsi in omega^2, with bisections where it stalls) that keep thrust(lo) <= T, to a
// bracket of 1e-12 of hi; hi itself when thrust(hi) <= T.
double SpeedFromBelow(const PropModel& model, double rho, double thrust_n, double v_m_s, double lo, double hi,
                      int steps);

// SpeedFromBelow within a grid cell whose end thrusts are known (thrust(lo) = t_lo_n <= T <
// thrust(hi) = t_hi_n, each as model.Evaluate(., rho, v_m_s) gives it): the same speed, without
// evaluating the ends again. *at_lo: the evaluation at the speed returned when it is above lo
// (left as it is when the speed is lo).
double SpeedFromBelowInCell(const PropModel& model, double rho, double thrust_n, double v_m_s, double lo, double t_lo_n,
                            double hi, double t_hi_n, int steps, PropEvaluation* at_lo);

// A speed at or below the evaluator's root for thrust T in axial inflow v (thrust rising with
// speed, M1), on [0, kPropSpeedCeilingRadS]; false when even the ceiling gives less. With
// start_rad_s in (0, ceiling) (a guess, such as a neighbouring sample's speed) the root is first
// bracketed by growing steps from it (factors 1.05, 1.05^2, 1.05^4, ...), then narrowed as
// SpeedFromBelow.
bool PropSpeedFromBelow(const PropModel& model, double rho, double thrust_n, double v_m_s, int steps, double* omega,
                        double start_rad_s = 0.0);

// The group's drive and the pack's voltage range, for the data part of the cruise bound below.
struct CruiseDriveBound {
  const Drive* drive = nullptr;  // the scenario's motor and an ESC (a class's ideal one is a bound)
  double v_full_v = 0, v_cut_v = 0;
};

// One propulsion group's parts as the cruise bound reads them.
struct CruisePropBound {
  const PropEntry* prop = nullptr;
  const PropModel* model = nullptr;
  PropAdjustment adjustment;  // the ranking scenario's (credibility.h)
  bool lossy = false;         // DriveIsLossy: no stage creates energy (docs/model.md section 10)
  // Also the propeller's own shaft power from its data (lossy only; a speed bisection per
  // sample, so off where a bound is read per candidate pair).
  bool with_prop_data = false;
};

// The cells the airspeed range of a free cruise is cut in (docs/search.md#g1).
inline constexpr int kFreeCruiseCells = 32;

// A free cruise's samples at one vehicle mass, read from the propeller alone (no motor, no ESC):
// the airspeeds V_k = lo + (hi - lo)*k/kFreeCruiseCells, the thrust per rotor T_k there and,
// from below at (T_k, V_k), the rotor's speed and the scenario's torque. A bound for every
// vehicle at least that heavy (M1, M3), so it can be kept per propeller and mass and read with
// any drive.
struct FreeCruiseSamples {
  std::array<double, kFreeCruiseCells + 1> v{}, thrust{}, omega{}, torque{};
  // Per cell k, the rotors' momentum power P_ideal/FM_max at T_k and the cell's inflow (the
  // airspeed read for it with forward-flight tables, else 0), W: read by every drive.
  std::array<double, kFreeCruiseCells> momentum_w{};
  int rotors = 0;
  bool points = false;       // every sample has its speed and torque (else none of them is used)
  bool shaft_rises = false;  // Q_k*omega_k rises with k (M4 seen on the samples)
  bool point_rises = false;  // Q_k and omega_k each rise with k (so does every loss floor)
  // A point per rotor that every feasible point of the range is at or above (needs no points;
  // docs/search.md#g1-torque-floor): the speed that the range's least thrust needs at the
  // propeller's largest CT (0: none), and R6's momentum power at that thrust over the highest
  // speed R2 and R12's top allow (0: none). That speed (rad/s, +inf: no limit) and the rule
  // that sets it.
  double omega_floor_rad_s = 0, torque_floor_nm = 0;
  double omega_ub_rad_s = std::numeric_limits<double>::infinity();
  const char* omega_ub_rule = nullptr;
};

// The samples of a wing-borne cruise with a free airspeed at vehicle mass mass_kg; the speeds and
// torques only `with_points` (a speed bisection per sample).
FreeCruiseSamples SampleFreeCruise(const Mission& m, const Segment& sg, const CruisePropBound& p, double mass_kg,
                                   bool with_points);

// A wing-borne cruise (lift_to_drag > 0) with a free airspeed in [lo, hi], flown at a vehicle
// mass of at least the samples' mass: P_lb (W, the rotors; the avionics P_av not included) with
//   (P_lb + P_av) * SegmentDurationS(sg, hi) <= the segment's energy at every airspeed of the range.
// 0 when no bound applies. The range is cut in cells [V_k, V_k+1]; on each, by the rules of
// prop_bounds.cc, the rotors' power is at least the largest of momentum theory's
// P_ideal/max_figure_of_merit, (with_prop_data) the propeller's shaft power from below, raised
// by the motor's loss floor `loss` (model/physics.h, LossFloorOf) when given, and (with `drive`)
// the drive's PDC from below, and the energy is at least that power plus P_av over the cell's
// shortest duration. The least cell gives P_lb.
double FreeCruiseRotorPowerFromSamples(const Mission& m, const Segment& sg, const CruisePropBound& p,
                                       const FreeCruiseSamples& s, const CruiseDriveBound* drive,
                                       const MotorLossFloor* loss = nullptr);

// The same from samples taken at mass_kg (with points when the bound reads them).
double FreeCruiseRotorPowerLowerBoundW(const Mission& m, const Segment& sg, const CruisePropBound& p,
                                       const CruiseDriveBound* drive, double mass_kg);

}  // namespace dynosize
