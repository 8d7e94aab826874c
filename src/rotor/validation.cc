#include "rotor/validation.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "common/text_format.h"
#include "common/units.h"
#include "fit/statistics.h"
#include "common/worker_threads.h"

namespace dynosize {

using fit::Quantile;
ErrorSummary Summarize(const std::vector<CasePrediction>& points, int props) {
  ErrorSummary s;
  s.props = props;
  std::vector<double> ct, cp, eta;
  for (const CasePrediction& p : points) {
    if (p.measured.j == 0.0) {
      ct.push_back(std::fabs(p.model.ct / p.measured.ct - 1.0));
      cp.push_back(std::fabs(p.model.cp / p.measured.cp - 1.0));
    } else {
      eta.push_back(std::fabs(p.model.efficiency - p.measured.eta));
    }
  }
  s.static_points = static_cast<int>(ct.size());
  s.sweep_points = static_cast<int>(eta.size());
  s.ct_median = Quantile(ct, 0.5);
  s.cp_median = Quantile(cp, 0.5);
  s.ct_p90 = Quantile(ct, 0.9);
  s.cp_p90 = Quantile(cp, 0.9);
  s.eta_median = Quantile(eta, 0.5);
  return s;
}

LeaveFamilyOutReport LeaveFamilyOut(const std::vector<RotorFitCase>& cases, const AirfoilPolar& start, int threads) {
  LeaveFamilyOutReport r;
  r.all = FitAirfoil(cases, start);
  std::vector<CasePrediction> in_sample;
  for (const RotorFitCase& c : cases) {
    for (const CasePrediction& p : EvaluateCase(c, r.all.polar)) in_sample.push_back(p);
  }
  r.in_sample = Summarize(in_sample, static_cast<int>(cases.size()));
  std::set<std::string> families;
  for (const RotorFitCase& c : cases) families.insert(c.family);
  r.folds.resize(families.size());
  std::vector<std::vector<CasePrediction>> fold_points(families.size());
  std::size_t k = 0;
  for (const std::string& f : families) r.folds[k++].family = f;
  ForEachOnThreads(r.folds.size(), threads, [&](int, std::size_t i) {
    FamilyFold& fold = r.folds[i];
    std::vector<RotorFitCase> train;
    int props = 0;
    for (const RotorFitCase& c : cases) {
      if (c.family != fold.family) train.push_back(c);
    }
    fold.fit = FitAirfoil(train, r.all.polar);
    for (const RotorFitCase& c : cases) {
      if (c.family != fold.family) continue;
      ++props;
      for (const CasePrediction& p : EvaluateCase(c, fold.fit.polar)) fold_points[i].push_back(p);
    }
    fold.errors = Summarize(fold_points[i], props);
  });
  for (std::size_t i = 0; i < r.folds.size(); ++i) {
    for (const CasePrediction& p : fold_points[i]) {
      r.left_out_points.push_back(p);
      r.left_out_family.push_back(r.folds[i].family);
    }
  }
  r.left_out = Summarize(r.left_out_points, static_cast<int>(cases.size()));
  return r;
}

ApcComparison CompareWithApc(const std::vector<ApcCase>& cases, const AirfoilPolar& polar) {
  ApcComparison out;
  std::vector<double> mct, act, mcp, acp;
  int closer_ct = 0, closer_cp = 0;
  for (const ApcCase& c : cases) {
    const Bemt bemt(c.apc_geometry, polar);
    const double d = 2.0 * c.apc_geometry.radius_m;
    std::vector<double> pmct, pact, pmcp, pacp;
    for (const MeasuredRotorPoint& m : c.measured.points) {
      if (m.j != 0.0) continue;  // static points: APC's tables and UIUC's agree on what J = 0 is
      const double n = RpmToRevPerSec(m.rpm);
      double thrust = 0.0, torque = 0.0;
      if (!Per3At(c.per3, m.rpm, 0.0, &thrust, &torque)) continue;
      // PER3 is computed at sea-level standard air (1.225 kg/m^3).
      const double apc_ct = thrust / (kIsaSeaLevelRhoKgM3 * n * n * std::pow(d, 4));
      const double apc_cp = torque * 2.0 * kPi * n / (kIsaSeaLevelRhoKgM3 * n * n * n * std::pow(d, 5));
      const BemtPoint b = bemt.Evaluate(RpmToRadPerSec(m.rpm), 0.0, c.measured.rho_kg_m3);
      const double e_mct = std::fabs(b.ct / m.ct - 1.0), e_act = std::fabs(apc_ct / m.ct - 1.0);
      const double e_mcp = std::fabs(b.cp / m.cp - 1.0), e_acp = std::fabs(apc_cp / m.cp - 1.0);
      pmct.push_back(e_mct);
      pact.push_back(e_act);
      pmcp.push_back(e_mcp);
      pacp.push_back(e_acp);
      if (e_mct <= e_act) ++closer_ct;
      if (e_mcp <= e_acp) ++closer_cp;
    }
    if (pmct.empty()) continue;
    ++out.props;
    out.points += static_cast<int>(pmct.size());
    out.rows.push_back(c.apc_geometry.name + " | " + c.measured.name + " | " + std::to_string(pmct.size()) + " | " +
                       PercentText(Quantile(pmct, 0.5)) + " | " + PercentText(Quantile(pact, 0.5)) + " | " +
                       PercentText(Quantile(pmcp, 0.5)) + " | " + PercentText(Quantile(pacp, 0.5)));
    mct.insert(mct.end(), pmct.begin(), pmct.end());
    act.insert(act.end(), pact.begin(), pact.end());
    mcp.insert(mcp.end(), pmcp.begin(), pmcp.end());
    acp.insert(acp.end(), pacp.begin(), pacp.end());
  }
  out.model_ct = Quantile(mct, 0.5);
  out.apc_ct = Quantile(act, 0.5);
  out.model_cp = Quantile(mcp, 0.5);
  out.apc_cp = Quantile(acp, 0.5);
  if (out.points > 0) {
    out.model_closer_ct = static_cast<double>(closer_ct) / out.points;
    out.model_closer_cp = static_cast<double>(closer_cp) / out.points;
  }
  return out;
}

}  // namespace dynosize
