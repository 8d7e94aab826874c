// The catalog schema: every key an entry may carry, its JSON type, unit (in the name), range and
// meaning. The reader (catalog.cc) checks entries against these tables, and `dynosize catalog
// schema` prints them, so the documentation cannot drift from the rules.
#pragma once

#include <string>
#include <vector>

#include "catalog/entries.h"

namespace dynosize {

enum class ValueType { kNumber, kInteger, kString, kBool, kObject, kArray };

struct KeySpec {
  std::string key;
  ValueType type = ValueType::kNumber;
  bool required = false;
  // Numeric range; the bounds are inclusive unless the *_exclusive flag is set.
  double min = -1e300;
  double max = 1e300;
  bool min_exclusive = false;
  bool max_exclusive = false;
  std::vector<std::string> choices;  // allowed strings, when not empty
  std::string doc;
};

// Keys of one kind, in the order the documentation lists them (common keys first).
const std::vector<KeySpec>& SchemaFor(ComponentKind kind);

// "a number > 0 and <= 10", "one of bldc, brushed", ...
std::string DescribeRule(const KeySpec& spec);

// Values allowed in source.values.
const std::vector<std::string>& ProvenanceMethods();

}  // namespace dynosize
