#include "api/mission_catalog.h"

#include <set>

#include "common/error.h"
#include "importers/sized_prop.h"

namespace dynosize::api {

MissionCatalog::MissionCatalog(const Catalog& base, const Mission& mission) : base_(&base) {
  Json props = Json::array();
  std::set<std::string> ids;
  for (const PropulsionGroup& g : mission.groups) {
    for (const PropSize& s : g.sized_props) {
      const std::string id = SizedPropId(s);
      if (!ids.insert(id).second) continue;
      bool present = false;
      for (const PropEntry& p : base.props()) present = present || p.id == id;
      if (!present) props.push_back(SizedPropJson(s));
    }
  }
  if (props.empty()) return;
  owned_ = std::make_unique<Catalog>(base);
  std::vector<std::string> problems;
  owned_->AddDocument(Json{{"props", props}}, mission.file + " (sized propellers)", &problems);
  if (!problems.empty()) throw DataError(problems.front());
}

}  // namespace dynosize::api
