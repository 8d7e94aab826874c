// Reading JSON input files strictly: one place for size limits, nesting limits, duplicate keys
// and error positions (file:line:column), shared by the catalog and mission readers.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace dynosize {

using Json = nlohmann::ordered_json;  // key order as written in the file

struct JsonReadOptions {
  std::size_t max_bytes = 64u << 20;  // refuse larger files before parsing (64 MiB)
  int max_depth = 32;                 // refuse deeper nesting (catalogs need 5)
};

// Parses `path`. Throws NoInputError when it cannot be opened, DataError naming
// file:line:column for a syntax error, a duplicate key, too deep nesting, a non-finite number
// (1e999) or a file over the size limit.
Json ReadJsonFile(const std::string& path, const JsonReadOptions& options = {});

// Same rules for text already in memory; `name` is used in messages.
Json ParseJsonText(const std::string& text, const std::string& name,
                   const JsonReadOptions& options = {});

// Serialises with two-space indentation and a final newline; throws InternalError when a number
// is not finite (nlohmann would silently write null).
std::string DumpJson(const Json& value, int indent = 2);

// Throws InternalError if any number in `value` is NaN or infinite; `what` names the document.
void CheckJsonFinite(const Json& value, const std::string& what);

// The output contract for a value that may be missing (a standard error of a held parameter, an
// error median over no points): the number when finite, else JSON null - never NaN.
inline Json NumberOrNull(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace dynosize
