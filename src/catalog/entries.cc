#include "catalog/entries.h"

#include <algorithm>
#include <cstddef>

namespace dynosize {

DataTier MethodTier(const std::string& method) {
  if (method == "measured" || method == "fitted") return DataTier::kMeasured;
  if (method == "computed") return DataTier::kManufacturerComputed;
  if (method == "datasheet" || method == "derived") return DataTier::kManufacturerStated;
  if (method == "estimated") return DataTier::kEstimated;
  return DataTier::kAssumed;
}

std::string ValueMethod(const EntryBase& e, const std::string& key) {
  if (!e.json.is_object()) return "";
  const auto src = e.json.find("source");
  if (src == e.json.end() || !src->is_object()) return "";
  const auto vals = src->find("values");
  if (vals == src->end() || !vals->is_object()) return "";
  const auto m = vals->find(key);
  return m != vals->end() && m->is_string() ? m->get<std::string>() : "";
}

DataTier ValueTier(const EntryBase& e, const std::string& key) {
  const std::string method = ValueMethod(e, key);
  return method.empty() ? e.tier : std::max(MethodTier(method), e.tier);
}

const char* TierName(DataTier tier) {
  return TierNames()[static_cast<std::size_t>(tier)].c_str();
}

const std::vector<std::string>& TierNames() {
  static const std::vector<std::string> kNames = {"measured", "manufacturer_computed",
                                                  "manufacturer_stated", "user_contributed",
                                                  "estimated", "assumed"};
  return kNames;
}

const char* KindArrayName(ComponentKind kind) {
  switch (kind) {
    case ComponentKind::kMotor: return "motors";
    case ComponentKind::kEsc: return "escs";
    case ComponentKind::kProp: return "props";
    case ComponentKind::kBattery: return "batteries";
  }
  return "?";
}

const char* KindNoun(ComponentKind kind) {
  switch (kind) {
    case ComponentKind::kMotor: return "motor";
    case ComponentKind::kEsc: return "ESC";
    case ComponentKind::kProp: return "propeller";
    case ComponentKind::kBattery: return "battery";
  }
  return "?";
}

}  // namespace dynosize
