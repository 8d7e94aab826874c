// dynosize command-line front end: parses flags (CLI11, only here) and calls apps/commands.h.
//
// Exit codes (see README): 0 ok, 64 usage, 65 bad input data, 66 missing input, 70 internal
// error, 73 cannot create output, 130 optimize or sweep stopped by SIGINT (its best so far / rows done so far written).
// Results go to stdout, messages to stderr; with --json stdout is exactly one JSON document.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "common/error.h"
#include "logs/steady_table.h"
#include "mission/mission.h"

namespace {

using dynosize::ExitCode;
namespace cli = dynosize::cli;

// One "dynosize: " line per problem (a catalog with several problems lists each on its line).
int Fail(ExitCode code, const std::string& message) {
  std::string out;
  std::size_t begin = 0;
  while (begin <= message.size()) {
    std::size_t end = message.find('\n', begin);
    if (end == std::string::npos) end = message.size();
    std::size_t b = begin;
    while (b < end && message[b] == ' ') ++b;  // continuation lines are indented in messages
    if (b < end || out.empty()) out += "dynosize: " + message.substr(b, end - b) + "\n";
    begin = end + 1;
  }
  std::cerr << out;
  return static_cast<int>(code);
}

// The log-reading flags of calibrate, diagnose and validate-stand (cli::LogInputOptions); every
// reader is offered to every command (logs::LogFormatNames, one list).
void AddLogInputOptions(CLI::App* cmd, dynosize::cli::LogInputOptions* in, const std::string& where_help) {
  cmd->add_option("--format", in->format, "log format: " + dynosize::logs::LogFormatHelp())
      ->check(CLI::IsMember(dynosize::logs::LogFormatNames()));
  cmd->add_option("--map", in->column_map,
                  "mapped tables: canonical_name=Source Header [unit] (repeatable)");
  cmd->add_flag("--drop-incomplete-rows", in->drop_incomplete_rows,
                "drop (and count) rows with an empty or text cell (e.g. a trailer row) in a used "
                "column instead of failing");
  cmd->add_flag("--decimal-comma", in->decimal_comma,
                "numbers are written with a decimal comma (1,5; cells separated by ';' or tabs)");
  cmd->add_option("--where", in->where,
                  "keep only rows whose column reads a value: Header=value (repeatable; " + where_help + ")");
  cmd->add_option("--esc-min-us", in->esc_min_us, "ESC pulse width at throttle 0, us");
  cmd->add_option("--esc-max-us", in->esc_max_us, "ESC pulse width at throttle 1, us");
}

// One Add*Command per subcommand: registers it and its flags on app, bound to the options
// struct, and returns it (true once the command line has chosen it).

CLI::App* AddSimulateCommand(CLI::App& app, cli::SimulateOptions& sim) {
  auto* simulate = app.add_subcommand(
      "simulate",
      "operating point(s) of a motor + ESC pair: forward (VDC, throttle, load) or inverse "
      "(VDC, torque, rpm -> throttle); --plot writes the paper's figures");
  simulate->add_option("--motor", sim.motor_id, "motor id from the catalog")->required();
  simulate->add_option("--esc", sim.esc_id, "ESC id from the catalog")->required();
  simulate->add_option("--vdc", sim.vdc_v, "supply voltage at the ESC, V");
  simulate->add_option("--throttle", sim.throttle, "throttle command, 0..1");
  simulate->add_option("--torque", sim.torque_nm, "load torque, N*m (hysteresis brake)");
  simulate->add_option("--rpm", sim.rpm, "shaft speed, rpm (with --throttle: fixed speed; with --torque: inverse)");
  simulate->add_option("--torque-law", sim.torque_law,
                       "propeller-like load Q = A + B*omega + C*omega^2 (N*m, omega in rad/s): A,B,C")
      ->delimiter(',')
      ->expected(3);
  simulate->add_option("--batch", sim.batch_csv,
                       "CSV of points (header: vdc_v,throttle,torque_nm,rpm; two of the last three per row)");
  simulate->add_option("--out", sim.out_csv, "with --batch: write the results CSV here (default stdout)");
  simulate->add_option("--plot", sim.plot_dir, "write the pair's figures (PNG + gnuplot script) into this folder");
  simulate->add_option("--prop", sim.prop_id,
                       "catalog propeller as the load: with --throttle (forward), --rpm or --thrust-n "
                       "(throttle solved), or alone (the table over throttle: thrust, current, rpm, g/W)");
  simulate->add_option("--prop-param", sim.prop_param,
                       "instead of --prop, a propeller from its size alone: DxP or DxPxB in inches (e.g. 40x13x2), "
                       "its blade from a family run through the blade-element model (docs/model.md section 13)");
  simulate->add_option("--prop-family", sim.prop_family,
                       "with --prop-param: apc_e, apc_sf, apc_sport, multirotor or evtol_rotor (default: multirotor from 12 in "
                       "at pitch/diameter <= 0.5, else apc_e)");
  simulate->add_option("--thrust-n", sim.thrust_n, "with --prop: the static thrust to hold, N");
  simulate->add_option("--rho-kg-m3", sim.rho_kg_m3, "with --prop: air density, kg/m^3 (default 1.225)");
  simulate->add_flag("--json", sim.json, "print one JSON object");
  return simulate;
}

CLI::App* AddCalibrateCommand(CLI::App& app, cli::CalibrateOptions& cal) {
  auto* calibrate = app.add_subcommand(
      "calibrate",
      "fit motor + ESC catalog entries (KE, KT, Rm, Io, RESC, C1, C0, tr_sat, sat_slope) to steady "
      "points of dyno / thrust-stand logs, with standard errors and identifiability");
  calibrate->add_option("logs", cal.logs, "log files of one motor + ESC pair")->required();
  calibrate->add_option("--motor-id", cal.motor_id, "id of the fitted motor entry");
  calibrate->add_option("--esc-id", cal.esc_id, "id of the fitted ESC entry");
  AddLogInputOptions(calibrate, &cal.input, "one motor of a multi-motor table");
  calibrate->add_option("--drivecalc-motor", cal.drivecalc_motor, "drivecalc: only this motor_id");
  calibrate->add_option("--prior-motor", cal.prior_motor,
                        "catalog motor whose KE, Rm, Io anchor the fit (Gaussian priors) and fill in what the "
                        "data cannot identify");
  calibrate->add_option("--prior-esc", cal.prior_esc,
                        "catalog ESC whose values are held where the data cannot identify them");
  calibrate->add_option("--out", cal.out, "catalog JSON file to add the entries to (written atomically)");
  calibrate->add_flag("--force", cal.force, "replace entries with the same ids in --out");
  calibrate->add_flag("--json", cal.json, "print one JSON object");
  calibrate->add_option("--plot", cal.plot_dir, "write measured-vs-predicted and residual figures here");
  calibrate->add_flag("--loo", cal.loo,
                      "also report leave-one-throttle-out (or leave-one-row-out) prediction errors");
  calibrate->add_flag("--drivecalc-all", cal.drivecalc_all,
                      "refit every DriveCalc motor in LOG (MData.csv) into --out (default "
                      "catalog/drivecalc_fitted.json)");
  calibrate->add_option("--kv-label", cal.kv_label,
                        "the motor's label Kv, rpm/V: a Gaussian prior on KE (10 % 1-sigma) and the check "
                        "'Kv within 25 % of the label'; stored in the entry");
  calibrate->add_option("--rm-label", cal.rm_label, "datasheet winding resistance, ohm: a prior on Rm (30 %)");
  calibrate->add_option("--io-label", cal.io_label, "datasheet no-load current, A: a prior on Io (50 %)");
  calibrate->add_option("--io-label-v", cal.io_label_v, "voltage at which --io-label holds, V");
  calibrate->add_option("--mass-kg", cal.mass_kg, "motor mass, kg (stored in the motor entry)");
  calibrate->add_option("--max-current-a", cal.max_current_a, "motor current rating, A (stored)");
  calibrate->add_option("--max-power-w", cal.max_power_w, "motor power rating, W (stored)");
  calibrate->add_option("--esc-max-current-a", cal.esc_max_current_a, "ESC current rating, A (stored)");
  calibrate->add_option("--esc-vdc-max-v", cal.esc_vdc_max_v, "ESC voltage rating, V (stored)");
  calibrate->add_option("--esc-mass-kg", cal.esc_mass_kg, "ESC mass, kg (stored)");
  calibrate->add_option("--prop-id", cal.prop_id,
                        "also write a static propeller entry (CT, CP vs rpm) from the log's thrust and torque");
  calibrate->add_option("--prop-diameter-in", cal.prop_diameter_in, "propeller diameter, inch (with --prop-id)");
  calibrate->add_option("--prop-pitch-in", cal.prop_pitch_in, "propeller pitch, inch (with --prop-id)");
  return calibrate;
}

// `catalog` and its subcommands: the options they fill and the subcommands, to dispatch on.
struct CatalogCli {
  cli::CatalogListOptions list;
  std::string show_id;
  std::string validate_dir;
  bool validate_json = false;
  cli::CatalogImportOptions import_opts;
  bool schema_json = false;
  CLI::App* list_cmd = nullptr;
  CLI::App* show_cmd = nullptr;
  CLI::App* validate_cmd = nullptr;
  CLI::App* import_cmd = nullptr;
  CLI::App* schema_cmd = nullptr;
  cli::InSystemLawOptions law_opts;
  CLI::App* law_cmd = nullptr;
  CLI::App* reynolds_cmd = nullptr;
};

void AddCatalogCommands(CLI::App& app, CatalogCli& c) {
  auto* catalog = app.add_subcommand("catalog", "list, show, validate the component catalog");
  catalog->require_subcommand(1);
  catalog->fallthrough();
  c.list_cmd = catalog->add_subcommand("list", "list the loaded components");
  c.list_cmd->add_option("--kind", c.list.kind, "motors, escs, props or batteries")
      ->check(CLI::IsMember({"motors", "escs", "props", "batteries"}));
  c.list_cmd->add_option("--kv-min", c.list.kv_min, "motors with Kv >= this, rpm/V");
  c.list_cmd->add_option("--kv-max", c.list.kv_max, "motors with Kv <= this, rpm/V");
  c.list_cmd->add_option("--mass-max-kg", c.list.mass_max_kg, "entries with mass <= this, kg");
  c.list_cmd->add_option("--current-min-a", c.list.current_min_a, "entries rated for >= this current, A");
  c.list_cmd->add_flag("--json", c.list.json, "print {kind: [entries as catalog JSON objects]}");
  c.show_cmd = catalog->add_subcommand("show", "print one entry with its derived SI parameters");
  c.show_cmd->add_option("id", c.show_id, "entry id")->required();
  c.validate_cmd = catalog->add_subcommand("validate", "report every problem in a catalog folder");
  c.validate_cmd->add_option("dir", c.validate_dir, "catalog folder (default: the one in use)");
  c.validate_cmd->add_flag("--json", c.validate_json, "print {\"valid\": bool, \"problems\": [...]}");
  c.import_cmd = catalog->add_subcommand(
      "import", "regenerate catalog JSON from the public data sets (shared/data)");
  c.import_cmd->add_option("--shared", c.import_opts.shared_data_dir,
                           "folder holding drivecalc/, uiuc_propdb/, ... (shared/data)")
      ->required();
  c.import_cmd->add_option("--out", c.import_opts.out_dir, "catalog folder to write")->required();
  c.import_cmd->add_flag("--json", c.import_opts.json, "print the import report as JSON");
  c.law_cmd = catalog->add_subcommand(
      "in-system-law",
      "fit the law that turns datasheet motor values into in-system ones on measured data, check it "
      "by leaving each motor out, and print the report (docs/in-system-law.md)");
  c.law_cmd->add_option("--shared", c.law_opts.shared_data_dir, "the shared data folder (../shared/data)")->required();
  c.law_cmd->add_flag("--constants", c.law_opts.constants,
                      "print the fitted coefficients as catalog/in_system.cc holds them instead of the report");
  c.law_cmd->add_option("--plot", c.law_opts.plot_png,
                        "write the KDE sheets' measured-vs-predicted current figure to this PNG");
  c.schema_cmd = catalog->add_subcommand("schema", "print every catalog key with its unit and rule");
  c.schema_cmd->add_flag("--json", c.schema_json, "print the schema as JSON");
  c.reynolds_cmd = catalog->add_subcommand(
      "prop-reynolds", "fit the propeller Reynolds-number law on the catalog's measured (UIUC) propellers and "
                       "check it by leaving each family out (markdown; docs/propeller_reynolds.md)");
}

CLI::App* AddDiagnoseCommand(CLI::App& app, cli::DiagnoseCliOptions& diag) {
  auto* diagnose = app.add_subcommand(
      "diagnose",
      "show what the model gets wrong in a measured log (cross-validated), name the cause "
      "(saturation, dead band, Io(omega), winding heating, KT droop, supply sag) and the gain");
  diagnose->add_option("log", diag.log, "steady-state or time-series log of one motor + ESC")->required();
  diagnose->add_option("--motor", diag.motor_id, "catalog motor to start from (else fitted on the log)");
  diagnose->add_option("--esc", diag.esc_id, "catalog ESC whose values are held where the log cannot fit them");
  AddLogInputOptions(diagnose, &diag.input, "one motor of a multi-motor table");
  diagnose->add_option("--folds", diag.folds, "k of the k-fold cross-validation (>= 2)");
  diagnose->add_option("--alpha", diag.alpha, "significance level of the nested F test");
  diagnose->add_flag("--json", diag.json, "print one JSON object (baseline, findings, ambiguous, extended_model)");
  diagnose->add_option("--plot", diag.plot_dir, "write residual, measured-vs-predicted and curve figures here");
  diagnose->add_option("--out", diag.out,
                       "catalog JSON file to add the extended model to (<id>_motor, <id>_esc; atomic)");
  diagnose->add_option("--id", diag.id, "id prefix of the --out entries (default: the log's base name)");
  diagnose->add_flag("--force", diag.force, "replace entries with the same ids in --out");
  diagnose->add_option("--kv-label", diag.kv_label,
                       "the motor's label Kv, rpm/V: the status check 'Kv within 25 % of the label'");
  return diagnose;
}

CLI::App* AddEvaluateCommand(CLI::App& app, cli::EvaluateOptions& eval) {
  auto* evaluate = app.add_subcommand(
      "evaluate", "one motor/ESC/propeller/battery combination flying a mission: operating point "
                  "per segment, battery state, objective, limits");
  evaluate->add_option("mission", eval.mission, "mission JSON file")->required();
  evaluate->add_option("--motor", eval.motor_id, "motor id (one group)");
  evaluate->add_option("--esc", eval.esc_id, "ESC id (one group)");
  evaluate->add_option("--prop", eval.prop_id, "propeller id (one group)");
  evaluate->add_option("--pick", eval.picks, "GROUP=MOTOR,ESC,PROP: a propulsion group's parts (repeatable)");
  evaluate->add_option("--battery", eval.battery_id, "battery (cell) id")->required();
  evaluate->add_option("--cells", eval.cells, "cells in series (default: the mission's, if fixed)")
      ->check(CLI::Range(1, dynosize::kMaxCellsSeries));
  evaluate->add_flag("--json", eval.json, "print one JSON object");
  evaluate->add_option("--plot", eval.plot_dir, "write per-segment efficiency maps here");
  return evaluate;
}

CLI::App* AddOptimizeCommand(CLI::App& app, cli::OptimizeOptions& optim) {
  auto* optimize = app.add_subcommand(
      "optimize", "the best motor/ESC/propeller/battery combinations of the catalog for a mission "
                  "(exact search with provably safe pruning)");
  optimize->add_option("mission", optim.mission, "mission JSON file")->required();
  optimize->add_option("--top", optim.top, "how many combinations to list")->check(CLI::Range(1, 1000));
  optimize->add_flag("--json", optim.json, "print one JSON object");
  optimize->add_flag("--quiet", optim.quiet, "no progress display");
  optimize->add_option("--threads", optim.threads, "worker threads (the answer does not depend on it)")
      ->check(CLI::Range(1, 64));
  optimize->add_flag("--stats", optim.stats, "print where the search's time went on stderr");
  optimize->add_flag("--variants", optim.variants,
                     "list every combination on its own (default: each result a different motor and propeller "
                     "per group, its other ESCs and packs listed inside it)");
  optimize->add_option("--time-limit", optim.time_limit_s,
                       "stop after S seconds and print the best found so far (marked interrupted; > 0)");
  optimize->add_option("--plot", optim.plot_dir,
                       "write the Pareto front and the top pick's efficiency maps here");
  return optimize;
}

CLI::App* AddSweepCommand(CLI::App& app, cli::SweepCliOptions& sw) {
  auto* sweep = app.add_subcommand(
      "sweep", "a trade study: the mission over a full-factorial grid of values (JSON paths of the mission), "
               "each point searched as optimize does; one CSV row per point");
  sweep->add_option("mission", sw.mission, "mission JSON file")->required();
  sweep->add_option("--vary", sw.vary,
                    "KEY=START:STOP:STEP or KEY=v1,v2,... with KEY a JSON path of the mission "
                    "(vehicle.mass_kg, battery.capacity_ah, segments[2].duration_s); repeatable: full factorial")
      ->required()
      ->allow_extra_args(false);
  sweep->add_option("--top", sw.top, "picks per point (one CSV line each)")->check(CLI::Range(1, 1000));
  sweep->add_option("--out", sw.out, "write the CSV (or JSON) here (default: stdout; atomic)");
  sweep->add_flag("--json", sw.json, "write the rows as one JSON object");
  sweep->add_option("--plot", sw.plot_dir,
                    "write the objective against each key and a carpet plot of the first two keys here");
  sweep->add_option("--threads", sw.threads, "points run at once (each point's answer does not depend on it)")
      ->check(CLI::Range(1, 64));
  sweep->add_flag("--quiet", sw.quiet, "no progress display");
  sweep->add_flag("--yes", sw.yes, "run a grid of more than 10^6 points");
  sweep->add_flag("--variants", sw.variants, "rank combinations, not designs (as optimize --variants)");
  sweep->add_option("--time-limit", sw.time_limit_s,
                    "stop after S seconds and write the rows done so far (> 0)");
  return sweep;
}

CLI::App* AddValidateStandCommand(CLI::App& app, cli::ValidateStandOptions& vst) {
  auto* validate_stand = app.add_subcommand(
      "validate-stand",
      "predict a measured stand table (thrust, current, rpm, torque) row by row from catalog "
      "entries, dynosize beside the plain first-order DC model");
  validate_stand->add_option("table", vst.table, "stand table (any --format: canonical, RCbenchmark/Tyto, a named-column table, ...)")->required();
  validate_stand->add_option("--motor", vst.motor_id, "motor id from the catalog")->required();
  validate_stand->add_option("--esc", vst.esc_id, "ESC id from the catalog")->required();
  validate_stand->add_option("--prop", vst.prop_id,
                             "propeller id from the catalog (the table's propeller); without it the "
                             "measured torque is the load");
  AddLogInputOptions(validate_stand, &vst.input, "one propeller of a multi-propeller table");
  validate_stand->add_option("--vdc", vst.vdc_v, "supply voltage, V, for tables without a voltage column");
  validate_stand->add_option("--lines", vst.lines, "FIRST-LAST: only rows from these lines of the file");
  validate_stand->add_option("--rho-kg-m3", vst.rho_kg_m3, "air density, kg/m^3 (default 1.225)");
  validate_stand->add_option("--baseline", vst.baseline,
                             "the plain DC model's R and Io: datasheet (default: what a DC calculator is given, "
                             "R = rm_dc_ohm (else rm_ohm/0.7492) + resc_ohm/0.7492, Io = 1.1095*io_a) or "
                             "as-stored (the catalog's rms numbers unchanged: rm_ohm + resc_ohm, io_a)")
      ->check(CLI::IsMember({"datasheet", "as-stored"}));
  validate_stand->add_flag("--ideal-esc", vst.ideal_esc,
                           "treat the ESC as ideal (no resistance, no saturation knee, eq 56) in both models: for "
                           "a motor whose R was fitted on stand rows with the table's ESC in the loop");
  validate_stand->add_flag("--rows", vst.rows, "also print every row's measured and predicted values");
  validate_stand->add_flag("--json", vst.json, "print one JSON object");
  validate_stand->add_option("--plot", vst.plot_dir, "write the measured-vs-predicted figure here");
  return validate_stand;
}

struct RotorCli {
  cli::RotorValidateOptions validate;
  CLI::App* validate_cmd = nullptr;
  std::string families_shared;
  CLI::App* families_cmd = nullptr;
  std::string entry_pe0, entry_id;
  CLI::App* entry_cmd = nullptr;
  cli::RotorHoverOptions hover;
  CLI::App* hover_cmd = nullptr;
};

void AddRotorHoverCommand(CLI::App* rotor, RotorCli& r) {
  cli::RotorHoverOptions& h = r.hover;
  r.hover_cmd = rotor->add_subcommand(
      "hover", "a parametric rotor (eVTOL class) at a hover thrust: the collective and speed of the best figure "
               "of merit within the tip Mach limit, its power, blade loading and what limits it");
  r.hover_cmd->add_option("--diameter-m", h.diameter_m, "rotor diameter, m")->required()->check(CLI::Range(0.05, 40.0));
  r.hover_cmd->add_option("--thrust-n", h.thrust_n, "hover thrust of this rotor, N")->required()->check(CLI::PositiveNumber);
  r.hover_cmd->add_option("--blades", h.blades, "blades (2-8)")->check(CLI::Range(2, 8));
  r.hover_cmd->add_option("--solidity", h.solidity, "blade area over disk area (0.02-0.3; default 0.10)");
  r.hover_cmd->add_option("--twist-deg", h.twist_deg, "linear twist, tip minus root, deg (default -10)");
  r.hover_cmd->add_option("--taper", h.taper, "tip chord over root chord (default 1)");
  r.hover_cmd->add_option("--root-cutout", h.root_cutout, "r/R where the blade starts (default 0.2)");
  r.hover_cmd->add_option("--tip-mach-max", h.tip_mach_max, "tip Mach limit (default 0.7)");
  r.hover_cmd->add_option("--rho-kg-m3", h.rho_kg_m3, "air density, kg/m^3 (default 1.225)");
  r.hover_cmd->add_flag("--json", h.json, "print one JSON object");
}

void AddRotorCommands(CLI::App& app, RotorCli& r) {
  cli::RotorValidateOptions& rv = r.validate;
  auto* rotor = app.add_subcommand("rotor", "propellers and rotors from their blade geometry (blade-element "
                                            "momentum theory, docs/model.md section 13)");
  rotor->require_subcommand(1);
  rotor->fallthrough();
  auto* validate = rotor->add_subcommand(
      "validate", "check the blade-element model against UIUC's measured propellers by leaving each family out, "
                  "and against APC's own tables (markdown; docs/validation.md)");
  validate->add_option("--shared", rv.shared_data_dir, "the shared data folder (../shared/data)")->required();
  validate->add_option("--threads", rv.threads, "folds fitted at once")->check(CLI::Range(1, 64));
  validate->add_flag("--constants", rv.constants,
                     "print the polar fitted on every family as src/rotor/uiuc_polar.h holds it");
  validate->add_option("--plot", rv.plot_png, "write the measured-vs-model figure to this PNG");
  validate->add_flag("--size-only", rv.size_only, "only the check of a propeller from its size alone (seconds)");
  r.validate_cmd = validate;
  r.families_cmd = rotor->add_subcommand(
      "families", "print src/rotor/family_data.cc: the propeller families' blade shapes derived from the data");
  r.families_cmd->add_option("--shared", r.families_shared, "the shared data folder (../shared/data)")->required();
  AddRotorHoverCommand(rotor, r);
  r.entry_cmd = rotor->add_subcommand(
      "entry", "print a catalog document holding the propeller of an APC geometry file (PE0) run through the "
               "blade-element model (tier estimated), for --catalog-add");
  r.entry_cmd->add_option("--pe0", r.entry_pe0, "APC geometry file (*-PERF.PE0)")->required();
  r.entry_cmd->add_option("--id", r.entry_id, "the entry's id (default bemt_apc_<name>, e.g. bemt_apc_14x7e)");
}

CLI::App* AddServeCommand(CLI::App& app, cli::ServeCliOptions& sv) {
  auto* serve = app.add_subcommand(
      "serve", "serve the web page (drive calculator, catalog, mission optimizer) and its JSON API on this "
               "machine until Ctrl-C (docs/web.md)");
  serve->add_option("--port", sv.port, "TCP port (0: any free port; the address is printed)")
      ->check(CLI::Range(0, 65535));
  serve->add_option("--host", sv.host, "address to listen on (default loopback; any other prints a warning)");
  serve->add_option("--web-dir", sv.web_dir, "the page's folder (default: the one installed beside the program)");
  serve->add_option("--jobs", sv.jobs, "solving requests at once")->check(CLI::Range(1, 64));
  serve->add_option("--queue", sv.queue, "solving requests waiting for a slot; beyond that 503")
      ->check(CLI::Range(0, 1000));
  serve->add_option("--max-search-time", sv.max_search_s, "an optimize request runs at most this long, s (> 0)")
      ->check(CLI::PositiveNumber);
  serve->add_flag("--quiet", sv.quiet, "no line per request on stderr");
  return serve;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dynosize: motor + ESC model, catalog, calibration and sizing for electric "
               "multirotors and eVTOL (Brown & Chopra's combined model)"};
  app.require_subcommand(1);
  app.fallthrough();  // --catalog may also follow the subcommand
  app.set_version_flag("--version", std::string(DYNOSIZE_VERSION));
  std::string catalog_dir;
  app.add_option("--catalog", catalog_dir,
                 "catalog folder (default: $DYNOSIZE_CATALOG or the bundled catalog)");
  std::vector<std::string> catalog_add;
  app.add_option("--catalog-add", catalog_add,
                 "a folder of your own parts read on top of the catalog (repeatable; after the folders "
                 "of $DYNOSIZE_CATALOG_PATH, colon-separated); an id the catalog already holds is an error")
      ->take_all()
      ->allow_extra_args(false);
  bool catalog_override = false;
  app.add_flag("--override", catalog_override,
               "an added entry (--catalog-add, $DYNOSIZE_CATALOG_PATH) replaces the catalog's entry of the "
               "same id and kind instead of being an error");
  cli::SimulateOptions sim;
  CLI::App* simulate = AddSimulateCommand(app, sim);
  cli::CalibrateOptions cal;
  CLI::App* calibrate = AddCalibrateCommand(app, cal);
  CatalogCli cat;
  AddCatalogCommands(app, cat);
  cli::DiagnoseCliOptions diag;
  CLI::App* diagnose = AddDiagnoseCommand(app, diag);
  cli::EvaluateOptions eval;
  CLI::App* evaluate = AddEvaluateCommand(app, eval);
  cli::OptimizeOptions optim;
  CLI::App* optimize = AddOptimizeCommand(app, optim);
  cli::ValidateStandOptions vst;
  CLI::App* validate_stand = AddValidateStandCommand(app, vst);
  cli::SweepCliOptions sw;
  CLI::App* sweep = AddSweepCommand(app, sw);
  cli::ServeCliOptions sv;
  CLI::App* serve = AddServeCommand(app, sv);
  RotorCli rot;
  AddRotorCommands(app, rot);

  if (argc > 1 && argv[1][0] != '-') {
    const std::string first = argv[1];
    if (first != "simulate" && first != "catalog" && first != "calibrate" && first != "diagnose" &&
        first != "evaluate" && first != "optimize" && first != "validate-stand" && first != "sweep" &&
        first != "serve" && first != "rotor") {
      return Fail(ExitCode::kUsage, "unknown subcommand '" + first +
                                        "': valid are simulate, calibrate, diagnose, catalog, evaluate, "
                                        "optimize, sweep, validate-stand, serve, rotor (see 'dynosize --help')");
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::CallForVersion&) {
    std::cout << DYNOSIZE_VERSION << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    // Help requested on a subcommand arrives here too.
    if (e.get_exit_code() == 0) {
      return app.exit(e);
    }
    return Fail(ExitCode::kUsage, std::string(e.what()) + " (see 'dynosize --help')");
  }

  try {
    const dynosize::CatalogFolders dir =
        dynosize::ResolveCatalogFolders(catalog_dir, catalog_add, catalog_override);
    if (*simulate) {
      sim.catalog = dir;
      return cli::RunSimulate(sim);
    }
    if (*calibrate) {
      cal.catalog = dir;
      return cli::RunCalibrate(cal);
    }
    if (*diagnose) {
      diag.catalog = dir;
      return cli::RunDiagnose(diag);
    }
    if (*evaluate) {
      eval.catalog = dir;
      return cli::RunEvaluate(eval);
    }
    if (*optimize) {
      optim.catalog = dir;
      return cli::RunOptimize(optim);
    }
    if (*sweep) {
      sw.catalog = dir;
      return cli::RunSweep(sw);
    }
    if (*serve) {
      sv.catalog = dir;
      return cli::RunServe(sv);
    }
    if (*rot.validate_cmd) {
      rot.validate.catalog = dir;
      return cli::RunRotorValidate(rot.validate);
    }
    if (*rot.families_cmd) return cli::RunRotorFamilies(rot.families_shared);
    if (*rot.entry_cmd) return cli::RunRotorEntry(rot.entry_pe0, rot.entry_id);
    if (*rot.hover_cmd) return cli::RunRotorHover(rot.hover);
    if (*validate_stand) {
      vst.catalog = dir;
      return cli::RunValidateStand(vst);
    }
    if (*cat.list_cmd) {
      cat.list.catalog = dir;
      return cli::RunCatalogList(cat.list);
    }
    if (*cat.show_cmd) return cli::RunCatalogShow(dir, cat.show_id);
    if (*cat.validate_cmd) {
      return cli::RunCatalogValidate(
          cat.validate_dir.empty() ? dir : dynosize::CatalogFolders{cat.validate_dir, {}, false}, cat.validate_json);
    }
    if (*cat.schema_cmd) return cli::RunCatalogSchema(cat.schema_json);
    if (*cat.reynolds_cmd) return cli::RunCatalogPropReynolds(dir);
    if (*cat.import_cmd) return cli::RunCatalogImport(cat.import_opts);
    if (*cat.law_cmd) {
      cat.law_opts.catalog = dir;
      return cli::RunInSystemLaw(cat.law_opts);
    }
  } catch (const dynosize::Error& e) {
    return Fail(e.code(), e.what());
  } catch (const std::exception& e) {
    return Fail(ExitCode::kInternal, std::string("internal error: ") + e.what());
  }
  return Fail(ExitCode::kUsage, "no subcommand (see 'dynosize --help')");
}
