// Trust tiers, the measured-propeller envelope, the data scenarios, folding propellers, the
// rating of unrated motors and the objective range (optimization/credibility.h).
#include "optimization/credibility.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <string>

#include "catalog/catalog.h"
#include "cli_runner.h"
#include "common/error.h"
#include "common/json_file.h"
#include "common/units.h"
#include "model/physics.h"
#include "optimization/mission_eval.h"
#include "optimization/search.h"
#include "prop/prop_model.h"

namespace dynosize {
namespace {

const Catalog& Bundled() {
  static const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  return cat;
}

// The example quadcopter with its pick before this change (issue 13: a folding glider prop
// whose DriveCalc power law promises FM 0.79 in hover).
Mission QuadMission(bool allow_folding, const char* ranking = "credible") {
  Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
  j["constraints"]["allow_folding_props_for_lift"] = allow_folding;
  j["objective"]["ranking"] = ranking;
  return ParseMission(j, "quad");
}

Combination OldQuadPick() {
  const Catalog& c = Bundled();
  return Combination{&c.motor("dc_m_56"), &c.esc("dc_e_142"), &c.prop("dc_p_127"), &c.battery("dc_b_363"), 4};
}

TEST(CredibilityTest, FmClassesAreThoseOfTheBundledUiucCatalog) {
  const std::vector<FmClass> computed = ComputePropFmClasses(Bundled().props());
  const std::vector<FmClass>& stated = PropFmClasses();
  ASSERT_EQ(computed.size(), stated.size());
  int total = 0;
  for (std::size_t i = 0; i < stated.size(); ++i) {
    EXPECT_EQ(computed[i].n, stated[i].n) << stated[i].label;
    // The constants are printed to 4 decimals.
    constexpr double kRounding = 5e-5;
    EXPECT_NEAR(computed[i].p10, stated[i].p10, kRounding) << stated[i].label;
    EXPECT_NEAR(computed[i].p50, stated[i].p50, kRounding) << stated[i].label;
    EXPECT_NEAR(computed[i].p90, stated[i].p90, kRounding) << stated[i].label;
    EXPECT_LT(stated[i].p10, stated[i].p50);
    EXPECT_LT(stated[i].p50, stated[i].p90);
    EXPECT_LE(stated[i].p90, 0.753) << "the largest median FM UIUC measured (model.md section 10)";
    total += stated[i].n;
  }
  EXPECT_EQ(total, 239) << "UIUC's measured static tables (model.md section 10)";
  EXPECT_STREQ(PropFmClassOf(0.3175).label, "12 in and over");
  EXPECT_STREQ(PropFmClassOf(0.254).label, "10-12 in");
}

// Measured over computed FM of the same APC products: UIUC "apcsf D.DxP.P" / "apce ..." (2
// blades) against APC PER3 "APC DxPSF" / "APC DxPE" of the bundled catalog.
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
    for (auto it = range.first; it != range.second; ++it) ratios.push_back(it->second / MedianStaticFigureOfMerit(p));
  }
  ASSERT_EQ(static_cast<int>(ratios.size()), kComputedFmRatio.pairs);
  std::sort(ratios.begin(), ratios.end());
  constexpr double kRounding = 5e-5;  // printed to 4 decimals
  EXPECT_NEAR(ratios.front(), kComputedFmRatio.min, kRounding);
  EXPECT_NEAR(ratios[ratios.size() / 2], kComputedFmRatio.median, kRounding);
  EXPECT_NEAR(ratios.back(), kComputedFmRatio.max, kRounding);
  EXPECT_LT(ratios.back(), 1.0) << "APC's computed data are optimistic for every product UIUC measured";
}

TEST(CredibilityTest, TiersFollowTheSourceLabels) {
  const Catalog& c = Bundled();
  std::string why;
  EXPECT_EQ(EntryTier(c.prop("uiuc_v1_apcsf_10.0x4.7_2"), ComponentKind::kProp), SourceTier::kMeasured);
  EXPECT_EQ(EntryTier(c.prop("apc_per3_10x45mr"), ComponentKind::kProp), SourceTier::kManufacturerComputed);
  EXPECT_EQ(EntryTier(c.prop("fu_p_apc_4.1x4.1e"), ComponentKind::kProp), SourceTier::kManufacturerComputed);
  EXPECT_EQ(EntryTier(c.prop("dc_p_127"), ComponentKind::kProp), SourceTier::kUserContributed);
  EXPECT_EQ(EntryTier(c.motor("dc_m_56"), ComponentKind::kMotor), SourceTier::kUserContributed);
  EXPECT_EQ(EntryTier(c.motor("dc_m_2_fit"), ComponentKind::kMotor), SourceTier::kMeasured);
  EXPECT_EQ(EntryTier(c.motor("fu_m_1"), ComponentKind::kMotor), SourceTier::kManufacturerStated);
  EXPECT_EQ(EntryTier(c.esc("dc_e_142"), ComponentKind::kEsc, &why), SourceTier::kAssumed);
  EXPECT_TRUE(why == "c1" || why == "c0") << why;  // the ESC prior's ideal constants
  SourceTier t;
  EXPECT_TRUE(LabelTier("fitted", "DriveCalc MData drivecalc_fitted.json", &t));
  EXPECT_EQ(t, SourceTier::kMeasured);
  EXPECT_TRUE(LabelTier("fitted", "sjkim-snu/propulsion_analysis motor tables sjkim_mfr_tables.json", &t));
  EXPECT_EQ(t, SourceTier::kManufacturerStated);
  // A T-Motor table fit: Rm fitted to the manufacturer's table, Io assumed: the worst counts.
  for (const MotorEntry& m : c.motors()) {
    if (m.file.find("sjkim_mfr_tables") == std::string::npos) continue;
    EXPECT_EQ(EntryTier(m, ComponentKind::kMotor, &why), SourceTier::kAssumed) << m.id;
    EXPECT_EQ(why, "io_a");
  }
  EXPECT_TRUE(LabelTier("fitted", "dronebuildcalc manufacturer tables", &t));
  EXPECT_EQ(t, SourceTier::kManufacturerStated);
  EXPECT_FALSE(LabelTier("derived", "x", &t));
  // No labels and an unknown data set: unknown provenance is assumed.
  MotorEntry bare;
  bare.json = Json::object();
  bare.json["source"] = {{"dataset", "my notes"}};
  EXPECT_EQ(EntryTier(bare, ComponentKind::kMotor), SourceTier::kAssumed);
}

TEST(CredibilityTest, CredibleFigureOfMeritIsTheClassMedianForUserData) {
  const PropEntry& p = Bundled().prop("dc_p_127");  // DriveCalc law, FM 0.79 in hover
  const PropModel model(p);
  const FmClass& k = PropFmClassOf(p.diameter_m);
  const double rho = 1.225, omega = RpmToRadPerSec(3400);
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
  // Forward-flight tables are used as given; static-only data in flow are adjusted.
  const PropEntry& apc = Bundled().prop("apc_per3_10x45mr");
  const PropEvaluation fwd = PropModel(apc).Evaluate(omega, rho, 8.0);
  PropEvaluation f2 = fwd;
  AdjustPropEvaluation(PropAdjustmentFor(apc, DataScenario::kPessimistic), apc.diameter_m, &f2);
  EXPECT_EQ(f2.power_w, fwd.power_w);
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
    if (EntryTier(p, ComponentKind::kProp) != SourceTier::kUserContributed || !p.power_law) continue;
    const PropEvaluation ev = PropModel(p).Evaluate(RpmToRadPerSec(4000), 1.225, 0.0);
    const double fm = FigureOfMerit(ev.thrust_n, ev.power_w, p.diameter_m, 1.225);
    if (fm >= 0.9 * PropFmClassOf(p.diameter_m).p10) continue;
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

TEST(CredibilityTest, FoldingPropellersByName) {
  auto named = [](const char* name) {
    PropEntry p;
    p.name = name;
    return IsFoldingProp(p);
  };
  EXPECT_TRUE(named("AeroCarbon 12.5x10.0"));
  EXPECT_TRUE(named("AeroCAM 12.0x8.0"));
  EXPECT_TRUE(named("Graupner CAM 12.0x7.0"));
  EXPECT_TRUE(named("Aero-Cam PP 14.0x8.0"));
  EXPECT_TRUE(named("Jamara Folding 6.0x4.0"));
  EXPECT_TRUE(named("CFK Folder 17.0x10.0"));
  EXPECT_TRUE(named("UIUC vol 3 ancf 12.5x9.0 (2 blades)"));
  EXPECT_FALSE(named("GrpCamSpeed 4.7x4.7"));
  EXPECT_FALSE(named("APC 10x4.5MR (PER3, computed)"));
  EXPECT_FALSE(named("UIUC vol 1 apcsf 10.0x4.7 (2 blades)"));
  EXPECT_FALSE(named("Zagi Carbon 5.1x4.9"));
  int n = 0;
  for (const PropEntry& p : Bundled().props()) n += IsFoldingProp(p);
  EXPECT_GT(n, 60);  // DriveCalc's Aeronaut/Graupner CAM families and UIUC's ancf set
  EXPECT_LT(n, 200);
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

// The rating laws are the FAST-UAV catalogue's: ln(I_max*V_nominal) on ln(m), and ln(I_max) on
// ln(m) and ln(Kv), least squares (3x3 normal equations of well-scaled logs: fine here).
TEST(CredibilityTest, UnratedMotorLawsAreTheFastUavFits) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  double a[3][4] = {};
  int n = 0;
  for (const MotorEntry& m : Bundled().motors()) {
    if (m.id.rfind("fu_m_", 0) != 0 || !m.mass_kg || !m.kv_rpm_per_v || !std::isfinite(m.params.max_current_a)) continue;
    if (!m.json.contains("vdc_nominal_v")) continue;
    const double x = std::log(*m.mass_kg), y = std::log(m.params.max_current_a * m.json.at("vdc_nominal_v").get<double>());
    sx += x; sy += y; sxx += x * x; sxy += x * y;
    const double row[3] = {1.0, x, std::log(*m.kv_rpm_per_v)};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) a[i][j] += row[i] * row[j];
      a[i][3] += row[i] * std::log(m.params.max_current_a);
    }
    ++n;
  }
  ASSERT_EQ(n, 204);
  const double b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double p1 = std::exp((sy - b * sx) / n);
  // Printed to 4 and 3 significant digits.
  EXPECT_NEAR(EstimatedMotorPowerW(1.0), p1, 0.5);
  EXPECT_NEAR(std::log(EstimatedMotorPowerW(0.1) / EstimatedMotorPowerW(1.0)) / std::log(0.1), b, 5e-4);
  for (int i = 0; i < 3; ++i) {  // Gauss-Jordan with partial pivoting
    int piv = i;
    for (int r = i + 1; r < 3; ++r) if (std::fabs(a[r][i]) > std::fabs(a[piv][i])) piv = r;
    for (int k = 0; k < 4; ++k) std::swap(a[i][k], a[piv][k]);
    for (int r = 0; r < 3; ++r) {
      if (r == i) continue;
      const double f = a[r][i] / a[i][i];
      for (int k = 0; k < 4; ++k) a[r][k] -= f * a[i][k];
    }
  }
  const double c0 = std::exp(a[0][3] / a[0][0]), c1 = a[1][3] / a[1][1], c2 = a[2][3] / a[2][2];
  EXPECT_NEAR(EstimatedMotorCurrentA(1.0, 1.0), c0, 5e-4);
  EXPECT_NEAR(std::log(EstimatedMotorCurrentA(0.1, 1.0) / EstimatedMotorCurrentA(1.0, 1.0)) / std::log(0.1), c1, 5e-4);
  EXPECT_NEAR(std::log(EstimatedMotorCurrentA(1.0, 10.0) / EstimatedMotorCurrentA(1.0, 1.0)) / std::log(10.0), c2, 5e-4);
  // Issue 13: the unrated 40 g Python 80 (1964 Kv) flew at 42-52 A rms; the law rates it near 14 A.
  EXPECT_NEAR(EstimatedMotorCurrentA(0.04, 1963.91), 14.3, 0.1);
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
  EXPECT_DOUBLE_EQ(p.max_power_w, EstimatedMotorPowerW(*motor.mass_kg));
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

// Parameters that create energy (model.md section 10) never give a feasible result.
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

TEST(CredibilityTest, ObjectiveRangeBracketsTheCredibleValue) {
  const Mission m = QuadMission(true);
  const Combination c = OldQuadPick();
  MissionResult r = MissionEvaluator(m, c).Solve();
  ASSERT_TRUE(r.feasible);
  AddObjectiveRange(m, c, &r);
  const ObjectiveRange& g = r.range;
  ASSERT_TRUE(g.computed);
  EXPECT_LE(g.low, r.objective);
  EXPECT_GE(g.high, r.objective);
  EXPECT_LT(g.low, g.high);
  EXPECT_TRUE(g.complete);
  // FM at the class p10 with the motor's Io and Rm 1.6x (user tier) needs more current than
  // the motor's rating: the low end says so, and is still a number.
  EXPECT_NE(g.low_breaks.find("motor_current"), std::string::npos) << g.low_breaks;
  EXPECT_LT(g.low, 0.9 * r.objective);
  // The DriveCalc law's FM 0.79 is held to the class median: the credible endurance is well
  // below the data's own (issue 13: 32.6 min as given; about 24 min with a measured prop).
  EXPECT_TRUE(g.as_given_feasible);
  EXPECT_LT(r.objective, 0.85 * g.as_given);
  EXPECT_LT(g.high, g.as_given) << "even the optimistic end holds the law to the class p90";
  ASSERT_EQ(g.tiers.size(), 4u);
  EXPECT_EQ(g.tiers[2].tier, SourceTier::kUserContributed);
  EXPECT_EQ(g.motor_rating, "catalog");
  // The hover point flies at the class median's figure of merit.
  const FmClass& k = PropFmClassOf(c.prop->diameter_m);
  for (const SegmentResult& s : r.segments) {
    if (s.type != SegmentType::kHover) continue;
    const double fm = FigureOfMerit(s.thrust_per_rotor_n, s.point.pmech_w, c.prop->diameter_m, m.rho_kg_m3);
    EXPECT_NEAR(fm, k.p50, 1e-6) << s.name;
  }
  // Ranked as given, the objective is the data's own and the range is the same.
  const Mission mg = QuadMission(true, "as_given");
  MissionResult rg = MissionEvaluator(mg, c).Solve();
  AddObjectiveRange(mg, c, &rg);
  EXPECT_NEAR(rg.objective, g.as_given, 1e-9 * g.as_given);
  EXPECT_NEAR(rg.range.low, g.low, 1e-6 * g.low);
  EXPECT_GE(rg.range.high, rg.objective) << "the range brackets the data's own value then";
}

// `evaluate --json` carries the range, the ranking, the tiers and the motor rating; the text
// says the same in words.
TEST(CredibilityTest, EvaluateReportsRangeAndTiers) {
  const std::string quad = std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json";
  const std::string args = "evaluate " + quad + " --motor dc_m_56 --esc dc_e_142 --prop dc_p_231 --battery dc_b_363 --cells 4";
  const auto js = testing_util::RunCli(args + " --json");
  ASSERT_EQ(js.code, 0) << js.err;
  const Json j = Json::parse(js.out);
  EXPECT_EQ(j.at("ranking"), "credible");
  ASSERT_EQ(j.at("objective_range").size(), 2u);
  EXPECT_LE(j.at("objective_range")[0].get<double>(), j.at("objective").get<double>());
  EXPECT_GE(j.at("objective_range")[1].get<double>(), j.at("objective").get<double>());
  EXPECT_GT(j.at("objective_as_given").get<double>(), j.at("objective").get<double>());
  EXPECT_EQ(j.at("tiers").at("propeller").at("tier"), "user_contributed");
  EXPECT_EQ(j.at("tiers").at("ESC").at("tier"), "assumed");
  EXPECT_EQ(j.at("motor_rating"), "catalog");
  EXPECT_NEAR(j.at("segments")[2].at("figure_of_merit").get<double>(), PropFmClassOf(0.3048).p50, 1e-9);
  const auto txt = testing_util::RunCli(args);
  ASSERT_EQ(txt.code, 0) << txt.err;
  EXPECT_NE(txt.out.find("with the spread of the data"), std::string::npos) << txt.out;
  EXPECT_NE(txt.out.find("data tiers: motor user_contributed"), std::string::npos) << txt.out;
}

// The goal of issue 13 on the example quadcopter (about 3 s of CPU on the bundled catalog):
// the pick hovers at a figure of merit measured props support, no point creates energy, the
// result has its range, and no folding propeller lifts it.
TEST(CredibilityTest, ExampleQuadPickIsCredible) {
  const Mission m = ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
  SearchOptions so;
  so.top_n = 1;
  const SearchResult s = SearchCatalog(m, Bundled(), so);
  ASSERT_EQ(s.best.size(), 1u);
  const Combination& c = s.best[0].combination;
  const MissionResult& r = s.best[0].result;
  EXPECT_FALSE(IsFoldingProp(*c.prop)) << c.prop->name;
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

}  // namespace
}  // namespace dynosize
