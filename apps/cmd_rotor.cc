// `dynosize rotor validate | hover | families` (src/rotor, docs/model.md section 13):
//   validate  the blade-element model against UIUC's measured propellers by leaving each family
//             out, against APC's own computed tables on the APC propellers UIUC measured, and a
//             propeller from its size alone; prints docs/validation.md's "Propellers from their geometry";
//   hover     a parametric eVTOL rotor's best hover design (rotor/parametric.h);
//   families  prints src/rotor/family_data.cc from the data.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "catalog/catalog.h"
#include "common/error.h"
#include "common/json_file.h"
#include "common/units.h"
#include "common/text_format.h"
#include "importers/blade_geometry.h"
#include "importers/sized_prop.h"
#include "report/rotor_figures.h"
#include "rotor/parametric.h"
#include "rotor/uiuc_polar.h"
#include "rotor/validation.h"

namespace dynosize::cli {
namespace {

std::map<std::string, FamilyBlade> ReadUiucBlades(const std::string& data) {
  std::map<std::string, FamilyBlade> out;
  for (int v = 1; v <= 3; ++v) {
    for (FamilyBlade& b : ReadUiucGeometry(data + "/uiuc_propdb/volume" + std::to_string(v) + "_geom.csv")) {
      out[b.geometry.name] = b;
    }
  }
  return out;
}

std::string Pct(double fraction) { return std::isfinite(fraction) ? PercentText(fraction) : "-"; }

void PrintPolar(const char* what, const AirfoilFitResult& f) {
  const AirfoilPolar& p = f.polar;
  std::printf("| %s | %.3f | %.2f | %.2f | %.4f | %.3f | %.2f | %s |\n", what, p.cl0, p.cl_alpha_per_rad, p.cl_max,
              p.cd0, p.cd2, p.re_exp, Pct(f.rms_relative).c_str());
}

void PrintLeaveFamilyOut(const LeaveFamilyOutReport& r) {
  std::printf("Leaving each family out: the polar fitted on the other families predicts the family's static CT\n"
              "and CP (median |model/measured - 1| over its points) and its efficiency in the wind-tunnel sweeps\n"
              "(median |eta_model - eta_measured|, at most 6 points per sweep).\n\n");
  std::printf("| family | propellers | static points | CT | CP | CT p90 | sweep points | efficiency |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const FamilyFold& f : r.folds) {
    const ErrorSummary& e = f.errors;
    std::printf("| %s | %d | %d | %s | %s | %s | %d | %s |\n", f.family.c_str(), e.props, e.static_points,
                Pct(e.ct_median).c_str(), Pct(e.cp_median).c_str(), Pct(e.ct_p90).c_str(), e.sweep_points,
                std::isfinite(e.eta_median) ? FixedText(e.eta_median, 3).c_str() : "-");
  }
  const ErrorSummary& a = r.left_out;
  const ErrorSummary& s = r.in_sample;
  std::printf("| **all, left out** | %d | %d | **%s** | **%s** | %s | %d | **%s** |\n", a.props, a.static_points,
              Pct(a.ct_median).c_str(), Pct(a.cp_median).c_str(), Pct(a.ct_p90).c_str(), a.sweep_points,
              FixedText(a.eta_median, 3).c_str());
  std::printf("| all, in sample (the polar fitted on every family) | %d | %d | %s | %s | %s | %d | %s |\n\n", s.props,
              s.static_points, Pct(s.ct_median).c_str(), Pct(s.cp_median).c_str(), Pct(s.ct_p90).c_str(),
              s.sweep_points, FixedText(s.eta_median, 3).c_str());
}

// The size-only goal is over the measured propellers of 12 in and more.
constexpr double kSizeOnlyMinDiameterM = 0.3048;

void PrintSizeOnly(const SizeOnlyCheck& c) {
  std::printf("### A propeller from its size alone\n\n");
  std::printf("Every measured propeller of the catalog of 12 in and more with a static table (%d propellers, %zu\n"
              "points: UIUC, KDE Direct's sheets), predicted from its diameter, pitch and blade count alone through its\n"
              "default family (`--prop-param DxPxB`; rotor/family.h), the family's shape derived without that\n"
              "propeller's own blade. Median over propellers of the median |predicted/measured - 1| of its points:\n"
              "static thrust **%s**, torque **%s**. Measured/predicted ratio p10-p90 over all points: thrust\n"
              "%.3f-%.3f, torque %.3f-%.3f (the range a sized propeller carries); each propeller's points inside the\n"
              "p10-p90 of the others': thrust %s, torque %s.\n\n",
              c.props, c.points.size(), Pct(c.thrust_median).c_str(), Pct(c.torque_median).c_str(), c.thrust_p10,
              c.thrust_p90, c.torque_p10, c.torque_p90, Pct(c.thrust_coverage).c_str(), Pct(c.torque_coverage).c_str());
  std::printf("| propeller | family | D in | points | thrust measured/predicted | torque measured/predicted |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (std::size_t i = 0; i < c.points.size();) {
    std::size_t k = i;
    double t = 0.0, q = 0.0;
    while (k < c.points.size() && c.points[k].prop_id == c.points[i].prop_id) {
      t += c.points[k].thrust_ratio;
      q += c.points[k].torque_ratio;
      ++k;
    }
    const double n = static_cast<double>(k - i);
    std::printf("| %s | %s | %.1f | %zu | %.3f | %.3f |\n", c.points[i].prop_id.c_str(), c.points[i].family.c_str(),
                c.points[i].diameter_in, k - i, t / n, q / n);
    i = k;
  }
  std::printf("\n");
}

}  // namespace

int RunRotorValidate(const RotorValidateOptions& o) {
  const std::string data = o.shared_data_dir;
  if (!std::filesystem::is_directory(data + "/uiuc_propdb")) {
    throw NoInputError(data + "/uiuc_propdb: no such folder (the UIUC geometry and measurements)");
  }
  const Catalog catalog = Catalog::Load(o.catalog);
  if (o.size_only) {
    PrintSizeOnly(CheckSizeOnly(catalog.props(), data, kSizeOnlyMinDiameterM));
    return 0;
  }
  const std::map<std::string, FamilyBlade> blades = ReadUiucBlades(data);
  const std::vector<RotorFitCase> cases = UiucCases(catalog.props(), blades);
  if (cases.empty()) throw DataError("no UIUC propeller of the catalog has a geometry table: is uiuc_propdb.json loaded?");
  if (o.constants) {
    const AirfoilPolar p = FitAirfoil(cases, kUiucFittedPolar).polar;
    std::printf("inline constexpr AirfoilPolar kUiucFittedPolar{\n    /*cl0=*/%.4g, /*cl_alpha_per_rad=*/%.4g, /*cl_max=*/%.4g, "
                "/*cl_min=*/%.4g,\n    /*cd0=*/%.4g, /*cd2=*/%.4g, /*cl_cd0=*/%.4g, /*re_ref=*/%.4g, /*re_exp=*/%.4g};\n",
                p.cl0, p.cl_alpha_per_rad, p.cl_max, p.cl_min, p.cd0, p.cd2, p.cl_cd0, p.re_ref, p.re_exp);
    return 0;
  }
  const LeaveFamilyOutReport r = LeaveFamilyOut(cases, kUiucFittedPolar, o.threads);
  std::set<std::string> families;
  for (const RotorFitCase& c : cases) families.insert(c.family);
  std::printf("## Propellers from their geometry: blade-element momentum theory (issue 52)\n\n");
  std::printf("`dynosize rotor validate --shared ../shared/data` (src/rotor, docs/model.md section 13): %zu UIUC "
              "propellers of %zu families whose blade UIUC measured (volumes 1-3), %d static and %d sweep points.\n\n",
              cases.size(), families.size(), r.in_sample.static_points, r.in_sample.sweep_points);
  PrintLeaveFamilyOut(r);
  std::printf("The polar (eqs B1-B2; cl_min %.2f, cl_cd0 %.2f, re_ref %.0f held):\n\n", r.all.polar.cl_min,
              r.all.polar.cl_cd0, r.all.polar.re_ref);
  std::printf("| fitted on | cl0 | cl_alpha /rad | cl_max | cd0 | cd2 | re_exp | rms residual |\n|---|---|---|---|---|---|---|---|\n");
  PrintPolar("every family (src/rotor/uiuc_polar.h)", r.all);
  for (const FamilyFold& f : r.folds) PrintPolar(("all but " + f.family).c_str(), f.fit);
  std::printf("\n");

  // APC: the model from APC's geometry with a polar fitted without APC's families.
  std::vector<RotorFitCase> non_apc;
  for (const RotorFitCase& c : cases) {
    if (c.family.rfind("apc", 0) != 0) non_apc.push_back(c);
  }
  const AirfoilFitResult apc_free = FitAirfoil(non_apc, r.all.polar);
  std::vector<ApcCase> apc;
  for (const RotorFitCase& c : cases) {
    const auto b = blades.find(UiucBladeNameOfId(c.name));
    const std::string file = ApcFileNameOfUiuc(c.family, b->second.diameter_in, b->second.pitch_in);
    const std::string pe0 = data + "/apc_geometry/geometry/" + file + "-PERF.PE0";
    const std::string per3 = data + "/apc_geometry/per3/PER3_" + file + ".csv";
    if (file.empty() || !std::filesystem::exists(pe0) || !std::filesystem::exists(per3)) continue;
    apc.push_back({c, ReadApcPe0(pe0), ReadApcPer3Csv(per3)});
  }
  const ApcComparison cmp = CompareWithApc(apc, apc_free.polar);
  std::printf("### APC's propellers that UIUC measured: dynosize from APC's geometry against APC's own tables\n\n");
  std::printf("%d propellers, %d static points: at each of UIUC's measured speeds, dynosize's blade-element model\n"
              "run on APC's published geometry (PE0) with the polar fitted without any APC family, and APC's computed\n"
              "PER3 table at the same speed, both against UIUC's measurement. Median |x/UIUC - 1|: CT dynosize %s,\n"
              "APC %s; CP dynosize %s, APC %s. dynosize is at least as close as APC's table at %s of the points\n"
              "in CT and %s in CP.\n\n",
              cmp.props, cmp.points, Pct(cmp.model_ct).c_str(), Pct(cmp.apc_ct).c_str(), Pct(cmp.model_cp).c_str(),
              Pct(cmp.apc_cp).c_str(), Pct(cmp.model_closer_ct).c_str(), Pct(cmp.model_closer_cp).c_str());
  std::printf("| APC | UIUC entry | points | CT dynosize | CT APC | CP dynosize | CP APC |\n|---|---|---|---|---|---|---|\n");
  for (const std::string& row : cmp.rows) std::printf("| %s |\n", row.c_str());
  std::printf("\n");
  PrintSizeOnly(CheckSizeOnly(catalog.props(), data, kSizeOnlyMinDiameterM));
  if (!o.plot_png.empty()) {
    WriteRotorValidationFigure(r, o.plot_png);
    std::printf("Figure: %s\n\n", o.plot_png.c_str());
  }
  return 0;
}

int RunRotorHover(const RotorHoverOptions& o) {
  ParametricRotor p;
  p.radius_m = 0.5 * o.diameter_m;
  p.blades = o.blades;
  p.solidity = o.solidity;
  p.twist_deg = o.twist_deg;
  p.taper = o.taper;
  p.root_cutout = o.root_cutout;
  const std::string bad = CheckParametricRotor(p);
  if (!bad.empty()) throw UsageError(bad);
  const HoverDesign d = DesignHover(p, kUiucFittedPolar, o.thrust_n, o.rho_kg_m3, o.tip_mach_max);
  const BemtPoint& b = d.point;
  if (o.json) {
    Json j = {{"feasible", d.feasible}, {"limit", d.limit}, {"message", d.message},
              {"collective_deg", d.collective_deg}, {"rpm", RadPerSecToRpm(b.omega_rad_s)},
              {"thrust_n", b.thrust_n}, {"torque_nm", b.torque_nm}, {"power_w", b.power_w},
              {"figure_of_merit", b.figure_of_merit}, {"tip_mach", b.tip_mach}, {"ct_over_sigma", b.ct_over_sigma},
              {"stalled_span", b.stalled_span}, {"reynolds_75", b.mean_reynolds},
              {"disk_loading_n_m2", d.disk_loading_n_m2}, {"power_loading_n_w", d.power_loading_n_w},
              {"induced_velocity_m_s", d.induced_velocity_m_s}, {"polar", "src/rotor/uiuc_polar.h"}};
    std::cout << DumpJson(j);
    return 0;
  }
  std::printf("rotor D %.3f m, %d blades, solidity %.3f, twist %.1f deg, taper %.2f, root cut-out %.2f\n", o.diameter_m,
              p.blades, p.solidity, p.twist_deg, p.taper, p.root_cutout);
  std::printf("  hover thrust   %10.1f N at rho %.3f kg/m^3 (disk loading %.0f N/m^2)\n", o.thrust_n, o.rho_kg_m3,
              d.disk_loading_n_m2);
  std::printf("  collective     %10.2f deg at 0.75 R (best figure of merit)\n", d.collective_deg);
  std::printf("  speed          %10.0f rpm (tip Mach %.3f, limit %.2f)\n", RadPerSecToRpm(b.omega_rad_s), b.tip_mach,
              o.tip_mach_max);
  std::printf("  power          %10.1f W, torque %.1f N*m, power loading %.2f N/W\n", b.power_w, b.torque_nm,
              d.power_loading_n_w);
  std::printf("  figure of merit %9.3f (momentum theory: 1; induced velocity %.2f m/s)\n", b.figure_of_merit,
              d.induced_velocity_m_s);
  std::printf("  blade loading  %10.3f CT/sigma (limit %.2f), %.0f %% of the span past stall, Re_75 %.2g\n",
              b.ct_over_sigma, kMaxBladeLoading, 100.0 * b.stalled_span, b.mean_reynolds);
  std::printf("  %s\n", d.limit.empty() ? "no limit binds" : ("limited by " + d.limit + ": " + d.message).c_str());
  if (!d.feasible) std::printf("  NOT FEASIBLE: the values above are the rotor at its tip Mach limit\n");
  return 0;
}

int RunRotorFamilies(const std::string& shared_data_dir) {
  const std::vector<RotorFamily> families = DeriveBundledFamilies(shared_data_dir);
  std::printf("// Generated by `dynosize rotor families --shared ../shared/data` (rotor/family.h): do not edit.\n"
              "#include \"rotor/family.h\"\n\nnamespace dynosize {\n\n"
              "const std::vector<RotorFamily>& BundledFamilies() {\n"
              "  static const std::vector<RotorFamily> kFamilies = {\n");
  for (const RotorFamily& f : families) {
    std::printf("      {\"%s\", \"%s\",\n       \"%s\",\n       %d, %.4g, %.4g, %.4g, %.4g,\n       {", f.id.c_str(),
                f.description.c_str(), f.source.c_str(), f.blades_averaged, f.d_min_in, f.d_max_in, f.pd_min, f.pd_max);
    for (int k = 0; k < kFamilyStations; ++k) std::printf("%s%.4f", k ? ", " : "", f.chord_over_r[k]);
    std::printf("},\n       {");
    for (int k = 0; k < kFamilyStations; ++k) std::printf("%s%.4f", k ? ", " : "", f.pitch_over_nominal[k]);
    std::printf("}},\n");
  }
  std::printf("  };\n  return kFamilies;\n}\n\n}  // namespace dynosize\n");
  return 0;
}

int RunRotorEntry(const std::string& pe0_file, const std::string& id) {
  const BladeGeometry blade = ReadApcPe0(pe0_file);
  std::string name = std::filesystem::path(pe0_file).stem().string();  // "14x7E-PERF"
  name = name.substr(0, name.find("-PERF"));
  std::string own_id = id;
  if (own_id.empty()) {
    own_id = "bemt_apc_" + name;
    std::transform(own_id.begin(), own_id.end(), own_id.begin(), [](unsigned char ch) { return std::tolower(ch); });
  }
  const Json doc = {{"comment", "written by dynosize rotor entry --pe0 " + std::filesystem::path(pe0_file).filename().string()},
                    {"props", Json::array({GeometryPropJson(blade, own_id, pe0_file)})}};
  std::printf("%s\n", DumpJson(doc).c_str());
  return 0;
}

}  // namespace dynosize::cli
