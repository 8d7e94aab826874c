// The subcommands of the dynosize CLI. apps/main.cc (the only file that includes CLI11) parses
// the command line into these option structs; each Run* function does the work and returns the
// exit code, throwing dynosize::Error for bad input (mapped to its exit code by main).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "api/log_input.h"
#include "catalog/catalog_path.h"

namespace dynosize::cli {

// How a measured log or stand table is read: the options calibrate, diagnose and validate-stand
// share (api/log_input.h).
using api::LogInputOptions;

struct SimulateOptions {
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
  std::string motor_id, esc_id;
  std::optional<double> vdc_v, throttle, torque_nm, rpm;
  std::vector<double> torque_law;  // a, b, c of Q = a + b*omega + c*omega^2 (SI)
  std::string batch_csv, out_csv, plot_dir;
  bool json = false;
  // A catalog propeller as the load: with --throttle (forward), --rpm or --thrust-n
  // (the throttle solved), or alone (the manufacturer-style table over throttle).
  std::string prop_id;
  // Or a propeller from its size alone (importers/sized_prop.h): "DxP[xB]" inches, its family.
  std::string prop_param, prop_family;
  std::optional<double> thrust_n;
  double rho_kg_m3 = 1.225;
};
int RunSimulate(const SimulateOptions& o);

// `dynosize validate-stand TABLE --motor M --esc E [--prop P]`: a measured stand table predicted
// row by row, dynosize against the plain first-order DC model (src/stand/stand.h).
struct ValidateStandOptions {
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
  std::string table;
  std::string motor_id, esc_id, prop_id;
  LogInputOptions input;
  std::optional<double> vdc_v;  // for tables without a voltage column
  std::string lines;            // "FIRST-LAST": keep rows from these file lines
  double rho_kg_m3 = 1.225;
  std::string baseline = "datasheet";  // the DC model's numbers: datasheet | as-stored
  bool ideal_esc = false;       // the ESC as eq (56)'s ideal chopper (stand::IdealEsc)
  bool json = false;
  bool rows = false;            // text: also print every row
  std::string plot_dir;
};
int RunValidateStand(const ValidateStandOptions& o);

struct CatalogListOptions {
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
  std::string kind;  // "" = all, else motors | escs | props | batteries
  bool json = false;
  std::optional<double> kv_min, kv_max, mass_max_kg, current_min_a;
};
int RunCatalogList(const CatalogListOptions& o);
int RunCatalogShow(const CatalogFolders& catalog, const std::string& id);
// `catalog validate [DIR]`: DIR alone when given, else the folders in use read together.
int RunCatalogValidate(const CatalogFolders& catalog, bool json);
int RunCatalogSchema(bool json);
// `catalog prop-reynolds`: the Reynolds-number law of catalog/prop_reynolds.h fitted on the
// catalog's UIUC entries, with its leave-one-family-out check (markdown on stdout).
int RunCatalogPropReynolds(const CatalogFolders& catalog);

// `dynosize catalog in-system-law --shared DIR`: the in-system law of catalog/in_system.h fitted
// on the KDE sheets and DriveCalc's refits (the catalog's drivecalc.json and
// drivecalc_fitted.json), checked by leaving each motor out: a Markdown report, or with
// --constants the coefficients as catalog/in_system.cc holds them.
struct InSystemLawOptions {
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
  std::string shared_data_dir;
  bool constants = false;
  std::string plot_png;  // measured vs predicted figure of the KDE sheets
};
int RunInSystemLaw(const InSystemLawOptions& o);

// `dynosize rotor validate` (apps/cmd_rotor.cc).
struct RotorValidateOptions {
  CatalogFolders catalog;
  std::string shared_data_dir;
  int threads = 2;
  bool constants = false;  // print kUiucFittedPolar as src/rotor/uiuc_polar.h holds it
  bool size_only = false;  // only the check of a propeller from its size alone
  std::string plot_png;
};
int RunRotorValidate(const RotorValidateOptions& o);
// `dynosize rotor hover`: a parametric rotor's best hover design at a thrust (rotor/parametric.h).
struct RotorHoverOptions {
  double diameter_m = 0.0;
  int blades = 3;
  double solidity = 0.10, twist_deg = -10.0, taper = 1.0, root_cutout = 0.2;
  double thrust_n = 0.0, rho_kg_m3 = 1.225, tip_mach_max = 0.7;
  bool json = false;
};
int RunRotorHover(const RotorHoverOptions& o);
// `dynosize rotor families --shared DIR`: prints src/rotor/family_data.cc from the data.
int RunRotorFamilies(const std::string& shared_data_dir);
// `dynosize rotor entry --pe0 FILE [--id ID]`: prints a catalog document {"props": [entry]}: the
// propeller of an APC geometry file through the blade-element model (importers/sized_prop.h
// GeometryPropJson), for --catalog-add.
int RunRotorEntry(const std::string& pe0_file, const std::string& id);

struct CalibrateOptions {
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
  std::vector<std::string> logs;
  std::string motor_id, esc_id;     // ids of the fitted entries
  LogInputOptions input;
  long long drivecalc_motor = -1;   // drivecalc: one motor id
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
  bool loo = false;  // The motor's label (Gaussian priors, src/identification/parameters.h): Kv in rpm/V, Rm in ohm,
  // no-load current in A at a voltage in V.
  std::optional<double> kv_label, rm_label, io_label, io_label_v;
  // Ratings stored in the written entries (sizing needs them: optimize skips a motor without mass).
  std::optional<double> mass_kg, max_current_a, max_power_w;
  std::optional<double> esc_max_current_a, esc_vdc_max_v, esc_mass_kg;
  // A static propeller entry (CT, CP vs rpm) from a log with thrust and torque.
  std::string prop_id;
  std::optional<double> prop_diameter_in, prop_pitch_in;
};
int RunCalibrate(const CalibrateOptions& o);

// `dynosize diagnose LOG [--motor ID --esc ID]`: what the model gets wrong in a measured log,
// the named cause, the extended model and its cross-validated gain (src/diagnosis/diagnose.h).
struct DiagnoseCliOptions {
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
  std::string log;
  std::string motor_id, esc_id;  // catalog entries to start from (optional)
  LogInputOptions input;
  int folds = 5;
  double alpha = 1e-3;
  bool json = false;
  std::string plot_dir;
  // Write the extended model as catalog entries <id>_motor and <id>_esc into this file
  // (atomically; an existing id is replaced only with force). Default id: the log's base name.
  std::string out;
  std::string id;
  bool force = false;
  std::optional<double> kv_label;  // the motor's label Kv, rpm/V: checked against the model
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
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
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
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
  std::string mission;
  int top = 5;
  bool json = false;
  bool quiet = false;
  int threads = 2;     // SearchOptions::threads
  bool stats = false;  // where the time went (candidate pairs, virtual-ESC evaluations) on stderr
  std::string plot_dir;
  bool variants = false;  // every combination on its own (not SearchOptions::distinct_designs)
  // Stop the search after this many seconds with the best so far (+inf: no limit; 0, < 0 or
  // NaN: a usage error).
  double time_limit_s = std::numeric_limits<double>::infinity();
};
int RunOptimize(const OptimizeOptions& o);

// `dynosize sweep MISSION --vary KEY=START:STOP:STEP|KEY=v1,v2 ... [--top N] [--out FILE]
// [--json] [--plot DIR]`: the mission over a full-factorial grid, each point searched
// (src/study/sweep.h); a CSV (or JSON) row per point.
struct SweepCliOptions {
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
  std::string mission;
  std::vector<std::string> vary;
  int top = 1;
  bool json = false;
  bool quiet = false;
  bool yes = false;    // run a grid over study::kLargeGridPoints points
  int threads = 2;     // points at once (study::SweepOptions::threads)
  std::string out;     // "" = stdout
  std::string plot_dir;
  bool variants = false;  // SearchOptions::distinct_designs off, as optimize --variants
  double time_limit_s = std::numeric_limits<double>::infinity();  // as optimize's
};
int RunSweep(const SweepCliOptions& o);

// `dynosize serve [--port 8080] [--host 127.0.0.1]`: the web page and its JSON API
// (src/server/web_server.h, docs/web.md) until Ctrl-C.
struct ServeCliOptions {
  CatalogFolders catalog;  // --catalog, --catalog-add, --override (catalog/catalog_path.h)
  std::string host = "127.0.0.1";
  int port = 8080;          // 0: any free port
  std::string web_dir;      // the page's folder ("" = beside the program, server/page_files.h)
  int jobs = 2;             // solving requests at once
  int queue = 8;            // more waiting; beyond that 503
  double max_search_s = 300.0;
  bool quiet = false;       // no line per request on stderr
};
int RunServe(const ServeCliOptions& o);

}  // namespace dynosize::cli
