// Counts per pruning rule for the catalog search, without building a string per pruned pair
// (rule names are literals). Internal to src/optimization (and its tests).
#pragma once

#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace dynosize::search_internal {

class RuleCounts {
 public:
  void Add(const char* rule, long long n) {
    for (auto& [name, count] : counts_) {
      if (name == rule || std::strcmp(name, rule) == 0) {  // the same literal: usually the same pointer
        count += n;
        return;
      }
    }
    counts_.emplace_back(rule, n);
  }
  void MergeInto(std::map<std::string, long long>* out) const {
    for (const auto& [name, count] : counts_) (*out)[name] += count;
  }
  void MergeInto(RuleCounts* out) const {
    for (const auto& [name, count] : counts_) out->Add(name, count);
  }

 private:
  std::vector<std::pair<const char*, long long>> counts_;
};

}  // namespace dynosize::search_internal
