#include "common/json_file.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "common/error.h"
#include "common/text_file.h"

namespace dynosize {

namespace {

std::string LineColumn(const std::string& text, std::size_t byte) {
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

void CheckFiniteRec(const Json& v, const std::string& path, const std::string& what) {
  if (v.is_number_float() && !std::isfinite(v.get<double>())) {
    throw InternalError(what + ": " + (path.empty() ? "/" : path) +
                        " is not a finite number; refusing to write it");
  }
  if (v.is_object()) {
    for (auto it = v.begin(); it != v.end(); ++it) CheckFiniteRec(*it, path + "/" + it.key(), what);
  } else if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i) CheckFiniteRec(v[i], path + "/" + std::to_string(i), what);
  }
}

}  // namespace

Json ParseJsonText(const std::string& text, const std::string& name,
                   const JsonReadOptions& options) {
  if (text.size() > options.max_bytes) {
    throw DataError(name + ": " + std::to_string(text.size()) + " bytes: larger than the " +
                    std::to_string(options.max_bytes) + "-byte limit for a JSON input");
  }
  // Keys seen in each open object, to refuse duplicates (nlohmann keeps the last silently).
  std::vector<std::set<std::string>> open_objects;
  std::string error;
  auto callback = [&](int depth, nlohmann::detail::parse_event_t event, Json& parsed) {
    using E = nlohmann::detail::parse_event_t;
    if (!error.empty()) return false;
    if (depth > options.max_depth) {
      error = "nesting deeper than " + std::to_string(options.max_depth) + " levels";
      throw DataError(name + ": " + error);
    }
    if (event == E::object_start) open_objects.emplace_back();
    if (event == E::object_end && !open_objects.empty()) open_objects.pop_back();
    if (event == E::key && !open_objects.empty()) {
      const std::string key = parsed.get<std::string>();
      if (!open_objects.back().insert(key).second) {
        throw DataError(name + ": duplicate key \"" + key + "\" in one object");
      }
    }
    if (event == E::value && parsed.is_number_float() && !std::isfinite(parsed.get<double>())) {
      throw DataError(name + ": a number out of the range of a double (" + parsed.dump() +
                      "): numbers must be finite");
    }
    return true;
  };
  try {
    return Json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/false);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() is "[json.exception.parse_error.101] parse error at line L, column C: ...".
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw DataError(name + ":" + LineColumn(text, e.byte > 0 ? e.byte - 1 : 0) +
                    ": invalid JSON: " + what);
  } catch (const nlohmann::json::exception& e) {
    // Number overflow (1e999) and similar: no byte position is given.
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw DataError(name + ": invalid JSON: " + what);
  }
}

Json ReadJsonFile(const std::string& path, const JsonReadOptions& options) {
  return ParseJsonText(ReadTextFile(path, options.max_bytes), path, options);
}

std::string DumpJson(const Json& value, int indent) {
  CheckJsonFinite(value, "JSON output");
  return value.dump(indent) + "\n";
}

void CheckJsonFinite(const Json& value, const std::string& what) {
  CheckFiniteRec(value, "", what);
}

}  // namespace dynosize
