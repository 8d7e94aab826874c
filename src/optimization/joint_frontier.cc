// The joint search's bounds over the other free groups' choices (joint_search.h; G2,
// docs/search.md#g2): the least power a free group's segment draws over every surviving
// choice, and the coupled bound's frontier of (extra mass, least energy).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/units.h"
#include "model/physics.h"
#include "optimization/components.h"
#include "optimization/credibility.h"
#include "optimization/joint_search.h"
#include "optimization/prop_bounds.h"

namespace dynosize::search_internal {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// e as a float no greater than e (a lower bound stays one).
float FloatBelow(double e) {
  float f = static_cast<float>(e);
  if (static_cast<double>(f) > e) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

// Floor codes (joint_search.h).
constexpr int kFloorCodeMantissaBits = 11;
constexpr std::uint32_t kFloorCodeMaxExponent = 30;
constexpr std::uint16_t kFloorCodeMax =  // the largest finite code
    1 + ((kFloorCodeMaxExponent << kFloorCodeMantissaBits) | ((1u << kFloorCodeMantissaBits) - 1));

double FloorOfCode(std::uint16_t q) {
  if (q == 0) return -std::numeric_limits<double>::infinity();
  if (q == kFloorCodeInf) return std::numeric_limits<double>::infinity();
  const std::uint32_t c = static_cast<std::uint32_t>(q) - 1;
  const std::uint32_t bits = (((c >> kFloorCodeMantissaBits) + 127u) << 23) |
                             ((c & ((1u << kFloorCodeMantissaBits) - 1)) << (23 - kFloorCodeMantissaBits));
  float f = 0;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

std::uint16_t CodeOfFloor(double e) {
  if (e == std::numeric_limits<double>::infinity()) return kFloorCodeInf;
  const float f = FloatBelow(e);
  if (!(f >= 1.0f)) return 0;
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  const std::uint32_t exponent = std::min((bits >> 23) - 127u, kFloorCodeMaxExponent);
  const std::uint32_t mantissa = exponent == (bits >> 23) - 127u
                                     ? (bits & 0x7FFFFFu) >> (23 - kFloorCodeMantissaBits)
                                     : (1u << kFloorCodeMantissaBits) - 1;  // above 2^31 J: the largest code
  return static_cast<std::uint16_t>(1 + ((exponent << kFloorCodeMantissaBits) | mantissa));
}

std::uint16_t LeastCodeAtOrAbove(double e) {
  const std::uint16_t code = CodeOfFloor(e);  // at or below e, the next one above it
  if (code == kFloorCodeInf || FloorOfCode(code) >= e) return code;
  return code < kFloorCodeMax ? static_cast<std::uint16_t>(code + 1) : kFloorCodeInf;
}

// The frontier of the level at or below outer_extra_kg (docs/search.md#g2-levels): level k
// puts the outer group k * kFrontierLevelStep of the option's lightest vehicle above its
// lightest, so a completion whose outer choice is at least that much heavier weighs at least
// the vehicle each of the level's points was computed at (M3). Computed when first asked.
int JointBounds::LevelOf(std::size_t o, double outer_extra_kg) const {
  int k = 0;
  if (outer_extra_kg > 0) {
    const double steps = outer_extra_kg / (kFrontierLevelStep * mass_min_kg_[o]);
    k = steps < kFrontierLevels - 1 ? static_cast<int>(std::floor(steps)) : kFrontierLevels - 1;
    while (k > 0 && !(FrontierLevelKg(o, k) <= outer_extra_kg)) --k;  // at or below, after rounding
  }
  return k;
}

const std::vector<std::uint16_t>* JointBounds::FloorsAtOrBelow(std::size_t o, int level) const {
  for (int j = std::min(level, kFrontierLevels - 1); j >= 0; --j) {
    const std::vector<std::uint16_t>& f = inner_floors_[o][static_cast<std::size_t>(j)];
    if (!f.empty()) return &f;
  }
  return nullptr;
}

// G2's inner filter (docs/search.md#g2-inner-filter). A completion with inner pair (motor,
// propeller) spends at least the pair's energy floor (inner_floors_, at the highest computed
// level at or below the choice's: a bound of the pair's segments at every vehicle of at least
// that level, M3) plus outer_energy's (the other groups' segments, and the outer group's at
// the vehicle with that pair, read at or below its mass): at or above cutoff it has no score
// below it.
bool JointBounds::InnerPairsBelow(std::size_t o, const OuterEnergy& outer_energy, double cutoff,
                                  std::vector<char>* allowed) const {
  if (inner_ < 0 || !outer_energy.valid || outer_energy.outer_j_by_kg.empty() || o >= inner_floors_.size() ||
      !std::isfinite(cutoff)) {
    return false;
  }
  const std::vector<std::uint16_t>* floors = FloorsAtOrBelow(o, LevelOf(o, outer_energy.raw_kg - mass_min_kg_[o]));
  if (!floors || floors->size() != inner_by_mass_.size()) return false;
  const auto& by_kg = outer_energy.outer_j_by_kg;
  allowed->assign(cat_.motors().size() * cat_.props().size(), 0);
  // The pairs (lightest first) by the entry of by_kg at or below their vehicle, each range
  // against the budget left there (min_energy: the score in Wh), as the least code at or above
  // it. The vehicle as OuterBound's frontier points take it, held 1e-6 below against the float
  // masses.
  const double shrink = 1.0 - 1e-6;
  const std::size_t n_pairs = floors->size();
  std::size_t begin = 0;
  for (std::size_t j = 0; j < by_kg.size() && begin < n_pairs; ++j) {
    std::size_t end = n_pairs;
    if (j + 1 < by_kg.size()) {  // the first pair whose vehicle reaches the next entry
      const double next_kg = by_kg[j + 1].first;
      end = static_cast<std::size_t>(
          std::partition_point(inner_pair_kg_.begin() + static_cast<std::ptrdiff_t>(begin), inner_pair_kg_.end(),
                               [&](float pair_kg) {
                                 return !(next_kg <= shrink * (outer_energy.raw_kg + InnerExtraKg(o, pair_kg)));
                               }) -
          inner_pair_kg_.begin());
    }
    const std::uint16_t below = LeastCodeAtOrAbove(cutoff * 3600.0 - outer_energy.rest_j - by_kg[j].second);
    for (std::size_t n = begin; n < end; ++n) {
      if ((*floors)[n] < below) (*allowed)[inner_by_mass_[n]] = 1;
    }
    begin = end;
  }
  return true;
}

const std::vector<JointBounds::FrontierPoint>& JointBounds::Frontier(std::size_t o, double outer_extra_kg) {
  const int k = LevelOf(o, outer_extra_kg);
  // A level already computed up to kFrontierLevelReuse below serves (any level at or below the
  // extra mass is a bound; each level costs a walk over the inner group's choices).
  for (int j = k; j >= 0 && j >= k - kFrontierLevelReuse; --j) {
    if (frontier_done_[o][static_cast<std::size_t>(j)]) return frontier_[o][static_cast<std::size_t>(j)];
  }
  const std::size_t ki = static_cast<std::size_t>(k);
  if (!frontier_done_[o][ki]) {
    frontier_[o][ki] = InnerFrontier(o, k);
    frontier_done_[o][ki] = 1;
  }
  return frontier_[o][ki];
}

// G2's coupled bound (min_energy, two free groups): the inner group's choices as a frontier of
// (extra mass over its lightest, least energy of its own segments at the vehicle with that mass
// and the outer group FrontierLevelKg(o, level) above its lightest), each choice that survives
// R0, R1, R3, R7 and the thrust-to-weight rule at that vehicle, taken lightest first and kept
// when its energy is below every lighter one's. Every feasible inner choice of a completion
// whose outer choice is at least that much above the outer group's lightest has a frontier
// point no heavier and with no more energy (M3). Choices whose floor (rotors*max(Q*omega,
// momentum) per segment) reaches the least energy so far are skipped when their drive cannot
// create energy (SegmentPowerBound), and so are the (motor, propeller) pairs whose energy at a
// level at or below this one (inner_floor_) reaches it (docs/search.md#g2-levels).
std::vector<JointBounds::FrontierPoint> JointBounds::InnerFrontier(std::size_t o, int level) {
  const double outer_extra_kg = FrontierLevelKg(o, level);
  const auto& motors = cat_.motors();
  const auto& props = cat_.props();
  const BatteryOption& bo = options_[o];
  const double esc_min = std::isfinite(escs_.min_mass_kg[o]) ? escs_.min_mass_kg[o] : 0.0;
  const int rotors = m_.groups[static_cast<std::size_t>(inner_)].rotors;
  const double base_kg = mass_min_kg_[o] + outer_extra_kg;  // the vehicle with the inner group at its lightest
  std::vector<std::size_t> segs;
  for (std::size_t si = 0; si < m_.segments.size(); ++si) {
    if (m_.segments[si].group == inner_) segs.push_back(si);
  }
  auto t_min = [&](std::size_t si) { return SegmentDurationS(m_.segments[si], m_.segments[si].airspeed_m_s.hi); };
  std::vector<double> floor_j(props.size(), kInf);  // per propeller at the lightest vehicle of the level
  for (std::size_t pi = 0; pi < props.size(); ++pi) {
    if (!PropAllowed(inner_, props[pi])) continue;
    const bool static_only = models_[pi]->data_kind() != PropDataKind::kTables || props[pi].j_tables.empty();
    double e = 0;
    for (std::size_t si : segs) {
      const RotorBound& rb = OuterRotor(static_cast<int>(pi), si, o, base_kg);
      const double p_ideal = rb.omega_rad_s > 0 ? IdealRotorPowerW(rb.thrust_n, props[pi].diameter_m, m_.rho_kg_m3,
                                                                   static_only ? 0.0 : rb.axial_airspeed_m_s)
                                                : 0.0;
      const double w = std::max(rb.torque_nm * rb.omega_rad_s, p_ideal / std::max(1.0, m_.constraints.max_figure_of_merit));
      e += (m_.vehicle.avionics_power_w + rb.rotors * w) * t_min(si);
    }
    floor_j[pi] = e;
  }
  std::vector<double> prop_kg(props.size());
  for (std::size_t pi = 0; pi < props.size(); ++pi) prop_kg[pi] = PropMassKg(props[pi]);
  // The (motor, propeller) list by mass, built once for every option and level (the order of
  // motor + propeller mass is the order of the group's mass: the ESC adds the same to each).
  if (inner_by_mass_.empty()) {
    std::vector<std::pair<double, std::uint32_t>> list;
    for (std::size_t mi = 0; mi < motors.size(); ++mi) {
      if (!motors[mi].mass_kg || !motors[mi].exclude_reason.empty()) continue;
      for (std::size_t pi = 0; pi < props.size(); ++pi) {
        if (!PropAllowed(inner_, props[pi])) continue;
        list.emplace_back(*motors[mi].mass_kg + prop_kg[pi], static_cast<std::uint32_t>(mi * props.size() + pi));
      }
    }
    std::sort(list.begin(), list.end());
    inner_by_mass_.reserve(list.size());
    inner_pair_kg_.reserve(list.size());
    for (const auto& e : list) {
      inner_by_mass_.push_back(e.second);
      inner_pair_kg_.push_back(static_cast<float>(e.first));
    }
  }
  // Per motor: its scenario parameters and R0, R1 (the lift group's voltage rule).
  std::vector<MotorParams> mps(motors.size());
  std::vector<char> usable(motors.size(), 0);  // 0: not yet, 1: usable, 2: fails R0/R1
  std::vector<char> all_lossy(motors.size(), 0);  // no drive of the motor can create energy
  std::vector<std::size_t> classes;
  for (std::size_t c = 0; c < escs_.classes.size(); ++c) {
    if (!escs_.per_option[o][c].empty()) classes.push_back(c);
  }
  // Each pair's energy floor from the highest computed level below this one: a bound at this
  // level too, whose vehicles are heavier (M1-M3; +inf: the pair fails a rule with every ESC
  // class); raised here to this level's where it is computed, and kept as this level's.
  const std::vector<std::uint16_t>* below = FloorsAtOrBelow(o, level);
  std::vector<float> floors(inner_by_mass_.size(), -std::numeric_limits<float>::infinity());
  if (below && below->size() == floors.size()) {
    for (std::size_t n = 0; n < floors.size(); ++n) floors[n] = FloatBelow(FloorOfCode((*below)[n]));
  }
  std::vector<FrontierPoint> front;
  double e_min = kInf;
  for (std::size_t n = 0; n < inner_by_mass_.size(); ++n) {
    const float e_known = floors[n];
    if (e_known >= e_min) continue;  // a lighter point has no more energy
    const std::uint32_t code = inner_by_mass_[n];
    const std::size_t mi = code / props.size(), pi = code % props.size();
    const MotorEntry& mo = motors[mi];
    const double kg = rotors * (*mo.mass_kg + prop_kg[pi] + esc_min);
    if (kg < inner_lightest_kg_[o]) {  // it fails R0, R1, R3 or R7 with every class (LightestSurvivorKg)
      floors[n] = FloatBelow(kInf);
      continue;
    }
    if (!usable[mi]) {
      bool excluded = false;
      mps[mi] = ScenarioMotorParams(mo, m_, nullptr, &excluded);
      usable[mi] = Lifts(inner_) && (excluded || bo.v_full > MotorMaxVoltageV(mo)) ? 2 : 1;  // R0, R1
      all_lossy[mi] = 1;
      for (std::size_t c : classes) {
        if (!DriveIsLossy(mps[mi], escs_.classes[c].c1, escs_.classes[c].c0)) all_lossy[mi] = 0;
      }
    }
    if (usable[mi] != 1 || (all_lossy[mi] && floor_j[pi] >= e_min)) {  // as the class loop's skip
      floors[n] = usable[mi] != 1 ? FloatBelow(kInf) : std::max(e_known, FloatBelow(floor_j[pi]));
      continue;
    }
    const MotorParams& mp = mps[mi];
    const double vehicle_kg = base_kg - inner_lightest_kg_[o] + kg;
    double e_pair = kInf;  // the least over the classes (a skipped class: its floor)
    for (std::size_t c : classes) {
      const EscClass& cls = escs_.classes[c];
      if (DriveIsLossy(mp, cls.c1, cls.c0) && floor_j[pi] >= e_min) {
        e_pair = std::min(e_pair, floor_j[pi]);
        continue;
      }
      // SegmentPowerBound reads the ESC's C1 and C0 for a free-airspeed cruise
      // (FreeCruisePowerLowerBoundW): a member's, as MinFreeGroupPower does.
      const EscEntry& member = cat_.escs()[static_cast<std::size_t>(cls.members.front())];
      const GroupParts parts{&mo, &member, &props[pi]};
      const Drive d(mp, ZeroResistanceEsc(cls));
      if (!ReachesThrustToWeight(inner_, d, static_cast<int>(pi), vehicle_kg, o)) continue;
      double e = 0;
      for (std::size_t si : segs) {
        const RotorBound& rb = OuterRotor(static_cast<int>(pi), si, o, vehicle_kg);
        const SegmentBound b = SegmentPowerBound(m_, si, parts, mp, d, ThrottleLimit(m_.constraints, cls.tr_sat), kInf,
                                                 *models_[pi], bo, vehicle_kg, rb);
        if (b.infeasible) {
          e = kInf;
          break;
        }
        e += b.power_w * t_min(si);
      }
      e_pair = std::min(e_pair, e);
      if (e < e_min) {
        e_min = e;
        front.push_back(FrontierPoint{kg - inner_lightest_kg_[o], e});
      }
    }
    floors[n] = std::max(e_known, FloatBelow(e_pair));
  }
  std::vector<std::vector<std::uint16_t>>& levels = inner_floors_[o];
  std::vector<std::uint16_t>& kept = levels[static_cast<std::size_t>(level)];
  kept.resize(floors.size());
  for (std::size_t n = 0; n < floors.size(); ++n) kept[n] = CodeOfFloor(floors[n]);
  // At most kKeptFloorLevels besides level 0: the one nearest above the kept level below it is
  // dropped (a level that reads from below reads that one's instead, a bound too).
  int count = 0, drop = -1, gap = kFrontierLevels, below_level = 0;
  for (int j = 1; j < kFrontierLevels; ++j) {
    if (levels[static_cast<std::size_t>(j)].empty()) continue;
    ++count;
    if (j - below_level < gap) {
      gap = j - below_level;
      drop = j;
    }
    below_level = j;
  }
  if (count > kKeptFloorLevels && drop > 0) std::vector<std::uint16_t>().swap(levels[static_cast<std::size_t>(drop)]);
  return front;
}

// G2: the least power bound over the group's (motor, ESC class, propeller) choices that survive
// R0, R1, R3 and R7 at this segment, at the lightest vehicle mass (M3: every heavier one draws
// no less). Propellers in order of their floor, rotors*max(Q*omega, momentum) + P_avionics (PDC
// >= Pmech for a drive that cannot create energy; SegmentPowerBound): once the floor reaches the least bound found, no energy-
// conserving drive on that propeller or a later one can go below it; drives that could create
// energy are checked on every propeller.
double JointBounds::MinFreeGroupPower(int group, std::size_t si, std::size_t o, double mass_kg) {
  const Mission& m = m_;
  const Segment& sg = m.segments[si];
  const BatteryOption& bo = options_[o];
  const auto& props = cat_.props();
  const auto& motors = cat_.motors();
  const std::vector<EscClass>& classes = escs_.classes;
  struct Cand {
    MotorParams mp;
    Drive drive;
    int cls;
    bool lossy;
    const MotorEntry* motor;
  };
  std::vector<Cand> cands;
  for (const MotorEntry& mo : motors) {
    if (!mo.exclude_reason.empty() || !mo.mass_kg) continue;
    bool excluded = false;
    const MotorParams mp = ScenarioMotorParams(mo, m, nullptr, &excluded);
    if (Lifts(group) && (excluded || bo.v_full > MotorMaxVoltageV(mo))) continue;  // R0, R1
    for (std::size_t c = 0; c < classes.size(); ++c) {
      if (escs_.per_option[o][c].empty()) continue;  // R1
      cands.push_back(Cand{mp, Drive(mp, ZeroResistanceEsc(classes[c])), static_cast<int>(c),
                           DriveIsLossy(mp, classes[c].c1, classes[c].c0), &mo});
    }
  }
  double best = kInf;
  if (sg.type == SegmentType::kCruise && sg.airspeed_m_s.free()) {
    // FreeCruisePowerLowerBoundW: momentum theory when the drive cannot create energy (the
    // class's catalog C0 is at most any scenario's), else none.
    for (const Cand& c : cands) {
      if (!c.lossy) return m.vehicle.avionics_power_w;
    }
    for (std::size_t pi = 0; pi < props.size(); ++pi) {
      if (!PropAllowed(group, props[pi]) || cands.empty()) continue;
      const Cand& c = cands.front();
      const GroupParts parts{c.motor, &cat_.escs()[static_cast<std::size_t>(classes[c.cls].members.front())], &props[pi]};
      best = std::min(best, m.vehicle.avionics_power_w + FreeCruisePowerLowerBoundW(m, sg, parts, *models_[pi], mass_kg));
    }
    return best;
  }
  if (sg.type == SegmentType::kShaft) return m.vehicle.avionics_power_w;
  struct PropFloor {
    double floor;
    std::size_t prop;
    RotorBound rb;
  };
  std::vector<PropFloor> floors;
  for (std::size_t pi = 0; pi < props.size(); ++pi) {
    if (!PropAllowed(group, props[pi])) continue;
    RotorBound rb = RotorLowerBound(m, sg, props[pi], *models_[pi], mass_kg);
    if (!(rb.omega_rad_s > 0)) return m.vehicle.avionics_power_w;  // no bound for this choice
    const bool static_only = models_[pi]->data_kind() != PropDataKind::kTables || props[pi].j_tables.empty();
    const double p_ideal = IdealRotorPowerW(rb.thrust_n, props[pi].diameter_m, m.rho_kg_m3,
                                            static_only ? 0.0 : rb.axial_airspeed_m_s);
    const double floor_w = std::max(rb.torque_nm * rb.omega_rad_s, p_ideal / std::max(1.0, m.constraints.max_figure_of_merit));
    floors.push_back({m.vehicle.avionics_power_w + rb.rotors * floor_w, pi, rb});
  }
  std::sort(floors.begin(), floors.end(), [](const PropFloor& a, const PropFloor& b) {
    return a.floor != b.floor ? a.floor < b.floor : a.prop < b.prop;
  });
  for (const PropFloor& f : floors) {
    const bool lossy_done = f.floor >= best;
    const GroupParts parts{nullptr, nullptr, &props[f.prop]};
    for (const Cand& c : cands) {
      if (lossy_done && c.lossy) continue;
      if (!ReachesThrustToWeight(group, c.drive, static_cast<int>(f.prop), mass_kg, o)) continue;
      const double tr_max = ThrottleLimit(m.constraints, classes[c.cls].tr_sat);
      const SegmentBound b = SegmentPowerBound(m, si, parts, c.mp, c.drive, tr_max, kInf, *models_[f.prop], bo,
                                               mass_kg, f.rb);
      if (!b.infeasible) best = std::min(best, b.power_w);
    }
  }
  return best;
}

}  // namespace dynosize::search_internal
