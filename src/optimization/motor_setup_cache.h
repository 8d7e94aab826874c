// Stage 4's motor set-up (pair_candidates.h, SetUpMotors) kept between the one-group searches
// of the joint search. Of what MotorSetUp reads, none is the outer group's choice or the
// cutoff: the catalog's motors and propeller count, the mission's ranking and
// estimate_unrated_motors (ScenarioMotorParams), whether the free group lifts and R0's
// propeller counts (StageFourFacts), and the battery options' full-charge voltages, the ESC
// classes and the ESCs each option rates (stages 1-2). An entry is reused only when all of
// these are equal, so a different option, ESC table or mission sets the motors up afresh.
// Internal to src/optimization (and its tests).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "optimization/pair_candidates.h"
#include "optimization/rule_counts.h"
#include "optimization/search_stages.h"

namespace dynosize::search_internal {

// What SetUpMotors reads that may differ between searches sharing a cache.
struct MotorSetupKey {
  const Catalog* catalog = nullptr;
  DataScenario ranking = DataScenario::kCredible;
  bool estimate_unrated = false, free_lifts = false;
  std::vector<std::pair<std::string, long long>> prop_frame_counts;
  std::vector<double> v_full;                   // per option
  std::vector<long long> rated;                 // per option
  std::vector<std::vector<double>> esc_classes;  // per class: c1, c0, tr_sat, sat_slope
  bool operator==(const MotorSetupKey& o) const;
};
MotorSetupKey MotorSetupKeyOf(const SearchContext& ctx, const MissionFacts& f);

struct MotorSetupCache::Entry {
  MotorSetupKey key;
  std::vector<std::unique_ptr<MotorSetup>> setups;  // SetUpMotors'
  RuleCounts pruned;                                // its counts, added again on each reuse
  long long skipped = 0;
};

// SetUpMotors for ctx: ctx.motor_setups' entry with this key when there is one, else set up
// on `threads` threads (and stored in ctx.motor_setups when set).
std::shared_ptr<const MotorSetupCache::Entry> CachedMotorSetups(const SearchContext& ctx, const MissionFacts& f,
                                                                int threads);

}  // namespace dynosize::search_internal
