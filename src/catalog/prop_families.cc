#include "catalog/prop_families.h"

#include <algorithm>
#include <set>

#include "common/error.h"

namespace dynosize {

namespace {

// [lo, hi] of two finite numbers, or a problem.
bool ReadRange(const Json& e, const char* key, double* lo, double* hi, std::string* rule) {
  const auto v = e.find(key);
  if (v == e.end()) {
    *rule = "missing (required: [min, max])";
    return false;
  }
  if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number()) {
    *rule = "= " + v->dump() + ": must be [min, max], numbers";
    return false;
  }
  *lo = (*v)[0].get<double>();
  *hi = (*v)[1].get<double>();
  return true;
}

// The entry as a PropSizing; "" when valid, else the first problem (key and rule).
std::string ReadOne(const Json& e, PropSizing* s) {
  static const std::set<std::string> kKeys = {"id", "name", "family", "diameter_m", "pitch_ratio", "blades", "source"};
  for (auto k = e.begin(); k != e.end(); ++k) {
    if (kKeys.count(k.key()) == 0) return "key '" + k.key() + "': unknown key for a propeller family";
  }
  for (const char* key : {"id", "name", "family"}) {
    const auto v = e.find(key);
    if (v == e.end() || !v->is_string() || v->get<std::string>().empty()) {
      return std::string("key '") + key + "': required, a non-empty string";
    }
  }
  s->id = e["id"].get<std::string>();
  s->family = e["family"].get<std::string>();
  std::string rule;
  if (!ReadRange(e, "diameter_m", &s->diameter_min_m, &s->diameter_max_m, &rule)) return "key 'diameter_m' " + rule;
  if (!ReadRange(e, "pitch_ratio", &s->pitch_ratio_min, &s->pitch_ratio_max, &rule)) return "key 'pitch_ratio' " + rule;
  const auto b = e.find("blades");
  if (b == e.end() || !b->is_array() || b->empty()) return "key 'blades': required, an array of blade counts";
  for (const Json& x : *b) {
    if (!x.is_number_integer()) return "key 'blades' = " + b->dump() + ": must hold integers";
    s->blades.push_back(x.get<int>());
  }
  const auto src = e.find("source");
  if (src == e.end() || !src->is_object() || !src->contains("dataset") || !(*src)["dataset"].is_string()) {
    return "key 'source': required, an object with \"dataset\" (and optionally \"reference\", \"note\")";
  }
  for (auto k = src->begin(); k != src->end(); ++k) {
    if (k.key() != "dataset" && k.key() != "reference" && k.key() != "note") {
      return "key 'source." + k.key() + "': unknown (allowed: dataset, reference, note)";
    }
    if (!k.value().is_string()) return "key 'source." + k.key() + "': must be a string";
  }
  s->source = (*src)["dataset"].get<std::string>();
  if (src->contains("reference")) s->source += "; " + (*src)["reference"].get<std::string>();
  try {
    CheckPropSizing(*s);
  } catch (const UsageError& err) {
    return err.what();
  }
  return "";
}

}  // namespace

void ReadPropFamilies(const Json& arr, const std::string& file, std::vector<PropSizing>* out,
                      std::vector<std::string>* problems) {
  if (!arr.is_array()) {
    problems->push_back(file + ": \"prop_families\" must be an array");
    return;
  }
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const Json& e = arr[i];
    std::string where = file + ": prop_families[" + std::to_string(i) + "]";
    if (!e.is_object()) {
      problems->push_back(where + ": must be an object, found " + e.dump());
      continue;
    }
    if (e.contains("id") && e["id"].is_string()) where += " id=" + e["id"].get<std::string>();
    PropSizing s;
    const std::string problem = ReadOne(e, &s);
    if (!problem.empty()) {
      problems->push_back(where + ": " + problem);
      continue;
    }
    const bool repeated = std::any_of(out->begin(), out->end(), [&](const PropSizing& f) { return f.id == s.id; });
    if (repeated) {
      problems->push_back(where + ": key 'id': repeats an earlier propeller family's id");
      continue;
    }
    out->push_back(std::move(s));
  }
}

}  // namespace dynosize
