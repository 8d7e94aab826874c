// The catalog a mission runs on: the loaded catalog plus the entries of the propellers the mission
// gives by their size alone (PropulsionGroup::sized_props; importers/sized_prop.h), so that a
// fixed group's sized "prop" is found by its id and a searched group's "sized_props" are offered
// to the search beside the catalog's propellers (within the group's max_prop_diameter_m, as any
// propeller). evaluate, optimize and sweep (the CLI, the Python module and the server) run the
// mission on it; SearchCatalog refuses a mission whose sized propellers its catalog lacks.
#pragma once

#include <memory>

#include "catalog/catalog.h"
#include "mission/mission.h"

namespace dynosize::api {

class MissionCatalog {
 public:
  // `base` must outlive this object; it is copied only when the mission gives sized propellers.
  MissionCatalog(const Catalog& base, const Mission& mission);
  const Catalog& get() const { return owned_ ? *owned_ : *base_; }

 private:
  const Catalog* base_;
  std::unique_ptr<Catalog> owned_;
};

}  // namespace dynosize::api
