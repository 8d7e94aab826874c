#include <filesystem>
#include <functional>
#include <set>

#include "catalog/catalog.h"
#include "common/error.h"
#include "common/text_file.h"
#include "importers/importers.h"

namespace dynosize {

namespace {

struct Importer {
  const char* folder;
  std::function<ImportedDataset(const std::string&)> run;
};

const std::vector<Importer>& Importers() {
  static const std::vector<Importer> kImporters = {
      {"drivecalc", ImportDriveCalc},
      {"uiuc_propdb", ImportUiuc},
      {"apc_per3_subset", ImportApcPer3},
      {"fastuav_catalogues", ImportFastUav},
      {"sjkim_mfr_motor_tables", ImportSjkimTables},
      {"dronebuildcalc_mfr_tables", ImportDroneBuildCalc},
      {"ctu_mrs_motor_tests", ImportCtuMrs},
      {"large_props_apc", ImportApcPer3Large},
      {"heavy_lift_motors", ImportHeavyLiftMotors},
      {"evtol_motors", ImportEvtolMotors},
      {"kde_direct_mfr_sheets", ImportKdeSheetsCatalog},
      {"hv_controllers", ImportHvControllers},
      {"packs_and_cells", ImportPacksAndCells},
  };
  return kImporters;
}

// A motor of an earlier data set that a later one states from the maker's own table (same name,
// same Kv: FAST-UAV's copies fu_m_103-117 of KDE Direct's datasheets, whose mass leaves out the
// wires, against heavy_lift_motors' KDE tables) is excluded by default with the reason: the
// search would otherwise list the same motor twice and prefer the copy for its lighter mass.
void ExcludeCopiesOfMakerTables(std::vector<ImportedDataset>* results) {
  for (std::size_t later = 0; later < results->size(); ++later) {
    const ImportedDataset& maker = (*results)[later];
    if (maker.report.dataset != "heavy_lift_motors") continue;
    for (std::size_t earlier = 0; earlier < later; ++earlier) {
      ImportedDataset& copy = (*results)[earlier];
      std::size_t n = 0;
      for (Json& m : copy.motors) {
        for (const Json& t : maker.motors) {
          if (m["name"] != t["name"] || m["kv_rpm_per_v"] != t["kv_rpm_per_v"] || m.contains("exclude")) continue;
          // "exclude" before "source", as EntryBuilder writes it.
          Json source = m["source"];
          m.erase("source");
          m["exclude"] = "a copy of " + t["id"].get<std::string>() + " (" + maker.report.output_file +
                         ": the maker's own table, with the mass of wires and bullets)";
          source["note"] = source.value("note", std::string()) + "; excluded by default: the maker's table is " +
                           t["id"].get<std::string>();
          m["source"] = std::move(source);
          ++n;
        }
      }
      if (n > 0) {
        copy.report.notes.push_back(std::to_string(n) + " motors excluded by default as copies of the maker's own "
                                    "table in " + maker.report.output_file);
      }
    }
  }
}

}  // namespace

ImportReport ImportAll(const std::string& shared_data_dir, const std::string& out_catalog_dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(shared_data_dir, ec)) {
    throw NoInputError(shared_data_dir + ": no such folder (expected shared/data with drivecalc/, "
                                         "uiuc_propdb/, ...)");
  }
  std::vector<ImportedDataset> results;
  for (const auto& imp : Importers()) {
    const std::string dir = shared_data_dir + "/" + imp.folder;
    if (!fs::is_directory(dir, ec)) throw NoInputError(dir + ": data-set folder missing");
    results.push_back(imp.run(dir));
    ExcludeImplausibleMotors(&results.back());
  }
  ExcludeCopiesOfMakerTables(&results);
  // Ids unique across everything written and the hand-made files already in the folder.
  std::set<std::string> written;
  for (const auto& r : results) written.insert(r.report.output_file);
  std::set<std::string> ids;
  if (fs::is_directory(out_catalog_dir, ec)) {
    for (const auto& entry : fs::directory_iterator(out_catalog_dir, ec)) {
      const std::string fname = entry.path().filename().string();
      if (entry.path().extension() != ".json" || written.count(fname)) continue;
      const Json doc = ReadJsonFile(entry.path().string());
      for (const char* kind : {"motors", "escs", "props", "batteries"}) {
        if (!doc.contains(kind)) continue;
        for (const auto& e : doc[kind]) {
          if (e.contains("id") && e["id"].is_string()) ids.insert(e["id"].get<std::string>());
        }
      }
    }
  }
  for (const auto& r : results) {
    for (const Json* arr : {&r.motors, &r.escs, &r.props, &r.batteries}) {
      for (const auto& e : *arr) {
        const std::string id = e["id"].get<std::string>();
        if (!ids.insert(id).second) {
          throw InternalError("importer " + r.report.dataset + " produced duplicate id '" + id + "'");
        }
      }
    }
  }
  MakeOutputDir(out_catalog_dir);
  ImportReport report;
  for (auto& r : results) {
    WriteFileAtomic(out_catalog_dir + "/" + r.report.output_file,
                    FormatCatalogDocument(r.comment, r.motors, r.escs, r.props, r.batteries));
    report.datasets.push_back(std::move(r.report));
  }
  return report;
}

}  // namespace dynosize
