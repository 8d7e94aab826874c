// `dynosize simulate`: the model of src/model on catalog entries, one point, a batch, or figures.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "catalog/catalog.h"
#include "commands.h"
#include "common/error.h"
#include "common/text_file.h"
#include "common/units.h"
#include "io/points_csv.h"
#include "model/sweep.h"
#include "report/drive_figures.h"
#include "report/point_json.h"

namespace dynosize::cli {

std::string DefaultCatalogDir() {
  if (const char* env = std::getenv("DYNOSIZE_CATALOG"); env && *env) return env;
  std::error_code ec;
  if (std::filesystem::is_directory(DYNOSIZE_DEFAULT_CATALOG, ec)) return DYNOSIZE_DEFAULT_CATALOG;
  return "catalog";
}

namespace {

std::string FlagValue(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

OperatingPoint Solve(const Drive& d, const PointRequest& r, const std::vector<double>& law) {
  if (!law.empty()) return d.AtLoad(r.vdc_v, *r.throttle, TorqueLaw{law[0], law[1], law[2]});
  if (r.throttle && r.torque_nm) return d.AtTorque(r.vdc_v, *r.throttle, *r.torque_nm);
  if (r.throttle && r.rpm) return d.AtSpeed(r.vdc_v, *r.throttle, RpmToRadPerSec(*r.rpm));
  return d.Inverse(r.vdc_v, *r.torque_nm, RpmToRadPerSec(*r.rpm));
}

std::string Assumed(const EntryBase& e) {
  std::string s;
  for (const auto& k : e.assumed_keys) s += (s.empty() ? "" : ", ") + k;
  return s;
}

void PrintPoint(const std::string& title, const OperatingPoint& p) {
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
  o << "  feasible       " << (p.feasible() ? "yes" : "NO");
  if (!p.feasible()) {
    o << " (";
    const auto names = LimitNames(p.limits);
    for (std::size_t i = 0; i < names.size(); ++i) o << (i ? ", " : "") << names[i];
    o << ")";
  }
  o << "\n";
  std::cout << o.str();
}

Json SweepJson(const Drive& d, double vdc_v);

void PrintSweep(const std::string& title, const Drive& d, double vdc_v) {
  CheckJsonFinite(SweepJson(d, vdc_v), "per-throttle table");  // numerical guard, as PrintPoint
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

Json SweepJson(const Drive& d, double vdc_v) {
  Json rows = Json::array();
  for (const auto& r : SummarizeThrottles(d, vdc_v)) {
    Json j;
    j["throttle"] = r.throttle;
    j["throttle_effective"] = r.throttle_effective;
    j["no_load_rpm"] = r.no_load_rpm;
    j["stall_torque_nm"] = r.stall_torque_nm;
    j["max_power_rpm"] = r.max_power_rpm;
    j["max_power_w"] = r.max_power_w;
    j["max_efficiency_rpm"] = r.max_efficiency_rpm;
    j["max_eta_system"] = r.max_eta_system;
    j["at_max_efficiency"] = PointToJson(r.at_max_efficiency);
    j["esc_timing_figure"] = d.EscTimingFigure(r.throttle);
    rows.push_back(j);
  }
  return rows;
}

}  // namespace

int RunSimulate(const SimulateOptions& o) {
  // Check the command line before reading anything.
  const bool point_mode = o.throttle || o.torque_nm || o.rpm || !o.torque_law.empty();
  if (!o.batch_csv.empty() && (point_mode || o.vdc_v)) {
    throw UsageError("--batch takes its points from the file: do not combine it with --vdc, "
                     "--throttle, --torque, --rpm or --torque-law");
  }
  if (!o.out_csv.empty() && o.batch_csv.empty()) throw UsageError("--out goes with --batch");
  if (o.batch_csv.empty() && !o.vdc_v) throw UsageError("--vdc is required (supply voltage, V)");
  PointRequest req;
  if (o.vdc_v) {
    req.vdc_v = *o.vdc_v;
    if (!(req.vdc_v > 0.0 && req.vdc_v <= kMaxRequestVdcV)) {
      throw UsageError("--vdc " + FlagValue(*o.vdc_v) + ": must be a finite number > 0 V and <= " +
                       FlagValue(kMaxRequestVdcV) + " V");
    }
  }
  if (point_mode) {
    req.throttle = o.throttle;
    req.torque_nm = o.torque_nm;
    req.rpm = o.rpm;
    if (!o.torque_law.empty()) {
      if (o.torque_nm || o.rpm) throw UsageError("--torque-law replaces --torque and --rpm");
      if (!o.throttle) throw UsageError("--torque-law needs --throttle");
      for (double c : o.torque_law) {
        if (!(std::fabs(c) <= kMaxTorqueLawCoefficient)) {
          throw UsageError("--torque-law " + FlagValue(c) + ": coefficients must be finite, at most " +
                           FlagValue(kMaxTorqueLawCoefficient) + " in magnitude (SI)");
        }
      }
      if (o.torque_law[2] < 0.0) throw UsageError("--torque-law: C must be >= 0 (a propeller's torque grows with speed)");
      req.torque_nm = 0.0;  // for the checks below: one load given (its coefficients are checked above)
    }
    if (o.throttle && !(*o.throttle >= 0.0 && *o.throttle <= 1.0)) {
      throw UsageError("--throttle " + FlagValue(*o.throttle) +
                       ": must be between 0 and 1 (a fraction: 0.6 for 60 %)");
    }
    if (o.torque_nm && !(*o.torque_nm >= 0.0 && *o.torque_nm <= kMaxRequestTorqueNm)) {
      throw UsageError("--torque " + FlagValue(*o.torque_nm) + ": must be a finite number >= 0 N*m and <= " +
                       FlagValue(kMaxRequestTorqueNm) + " N*m");
    }
    if (o.rpm && !(*o.rpm >= 0.0 && *o.rpm <= kMaxRequestRpm)) {
      throw UsageError("--rpm " + FlagValue(*o.rpm) + ": must be a finite number >= 0 and <= " +
                       FlagValue(kMaxRequestRpm));
    }
    if (!CheckPointRequest(req).empty()) {
      throw UsageError("give --throttle with one of --torque, --rpm, --torque-law (forward model), "
                       "or --torque and --rpm without --throttle (inverse)");
    }
  }

  const Catalog catalog = Catalog::Load(o.catalog_dir);
  const MotorEntry& motor = catalog.motor(o.motor_id);
  const EscEntry& esc = catalog.esc(o.esc_id);
  const Drive drive(motor.params, esc.params);
  const std::string title = motor.name + " + " + esc.name;
  std::string assumed;
  if (!motor.assumed_keys.empty()) assumed += "motor " + motor.id + ": " + Assumed(motor);
  if (!esc.assumed_keys.empty()) {
    assumed += (assumed.empty() ? "" : "; ") + std::string("ESC ") + esc.id + ": " + Assumed(esc);
  }
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
    const auto requests = ReadPointsCsv(o.batch_csv);
    std::ostringstream csv;
    const auto& cols = PointCsvColumns();
    for (std::size_t i = 0; i < cols.size(); ++i) csv << (i ? "," : "") << cols[i];
    csv << "\n";
    std::size_t infeasible = 0;
    for (const auto& r : requests) {
      const OperatingPoint p = Solve(drive, r, {});
      if (!p.feasible()) ++infeasible;
      csv << PointToCsvRow(p) << "\n";
    }
    if (o.out_csv.empty()) {
      std::cout << csv.str();
    } else {
      WriteFileAtomic(o.out_csv, csv.str());
      std::cerr << "wrote " << requests.size() << " points to " << o.out_csv << " ("
                << infeasible << " infeasible)\n";
    }
    note_assumed();
    return 0;
  }

  if (point_mode) {
    const OperatingPoint p = Solve(drive, req, o.torque_law);
    if (o.json) {
      Json j = PointToJson(p);
      j["motor"] = motor.id;
      j["esc"] = esc.id;
      if (!assumed.empty()) j["assumed"] = assumed;
      std::cout << DumpJson(j);
    } else {
      PrintPoint(title, p);
    }
    note_assumed();
    return 0;
  }

  // No point given: the characteristic table per throttle at --vdc.
  if (o.json) {
    Json j;
    j["motor"] = motor.id;
    j["esc"] = esc.id;
    j["vdc_v"] = req.vdc_v;
    j["throttles"] = SweepJson(drive, req.vdc_v);
    j["figures"] = figures;
    if (!assumed.empty()) j["assumed"] = assumed;
    std::cout << DumpJson(j);
  } else {
    PrintSweep(title, drive, req.vdc_v);
  }
  note_assumed();
  return 0;
}

}  // namespace dynosize::cli
