// The catalog a mission runs on: the loaded catalog plus the entries of the propellers the mission
// gives by their size alone, so that a fixed group's sized "prop" is found by its id and a searched
// group is offered its sized propellers beside the catalog's: its "sized_props" and the grid of its
// "prop_sizing" families, or of the catalog's prop_families within its max_prop_diameter_m (the
// one rule: mission.h OfferedSizes; the search offers each group its own). evaluate, optimize and
// sweep (the CLI, the Python module and the server) run the mission on it; SearchCatalog refuses a
// mission whose sized propellers its catalog lacks.
#pragma once

#include <memory>
#include <vector>

#include "catalog/catalog.h"
#include "mission/mission.h"

namespace dynosize::api {

// The most sized propellers one catalog may add (each entry is a blade-element run of about 2 ms,
// importers/sized_prop.h): past it, a DataError asks for narrower ranges.
inline constexpr int kMaxSizedPropsPerMission = 3000;

class MissionCatalog {
 public:
  // `base` must outlive this object; it is copied only when the mission offers sized propellers,
  // whose entries are built on `threads` threads.
  MissionCatalog(const Catalog& base, const Mission& mission, int threads = 2);
  // For the points of a sweep: every size any of them offers.
  MissionCatalog(const Catalog& base, const std::vector<Mission>& missions, int threads = 2);
  const Catalog& get() const { return owned_ ? *owned_ : *base_; }
  // How many sized propeller entries were added.
  int sized_props_added() const { return added_; }

 private:
  const Catalog* base_;
  std::unique_ptr<Catalog> owned_;
  int added_ = 0;
};

}  // namespace dynosize::api
