// Stages 0-3 of the catalog search into a SearchContext (search_stages.h): the propulsion groups
// (G1, docs/search.md#g1) and the stages' tables.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.h"
#include "optimization/components.h"
#include "optimization/search_stages.h"

namespace dynosize::search_internal {

void ResolveGroups(SearchContext* ctx) {
  const Mission& m = *ctx->mission;
  ctx->prop_offer = SizedPropOffer(m, *ctx->catalog);
  ctx->free_group = 0;
  ctx->fixed_parts.clear();
  ctx->fixed_groups_mass_kg = 0;
  if (!m.groups.empty()) {
    std::vector<int> free;
    for (int g = 0; g < GroupCount(m); ++g) {
      // given_parts: the joint search's virtual ESC (G2, as R5's) in place of the catalog entry.
      const bool given = ctx->given_parts && g < static_cast<int>(ctx->given_parts->size()) &&
                         (*ctx->given_parts)[static_cast<std::size_t>(g)].motor;
      ctx->fixed_parts.push_back(given ? (*ctx->given_parts)[static_cast<std::size_t>(g)]
                                       : FixedGroupParts(m, *ctx->catalog, g));
      if (!m.groups[g].fixed()) {
        free.push_back(g);
        continue;
      }
      const GroupParts& p = ctx->fixed_parts.back();
      if (!p.motor->mass_kg) throw DataError("motor '" + p.motor->id + "' has no mass_kg: the mission needs it");
      ctx->fixed_groups_mass_kg += m.groups[g].rotors * (*p.motor->mass_kg + EscMassKg(*p.esc) + PropMassKg(*p.prop));
    }
    if (free.empty()) {
      throw DataError(m.file + ": $.propulsion: every group has its motor, esc and prop: optimize has nothing to "
                      "choose; leave a group's parts out, or use evaluate");
    }
    if (free.size() > 1) {  // SearchCatalog gives such missions to the joint search (G2) instead
      throw std::logic_error("ResolveGroups: the one-group stages need exactly one free group, not " +
                             std::to_string(free.size()));
    }
    ctx->free_group = free.front();
    ctx->fixed_models.resize(m.groups.size());
    ctx->fixed_model_ptrs.assign(m.groups.size(), nullptr);
    for (int g = 0; g < GroupCount(m); ++g) {
      if (g == ctx->free_group) continue;
      ctx->fixed_models[g] = std::make_unique<PropModel>(*ctx->fixed_parts[g].prop);
      ctx->fixed_model_ptrs[g] = ctx->fixed_models[g].get();
    }
  }
  ctx->free_rotors = GroupRotors(m, ctx->free_group);
}

void PrepareStages(const Mission& m, const Catalog& cat, SearchContext* ctx) {
  ctx->mission = &m;
  ctx->catalog = &cat;
  ResolveGroups(ctx);
  ctx->options = BatteryOptions(m, cat);                  // stage 1
  ctx->escs = BuildEscTable(cat, ctx->options);           // stage 2 (R1)
  BuildPropGrids(m, cat, &ctx->grids, &ctx->models);      // stage 3
}

}  // namespace dynosize::search_internal
