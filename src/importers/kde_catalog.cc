// KDE Direct's propellers and stand ESC from KDE's own dynamometer sheets
// (shared/data/kde_direct_mfr_sheets, README there): the sheets measure thrust, torque and speed
// of KDE's carbon propellers (2 and 3 blades, 12.5-35.5 in) behind the KDE-UAS125UVC ESC.
//
// A propeller's static coefficients (UIUC definitions, docs/model.md section 11):
//     CT = T/(rho*n^2*D^4),  CP = 2*pi*Q/(rho*n^2*D^5),  n = rpm/60
// at the site's air density, which KDE's own sea-level estimate column states: KDE scales the
// measured thrust by rho_sl/rho_site (the ratio is the same on every row), so
// rho_site = 1.225 kg/m^3 / median(T_sealevel_est/T). Points are pooled over the motors and
// voltages that spun the propeller and binned by speed into the entry's static table.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "catalog/esc_prior.h"
#include "catalog/in_system.h"
#include "common/atmosphere.h"
#include "common/error.h"
#include "common/text_format.h"
#include "common/units.h"
#include "importers/importers.h"
#include "importers/csv.h"
#include "importers/kde_sheets.h"

namespace dynosize {

namespace {

constexpr const char* kDataset = "KDE Direct dynamometer sheets (kdedirect.com, via CWRU-VTOL/MotorDatabase)";
// Torque is printed to 0.01 N*m: below 0.2 N*m the rounding alone is more than 2.5 % of CP.
constexpr double kMinTorqueNm = 0.2;
// Points within this relative speed of a bin's first point share the bin (the sheets' motors
// and voltages put a propeller's points at scattered speeds).
constexpr double kBinWidth = 0.06;
constexpr int kDigits = 4;
// The ESC's continuous current rating, A, from its part number (UAS125).
constexpr double kRatedCurrentA = 125.0;

struct Point {
  double rpm, ct, cp;
};

// "30.5x9.7 DUAL" -> 30.5, 9.7, 2 blades; false for a label the sheets do not use.
bool ParseKdeProp(const std::string& label, double* d_in, double* p_in, int* blades) {
  const auto sp = label.find(' '), x = label.find('x');
  if (sp == std::string::npos || x == std::string::npos || x > sp) return false;
  const auto d = ParseNumber(label.substr(0, x)), p = ParseNumber(label.substr(x + 1, sp - x - 1));
  const std::string kind = label.substr(sp + 1);
  *blades = kind == "DUAL" ? 2 : kind == "TRIPLE" ? 3 : 0;
  if (!d || !p || *blades == 0) return false;
  *d_in = *d;
  *p_in = *p;
  return true;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The site's air density from KDE's sea-level estimate (header comment).
double SiteDensityKgM3(const std::vector<KdeSheetMotor>& motors) {
  std::vector<double> ratio;
  for (const auto& m : motors) {
    for (const auto& r : m.rows) {
      if (std::isfinite(r.thrust_sealevel_est_n) && r.thrust_n > 2.0) {
        ratio.push_back(r.thrust_sealevel_est_n / r.thrust_n);
      }
    }
  }
  if (ratio.empty()) throw DataError("kde_performance.csv: no row with a sea-level thrust estimate");
  return kIsaSeaLevelRhoKgM3 / Median(ratio);
}

Json StaticTable(std::vector<Point> pts) {
  std::sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) { return a.rpm < b.rpm; });
  Json rpm = Json::array(), ct = Json::array(), cp = Json::array();
  for (std::size_t i = 0; i < pts.size();) {
    std::size_t e = i;
    std::vector<double> w, t, p;
    while (e < pts.size() && pts[e].rpm <= pts[i].rpm * (1.0 + kBinWidth)) {
      w.push_back(pts[e].rpm);
      t.push_back(pts[e].ct);
      p.push_back(pts[e].cp);
      ++e;
    }
    double mean = 0.0;
    for (double x : w) mean += x;
    mean /= static_cast<double>(w.size());
    rpm.push_back(RoundSig(mean, 5));
    ct.push_back(RoundSig(Median(t), kDigits));
    cp.push_back(RoundSig(Median(p), kDigits));
    i = e;
  }
  return {{"rpm", rpm}, {"ct", ct}, {"cp", cp}};
}

void ImportProps(const std::vector<KdeSheetMotor>& motors, double rho, ImportedDataset* out) {
  std::map<std::string, std::vector<Point>> by_prop;
  std::map<std::string, std::vector<std::string>> motors_of;
  for (const auto& m : motors) {
    for (const auto& r : m.rows) {
      const std::string ex = "kde_performance.csv:" + std::to_string(r.line) + " " + r.prop;
      double d_in = 0, p_in = 0;
      int blades = 0;
      if (!ParseKdeProp(r.prop, &d_in, &p_in, &blades)) {
        out->report.Drop("prop points", "no propeller size or blade count on the sheet (OCR damage)", ex);
        continue;
      }
      if (r.prop == "15.5x6.3 TRIPLE") {
        out->report.Drop("prop points", "15.5x6.3 TRIPLE: probably 15.5x5.3 misprinted (README)", ex);
        continue;
      }
      if (!std::isfinite(r.torque_nm)) {
        out->report.Drop("prop points", "no torque (older sheet)", ex);
        continue;
      }
      if (r.torque_nm < kMinTorqueNm || !(r.rpm > 0) || !(r.thrust_n > 0)) {
        out->report.Drop("prop points", "torque below 0.2 N*m (printed to 0.01 N*m)", ex);
        continue;
      }
      const double n = RpmToRevPerSec(r.rpm), d = InchToMeter(d_in);
      const Point pt{r.rpm, r.thrust_n / (rho * n * n * std::pow(d, 4)),
                     2 * kPi * r.torque_nm / (rho * n * n * std::pow(d, 5))};
      // Static FM = CT^1.5/(sqrt(2)*CP) (docs/model.md section 10): above 1 the row beats
      // momentum theory, a misread sheet row (KDE7215XF-135's 880 rpm point: FM 1.01).
      if (std::pow(pt.ct, 1.5) / (std::sqrt(2.0) * pt.cp) > 1.0) {
        out->report.Drop("prop points", "static figure of merit above 1 (a misread sheet row)", ex);
        continue;
      }
      by_prop[r.prop].push_back(pt);
      auto& ms = motors_of[r.prop];
      if (std::find(ms.begin(), ms.end(), m.name) == ms.end()) ms.push_back(m.name);
    }
  }
  for (const auto& [label, pts] : by_prop) {
    double d_in = 0, p_in = 0;
    int blades = 0;
    ParseKdeProp(label, &d_in, &p_in, &blades);
    char size[48];
    std::snprintf(size, sizeof size, "%gx%gx%d", d_in, p_in, blades);
    EntryBuilder b("kde_p_" + Slug(size), std::string("KDE ") + size + " (KDE-CF" +
                                              (blades == 2 ? " DUAL" : " TRIPLE") + ", measured by KDE)");
    b.SetNum("diameter_m", InchToMeter(d_in), "datasheet");
    b.SetNum("pitch_m", InchToMeter(p_in), "datasheet");
    b.Set("blades", blades, "datasheet");
    b.Set("static_table", StaticTable(pts), "measured");
    std::string on;
    for (const auto& m : motors_of[label]) on += (on.empty() ? "" : ", ") + m;
    b.Source(kDataset, "kde_performance.csv, prop " + label,
             std::to_string(pts.size()) + " points on " + on + "; CT, CP at the site's " +
                 FixedText(rho, 3) +
                 " kg/m^3 (from KDE's sea-level estimate); points within 6 % speed binned "
                 "(median)");
    b.Tier("measured");
    out->props.push_back(b.Build());
    out->report.Keep("props");
  }
}

// KDE's stand ESC. Its resistance is the current-rating prior of every catalog ESC without a
// measured one (esc_prior.h): the KDE in-system law's R already holds the sheets' ESC and wiring
// (the law was fitted with an ideal ESC, docs/in-system-law.md), so a KDE motor with this ESC
// counts the prior's 1.3 mOhm twice (about 3 % of KDE10218XF-105's in-system R), but any other
// motor with it gets an ESC resistance like every other ESC's, not none. Its throttle map is
// the offset prior fitted on the same sheets.
void ImportEsc(const std::vector<KdeSheetMotor>& motors, ImportedDataset* out) {
  double vmax = 0.0;
  for (const auto& m : motors) {
    for (const auto& r : m.rows) vmax = std::max(vmax, r.vdc_v);
  }
  const EscPrior& prior = DefaultEscPrior();
  const ThrottleOffsetPrior& offset = KdeEscThrottleOffsetPrior();
  EntryBuilder b("kde_e_uas125uvc", "KDE-UAS125UVC");
  b.SetNum("resc_ohm", PriorEscResistanceOhm(kRatedCurrentA), "assumed", 3);
  b.SetNum("c1", prior.c1, "assumed");
  b.SetNum("c0", prior.c0, "assumed");
  b.SetNum("tr_sat", prior.tr_sat, "assumed");
  b.SetNum("sat_slope", prior.sat_slope, "assumed");
  b.SetNum("deadband", offset.deadband_p50, "fitted");
  b.SetNum("max_current_a", kRatedCurrentA, "derived");
  b.SetNum("vdc_max_v", RoundSig(vmax, 4), "measured");
  b.Source(kDataset, "kde_performance.csv (the ESC of every sheet)",
           "max_current_a from the part number (UAS125); vdc_max_v the highest supply the sheets "
           "ran it at; deadband the median throttle offset fitted on KDE's sheets (p10-p90 " +
               FixedText(offset.deadband_p10, 3) + " to " + FixedText(offset.deadband_p90, 3) +
               ", docs/in-system-law.md); resc_ohm from the current-rating prior, c1, c0, knee: "
               "esc_prior.h");
  b.Tier("manufacturer_stated");
  out->escs.push_back(b.Build());
  out->report.Keep("escs");
}

}  // namespace

ImportedDataset ImportKdeSheetsCatalog(const std::string& dir) {
  ImportedDataset out;
  out.report.dataset = "kde_direct_mfr_sheets";
  out.report.output_file = "kde_direct_sheets.json";
  out.comment =
      "Generated by dynosize ImportAll from shared/data/kde_direct_mfr_sheets: KDE Direct's "
      "carbon propellers and stand ESC from KDE's own dynamometer sheets (kdedirect.com, via "
      "CWRU-VTOL/MotorDatabase, MIT). Propellers: static CT, CP from measured thrust, torque "
      "and speed at the site's air density; the motors are in heavy_lift_motors.json. Do not "
      "edit by hand.";
  const std::vector<KdeSheetMotor> motors = ReadKdeSheets(dir);
  ImportProps(motors, SiteDensityKgM3(motors), &out);
  ImportEsc(motors, &out);
  return out;
}

}  // namespace dynosize
