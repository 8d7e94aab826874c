// The subcommands of the dynosize CLI. apps/main.cc (the only file that includes CLI11) parses
// the command line into these option structs; each Run* function does the work and returns the
// exit code, throwing dynosize::Error for bad input (mapped to its exit code by main).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace dynosize::cli {

// The catalog folder used when --catalog is not given: $DYNOSIZE_CATALOG, else the source
// tree's catalog/ the binary was built from, else ./catalog.
std::string DefaultCatalogDir();

struct SimulateOptions {
  std::string catalog_dir;
  std::string motor_id, esc_id;
  std::optional<double> vdc_v, throttle, torque_nm, rpm;
  std::vector<double> torque_law;  // a, b, c of Q = a + b*omega + c*omega^2 (SI)
  std::string batch_csv, out_csv, plot_dir;
  bool json = false;
};
int RunSimulate(const SimulateOptions& o);

struct CatalogListOptions {
  std::string catalog_dir;
  std::string kind;  // "" = all, else motors | escs | props | batteries
  bool json = false;
  std::optional<double> kv_min, kv_max, mass_max_kg, current_min_a;
};
int RunCatalogList(const CatalogListOptions& o);
int RunCatalogShow(const std::string& catalog_dir, const std::string& id);
int RunCatalogValidate(const std::string& dir, bool json);
int RunCatalogSchema(bool json);

// `dynosize catalog import --shared DIR --out DIR [--json]`: runs every importer
// (src/importers/importers.h ImportAll) on DIR/<dataset>/ and writes OUT/<dataset>.json; prints
// what was kept and dropped per data set (stdout), or the report as JSON.
struct CatalogImportOptions {
  std::string shared_data_dir;  // shared/data
  std::string out_dir;          // catalog folder to write
  bool json = false;
};
int RunCatalogImport(const CatalogImportOptions& o);

}  // namespace dynosize::cli
