// APC PER3 performance tables (shared/data/apc_per3_subset/PER3_<prop>.csv): thrust [kg] and
// torque [N*m] vs rpm and airspeed [m/s], COMPUTED by APC's blade-element code (not measured),
// converted to the UIUC coefficients: n = rpm/60, J = V/(n*D), CT = T/(rho*n^2*D^4),
// CP = 2*pi*Q/(rho*n^2*D^5) (P = 2*pi*n*Q), at APC's standard sea-level density 1.225 kg/m^3.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <map>

#include "common/atmosphere.h"
#include "common/error.h"
#include "common/units.h"
#include "importers/csv.h"
#include "importers/importers.h"

namespace dynosize {

namespace {

constexpr const char* kDataset = "APC PER3 performance data (computed by APC)";
// Torque is printed to 0.001 N*m: below 0.02 N*m static torque the rounding alone is more than
// 2.5 % of CP, so such (low-rpm) sweeps are left out.
constexpr double kMinStaticTorqueNm = 0.02;
// Coefficients kept to 4 significant digits: the source torque has 2-3.
constexpr int kDigits = 4;

struct PropSize {
  double d_in = 0, p_in = 0;
  int blades = 2;
  std::string type;  // MR, SF, E
};

// "10x45MR" -> 10 x 4.5 MR; "95x5MR" -> 9.5 x 5; "16x10E" -> 16 x 10; "25x125E" -> 25 x 12.5;
// "28x20-4" -> 28 x 20, 4 blades. APC names drop the decimal point: a diameter over 30 in, or a
// pitch of two or more digits larger than the diameter, had one.
bool ParseSize(const std::string& stem, PropSize* out) {
  const auto x = stem.find('x');
  if (x == std::string::npos || x == 0) return false;
  std::size_t e = x + 1;
  while (e < stem.size() && std::isdigit(static_cast<unsigned char>(stem[e]))) ++e;
  const auto d = ParseNumber(stem.substr(0, x));
  const auto p = ParseNumber(stem.substr(x + 1, e - x - 1));
  if (!d || !p) return false;
  out->d_in = *d > 30 ? *d / 10 : *d;
  out->p_in = (e - x - 1 >= 2 && *p > out->d_in) ? *p / 10 : *p;
  out->type = stem.substr(e);
  // "28x20-4": a dash and the blade count after the size.
  if (out->type.size() >= 2 && out->type[0] == '-' && std::isdigit(static_cast<unsigned char>(out->type[1]))) {
    out->blades = out->type[1] - '0';
    out->type = out->type.substr(2);
  }
  return out->d_in > 0 && out->p_in > 0;
}

}  // namespace

namespace {

// The PER3 files of one folder as the entries of one catalog document.
ImportedDataset ImportPer3Folder(const std::string& dir, ImportedDataset out) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f.rfind("PER3_", 0) == 0 && e.path().extension() == ".csv") files.push_back(f);
  }
  std::sort(files.begin(), files.end());
  const double rho = kIsaSeaLevelRhoKgM3;
  std::size_t low_total = 0;
  for (const std::string& f : files) {
    const std::string stem = f.substr(5, f.size() - 9);
    PropSize size;
    if (!ParseSize(stem, &size)) {
      out.report.Drop("props", "file name gives no size", f);
      continue;
    }
    const CsvTable t = ReadCsv(dir + "/" + f);
    const std::size_t c_rpm = t.Column("RPM"), c_q = t.Column("Torque (N-m)"),
                      c_v = t.Column("V(speed) (m/s)"), c_t = t.Column("Thrust (kg)");
    const double d = InchToMeter(size.d_in);
    std::map<double, std::vector<std::array<double, 3>>> sweeps;  // rpm -> (J, CT, CP)
    std::map<double, std::array<double, 2>> statics;               // rpm -> (CT, CP)
    for (const auto& r : t.rows) {
      const auto rpm = ParseNumber(t.Field(r, c_rpm)), q = ParseNumber(t.Field(r, c_q)),
                 v = ParseNumber(t.Field(r, c_v)), th = ParseNumber(t.Field(r, c_t));
      const std::string ex = f + ":" + std::to_string(r.line);
      if (!rpm || !q || !v || !th) {
        out.report.Drop("prop points", "PER3 row with an empty cell (APC printed NaN)", ex);
        continue;
      }
      if (!(*th > 0) || !(*q > 0) || !(*rpm > 0)) {
        out.report.Drop("prop points", "PER3 row at or beyond zero thrust/torque (windmilling)", ex);
        continue;
      }
      const double n = RpmToRevPerSec(*rpm);
      const double ct = KilogramForceToNewton(*th) / (rho * n * n * std::pow(d, 4));
      const double cp = 2 * kPi * *q / (rho * n * n * std::pow(d, 5));
      if (*v == 0.0) statics[*rpm] = {RoundSig(ct, kDigits), RoundSig(cp, kDigits)};
      else sweeps[*rpm].push_back({RoundSig(*v / (n * d), kDigits), RoundSig(ct, kDigits), RoundSig(cp, kDigits)});
    }
    Json st_rpm = Json::array(), st_ct = Json::array(), st_cp = Json::array();
    Json jt = Json::array();
    std::size_t low = 0;
    for (const auto& [rpm, coef] : statics) {
      const double n = RpmToRevPerSec(rpm);
      const double q_static = coef[1] * rho * n * n * std::pow(d, 5) / (2 * kPi);
      if (q_static < kMinStaticTorqueNm) {
        ++low;
        continue;
      }
      st_rpm.push_back(rpm);
      st_ct.push_back(coef[0]);
      st_cp.push_back(coef[1]);
      auto it = sweeps.find(rpm);
      if (it == sweeps.end()) continue;
      Json jj = Json::array(), ct = Json::array(), cp = Json::array();
      double last_j = 0;
      for (const auto& p : it->second) {
        if (!(p[0] > last_j)) continue;  // J rounded to 4 digits can repeat: keep the first
        last_j = p[0];
        jj.push_back(p[0]);
        ct.push_back(p[1]);
        cp.push_back(p[2]);
      }
      if (!jj.empty()) jt.push_back({{"rpm", rpm}, {"j", jj}, {"ct", ct}, {"cp", cp}});
    }
    low_total += low;
    if (st_rpm.empty()) {
      out.report.Drop("props", "no sweep with usable torque", f);
      continue;
    }
    char dbuf[32], pbuf[32];
    std::snprintf(dbuf, sizeof dbuf, "%g", size.d_in);
    std::snprintf(pbuf, sizeof pbuf, "%g", size.p_in);
    EntryBuilder b("apc_per3_" + Slug(stem), std::string("APC ") + dbuf + "x" + pbuf + size.type +
                                                 " (PER3, computed)");
    b.SetNum("diameter_m", d, "derived");
    b.SetNum("pitch_m", InchToMeter(size.p_in), "derived");
    if (size.blades == 2) b.Set("blades", 2, "assumed");
    else b.Set("blades", size.blades, "datasheet");
    b.Set("static_table", {{"rpm", st_rpm}, {"ct", st_ct}, {"cp", st_cp}}, "computed");
    if (!jt.empty()) b.Set("j_tables", jt, "computed");
    b.Source(kDataset, f, "computed by APC (blade-element), not measured; D and pitch from the file name");
    b.Tier("manufacturer_computed");
    KeepAuditedProp(b.Build(), f, &out);
  }
  out.report.notes.push_back(std::to_string(low_total) + " low-rpm sweeps (static torque < 0.02 "
                             "N*m, printed to 0.001 N*m) left out over " +
                             std::to_string(files.size()) + " files");
  return out;
}

}  // namespace

ImportedDataset ImportApcPer3(const std::string& dir) {
  ImportedDataset out;
  out.report.dataset = "apc_per3_subset";
  out.report.output_file = "apc_per3.json";
  out.comment =
      "Generated by dynosize ImportAll from shared/data/apc_per3_subset: APC PER3 performance "
      "files (data (c) APC Propellers; CSV from github.com/sjkim-snu/propulsion_analysis commit "
      "7c1c97e). COMPUTED by APC's blade-element code, not measured: source.values say "
      "'computed'; prefer UIUC entries for measured truth. Converted to CT, CP vs J at each "
      "rpm with rho = 1.225 kg/m^3 (APC standard day); size from the file name. Sweeps with "
      "static torque < 0.02 N*m (printed to 0.001 N*m) and rows with empty cells or zero/negative "
      "thrust are left out. Coefficients to 4 significant digits. Do not edit by hand.";
  return ImportPer3Folder(dir, std::move(out));
}

ImportedDataset ImportApcPer3Large(const std::string& dir) {
  ImportedDataset out;
  out.report.dataset = "large_props_apc";
  out.report.output_file = "apc_per3_large.json";
  out.comment =
      "Generated by dynosize ImportAll from shared/data/large_props_apc: APC PER3 performance "
      "files of APC's 24-28 in propellers, version v2022-0915 (data (c) APC Propellers; .dat "
      "from github.com/sammy183/APC-Propeller-Selection-Tool commit 245acca), converted as "
      "apc_per3.json. COMPUTED by APC's blade-element code, not measured (no measured data "
      "exist for these sizes in the stored sources). Do not edit by hand.";
  return ImportPer3Folder(dir, std::move(out));
}

}  // namespace dynosize
