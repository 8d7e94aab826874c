#include "common/json_pretty.h"

namespace dynosize {
namespace {

bool AllScalars(const Json& array) {
  for (const auto& e : array) {
    if (e.is_structured()) return false;
  }
  return true;
}

void Write(const Json& v, int indent, int depth, std::string* out) {
  const std::string pad(static_cast<std::size_t>(indent * (depth + 1)), ' ');
  const std::string close_pad(static_cast<std::size_t>(indent * depth), ' ');
  if (v.is_object() && !v.empty()) {
    *out += "{\n";
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      if (!first) *out += ",\n";
      first = false;
      *out += pad + Json(it.key()).dump() + ": ";
      Write(it.value(), indent, depth + 1, out);
    }
    *out += "\n" + close_pad + "}";
  } else if (v.is_array() && !v.empty() && !AllScalars(v)) {
    *out += "[\n";
    bool first = true;
    for (const auto& e : v) {
      if (!first) *out += ",\n";
      first = false;
      *out += pad;
      Write(e, indent, depth + 1, out);
    }
    *out += "\n" + close_pad + "]";
  } else if (v.is_array()) {
    *out += "[";
    bool first = true;
    for (const auto& e : v) {
      if (!first) *out += ", ";
      first = false;
      *out += e.dump();
    }
    *out += "]";
  } else {
    *out += v.dump();
  }
}

}  // namespace

std::string DumpJsonReadable(const Json& value, int indent) {
  CheckJsonFinite(value, "JSON output");
  std::string out;
  Write(value, indent, 0, &out);
  return out + "\n";
}

}  // namespace dynosize
