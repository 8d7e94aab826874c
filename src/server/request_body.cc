#include "server/request_body.h"

#include <algorithm>

#include "common/error.h"

namespace dynosize::server {

namespace {

// The size is held by the server before the body is read (ServeOptions::max_body_bytes); this
// is the parser's own bound above it.
constexpr std::size_t kMaxBodyBytes = 64u << 20;

}  // namespace

RequestBody::RequestBody(const std::string& text, const std::string& route, std::vector<std::string> valid)
    : route_(route) {
  JsonReadOptions o;
  o.max_bytes = kMaxBodyBytes;
  doc_ = ParseJsonText(text, route + " request body", o);
  if (!doc_.is_object()) throw UsageError(route + ": the request body must be a JSON object");
  std::sort(valid.begin(), valid.end());
  for (auto it = doc_.begin(); it != doc_.end(); ++it) {
    if (std::binary_search(valid.begin(), valid.end(), it.key())) continue;
    std::string list;
    for (const auto& v : valid) list += (list.empty() ? "" : ", ") + v;
    throw UsageError(route + ": unknown key '" + it.key() + "' (valid: " + list + ")");
  }
}

const Json* RequestBody::Find(const char* key) const {
  const auto it = doc_.find(key);
  return it == doc_.end() || it->is_null() ? nullptr : &*it;
}

std::optional<double> RequestBody::Number(const char* key) const {
  const Json* v = Find(key);
  if (!v) return std::nullopt;
  if (!v->is_number()) throw UsageError(Where(key) + " " + v->dump() + ": must be a number");
  return v->get<double>();
}

std::optional<long long> RequestBody::Integer(const char* key) const {
  const Json* v = Find(key);
  if (!v) return std::nullopt;
  if (!v->is_number_integer()) throw UsageError(Where(key) + " " + v->dump() + ": must be an integer");
  return v->get<long long>();
}

std::string RequestBody::Text(const char* key) const {
  const Json* v = Find(key);
  if (!v) return "";
  if (!v->is_string()) throw UsageError(Where(key) + " " + v->dump() + ": must be a string");
  return v->get<std::string>();
}

bool RequestBody::Flag(const char* key) const {
  const Json* v = Find(key);
  if (!v) return false;
  if (!v->is_boolean()) throw UsageError(Where(key) + " " + v->dump() + ": must be true or false");
  return v->get<bool>();
}

std::vector<double> RequestBody::Numbers(const char* key) const {
  const Json* v = Find(key);
  std::vector<double> out;
  if (!v) return out;
  if (!v->is_array()) throw UsageError(Where(key) + ": must be an array of numbers");
  for (const auto& x : *v) {
    if (!x.is_number()) throw UsageError(Where(key) + " " + x.dump() + ": must be a number");
    out.push_back(x.get<double>());
  }
  return out;
}

std::vector<std::string> RequestBody::Texts(const char* key) const {
  const Json* v = Find(key);
  std::vector<std::string> out;
  if (!v) return out;
  if (!v->is_array()) throw UsageError(Where(key) + ": must be an array of strings");
  for (const auto& x : *v) {
    if (!x.is_string()) throw UsageError(Where(key) + " " + x.dump() + ": must be a string");
    out.push_back(x.get<std::string>());
  }
  return out;
}

Mission RequestBody::MissionOf() const {
  const Json* v = Find("mission");
  if (!v) throw UsageError(route_ + ": the key 'mission' is required (the mission file's content)");
  if (!v->is_object()) throw UsageError(Where("mission") + ": must be a JSON object (the mission file's content)");
  return ParseMission(*v, "mission");
}

}  // namespace dynosize::server
