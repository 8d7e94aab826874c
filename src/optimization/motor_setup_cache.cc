// Stage 4's motor set-up kept between searches (motor_setup_cache.h).
#include "optimization/motor_setup_cache.h"

#include <memory>
#include <string>
#include <vector>

namespace dynosize::search_internal {

bool MotorSetupKey::operator==(const MotorSetupKey& o) const {
  return catalog == o.catalog && ranking == o.ranking && estimate_unrated == o.estimate_unrated &&
         free_lifts == o.free_lifts && prop_frame_counts == o.prop_frame_counts && v_full == o.v_full &&
         rated == o.rated && esc_classes == o.esc_classes;
}

MotorSetupKey MotorSetupKeyOf(const SearchContext& ctx, const MissionFacts& f) {
  MotorSetupKey k;
  k.catalog = ctx.catalog;
  k.ranking = ctx.mission->objective.ranking;
  k.estimate_unrated = ctx.mission->constraints.estimate_unrated_motors;
  k.free_lifts = f.free_lifts;
  for (const auto& [rule, n] : f.prop_frame_counts) k.prop_frame_counts.emplace_back(rule, n);
  for (const BatteryOption& bo : ctx.options) k.v_full.push_back(bo.v_full);
  k.rated = ctx.escs.rated;
  for (const EscClass& c : ctx.escs.classes) k.esc_classes.push_back({c.c1, c.c0, c.tr_sat, c.sat_slope});
  return k;
}

std::shared_ptr<const MotorSetupCache::Entry> CachedMotorSetups(const SearchContext& ctx, const MissionFacts& f,
                                                                int threads) {
  MotorSetupKey key = MotorSetupKeyOf(ctx, f);
  if (ctx.motor_setups) {
    for (const auto& e : ctx.motor_setups->entries) {
      if (e->key == key) return e;
    }
  }
  auto e = std::make_shared<MotorSetupCache::Entry>();
  e->key = std::move(key);
  e->setups = SetUpMotors(ctx, f, threads, &e->pruned, &e->skipped);
  if (ctx.motor_setups) ctx.motor_setups->entries.push_back(e);
  return e;
}

}  // namespace dynosize::search_internal
