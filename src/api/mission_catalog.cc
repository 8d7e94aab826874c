#include "api/mission_catalog.h"

#include <algorithm>
#include <set>
#include <string>

#include "common/error.h"
#include "common/worker_threads.h"
#include "importers/sized_prop.h"

namespace dynosize::api {

MissionCatalog::MissionCatalog(const Catalog& base, const Mission& mission, int threads)
    : MissionCatalog(base, std::vector<Mission>{mission}, threads) {}

MissionCatalog::MissionCatalog(const Catalog& base, const std::vector<Mission>& missions, int threads)
    : base_(&base) {
  std::vector<PropSize> todo;
  std::set<std::string> ids;
  for (const PropEntry& p : base.props()) {
    if (IsSizedPropId(p.id)) ids.insert(p.id);
  }
  std::string file;
  for (const Mission& m : missions) {
    file = m.file;
    for (int g = 0; g < GroupCount(m); ++g) {
      for (const PropSize& s : OfferedSizes(m, base.prop_families(), g)) {
        if (ids.insert(SizedPropId(s)).second) todo.push_back(s);
      }
      if (todo.size() > static_cast<std::size_t>(kMaxSizedPropsPerMission)) {
        throw DataError(m.file + (m.groups.empty() ? ": $.vehicle" : ": $.propulsion." + GroupName(m, g)) +
                        ": the propeller sizing offers more than " + std::to_string(kMaxSizedPropsPerMission) +
                        " sizes (each a blade-element run): narrow its diameter or pitch ratio ranges or blade counts");
      }
    }
  }
  if (todo.empty()) return;
  std::vector<Json> entries(todo.size());
  ForEachOnThreads(todo.size(), std::max(1, threads), [&](int, std::size_t i) { entries[i] = SizedPropJson(todo[i]); });
  Json props = Json::array();
  for (Json& e : entries) props.push_back(std::move(e));
  owned_ = std::make_unique<Catalog>(base);
  std::vector<std::string> problems;
  owned_->AddDocument(Json{{"props", props}}, file + " (sized propellers)", &problems);
  if (!problems.empty()) throw DataError(problems.front());
  added_ = static_cast<int>(todo.size());
}

}  // namespace dynosize::api
