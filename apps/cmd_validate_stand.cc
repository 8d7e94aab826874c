// `dynosize validate-stand TABLE --motor M --esc E [--prop P]`: a measured stand table predicted
// row by row through catalog entries (src/stand/stand.h), dynosize beside the plain DC model.
#include <charconv>
#include <filesystem>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "catalog/catalog.h"
#include "commands.h"
#include "common/error.h"
#include "common/json_file.h"
#include "common/text_format.h"
#include "common/units.h"
#include "logs/log_reader.h"
#include "report/stand_figures.h"
#include "stand/stand.h"

namespace dynosize::cli {

namespace {

using stand::kAtMeasuredRpm;
using stand::kAtMeasuredTorque;
using stand::kDynosize;
using stand::kFromThrottle;
using stand::kPlainDc;

// "FIRST-LAST" (either side may be empty) -> read options.
void ParseLines(const std::string& text, stand::StandReadOptions* o) {
  if (text.empty()) return;
  const auto dash = text.find('-');
  auto parse = [&](const std::string& part, std::size_t* out) {
    if (part.empty()) return true;
    const auto res = std::from_chars(part.data(), part.data() + part.size(), *out);
    return res.ec == std::errc() && res.ptr == part.data() + part.size() && *out > 0;
  };
  if (dash == std::string::npos || !parse(text.substr(0, dash), &o->first_line) ||
      !parse(text.substr(dash + 1), &o->last_line) ||
      (o->last_line && o->first_line > o->last_line)) {
    throw UsageError("--lines '" + text + "': expected FIRST-LAST, line numbers of the file (1 = header), "
                     "FIRST <= LAST, e.g. 2-12 or 13-");
  }
}

const char* ColumnLabel(const std::string& c) {
  if (c == "thrust_n") return "thrust";
  if (c == "idc_a") return "DC current";
  if (c == "rpm") return "rpm";
  if (c == "torque_nm") return "torque";
  return "throttle (points)";
}

void PrintSummary(const stand::StandTable& t, const stand::StandResult& r, const std::string& title) {
  std::ostringstream o;
  o << title << "\n";
  o << "  " << t.rows.size() << " rows";
  for (const auto& d : t.dropped) o << "; " << d.count << " dropped (" << d.reason << ")";
  if (t.vdc_from_option) o << "; VDC from --vdc";
  o << "\n";
  for (int mode : {stand::kAtMeasuredRpm, stand::kAtMeasuredTorque, stand::kFromThrottle}) {
    if (!r.mode_used[mode]) continue;
    o << "\n  "
      << (mode == kAtMeasuredRpm      ? "at the measured rpm"
          : mode == kAtMeasuredTorque ? "at the measured rpm and torque (motor + ESC alone)"
                                      : "forward from the throttle")
      << " (load: " << r.load[mode] << ")\n";
    o << "    column              n   dynosize MAE %  (bias)   plain DC MAE %  (bias)   better\n";
    for (const stand::ColumnError& a : r.errors[mode][kDynosize]) {
      const stand::ColumnError* b = stand::FindError(r, mode, kPlainDc, a.column);
      o << "    " << std::left << std::setw(18) << ColumnLabel(a.column) << std::right << std::setw(3) << a.n
        << std::setw(17) << FixedText(a.mae, 1) << std::setw(8) << ("(" + FixedText(a.bias, 1) + ")");
      if (b) {
        o << std::setw(17) << FixedText(b->mae, 1) << std::setw(8) << ("(" + FixedText(b->bias, 1) + ")") << "   "
          << (std::fabs(a.mae - b->mae) < 0.05 ? "same"
              : a.mae < b->mae                 ? "dynosize"
                                               : "plain DC");
      }
      o << "\n";
    }
    if (r.rows_infeasible[mode]) {
      o << "    " << r.rows_infeasible[mode] << " dynosize points flagged infeasible (see --rows or --json)\n";
    }
  }
  std::cout << o.str();
}

void PrintRows(const stand::StandTable& t, const stand::StandResult& r) {
  std::ostringstream o;
  o << std::fixed << "\n  rows (measured / dynosize / plain DC)\n"
    << "    line   VDC V  thr %  rpm meas  rpm dyn   rpm dc  IDC meas  IDC@rpm dyn  IDC@rpm dc  thrust meas N  thrust@rpm N  limits\n";
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const stand::StandRow& row = t.rows[i];
    const auto& at = r.rows[i].pred[kAtMeasuredRpm];
    const auto& fw = r.rows[i].pred[kFromThrottle];
    auto num = [](const std::optional<double>& v, int w, int prec, double scale = 1.0) {
      std::ostringstream s;
      s << std::fixed << std::setw(w) << std::setprecision(prec);
      if (v) s << *v * scale; else s << "-";
      return s.str();
    };
    auto opt = [](bool ok, double v) { return ok ? std::optional<double>(v) : std::nullopt; };
    std::string limits;
    for (const auto& l : at[kDynosize].limits) limits += (limits.empty() ? "" : ",") + l;
    if (!r.rows[i].prop_note.empty()) limits += (limits.empty() ? "" : ",") + std::string("prop_data_edge");
    o << std::setw(8) << row.line << num(row.vdc_v, 8, 2) << num(row.throttle, 7, 1, 100.0)
      << num(row.omega_rad_s, 10, 0, 1.0 / kRadPerSecPerRpm) << num(opt(fw[0].valid, fw[0].rpm), 9, 0)
      << num(opt(fw[1].valid, fw[1].rpm), 9, 0) << num(row.idc_a, 10, 2)
      << num(opt(at[0].valid, at[0].idc_a), 13, 2) << num(opt(at[1].valid, at[1].idc_a), 12, 2)
      << num(row.thrust_n, 15, 2) << num(at[0].valid ? at[0].thrust_n : std::nullopt, 14, 2) << "  "
      << (limits.empty() ? "-" : limits) << "\n";
  }
  std::cout << o.str();
}

Json PredictionJson(const stand::StandPrediction& p) {
  if (!p.valid) return nullptr;
  Json j;
  j["rpm"] = p.rpm;
  j["torque_nm"] = p.torque_nm;
  j["idc_a"] = p.idc_a;
  j["throttle"] = p.throttle;
  j["thrust_n"] = p.thrust_n ? Json(*p.thrust_n) : Json(nullptr);
  j["feasible"] = p.feasible;
  j["limits"] = p.limits;
  return j;
}

Json ResultJson(const stand::StandTable& t, const stand::StandResult& r) {
  Json j;
  j["rows_used"] = t.rows.size();
  Json dropped = Json::object();
  for (const auto& d : t.dropped) dropped[d.reason] = d.count;
  j["dropped"] = dropped;
  j["rows_outside_prop_data"] = r.rows_outside_prop_data;
  Json errors = Json::object(), rows = Json::array();
  for (int mode = 0; mode < stand::kStandModes; ++mode) {
    if (!r.mode_used[mode]) continue;
    Json m;
    m["load"] = r.load[mode];
    m["dynosize_infeasible_rows"] = r.rows_infeasible[mode];
    for (int model = 0; model < 2; ++model) {
      Json cols = Json::object();
      for (const auto& e : r.errors[mode][model]) {
        cols[e.column] = {{"n", e.n}, {"mae", e.mae}, {"bias", e.bias}, {"max_abs", e.max_abs},
                          {"unit", e.column == "throttle" ? "percentage points" : "percent"}};
      }
      m[stand::StandModelName(model)] = cols;
    }
    errors[stand::StandModeName(mode)] = m;
  }
  j["errors"] = errors;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const stand::StandRow& row = t.rows[i];
    Json x;
    x["line"] = row.line;
    x["vdc_v"] = row.vdc_v;
    auto put = [&](const char* k, const std::optional<double>& v, double scale = 1.0) {
      x["measured"][k] = v ? Json(*v * scale) : Json(nullptr);
    };
    put("throttle", row.throttle);
    put("rpm", row.omega_rad_s, 1.0 / kRadPerSecPerRpm);
    put("thrust_n", row.thrust_n);
    put("idc_a", row.idc_a);
    put("torque_nm", row.torque_nm);
    for (int mode = 0; mode < stand::kStandModes; ++mode) {
      if (!r.mode_used[mode]) continue;
      for (int model = 0; model < 2; ++model) {
        x[stand::StandModeName(mode)][stand::StandModelName(model)] = PredictionJson(r.rows[i].pred[mode][model]);
      }
    }
    if (!r.rows[i].prop_note.empty()) x["prop_note"] = r.rows[i].prop_note;
    rows.push_back(x);
  }
  j["rows"] = rows;
  return j;
}

}  // namespace

int RunValidateStand(const ValidateStandOptions& o) {
  const logs::LogReadOptions ro = api::ToLogReadOptions(o.input);
  stand::StandReadOptions so;
  ParseLines(o.lines, &so);
  if (o.vdc_v && !(*o.vdc_v > 0.0 && *o.vdc_v <= 1e5)) {
    throw UsageError("--vdc " + FixedText(*o.vdc_v, 3) + ": must be a finite number > 0 V and <= 100000 V");
  }
  so.vdc_v = o.vdc_v;
  stand::StandOptions po;
  po.rho_kg_m3 = o.rho_kg_m3;
  if (!(po.rho_kg_m3 > 0.0 && po.rho_kg_m3 <= 100.0)) {
    throw UsageError("--rho-kg-m3 " + FixedText(po.rho_kg_m3, 4) + ": must be a finite number > 0 and <= 100");
  }

  const Catalog catalog = Catalog::Load(o.catalog);
  const MotorEntry& motor = catalog.motor(o.motor_id);
  const EscEntry& esc = catalog.esc(o.esc_id);
  const PropEntry* prop_entry = o.prop_id.empty() ? nullptr : &catalog.prop(o.prop_id);
  const logs::SteadyTable log = logs::ReadLog(o.table, ro);
  const stand::StandTable table = stand::StandTableFromLog(log, so);
  EscEntry esc_used = esc;
  if (o.ideal_esc) esc_used.params = stand::IdealEsc(esc.params, motor.params.type);
  const Drive drive(motor.params, esc_used.params);
  const DcBaselineNumbers numbers =
      o.baseline == "as-stored" ? DcBaselineNumbers::kAsStored : DcBaselineNumbers::kDatasheet;
  const DcMotor dc = DcMotorFromCatalog(motor, esc_used, numbers);
  std::optional<PropModel> prop;
  if (prop_entry) prop.emplace(*prop_entry);
  const stand::StandResult result = stand::PredictStand(table, drive, dc, prop ? &*prop : nullptr, po);

  const std::string title = std::filesystem::path(o.table).filename().string() + ": " + motor.name + " + " + esc.name +
                            (prop_entry ? " + " + prop_entry->name : std::string(" (measured torque as the load)"));
  std::string figure;
  if (!o.plot_dir.empty()) {
    const std::string settings = std::string(numbers == DcBaselineNumbers::kAsStored ? " [--baseline as-stored]" : "") +
                                 (o.ideal_esc ? " [--ideal-esc]" : "");
    figure = WriteStandFigure(table, result, title + settings, o.plot_dir);
  }
  if (o.json) {
    Json j = ResultJson(table, result);
    j["table"] = o.table;
    j["motor"] = motor.id;
    j["esc"] = esc.id;
    j["prop"] = prop_entry ? Json(prop_entry->id) : Json(nullptr);
    j["rho_kg_m3"] = po.rho_kg_m3;
    j["baseline"] = {{"kv_rpm_per_v", dc.kv_rpm_per_v}, {"r_ohm", dc.r_ohm}, {"io_a", dc.io_a},
                     {"kt_nm_per_a", dc.kt_nm_per_a()}, {"numbers", DcBaselineName(numbers)}};
    j["ideal_esc"] = o.ideal_esc;
    j["figures"] = figure.empty() ? Json::array() : Json::array({figure});
    CheckJsonFinite(j, "validate-stand result");
    std::cout << DumpJson(j);
    return 0;
  }
  CheckJsonFinite(ResultJson(table, result), "validate-stand result");  // numerical guard
  PrintSummary(table, result, title);
  std::cout << "\n  plain DC model: label Kv " << FixedText(dc.kv_rpm_per_v, 1) << " rpm/V, R = "
            << (numbers == DcBaselineNumbers::kAsStored ? "rm_ohm + resc_ohm = " : "R_dc + RESC_dc = ")
            << FixedText(1000.0 * dc.r_ohm, 2) << " mOhm, Io "
            << (numbers == DcBaselineNumbers::kAsStored ? "io_a = " : "Io_dc = ") << FixedText(dc.io_a, 3)
            << " A (--baseline " << DcBaselineName(numbers)
            << "): I = Io + Q/KT_dc, KT_dc = 60/(2*pi*Kv), U = n/Kv + R*I, IDC = U*I/VDC\n";
  if (o.ideal_esc) {
    std::cout << "  ESC: ideal in both models (--ideal-esc: no resistance, no saturation knee, eq 56)\n";
  }
  if (o.rows) PrintRows(table, result);
  if (result.rows_outside_prop_data) {
    std::cerr << "note: " << result.rows_outside_prop_data
              << " rows use propeller data held at an edge (e.g. "
              << [&] {
                   for (const auto& rr : result.rows) if (!rr.prop_note.empty()) return rr.prop_note;
                   return std::string();
                 }()
              << ")\n";
  }
  if (!figure.empty()) std::cerr << "wrote " << figure << "\n";
  std::string assumed;
  for (const EntryBase* e : {static_cast<const EntryBase*>(&motor), static_cast<const EntryBase*>(&esc),
                             static_cast<const EntryBase*>(prop_entry)}) {
    if (!e || e->assumed_keys.empty()) continue;
    std::string keys;
    for (const auto& k : e->assumed_keys) keys += (keys.empty() ? "" : ", ") + k;
    assumed += (assumed.empty() ? "" : "; ") + e->id + ": " + keys;
  }
  if (!assumed.empty()) std::cerr << "note: predictions rest on assumed catalog values (" << assumed << ")\n";
  return 0;
}

}  // namespace dynosize::cli
