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

struct CalibrateOptions {
  std::string catalog_dir;
  std::vector<std::string> logs;
  std::string motor_id, esc_id;     // ids of the fitted entries
  std::string format = "auto";      // auto | canonical | rcbenchmark | mapped | drivecalc
  std::vector<std::string> column_map;  // mapped tables: canonical=Header [unit]
  long long drivecalc_motor = -1;   // drivecalc: one motor id
  bool drop_incomplete_rows = false;  // mapped: drop rows with an empty mapped cell
  double esc_min_us = 1000.0, esc_max_us = 2000.0;
  std::string prior_motor, prior_esc;  // catalog ids anchoring / filling in the fit
  std::string out;                  // catalog file to add the entries to
  bool force = false;
  bool json = false;
  std::string plot_dir;
  // Refit every DriveCalc motor with a no-load point and >= 3 loaded points in LOG (MData.csv)
  // and write them to --out (default catalog/drivecalc_fitted.json).
  bool drivecalc_all = false;
  // Also report leave-one-out prediction errors (one throttle level out; one row out for
  // logs without throttle and for --drivecalc-all, where the plain U = n/Kv + R*I fit is
  // reported beside it).
  bool loo = false;
};
int RunCalibrate(const CalibrateOptions& o);

// `dynosize diagnose LOG [--motor ID --esc ID]`: what the model gets wrong in a measured log,
// the named cause, the extended model and its cross-validated gain (src/diagnosis/diagnose.h).
struct DiagnoseCliOptions {
  std::string catalog_dir;
  std::string log;
  std::string motor_id, esc_id;  // catalog entries to start from (optional)
  std::string format = "auto";
  std::vector<std::string> column_map;
  bool drop_incomplete_rows = false;
  double esc_min_us = 1000.0, esc_max_us = 2000.0;
  int folds = 5;
  double alpha = 1e-3;
  bool json = false;
  std::string plot_dir;
  // Write the extended model as catalog entries <id>_motor and <id>_esc into this file
  // (atomically; an existing id is replaced only with force). Default id: the log's base name.
  std::string out;
  std::string id;
  bool force = false;
};
int RunDiagnose(const DiagnoseCliOptions& o);

// `dynosize catalog import --shared DIR --out DIR [--json]`: runs every importer
// (src/importers/importers.h ImportAll) on DIR/<dataset>/ and writes OUT/<dataset>.json; prints
// what was kept and dropped per data set (stdout), or the report as JSON.
struct CatalogImportOptions {
  std::string shared_data_dir;  // shared/data
  std::string out_dir;          // catalog folder to write
  bool json = false;
};
int RunCatalogImport(const CatalogImportOptions& o);

// `dynosize evaluate MISSION --motor ID --esc ID --prop ID --battery ID [--cells N] [--json]`:
// one combination flying the mission (src/optimization/mission_eval.h).
struct EvaluateOptions {
  std::string catalog_dir;
  std::string mission;
  std::string motor_id, esc_id, prop_id, battery_id;
  std::vector<std::string> picks;  // --pick GROUP=MOTOR,ESC,PROP (missions with propulsion groups)
  int cells = 0;  // 0: the mission's only cell count (an error when it gives a range)
  bool json = false;
  std::string plot_dir;
};
int RunEvaluate(const EvaluateOptions& o);

// `dynosize optimize MISSION [--top N] [--json] [--plot DIR]`: the best N combinations of the
// catalog (src/optimization/search.h).
struct OptimizeOptions {
  std::string catalog_dir;
  std::string mission;
  int top = 5;
  bool json = false;
  bool quiet = false;
  int threads = 2;     // SearchOptions::threads
  bool stats = false;  // where the time went (candidate pairs, virtual-ESC evaluations) on stderr
  std::string plot_dir;
};
int RunOptimize(const OptimizeOptions& o);

}  // namespace dynosize::cli
