// The propeller audit applied by every importer of non-measured propellers (import_common.h).
#include <cstdio>

#include "importers/importers.h"

namespace dynosize {

namespace {
constexpr std::size_t kMaxDeratedExamples = 3;
}

void KeepAuditedProp(Json entry, const std::string& example, ImportedDataset* out) {
  const PropAudit a = AuditProp(&entry);
  if (a.refused) {
    out->report.Drop("props", "beats momentum theory in its valid range (FM > 1)",
                     example + ": " + a.why);
    return;
  }
  if (a.derated) {
    ++out->report.props_derated;
    if (out->report.derated_examples.size() < kMaxDeratedExamples) {
      char buf[120];
      std::snprintf(buf, sizeof buf, " FM %.3f -> %.3f (x%.3g power)", a.fm_max, a.envelope_max,
                    a.factor);
      out->report.derated_examples.push_back(entry["id"].get<std::string>() + buf);
    }
  }
  out->props.push_back(std::move(entry));
  out->report.Keep("props");
}

}  // namespace dynosize
