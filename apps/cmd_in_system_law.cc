// `dynosize catalog in-system-law`: fits the in-system law (catalog/in_system.h) on the measured
// data and prints the report of docs/in-system-law.md (scripts/validation_in_system.sh).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "catalog/catalog.h"
#include "catalog/conventions.h"
#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"
#include "importers/kde_sheets.h"
#include "report/in_system_figure.h"
#include "stand/in_system_fit.h"

namespace dynosize::cli {

namespace {

// The sheets with measured torque; *without (optional) names the others.
std::vector<stand::LawMotor> KdeLawMotors(const std::string& dir, std::vector<std::string>* without = nullptr) {
  std::vector<stand::LawMotor> out;
  for (const auto& k : ReadKdeSheets(dir)) {
    if (!k.has_torque()) {
      if (without) without->push_back(k.name);
      continue;
    }
    stand::LawMotor m;
    m.name = k.name;
    m.datasheet = {k.kv_rpm_per_v, k.r_dc_ohm, k.io_dc_a, k.io_test_voltage_v};
    for (const auto& r : k.rows) {
      m.points.push_back({r.vdc_v, r.throttle, r.idc_a, r.rpm * kRadPerSecPerRpm, r.torque_nm, r.block});
    }
    out.push_back(std::move(m));
  }
  return out;
}

std::string CatalogIdsOf(const Catalog& raw, const std::string& name) {
  std::string ids;
  for (const auto& m : raw.motors()) {
    if (m.name == name) ids += (ids.empty() ? "" : ", ") + m.id;
  }
  return ids.empty() ? "-" : ids;
}

void PrintLawConstants(const char* name, const InSystemLaw& l) {
  std::printf("constexpr InSystemLaw %s{\n    /*r_scale=*/%.4g, /*r_add_ohm=*/%.4g, /*io_scale=*/%.4g, /*io_speed=*/%.4g,\n"
              "    /*r_ratio_p10=*/%.4g, /*r_ratio_p90=*/%.4g, /*io_ratio_p10=*/%.4g, /*io_ratio_p90=*/%.4g,\n"
              "    /*motors=*/%d, ...};\n",
              name, l.r_scale, l.r_add_ohm, l.io_scale, l.io_speed, l.r_ratio_p10, l.r_ratio_p90, l.io_ratio_p10,
              l.io_ratio_p90, l.motors);
}

std::string LawText(const InSystemLaw& l) {
  return "R_dc,sys = " + FixedText(l.r_scale, 3) + "*R_dc + " + FixedText(1e3 * l.r_add_ohm, 1) + " mOhm; Io_dc,sys = Io_dc*(" +
         FixedText(l.io_scale, 3) + (l.io_speed != 0.0 ? " + " + FixedText(l.io_speed, 3) + "*omega/omega_test" : std::string()) +
         "); one motor's R within x" + FixedText(l.r_ratio_p10, 2) + "-" + FixedText(l.r_ratio_p90, 2) + ", Io within x" +
         FixedText(l.io_ratio_p10, 2) + "-" + FixedText(l.io_ratio_p90, 2) + " (p10-p90)";
}

void PrintMotorTable(const stand::LawReport& r, const Catalog& raw) {
  std::cout << "| motor | catalog entry | points | sweeps | plain DC, datasheet values: IDC error / bias | "
               "in-system law: IDC error / bias | p10-p90 coverage | rpm forward (offset prior) | "
               "own R, Io over the law |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : r.left_out) {
    std::cout << "| " << c.name << " | " << CatalogIdsOf(raw, c.name) << " | " << c.points << " | " << c.sweeps << " | "
              << PercentText(c.datasheet_error) << " / " << PercentText(c.datasheet_bias) << " | "
              << PercentText(c.law_error) << " / " << PercentText(c.law_bias) << " | " << PercentText(c.coverage)
              << " | " << PercentText(c.rpm_error_forward) << " (dead band " << FixedText(c.deadband_prior, 3)
              << ") | x" << FixedText(c.own.r_ratio, 2) << ", x" << FixedText(c.own.io_ratio, 2) << " |\n";
  }
  std::cout << "| **all** | | " << r.points << " | " << r.sweeps << " | **" << PercentText(r.datasheet_error) << " / "
            << PercentText(r.datasheet_bias) << "** | **" << PercentText(r.law_error) << " / "
            << PercentText(r.law_bias) << "** | **" << PercentText(r.coverage) << "** | **"
            << PercentText(r.rpm_error_forward) << "** | |\n\n";
}

}  // namespace

int RunInSystemLaw(const InSystemLawOptions& o) {
  std::vector<std::string> no_torque;
  const std::vector<stand::LawMotor> kde = KdeLawMotors(o.shared_data_dir + "/kde_direct_mfr_sheets", &no_torque);
  std::string no_torque_text;
  for (const auto& n : no_torque) no_torque_text += (no_torque_text.empty() ? "" : ", ") + n;
  const Catalog raw = Catalog::Load(o.catalog, /*in_system_law=*/false);
  const std::vector<stand::LawForm> forms = {{true, false}, {false, false}, {false, true}, {true, true}};
  std::vector<stand::LawReport> reports;
  std::size_t best = 0;
  for (const auto& f : forms) {
    reports.push_back(stand::LeaveOneMotorOut(kde, f));
    // The held-out current and speed errors together choose the form (both are sizing numbers).
    const auto score = [](const stand::LawReport& r) { return r.law_error + r.rpm_error_forward; };
    if (score(reports.back()) < score(reports[best])) best = reports.size() - 1;
  }
  stand::RefitLawCheck dc_check;
  const InSystemLaw dc_law = stand::FitLawFromRefits(stand::DriveCalcRefitPairs(raw), &dc_check);
  const stand::LawReport& chosen = reports[best];
  const std::vector<stand::RefitPair> makers = stand::ManufacturerRefitPairs(raw, stand::DriveCalcRefitPairs(raw));
  if (!o.plot_png.empty()) {
    WriteInSystemLawFigure(kde, chosen, o.plot_png);
    std::cerr << "wrote " << o.plot_png << "\n";
  }
  if (o.constants) {
    PrintLawConstants("kManufacturerStatedLaw", chosen.law);
    PrintLawConstants("kUserContributedLaw", dc_law);
    return 0;
  }
  std::cout << "## KDE Direct stand sheets: the law by leaving each motor out\n\n"
            << kde.size() << " motors with measured torque (of " << kde.size() + no_torque.size() << "; "
            << (no_torque.empty() ? std::string("every sheet has torque") : no_torque_text + " have none") << "). "
            << "Each row: the law fitted on the other motors predicts this motor's DC current at the measured "
               "speed and torque from its datasheet values (ideal ESC, eq 56); error = median over the sweeps "
               "of the median |IDC_pred/IDC_meas - 1|, bias the same signed. The plain DC model with the "
               "datasheet values is the same machine as dynosize's rms model with the same numbers "
               "(catalog/conventions.h 1.), so its column is both. Coverage: share of the motor's points inside "
               "the p10-p90 range built from the other motors' scatter about the law. rpm forward: from the "
               "command at the measured torque, with the dead band prior of the other motors.\n\n"
            << "| law form | fitted on all motors | IDC error | IDC bias | coverage | rpm forward |\n|---|---|---|---|---|---|\n";
  for (const auto& r : reports) {
    std::cout << "| " << r.form.Describe() << " | " << LawText(r.law) << " | " << PercentText(r.law_error) << " | "
              << PercentText(r.law_bias) << " | " << PercentText(r.coverage) << " | "
              << PercentText(r.rpm_error_forward) << " |\n";
  }
  std::cout << "\nThe form with the smallest held-out current + speed error is the catalog's law for KDE Direct datasheets: **"
            << chosen.form.Describe() << "**.\n\n";
  PrintMotorTable(chosen, raw);
  std::cout << "Throttle offset of the sheets' ESC (KDE-UAS125UVC), dead band fitted per motor: p10 "
            << FixedText(chosen.throttle.deadband_p10, 3) << ", median " << FixedText(chosen.throttle.deadband_p50, 3)
            << ", p90 " << FixedText(chosen.throttle.deadband_p90, 3) << " (negative: voltage at zero command).\n\n";
  std::cout << "## Leaving a manufacturer out: AXI's datasheets against DriveCalc's measurements\n\n"
            << makers.size() << " manufacturer-stated motors of FAST-UAV's catalogue (not KDE) that DriveCalc "
            << "measured (same name and Kv within 5 %): their datasheet R and Io against DriveCalc's refit of the "
            << "same motor. Median |pred/refit - 1| (signed median), and the share inside the law's p10-p90:\n\n"
            << "| values | R error (bias) | Io error (bias) | R, Io inside p10-p90 |\n|---|---|---|---|\n";
  const std::vector<std::pair<std::string, InSystemLaw>> candidates = {
      {"datasheet as stated", InSystemLaw{}}, {"KDE law", chosen.law}, {"DriveCalc law", dc_law}};
  for (const auto& [label, l] : candidates) {
    const stand::RefitErrors e = stand::EvaluateOnRefits(makers, l);
    std::cout << "| " << label << " | " << PercentText(e.r_error) << " (" << PercentText(e.r_bias) << ") | "
              << PercentText(e.io_error) << " (" << PercentText(e.io_bias) << ") | "
              << (label == "datasheet as stated" ? std::string("-")
                                                 : PercentText(e.coverage_r) + ", " + PercentText(e.coverage_io))
              << " |\n";
  }
  std::cout << "\nNeither law transfers to another maker: KDE's datasheets are KDE's convention (and KDE's set-up), "
               "DriveCalc's database is its own. The catalog applies the KDE law to KDE Direct entries and the "
               "DriveCalc law to DriveCalc's database only; other makers' datasheets keep their values (and the "
               "tier's band in the ranges).\n\n";
  std::cout << "## DriveCalc: database values against refits of DriveCalc's own measurements\n\n"
            << dc_check.pairs << " motors (user_contributed) with R and Io in the database and a refit in "
            << "catalog/drivecalc_fitted.json (full-throttle points through an ESC and its wiring). Law: "
            << LawText(dc_law) << ". Held out (10 folds): median |R_pred/R_refit - 1| "
            << PercentText(dc_check.r_error_law) << " (bias " << PercentText(dc_check.r_bias_law) << ") against "
            << PercentText(dc_check.r_error_datasheet) << " (bias " << PercentText(dc_check.r_bias_datasheet)
            << ") with the database R; p10-p90 coverage R " << PercentText(dc_check.coverage_r) << ", Io "
            << PercentText(dc_check.coverage_io) << ".\n";
  return 0;
}

}  // namespace dynosize::cli
