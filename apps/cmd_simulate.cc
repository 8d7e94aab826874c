// `dynosize simulate`: the model of src/model on catalog entries, one point, a batch, or figures.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "api/simulate.h"
#include "api/simulate_request.h"
#include "catalog/catalog.h"
#include "commands.h"
#include "common/error.h"
#include "common/text_file.h"
#include "common/text_format.h"
#include "common/units.h"
#include "io/points_csv.h"
#include "model/sweep.h"
#include "report/drive_figures.h"
#include "catalog/in_system.h"
#include "report/point_json.h"
#include "report/stand_figures.h"
#include "stand/prop_point.h"
#include "stand/throttle_table.h"

namespace dynosize::cli {

namespace {

void PrintPoint(const std::string& title, const OperatingPoint& p, const std::string& extra = "",
                const std::vector<std::string>& extra_limits = {}) {
  // Numerical guard: the same finiteness check as the JSON output (report/point_json.h); a
  // non-finite result of in-range inputs is a bug (InternalError, exit 70), never printed.
  (void)PointToJson(p);
  std::ostringstream o;
  o << std::fixed;
  o << title << "\n";
  o << std::setprecision(2) << "  supply         " << std::setw(10) << p.vdc_v << " V\n";
  o << std::setprecision(1) << "  throttle       " << std::setw(10) << 100 * p.throttle
    << " %   effective " << 100 * p.throttle_effective << " %"
    << (p.saturated ? "  (ESC saturated)" : "") << "\n";
  o << std::setprecision(0) << "  speed          " << std::setw(10) << p.rpm << " rpm  ("
    << std::setprecision(1) << p.omega_rad_s << " rad/s)\n";
  o << std::setprecision(4) << "  torque         " << std::setw(10) << p.torque_nm << " N*m\n";
  o << std::setprecision(2) << "  Irms           " << std::setw(10) << p.irms_a << " A\n";
  o << "  VLL,rms        " << std::setw(10) << p.vll_rms_v << " V\n";
  o << "  IDC            " << std::setw(10) << p.idc_a << " A\n";
  o << std::setprecision(1) << "  PDC            " << std::setw(10) << p.pdc_w << " W\n";
  o << "  PAC            " << std::setw(10) << p.pac_w << " W\n";
  o << "  Pmech          " << std::setw(10) << p.pmech_w << " W\n";
  o << "  PESC (loss)    " << std::setw(10) << p.pesc_w << " W\n";
  o << "  efficiency     motor " << 100 * p.eta_motor << " %, ESC " << 100 * p.eta_esc
    << " %, system " << 100 * p.eta_system << " %\n";
  o << extra;
  const bool feasible = p.feasible() && extra_limits.empty();
  o << "  feasible       " << (feasible ? "yes" : "NO");
  if (!feasible) {
    o << " (";
    auto names = LimitNames(p.limits);
    names.insert(names.end(), extra_limits.begin(), extra_limits.end());
    for (std::size_t i = 0; i < names.size(); ++i) o << (i ? ", " : "") << names[i];
    o << ")";
  }
  o << "\n";
  std::cout << o.str();
}

void PrintSweep(const std::string& title, const Drive& d, double vdc_v) {
  CheckJsonFinite(api::ThrottleTableJson(d, vdc_v), "per-throttle table");  // numerical guard, as PrintPoint
  std::ostringstream o;
  o << std::fixed << title << " at VDC = " << std::setprecision(2) << vdc_v << " V\n";
  o << "  TR %  TR_eff %  no-load rpm  stall N*m  maxP rpm  maxP W  best-eta rpm  eta_sys %  Irms A\n";
  for (const auto& r : SummarizeThrottles(d, vdc_v)) {
    o << std::setprecision(0) << std::setw(6) << 100 * r.throttle << std::setprecision(1)
      << std::setw(10) << 100 * r.throttle_effective << std::setprecision(0) << std::setw(13)
      << r.no_load_rpm << std::setprecision(4) << std::setw(11) << r.stall_torque_nm
      << std::setprecision(0) << std::setw(10) << r.max_power_rpm << std::setprecision(1)
      << std::setw(8) << r.max_power_w << std::setprecision(0) << std::setw(14)
      << r.max_efficiency_rpm << std::setprecision(1) << std::setw(11) << 100 * r.max_eta_system
      << std::setprecision(2) << std::setw(8) << r.at_max_efficiency.irms_a << "\n";
  }
  std::cout << o.str();
}

std::string PropLines(const PropPoint& pp, const PropEntry& prop, double rho_kg_m3) {
  std::ostringstream o;
  o << std::fixed << "  propeller      " << prop.name << " (" << prop.id << "), D = " << std::setprecision(4)
    << prop.diameter_m << " m, rho = " << std::setprecision(3) << rho_kg_m3 << " kg/m^3, static\n";
  o << std::setprecision(2) << "  thrust         " << std::setw(10) << pp.thrust_n << " N  ("
    << std::setprecision(0) << pp.thrust_n / kNewtonPerGramForce << " gf)\n";
  o << std::setprecision(2) << "  g/W            " << std::setw(10) << pp.g_per_w
    << " gf per DC watt\n";
  o << std::setprecision(3) << "  figure of merit" << std::setw(10) << pp.figure_of_merit
    << " (momentum theory: < 1; measured small props <= 0.75)\n";
  return o.str();
}


// The manufacturer-style table; returns the notes (propeller data at an edge, no convergence).
std::vector<std::string> PrintPropTable(const std::string& title, double vdc_v, double rho_kg_m3,
                                        const std::vector<ThrottleTableRow>& rows) {
  (void)api::PropTableJson(rows);  // numerical guard, as PrintPoint
  std::vector<std::string> notes;
  std::ostringstream o;
  o << std::fixed << title << " at VDC = " << std::setprecision(2) << vdc_v << " V, rho = "
    << std::setprecision(3) << rho_kg_m3 << " kg/m^3, static\n";
  o << "  TR %     rpm  thrust N  thrust gf    IDC A    PDC W  Pmech W    g/W  eta_sys %     FM  limits\n";
  for (const auto& r : rows) {
    const OperatingPoint& p = r.point.drive;
    std::string flags;
    for (const auto& n : LimitNames(p.limits)) flags += (flags.empty() ? "" : ",") + n;
    if (p.saturated) flags += (flags.empty() ? "" : ",") + std::string("esc_saturated");
    if (r.figure_of_merit > 1.0) flags += (flags.empty() ? "" : ",") + std::string("beats_momentum_theory");
    if (!r.point.converged || !r.point.prop.InData()) {
      flags += (flags.empty() ? "" : ",") + std::string(r.point.converged ? "prop_data_edge" : "not_converged");
      std::ostringstream n;
      n << std::fixed << "TR " << std::setprecision(0) << 100 * r.throttle << " %: "
        << (r.point.converged ? "propeller outside its data: " + r.point.prop.Message() : r.point.message);
      notes.push_back(n.str());
    }
    o << std::setprecision(0) << std::setw(6) << 100 * r.throttle << std::setw(8) << p.rpm
      << std::setprecision(2) << std::setw(10) << r.thrust_n << std::setprecision(0) << std::setw(11)
      << r.thrust_n / kNewtonPerGramForce << std::setprecision(2) << std::setw(9) << p.idc_a
      << std::setprecision(1) << std::setw(9) << p.pdc_w << std::setw(9) << p.pmech_w
      << std::setprecision(2) << std::setw(7) << r.g_per_w << std::setprecision(1) << std::setw(11)
      << 100 * p.eta_system << std::setprecision(3) << std::setw(7) << r.figure_of_merit << "  "
      << (flags.empty() ? "-" : flags) << "\n";
  }
  std::cout << o.str();
  return notes;
}


// simulate --batch: one output row per input row (rows may name a propeller).
void RunBatch(const SimulateOptions& o, const Catalog& catalog, const Drive& drive) {
  const auto requests = ReadPointsCsv(o.batch_csv);
  bool with_prop = false;
  for (const auto& r : requests) with_prop = with_prop || !r.prop.empty();
  const api::BatchResult points = api::SimulateBatch(catalog, drive, requests, o.batch_csv);
  std::ostringstream csv;
  const auto& cols = PointCsvColumns();
  for (std::size_t i = 0; i < cols.size(); ++i) csv << (i ? "," : "") << cols[i];
  csv << (with_prop ? ",prop,thrust_n,g_per_w\n" : "\n");
  std::size_t infeasible = 0;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const PointRequest& r = requests[i];
    if (!points.feasible(i)) ++infeasible;
    if (!points.has_prop(i)) {
      csv << PointToCsvRow(points.point(i)) << (with_prop ? ",,,\n" : "\n");
      continue;
    }
    std::ostringstream extra;
    extra.precision(10);
    extra << "," << r.prop << "," << points.thrust_n(i) << "," << points.g_per_w(i);
    std::string row = PointToCsvRow(points.point(i));
    if (points.beats_momentum_theory(i)) {
      // The last two columns are feasible and limits (report/point_json.h): as the JSON says.
      std::string limits;
      for (const auto& n : points.LimitNames(i)) limits += (limits.empty() ? "" : ";") + n;
      row = row.substr(0, row.rfind(',', row.rfind(',') - 1)) + ",0," + limits;
    }
    csv << row << extra.str() << "\n";
  }
  if (o.out_csv.empty()) {
    std::cout << csv.str();
  } else {
    WriteFileAtomic(o.out_csv, csv.str());
    std::cerr << "wrote " << requests.size() << " points to " << o.out_csv << " ("
              << infeasible << " infeasible)\n";
  }
}

// The flags that choose what simulate solves (api/simulate_request.h).
api::SimulateRequest RequestOf(const SimulateOptions& o) {
  api::SimulateRequest r;
  r.motor_id = o.motor_id;
  r.esc_id = o.esc_id;
  r.vdc_v = o.vdc_v;
  r.throttle = o.throttle;
  r.torque_nm = o.torque_nm;
  r.rpm = o.rpm;
  r.torque_law = o.torque_law;
  r.prop_id = o.prop_id;
  r.prop_param = o.prop_param;
  r.prop_family = o.prop_family;
  r.thrust_n = o.thrust_n;
  r.rho_kg_m3 = o.rho_kg_m3;
  return r;
}

// simulate --prop: a point (--throttle, --rpm or --thrust-n) or the table over throttle.
int RunSimulateProp(const SimulateOptions& o) {
  if ((!o.prop_id.empty() || !o.prop_param.empty()) && !o.batch_csv.empty()) {
    throw UsageError("--prop does not go with --batch: name the propeller per row in a 'prop' column");
  }
  if (!o.out_csv.empty() && !o.prop_id.empty()) throw UsageError("--out goes with --batch");
  const api::SimulateRequest request = RequestOf(o);
  const PropPointRequest req = api::PropPointRequestOf(request);
  const bool point_mode = api::IsPointRequest(request);
  const Catalog catalog = Catalog::Load(o.catalog);
  const MotorEntry& motor = catalog.motor(o.motor_id);
  const EscEntry& esc = catalog.esc(o.esc_id);
  const PropEntry prop_entry = api::ResolveProp(catalog, request);
  const Gear& gear = motor.gear;
  const std::string title = motor.name + " + " + esc.name + " + " + prop_entry.name;
  const std::string assumed = api::AssumedNote(motor, esc, &prop_entry);
  std::vector<std::string> notes;
  if (point_mode) {
    const api::PropPointRun run = api::RunPropPoint(motor, esc, prop_entry, req);
    const PropPoint& pp = run.point;
    std::string gear_line;
    if (gear.geared()) {
      std::ostringstream g;
      g << std::fixed << std::setprecision(0) << "  propeller rpm  " << std::setw(10) << run.prop_rpm
        << "     (geared " << std::setprecision(2) << gear.ratio << ":1, efficiency " << std::setprecision(3)
        << gear.efficiency << "; gear loss " << std::setprecision(1) << run.shaft.gear_loss_w
        << " W; rpm, torque and Pmech above are the motor's shaft)\n";
      gear_line = g.str();
    }
    if (o.json) {
      std::cout << DumpJson(api::PropPointRunJson(run, motor, esc, prop_entry, o.rho_kg_m3));
    } else {
      PrintPoint(title, pp.drive, gear_line + PropLines(pp, prop_entry, o.rho_kg_m3),
                 pp.figure_of_merit > 1.0 ? std::vector<std::string>{"beats_momentum_theory"}
                                          : std::vector<std::string>{});
      if (pp.figure_of_merit > 1.0) {
        std::ostringstream w;
        w << "figure of merit " << pp.figure_of_merit
          << " > 1: the propeller data beat momentum theory here (model.md section 10)";
        notes.push_back(w.str());
      }
      if (!pp.converged) {
        notes.push_back(pp.note);
      } else if (!pp.prop.InData()) {
        notes.push_back("propeller outside its data: " + pp.prop.Message());
      } else if (!pp.note.empty()) {
        notes.push_back(pp.note);
      }
    }
  } else {
    // The table is the propeller's: solved at its shaft through the gearbox (model/gear.h).
    const Drive drive(MotorAtPropellerShaft(motor.params, gear), esc.params);
    const PropModel prop(prop_entry);
    if (gear.geared() && !o.json) {
      std::cerr << "note: geared " << gear.ratio << ":1 (model/gear.h): the table's rpm and Pmech are the "
                << "propeller's; the motor turns " << gear.ratio << " x faster\n";
    }
    const auto rows = PropThrottleTable(drive, prop, req.vdc_v, o.rho_kg_m3);
    std::string figure;
    if (!o.plot_dir.empty()) {
      figure = WriteThrottleTableFigure(rows, title + " at VDC = " + SignificantText(req.vdc_v) + " V", o.plot_dir);
    }
    if (o.json) {
      std::cout << DumpJson(api::PropTableRunJson(motor, esc, prop_entry, req.vdc_v, o.rho_kg_m3, rows,
                                                  figure.empty() ? std::vector<std::string>{}
                                                                 : std::vector<std::string>{figure}));
    } else {
      notes = PrintPropTable(title, req.vdc_v, o.rho_kg_m3, rows);
      if (!figure.empty()) std::cerr << "wrote " << figure << "\n";
    }
  }
  if (!o.json) {
    for (const auto& n : notes) std::cerr << "note: " << n << "\n";
    if (!assumed.empty()) std::cerr << "note: results rest on assumed catalog values (" << assumed << ")\n";
  }
  return 0;
}

// One operating point (text or JSON) with its p10-p90 range (api::SolvePointRange).
void PrintPointWithRange(const SimulateOptions& o, const PointRequest& req, const MotorEntry& motor,
                         const EscEntry& esc) {
  const std::string title = motor.name + " + " + esc.name;
  const api::PointRange range = api::SolvePointRange(motor, esc, req, o.torque_law);
  if (o.json) {
    std::cout << DumpJson(api::PointWithRangeJson(motor, esc, range));
    return;
  }
  const OperatingPoint& lo = range.lo;
  const OperatingPoint& hi = range.hi;
  PrintPoint(title, range.point);
  std::ostringstream r;
  r.setf(std::ios::fixed);
  r << std::setprecision(2) << "  range p10-p90  IDC " << std::min(lo.idc_a, hi.idc_a) << "-"
    << std::max(lo.idc_a, hi.idc_a) << " A, " << std::setprecision(1) << "PDC " << std::min(lo.pdc_w, hi.pdc_w)
    << "-" << std::max(lo.pdc_w, hi.pdc_w) << " W ("
    << (motor.datasheet_params ? "the in-system law's scatter" : "the motor's tier band") << ")\n";
  std::cout << r.str();
  const std::string law = InSystemSummary(motor);
  if (!law.empty()) std::cout << "  " << law << "\n";
}

}  // namespace

int RunSimulate(const SimulateOptions& o) {
  if (!o.prop_id.empty() || !o.prop_param.empty() || o.thrust_n) {
    if (!o.batch_csv.empty() && o.prop_id.empty() && o.prop_param.empty()) {
      throw UsageError("--thrust-n does not go with --batch: use a thrust_n column");
    }
    return RunSimulateProp(o);
  }
  // Check the command line before reading anything.
  const bool point_mode = o.throttle || o.torque_nm || o.rpm || !o.torque_law.empty();
  if (!o.batch_csv.empty() && (point_mode || o.vdc_v)) {
    throw UsageError("--batch takes its points from the file: do not combine it with --vdc, "
                     "--throttle, --torque, --rpm or --torque-law");
  }
  if (!o.out_csv.empty() && o.batch_csv.empty()) throw UsageError("--out goes with --batch");
  // The point (or the table's voltage), checked before anything is read (api/simulate_request.h).
  const PointRequest req = o.batch_csv.empty() ? api::PointRequestOf(RequestOf(o)) : PointRequest{};
  const Catalog catalog = Catalog::Load(o.catalog);
  const MotorEntry& motor = catalog.motor(o.motor_id);
  const EscEntry& esc = catalog.esc(o.esc_id);
  const Drive drive(motor.params, esc.params);
  const std::string title = motor.name + " + " + esc.name;
  const std::string assumed = api::AssumedNote(motor, esc, nullptr);
  // Said once the results are out, so that an error stays the only line on stderr.
  const auto note_assumed = [&] {
    if (!assumed.empty() && !o.json) {
      std::cerr << "note: results rest on assumed catalog values (" << assumed << ")\n";
    }
  };

  std::vector<std::string> figures;
  if (!o.plot_dir.empty()) {
    DriveFigureOptions fo;
    fo.vdc_v = req.vdc_v > 0 ? req.vdc_v : 0.0;
    if (!(fo.vdc_v > 0.0)) throw UsageError("--plot needs --vdc (the figures are drawn at one voltage)");
    fo.title = title;
    fo.esc_name = esc.name;
    figures = WriteDriveFigures(drive, fo, o.plot_dir);
    if (!o.json) {
      for (const auto& f : figures) std::cerr << "wrote " << f << "\n";
    }
  }

  if (!o.batch_csv.empty()) {
    RunBatch(o, catalog, drive);
    note_assumed();
    return 0;
  }

  if (point_mode) {
    PrintPointWithRange(o, req, motor, esc);
    note_assumed();
    return 0;
  }

  // No point given: the characteristic table per throttle at --vdc.
  if (o.json) {
    std::cout << DumpJson(api::DriveTableJson(motor, esc, req.vdc_v, figures));
  } else {
    PrintSweep(title, drive, req.vdc_v);
  }
  // The table has no feasibility column: say it when its points create energy (docs/model.md
  // section 10; the JSON carries the limit per point).
  if (!o.json) {
    int bad = 0, rows = 0;
    for (const auto& r : SummarizeThrottles(drive, req.vdc_v)) {
      ++rows;
      bad += (r.at_max_efficiency.limits & kLimitCreatesEnergy) ? 1 : 0;
    }
    if (bad) {
      std::cerr << "warning: the best-efficiency point creates energy (PESC < 0 or eta_motor > 1, limit "
                   "creates_energy) at " << bad << " of " << rows
                << " throttles: these motor/ESC constants break model.md section 10\n";
    }
  }
  note_assumed();
  return 0;
}

}  // namespace dynosize::cli
