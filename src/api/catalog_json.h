// `catalog list --json` and `catalog show` as library calls (the CLI, apps/cmd_catalog.cc, and the
// Python module's Catalog, python/, share them).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"

namespace dynosize::api {

// The filters of `catalog list`: a kind ("" = all, else motors | escs | props | batteries) and
// ranges; an entry without the filtered value does not pass.
struct CatalogListRequest {
  std::string kind;
  std::optional<double> kv_min, kv_max, mass_max_kg, current_min_a;
};

// Throws UsageError (the CLI's flags named) for a negative or non-finite bound, an empty Kv
// range, or Kv filters on another kind.
void CheckCatalogListRequest(const CatalogListRequest& o);
bool PassesListFilters(const CatalogListRequest& o, const Json& entry);

// The entries of one kind that pass the filters, in catalog order (the JSON list and the CLI's
// text table both read them).
template <typename Entry>
std::vector<const Entry*> SelectForList(const std::vector<Entry>& entries, const CatalogListRequest& o) {
  std::vector<const Entry*> out;
  for (const auto& e : entries) {
    if (PassesListFilters(o, e.json)) out.push_back(&e);
  }
  return out;
}

// {kind: [entries as catalog JSON objects]} (catalog list --json).
Json CatalogListJson(const Catalog& cat, const CatalogListRequest& o);

// One entry with its derived SI parameters (catalog show). Throws UsageError for an unknown id.
Json CatalogShowJson(const Catalog& cat, const std::string& id);

}  // namespace dynosize::api
