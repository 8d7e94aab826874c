// `dynosize diagnose LOG`: what the first-order model gets wrong in a measured log, the named
// cause, the extended model and the cross-validated gain (src/diagnosis/diagnose.h).
#include <cctype>
#include <cmath>
#include <optional>
#include <sstream>
#include <iostream>

#include <filesystem>

#include "api/diagnose.h"
#include "calibration/catalog_output.h"
#include "catalog/catalog.h"
#include "commands.h"
#include "common/error.h"
#include "common/json_file.h"
#include "diagnosis/diagnose.h"
#include "logs/log_reader.h"
#include "report/diagnosis_figures.h"

namespace dynosize::cli {

namespace {

using diagnosis::CauseId;


// A catalog id from a file name: [A-Za-z0-9_.+-] kept, anything else '_'.
std::string IdFrom(const std::string& path) {
  std::string stem = std::filesystem::path(path).stem().string();
  for (char& c : stem) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '+' || c == '-';
    if (!ok) c = '_';
  }
  if (stem.empty()) stem = "diagnosed";
  return stem.substr(0, 100);
}

// The extended model as catalog entries: fitted values say "fitted", values held at a default
// or at the --motor/--esc entry say "assumed", KT tied to KE says "derived".
void WriteExtendedEntries(const DiagnoseCliOptions& o, const diagnosis::DiagnoseResult& r) {
  const std::string id = o.id.empty() ? IdFrom(o.log) : o.id;
  auto fitted = [&](const std::string& key) {
    for (const auto& f : r.base_free_parameters) {
      if (f == key) return true;
    }
    for (const auto& f : r.findings) {
      if (f.parameters.count(key)) return true;
    }
    return false;
  };
  std::ostringstream ref;
  ref << "dynosize diagnose (" << r.mode << "), " << r.points_used << " points; findings:";
  for (const auto& f : r.findings) ref << " " << CauseId(f.cause);
  if (r.findings.empty()) ref << " none";
  auto method = [&](const std::string& key) -> std::string {
    if (key == "kt_nm_per_a" && !fitted(key)) return "derived";
    return fitted(key) ? "fitted" : "assumed";
  };
  std::vector<calibration::EntryValue> mv = {{"type", 0.0, "assumed",
                                              r.extended_motor.type == MotorType::kBldc ? "bldc" : "brushed"}};
  const Json motor = api::MotorValuesJson(r.extended_motor);
  for (auto it = motor.begin(); it != motor.end(); ++it) {
    if (it.key() != "type") mv.push_back({it.key(), it.value().get<double>(), method(it.key()), ""});
  }
  std::vector<calibration::EntryValue> ev;
  const Json esc = api::EscValuesJson(r.extended_esc);
  for (auto it = esc.begin(); it != esc.end(); ++it) ev.push_back({it.key(), it.value().get<double>(), method(it.key()), ""});
  calibration::EntryProvenance prov;
  prov.dataset = std::filesystem::path(o.log).filename().string();
  prov.reference = ref.str();
  std::string note;
  for (const auto& w : r.warnings) note += (note.empty() ? "" : "; ") + w;
  const Json m = calibration::ComponentEntryJson(id + "_motor", id + " motor (diagnosed, extended model)", mv, prov,
                                                 note, "motor");
  const Json e = calibration::ComponentEntryJson(id + "_esc", id + " ESC (diagnosed, extended model)", ev, prov,
                                                 note, "ESC");
  calibration::WriteCatalogEntries(o.out, {m}, {e}, o.force,
                                   "Extended models fitted by dynosize diagnose from dynamometer logs.");
  if (!o.json) std::cerr << "wrote " << id << "_motor, " << id << "_esc to " << o.out << "\n";
}

// --out writes the extended model only when its status is ok (the same rule as calibrate):
// otherwise exit 65 with one line naming the failed check, and the file is not touched.
void WriteIfOk(const DiagnoseCliOptions& o, const diagnosis::DiagnoseResult& r) {
  if (o.out.empty()) return;
  if (r.verdict.status != identification::Status::kOk) {
    const identification::Check* c = r.verdict.FirstFailed();
    std::ostringstream m;
    m << o.log << ": " << o.out << " not written: status " << identification::StatusName(r.verdict.status);
    if (c != nullptr) m << ", check " << c->name << " failed (" << c->value << " vs limit " << c->limit << ")";
    throw DataError(m.str());
  }
  WriteExtendedEntries(o, r);
}

}  // namespace

int RunDiagnose(const DiagnoseCliOptions& o) {
  const api::DiagnoseRequest request{o.log, o.motor_id, o.esc_id, o.input, o.folds, o.alpha, o.kv_label};
  const logs::LogReadOptions ro = api::ToLogReadOptions(o.input);
  api::CheckDiagnoseRequest(request);
  std::optional<Catalog> cat;
  if (!o.motor_id.empty() || !o.esc_id.empty()) cat = Catalog::Load(o.catalog);
  const diagnosis::DiagnoseOptions opt = api::DiagnoseOptionsOf(request, cat ? &*cat : nullptr);
  const logs::SteadyTable table = logs::ReadLog(o.log, ro);
  const std::string no_throttle = api::MissingThrottleLine(table);
  if (!o.json && !no_throttle.empty()) std::cerr << no_throttle << "\n";
  if (!o.json) std::cerr << table.BriefReport() << "\n";
  const diagnosis::DiagnoseResult r = diagnosis::Diagnose(table, opt);
  if (!o.plot_dir.empty()) {
    for (const auto& f : WriteDiagnosisFigures(o.plot_dir, table, r)) {
      if (!o.json) std::cerr << "wrote " << f << "\n";
    }
  }
  if (!o.json) {
    std::cout << r.FullReport();
    WriteIfOk(o, r);
    return 0;
  }
  std::cout << DumpJson(api::DiagnoseJson(r, no_throttle));
  WriteIfOk(o, r);
  return 0;
}

}  // namespace dynosize::cli
