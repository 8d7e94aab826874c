#include "catalog/prop_credibility.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <vector>

#include "common/text_format.h"
#include "model/physics.h"

namespace dynosize {

namespace {

// Reference density for dimensional evaluations; FM from coefficients does not depend on it.
constexpr double kRhoRef = 1.225;

double RpmAtTipSpeed(double tip_m_s, double diameter_m) {
  return RadPerSecToRpm(tip_m_s / (diameter_m / 2.0));
}

// FM of one static point given as coefficients, through physics.h on dimensional T and P at
// 1000 rpm (FM does not depend on the speed chosen).
double CoefficientFm(double ct, double cp, double diameter_m) {
  if (!(ct > 0.0) || !(cp > 0.0)) return 0.0;
  const double n = 1000.0 / 60.0, d4 = std::pow(diameter_m, 4);
  const double t = ct * kRhoRef * n * n * d4, p = cp * kRhoRef * n * n * n * d4 * diameter_m;
  return FigureOfMerit(t, p, diameter_m, kRhoRef);
}

double AxialFm(double ct, double cp, double j, double diameter_m) {
  if (!(ct > 0.0) || !(cp > 0.0)) return 0.0;
  const double n = 1000.0 / 60.0, d4 = std::pow(diameter_m, 4);
  const double t = ct * kRhoRef * n * n * d4, p = cp * kRhoRef * n * n * n * d4 * diameter_m;
  return FigureOfMerit(t, p, diameter_m, kRhoRef, j * n * diameter_m);
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace

PropValidRange ValidRange(const PropEntry& e) {
  PropValidRange r;
  for (const PropSweep& s : e.j_tables) {
    if (!s.j.empty()) r.j_hi = std::max(r.j_hi, s.j.back());
  }
  if (!e.static_table.rpm.empty()) {
    r.rpm_lo = e.static_table.rpm.front();
    r.rpm_hi = e.static_table.rpm.back();
    return r;
  }
  if (!e.j_tables.empty()) {
    r.rpm_lo = e.j_tables.front().rpm;
    r.rpm_hi = e.j_tables.back().rpm;
    return r;
  }
  const bool have_lo = e.rpm_min.has_value(), have_hi = e.rpm_max.has_value();
  r.rpm_assumed = !have_lo || !have_hi;
  r.rpm_lo = have_lo ? *e.rpm_min : RpmAtTipSpeed(kDefaultTipSpeedLoMS, e.diameter_m);
  r.rpm_hi = have_hi ? *e.rpm_max : RpmAtTipSpeed(kDefaultTipSpeedHiMS, e.diameter_m);
  if (!have_hi && e.max_rpm) r.rpm_hi = std::min(r.rpm_hi, *e.max_rpm);
  if (r.rpm_hi < r.rpm_lo) r.rpm_hi = r.rpm_lo;
  return r;
}

PropFmScan ScanFigureOfMerit(const PropEntry& e) {
  PropFmScan s;
  std::vector<double> fm;
  std::vector<double> rpm;
  const double d = e.diameter_m;
  if (!e.static_table.rpm.empty()) {
    const PropStaticTable& st = e.static_table;
    for (std::size_t i = 0; i < st.rpm.size(); ++i) {
      fm.push_back(CoefficientFm(st.ct[i], st.cp[i], d));
      rpm.push_back(st.rpm[i]);
      if (i + 1 < st.rpm.size()) {  // the interpolated curve between points
        fm.push_back(CoefficientFm(0.5 * (st.ct[i] + st.ct[i + 1]), 0.5 * (st.cp[i] + st.cp[i + 1]), d));
        rpm.push_back(0.5 * (st.rpm[i] + st.rpm[i + 1]));
      }
    }
  } else if (e.j_tables.empty() && e.ct_static && e.cp_static) {
    fm.push_back(CoefficientFm(*e.ct_static, *e.cp_static, d));
    rpm.push_back(ValidRange(e).rpm_lo);
  } else if (e.j_tables.empty() && e.power_law) {
    // T ~ k^b, P ~ k^d: FM ~ k^(1.5*b - d) is monotone in rpm, so the ends of the range bound
    // it; the points between give the median.
    const PropPowerLaw& law = *e.power_law;
    const PropValidRange r = ValidRange(e);
    constexpr int kSteps = 8;
    for (int i = 0; i <= kSteps; ++i) {
      const double x = r.rpm_lo * std::pow(r.rpm_hi / r.rpm_lo, static_cast<double>(i) / kSteps);
      const double k = x / 1000.0;
      const double t = law.thrust_law_n * std::pow(k, law.thrust_law_exp);
      const double p = law.power_law_w * std::pow(k, law.power_law_exp);
      fm.push_back(FigureOfMerit(t, p, d, law.rho_kg_m3));
      rpm.push_back(x);
    }
  }
  for (const PropSweep& sw : e.j_tables) {
    for (std::size_t i = 0; i < sw.j.size(); ++i) {
      if (sw.j[i] == 0.0 && e.static_table.rpm.empty()) {
        fm.push_back(CoefficientFm(sw.ct[i], sw.cp[i], d));
        rpm.push_back(sw.rpm);
        continue;
      }
      const double a = AxialFm(sw.ct[i], sw.cp[i], sw.j[i], d);
      if (a > s.axial_fm_max) {
        s.axial_fm_max = a;
        s.j_at_axial_max = sw.j[i];
      }
    }
  }
  if (fm.empty()) return s;
  const auto mx = std::max_element(fm.begin(), fm.end());
  s.fm_max = *mx;
  s.rpm_at_max = rpm[static_cast<std::size_t>(mx - fm.begin())];
  s.fm_min = *std::min_element(fm.begin(), fm.end());
  s.fm_median = Median(fm);
  return s;
}

std::string PropMomentumViolation(const PropEntry& e) {
  // Slack for rounding of stored coefficients (6 significant digits): far below any effect.
  constexpr double kLimit = 1.0 + 1e-6;
  const PropFmScan s = ScanFigureOfMerit(e);
  if (s.fm_max > kLimit) {
    const PropValidRange r = ValidRange(e);
    auto whole = [](double x) { return std::to_string(std::lround(x)); };
    return "static figure of merit " + SignificantText(s.fm_max, 4) + " at " + whole(s.rpm_at_max) +
           " rpm (valid range " + whole(r.rpm_lo) + "-" + whole(r.rpm_hi) +
           " rpm) > 1: beats momentum theory (model.md section 10)";
  }
  if (s.axial_fm_max > kLimit) {
    return "axial-flow figure of merit " + SignificantText(s.axial_fm_max, 4) +
           " at J = " + SignificantText(s.j_at_axial_max, 4) + " > 1: beats momentum theory (model.md section 10)";
  }
  return "";
}

double MedianStaticFigureOfMerit(const PropEntry& e) {
  std::vector<double> fm;
  for (std::size_t i = 0; i < e.static_table.rpm.size(); ++i) {
    const double f = CoefficientFm(e.static_table.ct[i], e.static_table.cp[i], e.diameter_m);
    if (f > 0.0) fm.push_back(f);
  }
  return Median(std::move(fm));
}

std::vector<FmEnvelopeClass> ComputeFmEnvelope(const std::vector<const PropEntry*>& measured) {
  std::vector<FmEnvelopeClass> out = FmEnvelope();
  for (FmEnvelopeClass& c : out) {
    std::vector<double> v;
    for (const PropEntry* e : measured) {
      if (e->static_table.rpm.empty() || e->diameter_m < c.d_lo_m || e->diameter_m >= c.d_hi_m) continue;
      const double fm = MedianStaticFigureOfMerit(*e);
      if (fm > 0.0) v.push_back(fm);
    }
    std::sort(v.begin(), v.end());
    c.n_props = static_cast<int>(v.size());
    c.p10 = SortedQuantile(v, 0.1);
    c.p50 = SortedQuantile(v, 0.5);
    c.p90 = SortedQuantile(v, 0.9);
    c.max = v.empty() ? 0.0 : v.back();
  }
  return out;
}

const std::vector<FmEnvelopeClass>& FmEnvelope() {
  // Generated from catalog/uiuc_propdb.json by ComputeFmEnvelope (per-propeller median static
  // FM; quantiles type 7); tests/catalog/prop_credibility_test.cc checks these numbers.
  static const std::vector<FmEnvelopeClass> kClasses = {
      {0.0, 0.1524, "D < 6 in", 39, 0.3875, 0.4782, 0.5724, 0.6261},
      {0.1524, 0.2286, "6 in <= D < 9 in", 23, 0.2405, 0.4062, 0.5967, 0.6424},
      {0.2286, 0.3048, "9 in <= D < 12 in", 149, 0.4066, 0.5683, 0.6536, 0.7192},
      {0.3048, 1e9, "D >= 12 in", 28, 0.3871, 0.6684, 0.7370, 0.7529},
  };
  return kClasses;
}

const FmEnvelopeClass& FmEnvelopeFor(double diameter_m) {
  const auto& classes = FmEnvelope();
  for (const FmEnvelopeClass& c : classes) {
    if (diameter_m < c.d_hi_m) return c;
  }
  return classes.back();
}

bool NameSaysFolding(const std::string& name) {
  std::string s = name;
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* k : {"fold", "klapp", "ancf ", "aerocarbon"}) {
    if (s.find(k) != std::string::npos) return true;
  }
  return false;
}

}  // namespace dynosize
