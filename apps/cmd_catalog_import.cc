// `dynosize catalog import`: a thin wrapper around ImportAll.
#include <iostream>

#include "commands.h"
#include "common/json_file.h"
#include "importers/importers.h"

namespace dynosize::cli {

int RunCatalogImport(const CatalogImportOptions& o) {
  const ImportReport report = ImportAll(o.shared_data_dir, o.out_dir);
  if (o.json) {
    std::cout << DumpJson(report.ToJson());
  } else {
    std::cout << report.FullReport();
  }
  return 0;
}

}  // namespace dynosize::cli
