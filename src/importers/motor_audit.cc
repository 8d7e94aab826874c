// The motor audit applied to every imported data set (importers.h): motors whose motor constant
// no winding of their frame can have are excluded by default (catalog/motor_credibility.h).
#include <cstdio>

#include "catalog/conventions.h"
#include "catalog/motor_credibility.h"
#include "importers/importers.h"

namespace dynosize {

namespace {
constexpr std::size_t kMaxExcludedExamples = 3;

// The DC-circuit resistance of an imported motor entry (catalog/conventions.h): rm_dc_ohm when
// the source stated it, a brushed motor's rm_ohm, else rm_ohm/0.7492.
double DcResistance(const Json& e) {
  if (e.contains("rm_dc_ohm")) return e["rm_dc_ohm"].get<double>();
  if (!e.contains("rm_ohm")) return 0.0;
  const double rm = e["rm_ohm"].get<double>();
  return e.value("type", std::string("bldc")) == "brushed" ? rm : rm / kRmsPerDcResistance;
}
}  // namespace

void ExcludeImplausibleMotors(ImportedDataset* out) {
  std::vector<MotorKmInput> in;
  for (const Json& e : out->motors) {
    const bool user = e.contains("source") && e["source"].value("tier", std::string()) == "user_contributed";
    in.push_back({e.value("name", std::string()), e.value("kv_rpm_per_v", 0.0), DcResistance(e),
                  e.value("mass_kg", 0.0), user});
  }
  const std::vector<FamilyOutlier> outliers = ImplausibleMotorConstants(in);
  std::vector<std::string> examples;
  for (const FamilyOutlier& o : outliers) {
    Json& e = out->motors[o.index];
    const std::string why = FamilyOutlierReason(o);
    // "exclude" before "source", as EntryBuilder writes it; an earlier reason is kept.
    Json source = e["source"];
    e.erase("source");
    e["exclude"] = e.contains("exclude") ? e["exclude"].get<std::string>() + "; " + why : why;
    source["note"] = source.value("note", std::string()) + "; excluded by default: " + why;
    e["source"] = std::move(source);
    if (examples.size() < kMaxExcludedExamples) {
      char buf[64];
      std::snprintf(buf, sizeof buf, " (%.2gx)", o.ratio);
      examples.push_back(e["id"].get<std::string>() + " " + e.value("name", std::string()) + buf);
    }
  }
  if (outliers.empty()) return;
  char head[300];
  std::snprintf(head, sizeof head,
                "%zu motor(s) excluded by default: motor constant KT/sqrt(R) above %gx the median of the other "
                "windings of the same frame, or above %gx the typical value for the motor's mass (R likely "
                "wrong; catalog/motor_credibility.h), e.g.",
                outliers.size(), kFamilyKmRatioMax, kMassKmRatioMax);
  std::string note = head;
  for (const auto& x : examples) note += " " + x + ";";
  note.pop_back();
  out->report.notes.push_back(note);
}

}  // namespace dynosize
