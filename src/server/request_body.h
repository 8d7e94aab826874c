// A JSON request body of `dynosize serve` read strictly: the reader of the catalog and missions
// (duplicate keys, nesting depth, non-finite numbers refused), an unknown key an error listing
// the valid ones (sorted), a value of the wrong type an error naming the route and the key.
// null is the same as an absent key.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/json_file.h"
#include "mission/mission.h"

namespace dynosize::server {

class RequestBody {
 public:
  // Throws DataError for text that is not JSON ("<route> request body:line:column: ..."),
  // UsageError for a body that is not an object or holds a key not in `valid`.
  RequestBody(const std::string& text, const std::string& route, std::vector<std::string> valid);

  const Json* Find(const char* key) const;  // null when absent or null
  std::optional<double> Number(const char* key) const;
  std::optional<long long> Integer(const char* key) const;
  std::string Text(const char* key) const;  // "" when absent
  bool Flag(const char* key) const;         // false when absent
  std::vector<double> Numbers(const char* key) const;
  std::vector<std::string> Texts(const char* key) const;
  // The mission: a JSON object with the content of a mission file (read by the mission reader).
  Mission MissionOf() const;
  // "<route>: <key>", the start of an error message about a key.
  std::string Where(const char* key) const { return route_ + ": " + key; }

 private:
  std::string route_;
  Json doc_;
};

}  // namespace dynosize::server
