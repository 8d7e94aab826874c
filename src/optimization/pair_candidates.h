// Stage 4 of the catalog search (search_stages.h): the motors set up once, the candidate pairs
// with their bounds (pair_bounds.h), and R11's keys for classes of motors (docs/search.md#r11).
// Internal to src/optimization (and its tests).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "common/worker_threads.h"
#include "model/physics.h"
#include "optimization/pair_bounds.h"
#include "optimization/rule_counts.h"
#include "optimization/search_stages.h"

namespace dynosize::search_internal {

// A motor's combinations with the ESCs that pass R0 and R1 (what a motor-level rule removes).
long long CombinationsPerMotor(const SearchContext& ctx);

// What stage 4 reads for each of one motor's pairs, worked out once per motor (MotorSetUp).
struct MotorSetup {
  int motor = 0;
  double mass_kg = 0;
  MotorParams mp;           // the scenario's (credibility.h)
  std::vector<Drive> ideal;  // per ESC class, with no ESC resistance (R3, R4, R7)
  // Per option: R7's largest no-load speed of those drives at full throttle and the option's
  // full-charge voltage; NaN when R1 refuses the option for the motor (motor_voltage).
  std::vector<double> w_nl;
  bool lossy = true;  // every class's drive is lossy (DriveIsLossy): R11 applies
  MotorLossFloor loss;  // R11's loss floor (model/physics.h)
};

// Stage 4 for one pair of a set-up motor whose option R1 lets through and whose propeller
// passed R0: false with its rule counted (its option's ESCs), or true with *c (R4's bound).
// cutoff: only a bound below it is needed (the stream drops a pair at or above it): when the
// pair's bound is below the cutoff *c holds it, else a bound at or above the cutoff (R13's
// pieces are assembled only while they may be below both, docs/search.md#r13).
bool PairCandidate(const SearchContext& ctx, const MissionFacts& f, const MotorSetup& s, std::size_t pi, std::size_t o,
                   PairLoads* loads, Candidate* c, RuleCounts* pruned,
                   double cutoff = std::numeric_limits<double>::infinity());

struct PropKey {
  double bound = 0;  // R11: a lower bound of the score of every pair of the class's motors
  int prop = 0, option = 0;
};

// R11's key of (pi, o) for lossy motors of at least motor_kg whose loss floors are at least
// `loss`'s.
double PropOnlyBound(const SearchContext& ctx, const MissionFacts& f, std::size_t pi, std::size_t o, double motor_kg,
                     const MotorLossFloor& loss, PairLoads* loads);

// R11's class of motors: its lightest mass and its members' least loss floors.
struct MotorClass {
  double mass_kg = 0;
  MotorLossFloor loss;
};

// Every (propeller R0 lets through, option) with R11's key for the motors of class c, sorted
// by (key, option, propeller); with lossy false (motors R11 does not apply to) every key is
// -inf, in option then propeller order.
std::vector<PropKey> ClassKeys(const SearchContext& ctx, const MissionFacts& f, const MotorClass& c, bool lossy);

// R11's classes of the set-up motors (null: skipped or refused): per motor its class, the last
// class (lightest mass 0, no loss floor) for the motors R11 does not apply to (a drive that
// may create energy); and the classes.
std::vector<int> MotorClasses(const std::vector<const MotorSetup*>& setups, std::vector<MotorClass>* classes);

// The motors of a search set up on `threads` threads (null where skipped or refused; the
// counts of SkipMotor and MotorSetUp in *pruned, *skipped).
std::vector<std::unique_ptr<MotorSetup>> SetUpMotors(const SearchContext& ctx, const MissionFacts& f, int threads,
                                                     RuleCounts* pruned, long long* skipped);

std::vector<const MotorSetup*> Pointers(const std::vector<std::unique_ptr<MotorSetup>>& setups);

}  // namespace dynosize::search_internal
