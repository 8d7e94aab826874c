#include "optimization/credibility.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "catalog/conventions.h"
#include "catalog/esc_prior.h"
#include "catalog/in_system.h"
#include "catalog/prop_credibility.h"
#include "catalog/prop_reynolds.h"
#include "common/units.h"
#include "model/physics.h"

namespace dynosize {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Relative band of Rm and Io per tier of the value (pessimistic x(1 + b), optimistic /(1 + b)):
//   measured   0.10  a 25 K winding temperature rise at +0.393 %/K (copper, docs/model.md section 9)
//   computed,  0.25  datasheets measure R and Io differently from the rms circuit (ohmmeter, Io
//   stated         at a stated voltage; docs/model.md section 8): an allowance
//   user       0.60  DriveCalc's data-base Rm is about 1.6x below a fit of DriveCalc's own
//                    measurements (catalog/README.md)
//   assumed    1.00  a factor of 2 either way
bool HasAssumed(const EntryBase& e, const char* key) {
  return std::find(e.assumed_keys.begin(), e.assumed_keys.end(), key) != e.assumed_keys.end();
}

// The motor's Kv: the catalog's, else from KE (docs/model.md section 8: Kv = 0.675/(KE*pi/30) for a
// BLDC, 1/(KE*pi/30) brushed), rpm/V.
double MotorKvRpmPerV(const MotorEntry& motor) {
  if (motor.kv_rpm_per_v) return *motor.kv_rpm_per_v;
  const double k = motor.params.type == MotorType::kBldc ? 3.0 / (std::sqrt(2.0) * kPi) : 1.0;
  return k / (motor.params.ke_v_s_per_rad * kPi / 30.0);
}

}  // namespace

PropAdjustment PropAdjustmentFor(const PropEntry& prop, DataScenario scenario) {
  PropAdjustment a;
  if (scenario == DataScenario::kAsGiven) return a;
  const ReynoldsLaw& law = DefaultReynoldsLaw();
  if (scenario == DataScenario::kPessimistic) a.reynolds_fm_exp = law.fm_p90 - law.fm_exp();
  if (scenario == DataScenario::kOptimistic) a.reynolds_fm_exp = std::max(law.fm_p10, 0.0) - law.fm_exp();
  const DataTier tier = prop.tier;
  const FmEnvelopeClass& k = FmEnvelopeFor(prop.diameter_m);
  if (tier == DataTier::kMeasured) {
    if (scenario == DataScenario::kPessimistic) a.power_factor = 1.0 + kMeasuredPowerBand;
    if (scenario == DataScenario::kOptimistic) {
      a.power_factor = 1.0 - kMeasuredPowerBand;
      a.fm_cap = 1.0;  // never beyond momentum theory
    }
    return a;
  }
  if (tier == DataTier::kManufacturerComputed) {
    // The ratio applies to the manufacturer's raw data, stored/power_derate_factor (credibility.h:
    // the catalog's derating is not applied twice).
    double ratio = kComputedFmRatio.median;
    switch (scenario) {
      case DataScenario::kPessimistic: ratio = kComputedFmRatio.min; break;
      case DataScenario::kOptimistic: ratio = kComputedFmRatio.max; a.fm_cap = k.p90; break;
      default: a.fm_cap = k.p90; break;
    }
    a.power_factor = std::max(1.0, 1.0 / (ratio * prop.power_derate_factor));
    return a;
  }
  switch (scenario) {
    case DataScenario::kPessimistic: a.fm_cap = k.p10; break;
    case DataScenario::kOptimistic: a.fm_cap = k.p90; break;
    default: a.fm_cap = k.p50; break;
  }
  return a;
}

void AdjustPropEvaluation(const PropAdjustment& adj, double diameter_m, PropEvaluation* ev) {
  if (adj.identity() || !(ev->omega_rad_s > 0.0) || !(ev->power_w > 0.0)) return;
  // The Reynolds band below the data: r^-x with r <= 1 (x > 0 pessimistic, < 0 optimistic; the
  // torque Q ~ n^(2 + b - x) still rises with the speed for |x| < 1, search.cc M1).
  const double k_re = ev->reynolds_ratio < 1.0 && adj.reynolds_fm_exp != 0.0
                          ? std::pow(ev->reynolds_ratio, -adj.reynolds_fm_exp) : 1.0;
  double p = k_re * ev->power_w;
  if (!(ev->airspeed_m_s > 0.0 && !ev->no_forward_flight_data)) {  // static: the tier's rule
    p *= adj.power_factor;
    if (adj.fm_cap < 1e300) p = std::max(p, IdealRotorPowerW(ev->thrust_n, diameter_m, ev->rho_kg_m3) / adj.fm_cap);
  }
  const double k = p / ev->power_w;
  ev->power_w = p;
  ev->torque_nm *= k;
  ev->cp *= k;
}

bool MissionUsesRotorLift(const Mission& m) {
  for (const Segment& s : m.segments) {
    if (s.type == SegmentType::kHover || s.type == SegmentType::kClimb) return true;
    if (s.type == SegmentType::kCruise && !(s.lift_to_drag > 0)) return true;
  }
  return false;
}

bool FoldingPropRefused(const PropEntry& prop, const Mission& m) {
  return !m.constraints.allow_folding_props_for_lift && MissionUsesRotorLift(m) && prop.folding;
}

double MotorMaxVoltageV(const MotorEntry& motor) {
  if (!motor.json.is_object()) return kInf;
  const auto it = motor.json.find("cells_max");  // one look-up: the search asks per motor and pair
  if (it == motor.json.end() || !it->is_number()) return kInf;
  // 1e-9 relative: a full pack's OCV is 4.2 V per cell up to the rounding of its table.
  return 4.2 * it->get<double>() * (1.0 + 1e-9);
}

MotorParams ScenarioMotorParams(const MotorEntry& motor, const Mission& m, bool* rating_estimated,
                                bool* excluded) {
  MotorParams p = motor.params;
  const bool unrated = !std::isfinite(p.max_current_a) && !std::isfinite(p.max_power_w);
  // The importer's estimate from the mass (catalog/conventions.h): a rating no source states.
  const bool catalog_estimate = !std::isfinite(p.max_current_a) && HasAssumed(motor, "max_power_w");
  const bool estimate = m.constraints.estimate_unrated_motors;
  if (unrated && estimate && motor.mass_kg) p.max_power_w = EstimatedMotorPowerW(*motor.mass_kg);
  // No source rating (none at all, or the importer's power estimate): the current law too.
  if ((unrated || catalog_estimate) && estimate && motor.mass_kg) {
    const double kv = MotorKvRpmPerV(motor);
    if (kv > 0.0 && std::isfinite(kv)) p.max_current_a = EstimatedMotorCurrentA(*motor.mass_kg, kv);
  }
  if (rating_estimated) *rating_estimated = estimate && ((unrated && motor.mass_kg) || catalog_estimate);
  if (excluded) *excluded = !estimate && (unrated || catalog_estimate);
  const DataScenario s = m.objective.ranking;
  if (s == DataScenario::kPessimistic || s == DataScenario::kOptimistic) {
    // Values the in-system law gave: one motor's p10/p90 scatter about the law (in_system.h,
    // fitted on measured systems); the others: the tier's band.
    const MotorParams spread = MotorSpreadParams(motor, s == DataScenario::kPessimistic);
    p.rm_ohm = spread.rm_ohm;
    p.io_a = spread.io_a;
    p.io1_a_s_per_rad = spread.io1_a_s_per_rad;
  }
  ApplyPeakRatings(&p);  // the peak ratings for segments no longer than their duration (issue 51)
  return MotorAtPropellerShaft(p, motor.gear);  // the one place a mission meets the gearbox
}

EscParams ScenarioEscParams(const EscEntry& esc, DataScenario s) {
  EscParams p = esc.params;
  ApplyPeakRatings(&p);  // the peak rating for segments no longer than its duration (issue 51)
  if (s != DataScenario::kPessimistic && s != DataScenario::kOptimistic) return p;
  const bool up = s == DataScenario::kPessimistic;
  const DataTier tr = ValueTier(esc, "resc_ohm");
  // An assumed RESC is the prior's law (esc_prior.h): its scatter is a factor exp(sd) either way.
  const double kr = tr == DataTier::kAssumed ? std::exp(DefaultEscPrior().resistance_log_sd) : 1.0 + TierValueBand(tr);
  p.resc_ohm = up ? p.resc_ohm * kr : p.resc_ohm / kr;
  if (up && ValueTier(esc, "c0") == DataTier::kAssumed) {
    p.c0 = std::max(p.c0, kAssumedEscC0Pessimistic);
  }
  return p;
}

}  // namespace dynosize
