#include "catalog/prop_reynolds.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "catalog/prop_credibility.h"
#include "common/text_format.h"
#include "common/units.h"

namespace dynosize {

namespace {

// Least-squares slope of y against x.
double Slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= static_cast<double>(x.size());
  my /= static_cast<double>(y.size());
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  return sxy / sxx;
}

}  // namespace

double ReynoldsNumber75(double omega_rad_s, double diameter_m, double rho_kg_m3) {
  const double r = 0.5 * diameter_m;
  return rho_kg_m3 * (0.75 * omega_rad_s * r) * (kChordOverRadius75 * r) / kAirViscosityPaS;
}

bool FitReynoldsSlopesFrom(const PropEntry& e, double rpm_from, ReynoldsSlopes* out) {
  const PropStaticTable& st = e.static_table;
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < st.rpm.size(); ++i) {
    if (st.rpm[i] >= rpm_from && st.ct[i] > 0 && st.cp[i] > 0) idx.push_back(i);
  }
  if (idx.size() < 3) return false;
  const double lo = st.rpm[idx.front()], hi = st.rpm[idx.back()];
  if (!(hi >= kMinSpeedSpan * lo)) return false;
  // The lower half of the speeds (geometric middle), at least 3 points.
  const double mid = std::sqrt(lo * hi);
  std::vector<double> x, ct, cp;
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const std::size_t i = idx[k];
    if (st.rpm[i] > mid && x.size() >= 3) break;
    x.push_back(std::log(st.rpm[i]));
    ct.push_back(std::log(st.ct[i]));
    cp.push_back(std::log(st.cp[i]));
  }
  out->ct_exp = Slope(x, ct);
  out->cp_exp = Slope(x, cp);
  return std::isfinite(out->ct_exp) && std::isfinite(out->cp_exp);
}

bool FitReynoldsSlopes(const PropEntry& e, ReynoldsSlopes* out) { return FitReynoldsSlopesFrom(e, 0.0, out); }

ReynoldsLaw FitReynoldsLaw(const std::vector<const PropEntry*>& measured) {
  std::vector<double> a, b, fm;
  for (const PropEntry* e : measured) {
    ReynoldsSlopes s;
    if (!FitReynoldsSlopes(*e, &s)) continue;
    a.push_back(s.ct_exp);
    b.push_back(s.cp_exp);
    fm.push_back(s.fm_exp());
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::sort(fm.begin(), fm.end());
  ReynoldsLaw law;
  law.n_props = static_cast<int>(a.size());
  law.ct_p10 = SortedQuantile(a, 0.1), law.ct_p50 = SortedQuantile(a, 0.5), law.ct_p90 = SortedQuantile(a, 0.9);
  law.cp_p10 = SortedQuantile(b, 0.1), law.cp_p50 = SortedQuantile(b, 0.5), law.cp_p90 = SortedQuantile(b, 0.9);
  law.fm_p10 = SortedQuantile(fm, 0.1), law.fm_p50 = SortedQuantile(fm, 0.5), law.fm_p90 = SortedQuantile(fm, 0.9);
  return law;
}

const ReynoldsLaw& DefaultReynoldsLaw() {
  // FitReynoldsLaw on catalog/uiuc_propdb.json; tests/catalog/prop_reynolds_test.cc checks it.
  // Stored to 3 decimals.
  static const ReynoldsLaw kLaw{239, 0.036, 0.137, 0.256, -0.160, -0.066, 0.073, 0.085, 0.261, 0.461};
  return kLaw;
}

ReynoldsFactors ReynoldsCorrection(const ReynoldsLaw& law, double rpm, double rpm_ref) {
  ReynoldsFactors f;
  if (!(rpm > 0) || !(rpm < rpm_ref)) return f;
  f.ratio = rpm / rpm_ref;
  f.ct = std::pow(f.ratio, law.ct_exp());
  f.cp = std::pow(f.ratio, law.cp_exp());
  return f;
}

std::string UiucFamily(const std::string& id) {
  if (id.rfind("uiuc_v", 0) != 0) return "";
  const std::size_t a = id.find('_', 5);
  if (a == std::string::npos) return "";
  const std::size_t b = id.find('_', a + 1);
  return id.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1);
}

std::vector<ReynoldsLeaveOutPoint> ReynoldsLeaveOneFamilyOut(const std::vector<const PropEntry*>& measured) {
  std::map<std::string, ReynoldsLaw> by_family;  // the law without each family
  std::vector<ReynoldsLeaveOutPoint> out;
  for (const PropEntry* e : measured) {
    const PropStaticTable& st = e->static_table;
    if (st.rpm.size() < 4 || st.rpm.back() * kLeaveOutFraction < st.rpm.front()) continue;
    std::size_t edge = 0;
    while (edge < st.rpm.size() && st.rpm[edge] * kLeaveOutFraction < st.rpm.front()) ++edge;
    if (edge == 0 || edge >= st.rpm.size() || !(st.ct[edge] > 0) || !(st.cp[edge] > 0)) continue;
    const std::string fam = UiucFamily(e->id);
    auto it = by_family.find(fam);
    if (it == by_family.end()) {
      std::vector<const PropEntry*> others;
      for (const PropEntry* o : measured) {
        if (UiucFamily(o->id) != fam || fam.empty()) {
          if (o != e) others.push_back(o);
        }
      }
      it = by_family.emplace(fam, FitReynoldsLaw(others)).first;
    }
    const ReynoldsLaw& law = it->second;
    const double rpm_edge = st.rpm[edge];
    for (std::size_t i = 0; i < edge; ++i) {
      if (st.rpm[i] < kLeaveOutFraction * rpm_edge || !(st.ct[i] > 0) || !(st.cp[i] > 0)) continue;
      ReynoldsLeaveOutPoint p;
      p.prop_id = e->id;
      p.family = fam;
      p.rpm = st.rpm[i];
      p.rpm_edge = rpm_edge;
      p.ct = st.ct[i];
      p.cp = st.cp[i];
      p.ct_held = st.ct[edge];
      p.cp_held = st.cp[edge];
      const ReynoldsFactors f = ReynoldsCorrection(law, p.rpm, rpm_edge);
      p.ct_corr = p.ct_held * f.ct;
      p.cp_corr = p.cp_held * f.cp;
      p.fm_ratio_lo = std::pow(f.ratio, law.fm_p90);
      p.fm_ratio_hi = std::pow(f.ratio, std::max(law.fm_p10, 0.0));
      out.push_back(p);
    }
  }
  return out;
}

std::string ReynoldsReportMarkdown(const std::vector<const PropEntry*>& measured) {
  const ReynoldsLaw law = FitReynoldsLaw(measured);
  std::vector<double> re_lo;
  for (const PropEntry* e : measured) {
    if (!e->static_table.rpm.empty()) {
      re_lo.push_back(ReynoldsNumber75(RpmToRadPerSec(e->static_table.rpm.front()), e->diameter_m, 1.225));
    }
  }
  std::sort(re_lo.begin(), re_lo.end());
  std::ostringstream o;
  o << "## The law\n\n"
    << "Propellers fitted: " << law.n_props << " (static tables with at least 3 points spanning at least "
    << FixedText(kMinSpeedSpan, 1) << "x in rpm; slopes over the lower half of each table's speeds).\n"
    << "Re_75 at the lowest measured speed (rho 1.225 kg/m^3, mu " << kAirViscosityPaS
    << " Pa*s, c/R = " << kChordOverRadius75 << " at 0.75 R): p10 " << FixedText(SortedQuantile(re_lo, 0.1), 0)
    << ", p50 " << FixedText(SortedQuantile(re_lo, 0.5), 0) << ", p90 " << FixedText(SortedQuantile(re_lo, 0.9), 0)
    << ".\n\n"
    << "| exponent | p10 | p50 | p90 | applied |\n| --- | --- | --- | --- | --- |\n"
    << "| a (CT ~ Re^a) | " << FixedText(law.ct_p10, 3) << " | " << FixedText(law.ct_p50, 3) << " | " << FixedText(law.ct_p90, 3)
    << " | " << FixedText(law.ct_exp(), 3) << " |\n"
    << "| b (CP ~ Re^b) | " << FixedText(law.cp_p10, 3) << " | " << FixedText(law.cp_p50, 3) << " | " << FixedText(law.cp_p90, 3)
    << " | " << FixedText(law.cp_exp(), 3) << " |\n"
    << "| e = 1.5a - b (FM ~ Re^e) | " << FixedText(law.fm_p10, 3) << " | " << FixedText(law.fm_p50, 3) << " | "
    << FixedText(law.fm_p90, 3) << " | " << FixedText(law.fm_exp(), 3) << " (ranges: p90 pessimistic, max(p10, 0) optimistic) |\n\n";
  for (double r : {0.8, 0.6, 0.4}) {
    o << "At " << FixedText(r, 1) << "x the lowest measured speed: CT x " << FixedText(std::pow(r, law.ct_exp()), 3)
      << ", CP x " << FixedText(std::pow(r, law.cp_exp()), 3) << ", FM x " << FixedText(std::pow(r, law.fm_exp()), 3)
      << " (p10-p90 " << FixedText(std::pow(r, law.fm_p90), 3) << "-" << FixedText(std::pow(r, std::max(law.fm_p10, 0.0)), 3)
      << ").\n";
  }
  const std::vector<ReynoldsLeaveOutPoint> pts = ReynoldsLeaveOneFamilyOut(measured);
  std::vector<double> ct_h, ct_c, cp_h, cp_c, fm_h, fm_c, ct_hb, ct_cb, cp_hb, cp_cb, fm_hb, fm_cb;
  int covered = 0;
  std::map<std::string, int> props;
  for (const ReynoldsLeaveOutPoint& p : pts) {
    props[p.prop_id]++;
    auto rel = [](double pred, double meas) { return 100.0 * (pred / meas - 1.0); };
    const double fm = std::pow(p.ct, 1.5) / p.cp, fm_held = std::pow(p.ct_held, 1.5) / p.cp_held,
                 fm_corr = std::pow(p.ct_corr, 1.5) / p.cp_corr;
    ct_hb.push_back(rel(p.ct_held, p.ct)), ct_cb.push_back(rel(p.ct_corr, p.ct));
    cp_hb.push_back(rel(p.cp_held, p.cp)), cp_cb.push_back(rel(p.cp_corr, p.cp));
    fm_hb.push_back(rel(fm_held, fm)), fm_cb.push_back(rel(fm_corr, fm));
    ct_h.push_back(std::fabs(ct_hb.back())), ct_c.push_back(std::fabs(ct_cb.back()));
    cp_h.push_back(std::fabs(cp_hb.back())), cp_c.push_back(std::fabs(cp_cb.back()));
    fm_h.push_back(std::fabs(fm_hb.back())), fm_c.push_back(std::fabs(fm_cb.back()));
    const double ratio = fm / fm_held;
    if (ratio >= p.fm_ratio_lo * (1 - 1e-12) && ratio <= p.fm_ratio_hi * (1 + 1e-12)) ++covered;
  }
  o << "\n## Leave one family out\n\n"
    << "Each propeller whose static table spans at least " << FixedText(1 / kLeaveOutFraction, 2)
    << "x pretends its data start at its first point at or above rpm_lo/" << kLeaveOutFraction
    << "; its points down to " << kLeaveOutFraction << "x that edge are predicted from the edge's coefficients, "
    << "held (the rule before the law) or corrected with the law fitted without the propeller's UIUC family. "
    << props.size() << " propellers, " << pts.size() << " points.\n\n"
    << "| coefficient | held: median abs error % | held: median bias % | corrected: median abs error % | corrected: median bias % |\n"
    << "| --- | --- | --- | --- | --- |\n";
  auto row = [&](const char* name, const std::vector<double>& h, const std::vector<double>& hb,
                 const std::vector<double>& c, const std::vector<double>& cb) {
    o << "| " << name << " | " << FixedText(fit::Median(h), 2) << " | " << FixedText(fit::Median(hb), 2) << " | "
      << FixedText(fit::Median(c), 2) << " | " << FixedText(fit::Median(cb), 2) << " |\n";
  };
  row("CT", ct_h, ct_hb, ct_c, ct_cb);
  row("CP", cp_h, cp_hb, cp_c, cp_cb);
  row("FM = CT^1.5/(CP*sqrt(pi/2))", fm_h, fm_hb, fm_c, fm_cb);
  // Per family: where the law helps and where it does not.
  struct Fam {
    std::map<std::string, int> props;
    std::vector<double> held, corr;
  };
  std::map<std::string, Fam> fams;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    Fam& f = fams[pts[i].family];
    f.props[pts[i].prop_id]++;
    f.held.push_back(fm_h[i]);
    f.corr.push_back(fm_c[i]);
  }
  o << "\nPer UIUC family (each left out of its own law), FM: median absolute error %, held -> corrected:\n\n"
    << "| family | props | points | held | corrected |\n| --- | ---: | ---: | ---: | ---: |\n";
  for (const auto& [name, f] : fams) {
    o << "| " << name << " | " << f.props.size() << " | " << f.held.size() << " | " << FixedText(fit::Median(f.held), 2)
      << " | " << FixedText(fit::Median(f.corr), 2) << " |\n";
  }
  o << "\nMeasured FM/FM_edge inside the law's p10-p90 band: " << covered << " of " << pts.size() << " points ("
    << FixedText(pts.empty() ? 0.0 : 100.0 * covered / static_cast<double>(pts.size()), 1) << " %).\n";
  return o.str();
}

}  // namespace dynosize
