// The Reynolds-number law below a propeller's data (catalog/prop_reynolds.h): its constants are
// what the bundled UIUC tables give, its direction is the data's (CT falls, CP rises at lower
// Re), and it predicts a real UIUC propeller's low-speed points, left out with its family,
// better than holding the edge coefficients.
#include "catalog/prop_reynolds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "catalog/catalog.h"
#include "catalog/prop_credibility.h"
#include "common/json_file.h"

namespace dynosize {
namespace {

const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";
const std::string kUiuc = DYNOSIZE_SHARED_DIR "/data/uiuc_propdb";

bool HaveBundled() { return std::filesystem::exists(kCatalog + "/uiuc_propdb.json"); }

struct Bundled {
  Catalog cat;
  std::vector<const PropEntry*> measured;
};

void LoadBundled(Bundled* b) {
  std::vector<std::string> problems;
  b->cat.AddDocument(ReadJsonFile(kCatalog + "/uiuc_propdb.json"), "uiuc_propdb.json", &problems);
  ASSERT_TRUE(problems.empty()) << problems[0];
  for (const PropEntry& p : b->cat.props()) b->measured.push_back(&p);
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string f;
  while (std::getline(s, f, ',')) out.push_back(f);
  return out;
}

TEST(ReynoldsLaw, ConstantsMatchTheMeasuredPropellers) {
  if (!HaveBundled()) GTEST_SKIP() << "no catalog/uiuc_propdb.json";
  Bundled b;
  LoadBundled(&b);
  const ReynoldsLaw fresh = FitReynoldsLaw(b.measured);
  const ReynoldsLaw& k = DefaultReynoldsLaw();
  EXPECT_EQ(fresh.n_props, k.n_props);
  // The constants are stored to 3 decimals.
  constexpr double kStored = 5.1e-4;
  EXPECT_NEAR(fresh.ct_p10, k.ct_p10, kStored);
  EXPECT_NEAR(fresh.ct_p50, k.ct_p50, kStored);
  EXPECT_NEAR(fresh.ct_p90, k.ct_p90, kStored);
  EXPECT_NEAR(fresh.cp_p10, k.cp_p10, kStored);
  EXPECT_NEAR(fresh.cp_p50, k.cp_p50, kStored);
  EXPECT_NEAR(fresh.cp_p90, k.cp_p90, kStored);
  EXPECT_NEAR(fresh.fm_p10, k.fm_p10, kStored);
  EXPECT_NEAR(fresh.fm_p50, k.fm_p50, kStored);
  EXPECT_NEAR(fresh.fm_p90, k.fm_p90, kStored);
}

// The data's direction: at lower Reynolds number CT falls and CP rises (the median propeller),
// so the figure of merit falls; the scatter is ordered.
TEST(ReynoldsLaw, CtFallsAndCpRisesBelowTheData) {
  const ReynoldsLaw& k = DefaultReynoldsLaw();
  EXPECT_GT(k.ct_exp(), 0.0);
  EXPECT_LT(k.cp_exp(), 0.0);
  EXPECT_LE(k.fm_p10, k.fm_p50);
  EXPECT_LE(k.fm_p50, k.fm_p90);
  const ReynoldsFactors f = ReynoldsCorrection(k, 3000.0, 6000.0);
  EXPECT_DOUBLE_EQ(f.ratio, 0.5);
  EXPECT_LT(f.ct, 1.0);
  EXPECT_GT(f.cp, 1.0);
  EXPECT_LT(std::pow(f.ct, 1.5) / f.cp, 1.0);  // FM falls: never beyond the edge's
  const ReynoldsFactors above = ReynoldsCorrection(k, 7000.0, 6000.0);
  EXPECT_EQ(above.ct, 1.0);
  EXPECT_EQ(above.cp, 1.0);
}

// c/R at 0.75 R: the median over UIUC's blade geometry tables.
TEST(ReynoldsLaw, ChordRatioIsUiucsMedian) {
  if (!std::filesystem::exists(kUiuc + "/volume1_geom.csv")) GTEST_SKIP() << "no ../shared/data/uiuc_propdb";
  std::map<std::string, std::vector<std::pair<double, double>>> blades;
  for (int v = 1; v <= 3; ++v) {
    std::ifstream in(kUiuc + "/volume" + std::to_string(v) + "_geom.csv");
    std::string line;
    std::getline(in, line);  // BladeName,Family,D,P,c/R,r/R,beta
    while (std::getline(in, line)) {
      const auto f = SplitCsv(line);
      ASSERT_GE(f.size(), 6u) << line;
      blades[std::to_string(v) + f[0]].emplace_back(std::stod(f[5]), std::stod(f[4]));
    }
  }
  std::vector<double> c75;
  for (auto& [name, pts] : blades) {
    std::sort(pts.begin(), pts.end());
    for (std::size_t i = 1; i < pts.size(); ++i) {
      if (pts[i - 1].first <= 0.75 && 0.75 <= pts[i].first) {
        const double t = (0.75 - pts[i - 1].first) / (pts[i].first - pts[i - 1].first);
        c75.push_back(pts[i - 1].second + t * (pts[i].second - pts[i - 1].second));
        break;
      }
    }
  }
  std::sort(c75.begin(), c75.end());
  ASSERT_GE(c75.size(), 100u);
  EXPECT_NEAR(SortedQuantile(c75, 0.5), kChordOverRadius75, 5e-4);  // stored to 3 decimals
}

// A real propeller read from UIUC's own file (not the importer's copy), left out of the law's
// fit with its whole family: its static points below 1/0.6 of its lowest speed are predicted
// from the point there, with the law and by holding the edge; the law is closer on CT, CP and
// the figure of merit.
TEST(ReynoldsLaw, PredictsALeftOutUiucPropellerBetterThanHoldingTheEdge) {
  if (!HaveBundled()) GTEST_SKIP() << "no catalog/uiuc_propdb.json";
  if (!std::filesystem::exists(kUiuc + "/volume1_exp.csv")) GTEST_SKIP() << "no ../shared/data/uiuc_propdb";
  // GWS DD 9x5 (volume 1; the propeller of the quadplane example's pick; its family gwsdd is
  // left out of the fit). Not every family gains: on APC's E and SF families holding the edge
  // is closer (docs/propeller_reynolds.md, per family); the next test covers them all.
  const std::string name = "gwsdd 9.0x5.0 - 2";
  std::ifstream in(kUiuc + "/volume1_exp.csv");
  std::string line;
  std::getline(in, line);  // PropName,BladeName,Family,B,D,P,J,N,CT,CP,eta
  std::vector<double> rpm, ct, cp;
  while (std::getline(in, line)) {
    const auto f = SplitCsv(line);
    if (f.size() < 10 || f[0] != name || std::stod(f[6]) != 0.0) continue;
    rpm.push_back(std::stod(f[7]));
    ct.push_back(std::stod(f[8]));
    cp.push_back(std::stod(f[9]));
  }
  ASSERT_GE(rpm.size(), 8u) << name << " static rows";
  Bundled b;
  LoadBundled(&b);
  std::vector<const PropEntry*> others;
  for (const PropEntry* p : b.measured) {
    if (UiucFamily(p->id) != "gwsdd") others.push_back(p);
  }
  ASSERT_LT(others.size(), b.measured.size());
  const ReynoldsLaw law = FitReynoldsLaw(others);
  std::size_t edge = 0;
  while (edge < rpm.size() && rpm[edge] * kLeaveOutFraction < rpm.front()) ++edge;
  ASSERT_LT(edge, rpm.size());
  double err_held[3] = {0, 0, 0}, err_corr[3] = {0, 0, 0};
  int n = 0;
  for (std::size_t i = 0; i < edge; ++i) {
    const ReynoldsFactors f = ReynoldsCorrection(law, rpm[i], rpm[edge]);
    const double fm = std::pow(ct[i], 1.5) / cp[i];
    const double fm_held = std::pow(ct[edge], 1.5) / cp[edge];
    const double fm_corr = std::pow(ct[edge] * f.ct, 1.5) / (cp[edge] * f.cp);
    err_held[0] += std::fabs(ct[edge] / ct[i] - 1), err_corr[0] += std::fabs(ct[edge] * f.ct / ct[i] - 1);
    err_held[1] += std::fabs(cp[edge] / cp[i] - 1), err_corr[1] += std::fabs(cp[edge] * f.cp / cp[i] - 1);
    err_held[2] += std::fabs(fm_held / fm - 1), err_corr[2] += std::fabs(fm_corr / fm - 1);
    ++n;
  }
  ASSERT_GE(n, 3);
  EXPECT_LT(err_corr[0], err_held[0]) << "CT";
  EXPECT_LT(err_corr[2], err_held[2]) << "FM";
  // CP's slope scatters most across propellers (p10-p90 -0.160 to 0.073): on this one the law's
  // CP is off by at most 1 % a point more than the held one, while CT and FM gain.
  EXPECT_LT(err_corr[1] / n, err_held[1] / n + 0.01) << "CP";
}

// Over every UIUC propeller left out with its family: the corrected figure of merit is closer
// than the held one (median absolute error), and the p10-p90 band covers most points.
TEST(ReynoldsLaw, LeaveOneFamilyOutBeatsHoldingTheEdge) {
  if (!HaveBundled()) GTEST_SKIP() << "no catalog/uiuc_propdb.json";
  Bundled b;
  LoadBundled(&b);
  const auto pts = ReynoldsLeaveOneFamilyOut(b.measured);
  ASSERT_GE(pts.size(), 200u);
  std::vector<double> held, corr;
  int covered = 0;
  for (const auto& p : pts) {
    const double fm = std::pow(p.ct, 1.5) / p.cp;
    held.push_back(std::fabs(std::pow(p.ct_held, 1.5) / p.cp_held / fm - 1));
    corr.push_back(std::fabs(std::pow(p.ct_corr, 1.5) / p.cp_corr / fm - 1));
    const double ratio = fm / (std::pow(p.ct_held, 1.5) / p.cp_held);
    covered += ratio >= p.fm_ratio_lo * (1 - 1e-12) && ratio <= p.fm_ratio_hi * (1 + 1e-12);
  }
  std::sort(held.begin(), held.end());
  std::sort(corr.begin(), corr.end());
  EXPECT_LT(SortedQuantile(corr, 0.5), SortedQuantile(held, 0.5));
  // A p10-p90 band should hold about 80 % of the points; at least 60 % here.
  EXPECT_GT(covered, static_cast<int>(0.6 * static_cast<double>(pts.size())));
}

}  // namespace
}  // namespace dynosize
