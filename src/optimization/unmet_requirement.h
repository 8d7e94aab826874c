// One requirement of a mission that no part of the catalog meets on its own (no_design.h
// finds them; the search returns them with an empty result, SearchResult::no_design_because).
// Values are SI (N, W, V, m, J), as `unit` says.
#pragma once

#include <string>
#include <vector>

namespace dynosize {

struct UnmetRequirement {
  // What is required, e.g. "hover_thrust_per_rotor", "controller_voltage" (no_design.h lists
  // every name with its equation).
  std::string requirement;
  // At least what the mission needs (a lower bound, taken at the lightest vehicle the catalog
  // can build), and at most what the best available part(s) can give (an upper bound):
  // needed > best_available proves that no combination meets the requirement.
  double needed = 0.0;
  double best_available = 0.0;
  std::string unit;  // "N", "W", "V", "m" or "J"
  // Catalog ids of the part(s) that give best_available (the mission's limit itself gives it
  // for frame_prop_diameter: empty there).
  std::vector<std::string> components;
  // One line in words: what is compared with what, and where the mission sets it.
  std::string description;
  // The search's pruning rule(s) that remove combinations for the same reason (docs/search.md),
  // comma-separated; "" when no single rule does.
  std::string search_rule;
  std::string group;  // the propulsion group ("" without a "propulsion" key)
};

}  // namespace dynosize
