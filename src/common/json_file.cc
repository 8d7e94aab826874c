#include "common/json_file.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "common/error.h"
#include "common/text_encoding.h"
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
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw DataError(name + ": empty file: expected a JSON object");
  }
  if (const std::string enc = UnsupportedTextEncoding(std::string_view(text).substr(0, 64));
      !enc.empty()) {
    throw DataError(name + ": the file is " + enc + ": save it as UTF-8");
  }
  // The open containers, to name the JSON path in messages and to refuse duplicate keys
  // (nlohmann keeps the last silently). The stack is bounded by max_depth.
  struct Frame {
    bool array = false;
    std::size_t index = 0;   // arrays: the element being read
    std::string key;         // objects: the key being read
    std::set<std::string> keys;
  };
  std::vector<Frame> open;
  auto path = [&open]() {
    std::string p;
    for (const Frame& f : open) p += "/" + (f.array ? std::to_string(f.index) : f.key);
    return p.empty() ? std::string("/") : p;
  };
  auto element_done = [&open]() {
    if (!open.empty() && open.back().array) ++open.back().index;
  };
  auto callback = [&](int depth, nlohmann::detail::parse_event_t event, Json& parsed) {
    using E = nlohmann::detail::parse_event_t;
    if (depth > options.max_depth) {
      throw DataError(name + ": " + path() + ": nesting deeper than " +
                      std::to_string(options.max_depth) + " levels (rule: catalogs and missions "
                      "need far fewer)");
    }
    switch (event) {
      case E::object_start:
      case E::array_start:
        open.emplace_back();
        open.back().array = event == E::array_start;
        break;
      case E::object_end:
      case E::array_end:
        if (!open.empty()) open.pop_back();
        element_done();
        break;
      case E::key: {
        std::string key = parsed.get<std::string>();
        if (!open.empty()) {
          if (!open.back().keys.insert(key).second) {
            throw DataError(name + ": " + path() + ": duplicate key \"" + key +
                            "\" (rule: each key once per object)");
          }
          open.back().key = std::move(key);
        }
        break;
      }
      case E::value:
        if (parsed.is_number_float() && !std::isfinite(parsed.get<double>())) {
          throw DataError(name + ": " + path() + ": a number out of the range of a double (" +
                          parsed.dump() + "): numbers must be finite");
        }
        element_done();
        break;
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
    throw DataError(name + ":" + LineColumn(text, e.byte > 0 ? e.byte - 1 : 0) + ": " + path() +
                    ": invalid JSON: " + what);
  } catch (const nlohmann::json::exception& e) {
    // Number overflow (1e999) and similar: no byte position is given.
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw DataError(name + ": " + path() + ": invalid JSON: " + what +
                    " (rule: numbers must be finite doubles)");
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
