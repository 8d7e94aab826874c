// Trust tiers, the measured-propeller envelope, the data scenarios, folding propellers, the
// rating of unrated motors (optimization/credibility.h), and the objective range where those
// rules decide it (objective_range.h; its own tests: objective_range_test.cc).
#include "optimization/credibility.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <string>

#include "catalog/catalog.h"
#include "catalog/conventions.h"
#include "catalog/prop_credibility.h"
#include "catalog/prop_reynolds.h"
#include "cli_runner.h"
#include "common/error.h"
#include "common/json_file.h"
#include "common/units.h"
#include "model/physics.h"
#include "optimization/credibility_fixture.h"
#include "optimization/mission_eval.h"
#include "optimization/objective_range.h"
#include "optimization/search.h"
#include "prop/prop_model.h"

namespace dynosize {
namespace {

using credibility_fixture::Bundled;
using credibility_fixture::OldQuadPick;
using credibility_fixture::QuadMission;

// Measured over computed FM of the same APC products: UIUC "apcsf D.DxP.P" / "apce ..." (2
// blades) against APC PER3 "APC DxPSF" / "APC DxPE" of the bundled catalog, on APC's raw data
// (the catalog's derating undone: FM scales as 1/CP).
// Below a propeller's data the scenarios widen the Reynolds correction with the distance from
// the data (credibility.h): the pessimistic power at the same thrust x r^-(e_p90 - e_applied),
// the optimistic x r^-(max(e_p10, 0) - e_applied); at and above the data nothing changes; the
// optimistic end never beats the edge's figure of merit (nor momentum theory).
TEST(CredibilityTest, ReynoldsBandWidensWithTheDistanceFromTheData) {
  PropEntry p;
  p.id = "measured";
  p.diameter_m = 0.254;
  p.tier = DataTier::kMeasured;
  p.static_table = {{4000, 6000}, {0.11, 0.12}, {0.045, 0.046}};
  const PropModel model(p);
  const ReynoldsLaw& law = DefaultReynoldsLaw();
  const double rho = 1.225;
  const PropEvaluation edge = model.Evaluate(RpmToRadPerSec(4000), rho);
  for (const double rpm : {3600.0, 2400.0, 1600.0}) {
    const PropEvaluation raw = model.Evaluate(RpmToRadPerSec(rpm), rho);
    const double r = rpm / 4000.0;
    ASSERT_DOUBLE_EQ(raw.reynolds_ratio, r);
    PropEvaluation pess = raw, opt = raw, cred = raw;
    AdjustPropEvaluation(PropAdjustmentFor(p, DataScenario::kPessimistic), p.diameter_m, &pess);
    AdjustPropEvaluation(PropAdjustmentFor(p, DataScenario::kOptimistic), p.diameter_m, &opt);
    AdjustPropEvaluation(PropAdjustmentFor(p, DataScenario::kCredible), p.diameter_m, &cred);
    EXPECT_DOUBLE_EQ(cred.power_w, raw.power_w);  // measured: the credible value is the model's
    const double k_pess = (1.0 + kMeasuredPowerBand) * std::pow(r, -(law.fm_p90 - law.fm_exp()));
    const double k_opt = (1.0 - kMeasuredPowerBand) * std::pow(r, -(std::max(law.fm_p10, 0.0) - law.fm_exp()));
    EXPECT_NEAR(pess.power_w / raw.power_w, k_pess, 1e-12);
    EXPECT_NEAR(opt.power_w / raw.power_w, k_opt, 1e-12);
    EXPECT_EQ(pess.thrust_n, raw.thrust_n);  // thrust is never changed
    // The band widens with the distance from the data.
    static double last_width = 0.0;
    const double width = k_pess / k_opt;
    EXPECT_GT(width, last_width);
    last_width = width;
    // The optimistic end without the measured band is no better than the edge's FM.
    const double fm_edge = FigureOfMerit(edge.thrust_n, edge.power_w, p.diameter_m, rho);
    const double fm_opt = FigureOfMerit(opt.thrust_n, opt.power_w / (1.0 - kMeasuredPowerBand), p.diameter_m, rho);
    EXPECT_LE(fm_opt, fm_edge * (1 + 1e-12));
    EXPECT_LT(FigureOfMerit(opt.thrust_n, opt.power_w, p.diameter_m, rho), 1.0);
  }
  const PropEvaluation in_data = model.Evaluate(RpmToRadPerSec(5000), rho);
  PropEvaluation pess = in_data;
  AdjustPropEvaluation(PropAdjustmentFor(p, DataScenario::kPessimistic), p.diameter_m, &pess);
  EXPECT_NEAR(pess.power_w / in_data.power_w, 1.0 + kMeasuredPowerBand, 1e-12);
}

TEST(CredibilityTest, ComputedToMeasuredRatioIsThatOfTheSameApcProducts) {
  const std::regex uiuc(R"(UIUC vol \d (apcsf|apce) (\d+\.\d)x(\d+\.\d) \(2 blades\))");
  const std::regex per3(R"(APC (\d+(?:\.\d)?)x(\d+(?:\.\d)?)(SF|E) \(PER3.*)");
  std::multimap<std::string, double> measured;
  auto key = [](const std::string& fam, const std::string& d, const std::string& p) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s %.1f %.1f", fam.c_str(), std::stod(d), std::stod(p));
    return std::string(buf);
  };
  std::smatch mt;
  for (const PropEntry& p : Bundled().props()) {
    if (std::regex_match(p.name, mt, uiuc) && !p.static_table.rpm.empty()) {
      measured.emplace(key(mt[1], mt[2], mt[3]), MedianStaticFigureOfMerit(p));
    }
  }
  std::vector<double> ratios;
  for (const PropEntry& p : Bundled().props()) {
    if (!std::regex_match(p.name, mt, per3)) continue;
    const auto range = measured.equal_range(key(mt[3] == "SF" ? "apcsf" : "apce", mt[1], mt[2]));
    for (auto it = range.first; it != range.second; ++it) ratios.push_back(it->second / (MedianStaticFigureOfMerit(p) * p.power_derate_factor));
  }
  ASSERT_EQ(static_cast<int>(ratios.size()), kComputedFmRatio.pairs);
  std::sort(ratios.begin(), ratios.end());
  constexpr double kRounding = 5e-5;  // printed to 4 decimals
  EXPECT_NEAR(ratios.front(), kComputedFmRatio.min, kRounding);
  EXPECT_NEAR(ratios[ratios.size() / 2], kComputedFmRatio.median, kRounding);
  EXPECT_NEAR(ratios.back(), kComputedFmRatio.max, kRounding);
  EXPECT_LT(ratios.back(), 1.0) << "APC's computed data are optimistic for every product UIUC measured";
}

// The tiers are the catalog's (EntryBase::tier); the bands of the pessimistic/optimistic
// scenarios read one value's tier (ValueTier), never better than the entry's.
TEST(CredibilityTest, TiersAreTheCatalogs) {
  const Catalog& c = Bundled();
  EXPECT_EQ(c.prop("uiuc_v1_apcsf_10.0x4.7_2").tier, DataTier::kMeasured);
  EXPECT_EQ(c.prop("apc_per3_10x45mr").tier, DataTier::kManufacturerComputed);
  EXPECT_EQ(c.prop("dc_p_127").tier, DataTier::kUserContributed);
  const EscEntry& esc = c.esc("dc_e_142");
  EXPECT_EQ(esc.tier, DataTier::kUserContributed);
  EXPECT_EQ(ValueTier(esc, "c0"), DataTier::kAssumed) << "the ESC prior's ideal constants";
  EXPECT_EQ(ValueTier(esc, "no_such_key"), DataTier::kUserContributed);
  const MotorEntry& fitted = c.motor("dc_m_2_fit");  // DriveCalc measurements: user submissions
  EXPECT_EQ(fitted.tier, DataTier::kUserContributed);
  EXPECT_EQ(ValueTier(fitted, "rm_ohm"), DataTier::kUserContributed) << "'fitted' is measured, capped by the entry";
  // The pessimistic scenario moves a user-contributed motor's Rm by its band (x1.6) and leaves
  // the credible scenario alone.
  Mission m = QuadMission(true);
  EXPECT_EQ(ScenarioMotorParams(fitted, m).rm_ohm, fitted.params.rm_ohm);
  m.objective.ranking = DataScenario::kPessimistic;
  EXPECT_NEAR(ScenarioMotorParams(fitted, m).rm_ohm, 1.6 * fitted.params.rm_ohm, 1e-12);
  EXPECT_EQ(ScenarioEscParams(esc, DataScenario::kPessimistic).c0, std::max(esc.params.c0, kAssumedEscC0Pessimistic));
}

TEST(CredibilityTest, CredibleFigureOfMeritIsTheClassMedianForUserData) {
  // DriveCalc law, FM 0.79 as submitted, derated by the catalog to its class maximum (0.753 at
  // the top of its range): still above the class p90, so every cap below binds.
  const PropEntry& p = Bundled().prop("dc_p_127");
  const PropModel model(p);
  const FmEnvelopeClass& k = FmEnvelopeFor(p.diameter_m);
  const double rho = 1.225, omega = RpmToRadPerSec(ScanFigureOfMerit(p).rpm_at_max);
  const PropEvaluation raw = model.Evaluate(omega, rho, 0.0);
  const double fm_raw = FigureOfMerit(raw.thrust_n, raw.power_w, p.diameter_m, rho);
  ASSERT_GT(fm_raw, k.p90) << "the test needs data above the class envelope";
  // Rounding of a few operations: 1e-12 relative.
  constexpr double kTol = 1e-12;
  struct Case { DataScenario s; double fm; };
  for (const Case& cs : {Case{DataScenario::kCredible, k.p50}, Case{DataScenario::kPessimistic, k.p10},
                         Case{DataScenario::kOptimistic, k.p90}, Case{DataScenario::kAsGiven, fm_raw}}) {
    PropEvaluation ev = raw;
    AdjustPropEvaluation(PropAdjustmentFor(p, cs.s), p.diameter_m, &ev);
    EXPECT_EQ(ev.thrust_n, raw.thrust_n);
    EXPECT_NEAR(FigureOfMerit(ev.thrust_n, ev.power_w, p.diameter_m, rho), cs.fm, kTol * cs.fm);
    EXPECT_NEAR(ev.torque_nm * ev.omega_rad_s, ev.power_w, kTol * ev.power_w);
  }
  // Forward-flight tables are used as given (below their speeds with the Reynolds band only,
  // prop_reynolds.h); static-only data in flow are adjusted.
  const PropEntry& apc = Bundled().prop("apc_per3_10x45mr");
  const PropEvaluation fwd = PropModel(apc).Evaluate(omega, rho, 8.0);
  PropEvaluation f2 = fwd;
  AdjustPropEvaluation(PropAdjustmentFor(apc, DataScenario::kPessimistic), apc.diameter_m, &f2);
  const ReynoldsLaw& law = DefaultReynoldsLaw();
  const double k_re = fwd.reynolds_ratio < 1.0 ? std::pow(fwd.reynolds_ratio, -(law.fm_p90 - law.fm_exp())) : 1.0;
  EXPECT_NEAR(f2.power_w, fwd.power_w * k_re, 1e-12 * fwd.power_w);
  const PropEvaluation fwd_in = PropModel(apc).Evaluate(RpmToRadPerSec(6000), rho, 8.0);
  PropEvaluation f3 = fwd_in;
  AdjustPropEvaluation(PropAdjustmentFor(apc, DataScenario::kPessimistic), apc.diameter_m, &f3);
  EXPECT_EQ(f3.power_w, fwd_in.power_w);
  PropEvaluation s2 = model.Evaluate(omega, rho, 5.0);
  ASSERT_TRUE(s2.no_forward_flight_data);
  const double p_before = s2.power_w;
  AdjustPropEvaluation(PropAdjustmentFor(p, DataScenario::kCredible), p.diameter_m, &s2);
  EXPECT_GT(s2.power_w, p_before);
}

TEST(CredibilityTest, DataWorseThanTheCapAreKeptAndMeasuredDataGetTheirBand) {
  const PropEntry& measured = Bundled().prop("uiuc_v1_apcsp_10.0x8.0_2");  // median FM 0.41
  const PropModel model(measured);
  const PropEvaluation raw = model.Evaluate(RpmToRadPerSec(5000), 1.225, 0.0);
  EXPECT_TRUE(PropAdjustmentFor(measured, DataScenario::kCredible).identity());
  PropEvaluation pess = raw;
  AdjustPropEvaluation(PropAdjustmentFor(measured, DataScenario::kPessimistic), measured.diameter_m, &pess);
  EXPECT_NEAR(pess.power_w, raw.power_w * (1 + kMeasuredPowerBand), 1e-12 * raw.power_w);
  // A user-contributed propeller whose FM is below the class median keeps its data.
  for (const PropEntry& p : Bundled().props()) {
    if (p.tier != DataTier::kUserContributed || !p.power_law) continue;
    const PropEvaluation ev = PropModel(p).Evaluate(RpmToRadPerSec(4000), 1.225, 0.0);
    const double fm = FigureOfMerit(ev.thrust_n, ev.power_w, p.diameter_m, 1.225);
    if (fm >= 0.9 * FmEnvelopeFor(p.diameter_m).p10) continue;
    if (ev.reynolds_ratio < 1.0) continue;  // below its data the Reynolds band widens the range
    PropEvaluation adj = ev;
    AdjustPropEvaluation(PropAdjustmentFor(p, DataScenario::kPessimistic), p.diameter_m, &adj);
    EXPECT_EQ(adj.power_w, ev.power_w) << p.id;
    return;
  }
  FAIL() << "no user-contributed propeller below its class p10 at 4000 rpm";
}

// The search needs M1 (torque rises with speed) of the adjusted data too.
TEST(CredibilityTest, AdjustedTorqueRisesWithSpeed) {
  int checked = 0;
  for (const PropEntry& p : Bundled().props()) {
    if (!p.power_law) continue;
    const PropModel model(p);
    const PropAdjustment adj = PropAdjustmentFor(p, DataScenario::kCredible);
    double last = 0;
    for (int i = 1; i <= 200; ++i) {
      PropEvaluation ev = model.Evaluate(30.0 * i, 1.225, 0.0);
      AdjustPropEvaluation(adj, p.diameter_m, &ev);
      ASSERT_GT(ev.torque_nm, last) << p.id << " at " << 30.0 * i << " rad/s";
      last = ev.torque_nm;
    }
    ++checked;
  }
  EXPECT_GT(checked, 250);
}

// Folding is the catalog's flag (PropEntry::folding, set by the importers), not a name rule.
TEST(CredibilityTest, FoldingIsTheCatalogsFlag) {
  const Mission m = QuadMission(false);
  PropEntry p = *OldQuadPick().prop;
  ASSERT_TRUE(p.folding) << p.name;
  EXPECT_TRUE(FoldingPropRefused(p, m));
  p.folding = false;
  EXPECT_FALSE(FoldingPropRefused(p, m)) << "the name alone does not refuse it";
  int n = 0;
  for (const PropEntry& e : Bundled().props()) n += FoldingPropRefused(e, m);
  EXPECT_EQ(n, 102) << "62 DriveCalc folders and UIUC's 40 Aeronaut CAM folders (catalog/README.md)";
}

TEST(CredibilityTest, FoldingPropIsRefusedForLiftUnlessAllowed) {
  const MissionResult refused = MissionEvaluator(QuadMission(false), OldQuadPick()).Solve();
  EXPECT_FALSE(refused.feasible);
  bool named = false;
  for (const Violation& v : refused.violations) named |= v.constraint == "prop_folding";
  EXPECT_TRUE(named);
  const MissionResult allowed = MissionEvaluator(QuadMission(true), OldQuadPick()).Solve();
  EXPECT_TRUE(allowed.feasible);
  // A wing-borne cruise alone does not lift on the rotors.
  Mission glider = QuadMission(false);
  glider.segments = {glider.segments[1]};
  glider.segments[0].lift_to_drag = 8;
  EXPECT_FALSE(MissionUsesRotorLift(glider));
  EXPECT_FALSE(FoldingPropRefused(*OldQuadPick().prop, glider));
}

TEST(CredibilityTest, UnratedMotorIsRatedFromItsMassOrExcluded) {
  MotorEntry motor = Bundled().motor("dc_m_56");
  motor.params.max_current_a = std::numeric_limits<double>::infinity();
  motor.params.max_power_w = std::numeric_limits<double>::infinity();
  Combination c = OldQuadPick();
  c.motor = &motor;
  Mission m = QuadMission(true);
  bool estimated = false, excluded = false;
  const MotorParams p = ScenarioMotorParams(motor, m, &estimated, &excluded);
  EXPECT_TRUE(estimated);
  EXPECT_FALSE(excluded);
  EXPECT_DOUBLE_EQ(p.max_power_w, EstimatedMotorPowerW(*motor.mass_kg)) << "catalog/conventions.h";
  EXPECT_DOUBLE_EQ(p.max_current_a, EstimatedMotorCurrentA(*motor.mass_kg, *motor.kv_rpm_per_v));
  MissionResult r = MissionEvaluator(m, c).Solve();
  bool said = false;
  for (const std::string& w : r.warnings) said |= w.find("estimated from its mass") != std::string::npos;
  EXPECT_TRUE(said);
  m.constraints.estimate_unrated_motors = false;
  r = MissionEvaluator(m, c).Solve();
  EXPECT_FALSE(r.feasible);
  bool named = false;
  for (const Violation& v : r.violations) named |= v.constraint == "motor_unrated";
  EXPECT_TRUE(named);
}

// A motor the importer rated from its mass (max_power_w "assumed") counts as unrated: used by
// default and said to be estimated, left out by unrated_motors = "exclude".
TEST(CredibilityTest, ImporterEstimateCountsAsUnrated) {
  const MotorEntry* est = nullptr;
  for (const MotorEntry& m : Bundled().motors()) {
    if (!std::isfinite(m.params.max_current_a) && m.exclude_reason.empty() &&
        std::find(m.assumed_keys.begin(), m.assumed_keys.end(), "max_power_w") != m.assumed_keys.end()) {
      est = &m;
      break;
    }
  }
  ASSERT_NE(est, nullptr) << "the bundled catalog has motors rated from their mass (catalog/README.md)";
  ASSERT_TRUE(est->mass_kg.has_value());
  EXPECT_NEAR(est->params.max_power_w, EstimatedMotorPowerW(*est->mass_kg), 1e-3 * est->params.max_power_w)
      << "stored to 3 significant digits";
  Mission m = QuadMission(true);
  bool estimated = false, excluded = true;
  const MotorParams p = ScenarioMotorParams(*est, m, &estimated, &excluded);
  EXPECT_EQ(p.max_power_w, est->params.max_power_w) << "the importer's estimate is kept";
  ASSERT_TRUE(est->kv_rpm_per_v.has_value());
  EXPECT_DOUBLE_EQ(p.max_current_a, EstimatedMotorCurrentA(*est->mass_kg, *est->kv_rpm_per_v));
  EXPECT_TRUE(estimated);
  EXPECT_FALSE(excluded);
  m.constraints.estimate_unrated_motors = false;
  ScenarioMotorParams(*est, m, &estimated, &excluded);
  EXPECT_FALSE(estimated);
  EXPECT_TRUE(excluded);
  // A motor with a stated rating is neither.
  ScenarioMotorParams(Bundled().motor("dc_m_56"), m, &estimated, &excluded);
  EXPECT_FALSE(estimated);
  EXPECT_FALSE(excluded);
  // The 40 g, 1964 Kv motor (rated 275 W from its mass by the importer) flew the
  // eVTOL at 42 A rms and 8 % throttle; the current law holds it near 14 A.
  const MotorEntry& small = Bundled().motor("dc_m_223");
  m.constraints.estimate_unrated_motors = true;
  const MotorParams ps = ScenarioMotorParams(small, m, &estimated, &excluded);
  EXPECT_TRUE(estimated);
  EXPECT_NEAR(ps.max_current_a, 14.3, 0.1);
}

// Manufacturer-computed propellers the catalog derated at import (power x d) are not derated
// twice: the measured/computed ratio applies to the raw data, f' = max(1, 1/(ratio*d)).
TEST(CredibilityTest, ComputedRatioAppliesToTheRawDataOfADeratedProp) {
  int derated = 0;
  for (const PropEntry& p : Bundled().props()) {
    if (p.tier != DataTier::kManufacturerComputed) continue;
    const PropAdjustment a = PropAdjustmentFor(p, DataScenario::kCredible);
    EXPECT_NEAR(a.power_factor, std::max(1.0, 1.0 / (kComputedFmRatio.median * p.power_derate_factor)), 1e-12) << p.id;
    EXPECT_GE(a.power_factor, 1.0) << p.id;
    EXPECT_EQ(a.fm_cap, FmEnvelopeFor(p.diameter_m).p90) << p.id;
    if (p.power_derate_factor <= 1.0) continue;
    ++derated;
    // Credible power over the raw data's is 1/0.880 (or the derate when that is larger).
    const PropAdjustment pess = PropAdjustmentFor(p, DataScenario::kPessimistic);
    EXPECT_NEAR(pess.power_factor * p.power_derate_factor, std::max(p.power_derate_factor, 1.0 / kComputedFmRatio.min), 1e-12)
        << p.id;
  }
  EXPECT_GE(derated, 30) << "34 APC PER3 tables and 1 FAST-UAV prop are derated (catalog/README.md)";
}

TEST(CredibilityTest, MotorVoltageRatingFromItsCellCount) {
  const MotorEntry& maxon = Bundled().motor("fu_m_142");  // maxon EC 13, cells_max 4
  EXPECT_NEAR(MotorMaxVoltageV(maxon), 16.8, 1e-6);
  EXPECT_TRUE(std::isinf(MotorMaxVoltageV(Bundled().motor("dc_m_56"))));
  Combination c = OldQuadPick();
  c.motor = &maxon;
  for (int cells : {4, 6}) {
    c.cells = cells;
    const MissionResult r = MissionEvaluator(QuadMission(true), c).Solve();
    bool named = false;
    for (const Violation& v : r.violations) named |= v.constraint == "motor_voltage";
    EXPECT_EQ(named, cells == 6) << cells << "S: a full 4S pack is exactly 16.8 V";
  }
}

// Parameters that create energy (docs/model.md section 10) never give a feasible result.
TEST(CredibilityTest, EnergyCreatingPartsAreInfeasible) {
  Combination c = OldQuadPick();
  const Mission m = QuadMission(true);
  ASSERT_TRUE(MissionEvaluator(m, c).Solve().feasible);
  MotorEntry motor = *c.motor;
  motor.params.kt_nm_per_a = 1.3 * kPacPerVllIrms * motor.params.ke_v_s_per_rad;  // eta_motor > 1
  EscEntry esc = *c.esc;
  esc.params.c1 = 0.6;  // c1 + c0 < 1.1095: PESC < 0
  for (int which = 0; which < 2; ++which) {
    Combination bad = c;
    if (which == 0) bad.motor = &motor;
    else bad.esc = &esc;
    const MissionResult r = MissionEvaluator(m, bad).Solve();
    EXPECT_FALSE(r.feasible) << which;
    bool named = false;
    for (const Violation& v : r.violations) named |= v.constraint == "creates_energy";
    EXPECT_TRUE(named) << which;
  }
}

// The credibility model on the example quadcopter's search (about 3 s of CPU on the bundled
// catalog): the pick hovers at a figure of merit measured props support, no point creates energy, the
// result has its range, and no folding propeller lifts it.
TEST(CredibilityTest, ExampleQuadPickIsCredible) {
  const Mission m = ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
  SearchOptions so;
  so.top_n = 1;
  const SearchResult s = SearchCatalog(m, Bundled(), so);
  ASSERT_EQ(s.best.size(), 1u);
  const Combination& c = s.best[0].combination;
  const MissionResult& r = s.best[0].result;
  EXPECT_FALSE(c.prop->folding) << c.prop->name;
  EXPECT_TRUE(r.range.computed);
  ASSERT_LT(c.prop->diameter_m, 0.5);
  for (const SegmentResult& seg : r.segments) {
    EXPECT_GE(seg.point.pesc_w, 0.0) << seg.name;
    EXPECT_LE(seg.point.eta_motor, 1.0) << seg.name;
    if (seg.type != SegmentType::kHover) continue;
    const double fm = FigureOfMerit(seg.thrust_per_rotor_n, seg.point.pmech_w, c.prop->diameter_m, m.rho_kg_m3);
    EXPECT_LE(fm, 0.72) << seg.name << ": above what measured props below 0.5 m support";
  }
}

TEST(CredibilityTest, MissionKeysAreChecked) {
  Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
  EXPECT_EQ(ParseMission(j, "q").objective.ranking, DataScenario::kCredible);
  EXPECT_FALSE(ParseMission(j, "q").constraints.allow_folding_props_for_lift);
  EXPECT_TRUE(ParseMission(j, "q").constraints.estimate_unrated_motors);
  Json bad = j;
  bad["objective"]["ranking"] = "optimistic";
  EXPECT_THROW(ParseMission(bad, "q"), DataError);
  bad = j;
  bad["constraints"]["unrated_motors"] = "ignore";
  try {
    ParseMission(bad, "q");
    FAIL() << "accepted";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("$.constraints.unrated_motors"), std::string::npos) << e.what();
  }
  bad = j;
  bad["constraints"]["allow_folding_props_for_lift"] = "yes";
  EXPECT_THROW(ParseMission(bad, "q"), DataError);
}

// Propulsion groups: a folding propeller is refused only where it lifts (the lift group), never
// on a wing-borne pusher; and the objective range flies every group on its own parts.
TEST(CredibilityTest, FoldingIsRefusedOnTheLiftGroupOnly) {
  Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadplane_2kg.json");
  j["propulsion"]["pusher"]["prop"] = "dc_p_52";  // AeroCarbon 9x5, a folding propeller
  const Mission m = ParseMission(j, "quadplane");
  const Catalog& cat = Bundled();
  ASSERT_TRUE(cat.prop("dc_p_52").folding);
  auto flown = [&](const char* lift_prop) {
    Combination c{&cat.motor("dc_m_550"), &cat.esc("dc_e_145"), &cat.prop(lift_prop), &cat.battery("dc_b_361"), 4, {}};
    c.groups = {GroupParts{c.motor, c.esc, c.prop}, FixedGroupParts(m, cat, 1)};
    MissionResult r = MissionEvaluator(m, c).Solve();
    AddObjectiveRange(m, c, &r);
    return r;
  };
  auto names = [](const MissionResult& r, const char* constraint) {
    for (const Violation& v : r.violations) {
      if (v.constraint == constraint) return true;
    }
    return false;
  };
  // (It fails prop_no_forward_flight_data: DriveCalc's folding laws are static only.)
  const MissionResult pusher_folds = flown("uiuc_v2_gwsdd_9.0x5.0_2");
  EXPECT_FALSE(names(pusher_folds, "prop_folding")) << "a folding pusher is what folding props are for";
  EXPECT_TRUE(names(pusher_folds, "prop_no_forward_flight_data"));
  const MissionResult lift_folds = flown("dc_p_51");  // AeroCAM 9x5, folding
  EXPECT_FALSE(lift_folds.feasible);
  EXPECT_TRUE(names(lift_folds, "prop_folding"));
  // The example's own pusher (fixed, rated): feasible, and its range brackets the objective.
  const Mission ex = ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadplane_2kg.json");
  Combination c{&cat.motor("dc_m_550"), &cat.esc("dc_e_145"), &cat.prop("uiuc_v2_gwsdd_9.0x5.0_2"),
                &cat.battery("dc_b_361"), 4, {}};
  c.groups = {GroupParts{c.motor, c.esc, c.prop}, FixedGroupParts(ex, cat, 1)};
  MissionResult r = MissionEvaluator(ex, c).Solve();
  ASSERT_TRUE(r.feasible);
  AddObjectiveRange(ex, c, &r);
  ASSERT_TRUE(r.range.computed);
  EXPECT_LE(r.range.low, r.objective);
  EXPECT_GE(r.range.high, r.objective);
  EXPECT_LT(r.range.low, r.range.high);
}

}  // namespace
}  // namespace dynosize
