// One combination flying a mission (optimization/mission_eval.h): the physical contract (a
// point that creates energy is never feasible), thrust-to-weight, winding temperature and the
// designer's summary, each checked against a hand calculation.
#include "optimization/mission_eval.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <filesystem>
#include <string>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "battery/battery.h"
#include "common/units.h"
#include "model/physics.h"
#include "prop/prop_model.h"
#include "optimization/search_stages.h"
#include "optimization/small_catalog.h"

namespace dynosize {
namespace {

namespace fs = std::filesystem;

const char* kHoverQuad = R"({
  "name": "eval quad",
  "vehicle": {"mass_kg": 0.75, "rotors": 4, "drag_area_m2": 0.04, "drag_coefficient": 1.0, "avionics_power_w": 5},
  "battery": {"id": "dc_b_361", "cells": 4, "reserve_soc": 0.2},
  "constraints": {"min_thrust_to_weight": 1.1, "allow_folding_props_for_lift": true},
  "objective": {"type": "max_endurance", "segment": "loiter", "ranking": "as_given"},
  "segments": [
    {"name": "takeoff", "type": "climb", "rate_m_s": 2, "distance_m": 30},
    {"name": "loiter", "type": "hover", "duration_s": 300},
    {"name": "landing", "type": "climb", "rate_m_s": -1, "distance_m": 30}
  ]
})";

// The small catalog's propellers are folding ones and its data are taken as given: these tests
// check the evaluator's physics and hand calculations, not the credibility rules
// (credibility_test.cc).
class MissionEvalTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = testing_util::WriteSmallCatalog("mission_eval"); }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static Catalog SmallCatalog() { return Catalog::Load((dir_ / "catalog").string()); }
  static Mission Quad() { return ParseMission(ParseJsonText(kHoverQuad, "quad"), "quad"); }
  static fs::path dir_;
};
fs::path MissionEvalTest::dir_;

bool Names(const MissionResult& r, const std::string& constraint) {
  for (const Violation& v : r.violations) {
    if (v.constraint == constraint) return true;
  }
  return false;
}

// Parameters that break docs/model.md section 10 would fly on free energy; the
// evaluator must call such a point infeasible ("creates_energy") and never rank it.
TEST_F(MissionEvalTest, APointThatCreatesEnergyIsNeverFeasible) {
  const Catalog cat = SmallCatalog();
  const Mission m = Quad();
  const Combination good{&cat.motor("dc_m_1020"), &cat.esc("dc_e_56"), &cat.prop("dc_p_173"), &cat.battery("dc_b_361"), 4, {}};
  const MissionResult base = MissionEvaluator(m, good).Solve();
  ASSERT_TRUE(base.feasible) << "the reference combination must fly";
  EXPECT_FALSE(Names(base, "creates_energy"));

  // ESC: C1 + C0 far below the ideal 1.1095 gives PDC < PAC (PESC < 0) at every point.
  EscEntry esc = cat.esc("dc_e_56");
  esc.params.c1 = 0.6;
  esc.params.c0 = 0.0;
  ASSERT_FALSE(EscEnergyViolation(esc.params).empty());
  Combination c = good;
  c.esc = &esc;
  const MissionResult r_esc = MissionEvaluator(m, c).Solve();
  EXPECT_FALSE(r_esc.feasible);
  EXPECT_TRUE(Names(r_esc, "creates_energy"));
  for (const Violation& v : r_esc.violations) {
    if (v.constraint == "creates_energy") {
      // The ESC's efficiency PAC/PDC: above 1, at most 1.1095/0.6 (eq 56's ideal ESC over
      // this one's C1; RESC only lowers PAC).
      EXPECT_GT(v.value, 1.0);
      EXPECT_LE(v.value, 1.1095 / 0.6);
    }
  }
  // It would otherwise look better than the real ESC: less power drawn for the same thrust.
  ContinuousVars v;
  v.airspeed_m_s.assign(m.segments.size(), 0.0);
  const MissionResult sim = MissionEvaluator(m, c).Simulate(v);
  EXPECT_LT(sim.segments[1].point.pdc_w, base.segments[1].point.pdc_w);
  EXPECT_FALSE(sim.feasible);

  // Motor: KT above sqrt(27/10)*KE makes eta_motor > 1 at light load.
  MotorEntry motor = cat.motor("dc_m_1020");
  motor.params.kt_nm_per_a = 1.5 * MaxKtPerKe(motor.params.type) * motor.params.ke_v_s_per_rad;
  motor.params.io_a = 0.0;
  ASSERT_FALSE(MotorEnergyViolation(motor.params).empty());
  c = good;
  c.motor = &motor;
  const MissionResult r_motor = MissionEvaluator(m, c).Solve();
  EXPECT_FALSE(r_motor.feasible);
  EXPECT_TRUE(Names(r_motor, "creates_energy"));
}

// Thrust-to-weight: the full-throttle thrust of the lift rotors at the mission's end, against a
// hand calculation without the pack's sag (an upper bound a few per cent above), and as a
// constraint just above and just below the value.
TEST_F(MissionEvalTest, ThrustToWeightAtFullThrottleOnTheLowestVoltage) {
  const Catalog cat = SmallCatalog();
  const Mission m = Quad();
  const Combination c{&cat.motor("dc_m_1020"), &cat.esc("dc_e_56"), &cat.prop("dc_p_173"), &cat.battery("dc_b_361"), 4, {}};
  const MissionResult r = MissionEvaluator(m, c).Solve();
  ASSERT_TRUE(r.feasible);
  ASSERT_EQ(r.lift_rotors, 4);
  ASSERT_GT(r.thrust_to_weight, 1.0);
  // By hand: OCV at the final SOC, full throttle, the speed where the motor's torque meets the
  // propeller's (bisection on a fine bracket), four rotors over the weight.
  const BatteryPack pack(PackFromEntry(*c.battery, 4, 1));
  const double v = pack.OcvV(r.final_soc);
  const Drive drive(c.motor->params, c.esc->params);
  const PropModel prop(*c.prop);
  // Held at the current rating when full throttle would exceed it.
  const double i_cap = std::min(c.motor->params.max_current_a, c.esc->params.max_current_a);
  double lo = 0, hi = drive.NoLoadSpeed(v, 1.0);
  for (int i = 0; i < 200; ++i) {
    const double w = 0.5 * (lo + hi);
    const double q = prop.Evaluate(w, m.rho_kg_m3, 0.0).torque_nm;
    const OperatingPoint p = drive.Inverse(v, q, w);
    const bool fits = drive.AtSpeed(v, 1.0, w).torque_nm > q && std::max(p.idc_a, p.irms_a) < i_cap;
    (fits ? lo : hi) = w;
  }
  const double tw_no_sag = 4 * prop.Evaluate(lo, m.rho_kg_m3, 0.0).thrust_n / (r.total_mass_kg * kStandardGravity);
  // The sag only lowers it (not at all when the motor's Irms rating holds it: then the torque,
  // and so the speed, is set by the current alone, eq 42); the bisection's 1e-9 covers rounding.
  EXPECT_LE(r.thrust_to_weight, tw_no_sag * (1 + 1e-9));
  EXPECT_GT(r.thrust_to_weight, 0.9 * tw_no_sag);   // a 4S pack of this size sags < 10 % at full power

  Json j = ParseJsonText(kHoverQuad, "quad");
  j["constraints"]["min_thrust_to_weight"] = r.thrust_to_weight * 1.05;
  const MissionResult tight = MissionEvaluator(ParseMission(j, "q"), c).Solve();
  EXPECT_TRUE(Names(tight, "min_thrust_to_weight"));
  // max_endurance: a shorter loiter leaves more charge, so the limit may still be met earlier.
  if (tight.feasible) { EXPECT_LT(tight.objective, r.objective); }
  j["constraints"]["min_thrust_to_weight"] = 50.0;
  const MissionResult never = MissionEvaluator(ParseMission(j, "q"), c).Solve();
  EXPECT_FALSE(never.feasible);
  EXPECT_TRUE(Names(never, "min_thrust_to_weight"));
}

// Winding temperature: the evaluator's closed form against a fixed-point iteration by hand, and
// the constraint.
TEST_F(MissionEvalTest, WindingTemperatureMatchesAHandCalculation) {
  const Catalog cat = SmallCatalog();
  const Mission m = Quad();
  const Combination c{&cat.motor("dc_m_1020"), &cat.esc("dc_e_56"), &cat.prop("dc_p_173"), &cat.battery("dc_b_361"), 4, {}};
  const MissionEvaluator ev(m, c);
  const MissionResult r = ev.Solve();
  ASSERT_TRUE(r.feasible);
  const OperatingPoint& p = r.segments[1].point;
  const MotorParams& mp = c.motor->params;
  const double kp = std::sqrt(27.0 / 10.0);
  const double rth = mp.rth_k_per_w > 0 ? mp.rth_k_per_w : AssumedMotorRthKPerW(*c.motor->mass_kg);
  const double p0 = p.pac_w - p.pmech_w - kp * mp.rm_ohm * p.irms_a * p.irms_a;
  double t = m.air_temperature_c;
  for (int i = 0; i < 200; ++i) {
    t = m.air_temperature_c + rth * (kp * mp.rm_ohm * (1 + 0.00393 * (t - 25.0)) * p.irms_a * p.irms_a + p0);
  }
  EXPECT_NEAR(ev.WindingTempC(p), t, 1e-9 * t);
  EXPECT_GE(r.segments[1].winding_temp_c, t - 1e-9 * t);  // the segment's hottest point
  EXPECT_GT(t, m.air_temperature_c);
  EXPECT_GE(r.summary.winding_temp_max_c, r.segments[1].winding_temp_c);
  // Assumed when the catalog has none: listed.
  if (!(mp.rth_k_per_w > 0)) {
    bool listed = false;
    for (const auto& a : r.assumed) listed |= a.find("rth_k_per_w") != std::string::npos;
    EXPECT_TRUE(listed);
  }
  Json j = ParseJsonText(kHoverQuad, "quad");
  j["constraints"]["max_winding_temp_c"] = std::max(20.0, 0.5 * (m.air_temperature_c + t));
  ASSERT_GT(t, 21.0) << "the limit must bind";
  const MissionResult hot = MissionEvaluator(ParseMission(j, "q"), c).Solve();
  EXPECT_FALSE(hot.feasible);
  EXPECT_TRUE(Names(hot, "max_winding_temp_c"));
}

// The designer's summary: the hover at half charge lies inside the loiter's throttle range
// (which runs from near full to the reserve), endurances by coulomb counting.
TEST_F(MissionEvalTest, SummaryAgreesWithTheMission) {
  const Catalog cat = SmallCatalog();
  const Mission m = Quad();
  const Combination c{&cat.motor("dc_m_1020"), &cat.esc("dc_e_56"), &cat.prop("dc_p_173"), &cat.battery("dc_b_361"), 4, {}};
  const MissionResult r = MissionEvaluator(m, c).Solve();
  ASSERT_TRUE(r.feasible);
  const DesignSummary& d = r.summary;
  ASSERT_TRUE(d.valid);
  const SegmentResult& loiter = r.segments[1];
  ASSERT_LT(loiter.soc_end, 0.5);
  ASSERT_GT(loiter.soc_start, 0.5);
  EXPECT_GE(d.hover_throttle, loiter.throttle_min);
  EXPECT_LE(d.hover_throttle, loiter.throttle_max);
  const double q_c = 3600.0 * r.capacity_ah * (1 - m.battery.reserve_soc);
  EXPECT_NEAR(d.hover_endurance_s, q_c / d.hover_battery_current_a, 1e-9 * d.hover_endurance_s);
  // The whole max_endurance mission is mostly loiter: its time is close to the hover endurance
  // (the climb and descent cost a little more, the sag is the same).
  EXPECT_NEAR(r.endurance_s, d.hover_endurance_s, 0.1 * d.hover_endurance_s);
  EXPECT_LT(d.full_throttle_endurance_s, d.hover_endurance_s);
  EXPECT_GT(d.full_throttle_thrust_n, r.total_mass_kg * kStandardGravity);
  EXPECT_GT(d.max_climb_rate_m_s, 0.0);
  // max_endurance ends at the reserve: the charge left is the reserve itself.
  EXPECT_NEAR(d.reserve_hover_s, 3600.0 * r.capacity_ah * r.final_soc / d.hover_battery_current_a, 1e-6 * d.reserve_hover_s);
}

// The max_endurance stretch ends on the limit that moves with it: of the checks from the
// stretch's second point on, the smallest slack is 0 to within the root finder's tolerance.
// Once with the reserve ending it; once with a throttle limit just below the hover's throttle
// at the reserve, so that the throttle (rising as the pack's voltage falls) ends it first.
// This combination's thrust-to-weight is held at the current rating: a limit that does not
// move with the stretch, with a slack that must not slow or mislead the root finder.
TEST_F(MissionEvalTest, TheStretchEndsOnTheLimitThatEndsIt) {
  // The stretch is found to 1e-6 of its length; a slack moves by about as much.
  constexpr double kSlackTolerance = 1e-5;
  const Catalog cat = SmallCatalog();
  const Combination c{&cat.motor("dc_m_1020"), &cat.esc("dc_e_56"), &cat.prop("dc_p_173"), &cat.battery("dc_b_361"), 4, {}};
  Json j = ParseJsonText(kHoverQuad, "quad");
  const MissionResult by_reserve = MissionEvaluator(ParseMission(j, "quad"), c).Solve();
  ASSERT_TRUE(by_reserve.feasible);
  EXPECT_STREQ(by_reserve.stretch_slacks.Worst(), "reserve_soc");
  EXPECT_GE(by_reserve.stretch_slacks.Of(nullptr), 0.0);
  EXPECT_LT(by_reserve.stretch_slacks.Of(nullptr), kSlackTolerance);
  const SegmentResult& loiter = by_reserve.segments[1];
  ASSERT_LT(loiter.throttle_min, loiter.throttle_max);
  j["constraints"]["max_throttle"] = 0.5 * (loiter.throttle_min + loiter.throttle_max);
  const MissionResult by_throttle = MissionEvaluator(ParseMission(j, "quad"), c).Solve();
  ASSERT_TRUE(by_throttle.feasible);
  EXPECT_STREQ(by_throttle.stretch_slacks.Worst(), "max_throttle");
  EXPECT_GE(by_throttle.stretch_slacks.Of(nullptr), 0.0);
  EXPECT_LT(by_throttle.stretch_slacks.Of(nullptr), kSlackTolerance);
  EXPECT_LT(by_throttle.endurance_s, by_reserve.endurance_s);
  EXPECT_GT(by_throttle.final_soc, by_reserve.final_soc);
}

// The 1-D search over a capacity range (grid, then Brent's method) finds the best capacity:
// no capacity of a fine scan, each flown with its own longest stretch, beats it.
TEST_F(MissionEvalTest, TheCapacitySearchFindsTheBestCapacity) {
  // Brent's method ends within 1e-6 of the range; the endurance is flat at an inner optimum
  // and moves ~1e-6 relative per 1e-6 of the range at a boundary one.
  constexpr double kRelativeTolerance = 1e-6;
  constexpr int kScan = 60;
  const Catalog cat = SmallCatalog();
  Json j = ParseJsonText(kHoverQuad, "quad");
  j["battery"]["capacity_ah"] = {1.0, 12.0};
  const Mission m = ParseMission(j, "quad");
  int checked = 0;
  for (const char* prop : {"dc_p_173", "dc_p_372"}) {
    const Combination c{&cat.motor("dc_m_1020"), &cat.esc("dc_e_56"), &cat.prop(prop), &cat.battery("dc_b_361"), 4, {}};
    const MissionEvaluator ev(m, c);
    const MissionResult best = ev.Solve();
    if (!best.feasible) continue;
    ++checked;
    for (int k = 0; k <= kScan; ++k) {
      ContinuousVars v;
      v.capacity_ah = 1.0 + 11.0 * k / kScan;
      const MissionResult r = ev.Simulate(v);
      if (r.feasible) {
        EXPECT_LE(r.endurance_s, best.endurance_s * (1 + kRelativeTolerance)) << prop << " at " << v.capacity_ah << " Ah";
      }
    }
  }
  EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// The quadplane example with its pick, flown with and without
// the stopped lift rotors' drag area. The cruise's thrust rises by exactly 1/2*rho*V^2*Cd*A
// (the pusher's thrust, what its propeller is solved for), and its shaft power and energy rise
// with it (the same pusher, more load). Uses the bundled catalog.
TEST(MissionEvalCruiseDragTest, TheQuadplaneCruiseCarriesTheStoppedRotorsDrag) {
  const std::string root = DYNOSIZE_SOURCE_DIR;
  const Catalog cat = Catalog::Load(root + "/catalog");
  Mission m = ReadMission(root + "/examples/missions/quadplane_2kg.json");
  int lift = 0, pusher = 0;
  for (int g = 0; g < GroupCount(m); ++g) (m.groups[g].name == "lift" ? lift : pusher) = g;
  std::size_t cruise = 0;
  while (m.segments[cruise].type != SegmentType::kCruise) ++cruise;
  Combination c;
  c.battery = &cat.battery("dc_b_361");
  c.cells = 4;
  c.groups.assign(2, GroupParts{});
  c.groups[lift] = GroupParts{&cat.motor("dc_m_550"), &cat.esc("dc_e_145"), &cat.prop("uiuc_v2_gwsdd_9.0x5.0_2")};
  c.groups[pusher] = GroupParts{&cat.motor(m.groups[pusher].motor_id), &cat.esc(m.groups[pusher].esc_id),
                                &cat.prop(m.groups[pusher].prop_id)};
  c.motor = c.groups[lift].motor;
  c.esc = c.groups[lift].esc;
  c.prop = c.groups[lift].prop;
  const double area = m.groups[lift].idle_drag_area_m2;
  ASSERT_GT(area, 0.0);
  const MissionResult with = MissionEvaluator(m, c).Solve();
  m.groups[lift].idle_drag_area_m2 = 0.0;
  const MissionResult without = MissionEvaluator(m, c).Solve();
  ASSERT_EQ(with.segments.size(), m.segments.size());
  ASSERT_EQ(without.segments.size(), m.segments.size());
  EXPECT_DOUBLE_EQ(with.total_mass_kg, without.total_mass_kg);
  const SegmentResult& a = with.segments[cruise];
  const SegmentResult& b = without.segments[cruise];
  const double v = m.segments[cruise].airspeed_m_s.lo;
  const double added = 0.5 * m.rho_kg_m3 * v * v * m.vehicle.drag_coefficient * area;
  EXPECT_NEAR(a.thrust_per_rotor_n - b.thrust_per_rotor_n, added, 1e-12 * a.thrust_per_rotor_n);
  // The propulsive power T*V rises by added*V; the shaft power by at least that (the
  // propeller's efficiency is below 1).
  EXPECT_GT(a.point.pmech_w - b.point.pmech_w, added * v);
  EXPECT_GT(with.energy_wh, without.energy_wh);
}

// The figure-of-merit limit by inflow (mission.h, docs/model.md section 11). The quadplane's
// pusher on UIUC's measured APC 8.5x7 sweeps at 14 m/s reaches an axial-flow figure of merit
// between the static limit 0.8 and the axial one 0.95: the default passes it, the axial limit
// held at 0.8 refuses it in the cruise; the hover (at rest) is judged by the static limit
// whatever the axial one is.
TEST(MissionEvalCruiseDragTest, CruiseIsJudgedByTheAxialFigureOfMeritLimitAndHoverByTheStaticOne) {
  const std::string root = DYNOSIZE_SOURCE_DIR;
  const Catalog cat = Catalog::Load(root + "/catalog");
  Json j = ReadJsonFile(root + "/examples/missions/quadplane_2kg.json");
  j["propulsion"]["lift"]["motor"] = "dc_m_550";
  j["propulsion"]["lift"]["esc"] = "dc_e_145";
  j["propulsion"]["lift"]["prop"] = "uiuc_v2_gwsdd_9.0x5.0_2";
  j["propulsion"]["pusher"]["motor"] = "fu_m_166";
  j["propulsion"]["pusher"]["esc"] = "dc_e_56";
  j["propulsion"]["pusher"]["prop"] = "uiuc_v1_ance_8.5x7.0_2";
  j["segments"][1]["airspeed_m_s"] = 14.0;
  auto fly = [&](double static_limit, double axial_limit) {
    Json e = j;
    e["constraints"]["max_figure_of_merit"] = static_limit;
    e["constraints"]["max_axial_figure_of_merit"] = axial_limit;
    const Mission m = ParseMission(e, "quadplane");
    Combination c;
    c.battery = &cat.battery("dc_b_361");
    c.cells = 4;
    for (int g = 0; g < GroupCount(m); ++g) c.groups.push_back(FixedGroupParts(m, cat, g));
    return MissionEvaluator(m, c).Solve();
  };
  auto fails_in = [](const MissionResult& r, const std::string& segment) {
    for (const Violation& v : r.violations) {
      if (v.constraint == "prop_figure_of_merit" && v.segment == segment) return true;
    }
    return false;
  };
  const MissionResult by_default = fly(0.8, 0.95);
  ASSERT_EQ(by_default.segments.size(), 4u);
  ASSERT_EQ(by_default.segments[1].name, "cruise");
  ASSERT_EQ(by_default.segments[2].name, "hover_check");
  // The pusher's figure of merit as its data give it at the cruise's point (direct drive).
  const PropEntry& pusher = cat.prop("uiuc_v1_ance_8.5x7.0_2");
  ASSERT_EQ(cat.motor("fu_m_166").gear.ratio, 1.0);
  const SegmentResult& cruise = by_default.segments[1];
  const double rho = ParseMission(j, "quadplane").rho_kg_m3, v = 14.0;
  const PropEvaluation ev = PropModel(pusher).Evaluate(cruise.point.omega_rad_s, rho, v);
  const double fom = FigureOfMerit(ev.thrust_n, ev.power_w, pusher.diameter_m, rho, v);
  EXPECT_GT(fom, 0.8);
  EXPECT_LT(fom, 0.95);
  EXPECT_FALSE(fails_in(by_default, "cruise"));
  EXPECT_TRUE(fails_in(fly(0.8, 0.8), "cruise"));
  // The lift rotors at rest (the hover, and the landing: a descent's inflow is taken as 0): a
  // static limit below what they reach fails them, however high the axial one. The result
  // keeps the worst violation per constraint, in one of those segments.
  EXPECT_FALSE(fails_in(by_default, "hover_check") || fails_in(by_default, "landing"));
  const MissionResult low = fly(0.3, 0.95);
  EXPECT_TRUE(fails_in(low, "hover_check") || fails_in(low, "landing"));
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// A geared motor of the small catalog (dc_m_1600, Hacker A20
// with a 4:1 gearbox of efficiency 0.975) hovers with its propeller turning at the propeller's
// own speed (its data give the hover thrust there), the motor at 4 x that speed, and the gear
// loss is in the energy: the same combination with a loss-free gearbox (efficiency 1) draws
// less, by at least the gear loss (same propeller point, the motor's torque 1/eta higher).
TEST_F(MissionEvalTest, AGearedMotorTurnsThePropellerAtItsOwnSpeedAndPaysTheGearLoss) {
  const Catalog cat = SmallCatalog();
  const Mission m = Quad();
  const MotorEntry& geared = cat.motor("dc_m_1600");
  ASSERT_GT(geared.gear.ratio, 1.0);
  ASSERT_LT(geared.gear.efficiency, 1.0);
  MotorEntry lossless = geared;
  lossless.gear.efficiency = 1.0;
  int checked = 0;
  for (const EscEntry& e : cat.escs()) {
    for (const PropEntry& p : cat.props()) {
      Combination c{&geared, &e, &p, &cat.battery("dc_b_361"), 4, {}};
      const MissionResult r = MissionEvaluator(m, c).Solve();
      if (r.segments.size() != m.segments.size() || !r.feasible) continue;
      const SegmentResult& hover = r.segments[1];
      ASSERT_EQ(hover.type, SegmentType::kHover);
      // The propeller's own speed: its data give the hover thrust at the point's speed.
      const PropEvaluation ev = PropModel(p).Evaluate(hover.point.omega_rad_s, m.rho_kg_m3, 0.0);
      EXPECT_NEAR(ev.thrust_n, hover.thrust_per_rotor_n, 1e-6 * hover.thrust_per_rotor_n) << p.id;
      // The motor turns 4x faster against Q/(N*eta): the electrical point is the motor's own.
      const MotorShaft shaft = MotorShaftOf(hover.point.omega_rad_s, hover.point.torque_nm, geared.gear);
      const OperatingPoint at_motor = Drive(geared.params, e.params).Inverse(hover.point.vdc_v, shaft.torque_nm, shaft.omega_rad_s);
      EXPECT_NEAR(at_motor.pdc_w, hover.point.pdc_w, 1e-9 * hover.point.pdc_w) << p.id;
      // The gear loss in the energy.
      Combination c1 = c;
      c1.motor = &lossless;
      const MissionResult r1 = MissionEvaluator(m, c1).Solve();
      ASSERT_EQ(r1.segments.size(), m.segments.size());
      const SegmentResult& h1 = r1.segments[1];
      EXPECT_GT(r1.objective, r.objective) << p.id << ": max endurance is longer without the gear loss";
      EXPECT_GT(shaft.gear_loss_w, 0.0);
      EXPECT_NEAR(h1.point.omega_rad_s, hover.point.omega_rad_s, 1e-3 * hover.point.omega_rad_s) << p.id;
      // 0.9: the two end points sit at slightly different pack voltages (the lossless run has
      // drawn less), which moves PDC by a little at the same shaft point.
      EXPECT_GE(hover.point.pdc_w - h1.point.pdc_w, 0.9 * shaft.gear_loss_w) << p.id;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0) << "the geared motor must hover with some ESC and propeller of the small catalog";
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// The quadplane example (its pusher fixed) with a capacity range and a cruise airspeed range, and
// its combination with the lift drive dc_m_550 + `esc` + GWS 9x5 on a 4S dc_b_361 pack (the
// bundled catalog).
struct QuadplaneWithRanges {
  Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  Mission m;
  int lift = 0, pusher = 0;
  QuadplaneWithRanges(double capacity_hi_ah, double airspeed_lo_m_s, double airspeed_hi_m_s) {
    Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadplane_2kg.json");
    j["battery"]["capacity_ah"] = {2.0, capacity_hi_ah};
    for (Json& s : j["segments"]) {
      if (s["type"] == "cruise") s["airspeed_m_s"] = {airspeed_lo_m_s, airspeed_hi_m_s};
    }
    m = ParseMission(j, "quadplane with ranges");
    for (int g = 0; g < GroupCount(m); ++g) (m.groups[g].name == "lift" ? lift : pusher) = g;
  }
  Combination With(const char* esc) const {
    Combination c;
    c.battery = &cat.battery("dc_b_361");
    c.cells = 4;
    c.groups.assign(2, GroupParts{});
    c.groups[lift] = GroupParts{&cat.motor("dc_m_550"), &cat.esc(esc), &cat.prop("uiuc_v2_gwsdd_9.0x5.0_2")};
    c.groups[pusher] = GroupParts{&cat.motor(m.groups[pusher].motor_id), &cat.esc(m.groups[pusher].esc_id),
                                  &cat.prop(m.groups[pusher].prop_id)};
    c.motor = c.groups[lift].motor;
    c.esc = c.groups[lift].esc;
    c.prop = c.groups[lift].prop;
    return c;
  }
};

// Two free variables (the capacity and the cruise airspeed) with the optimum on a feasibility
// boundary: the quadplane example's lift drive of its first design with a capacity range and an
// airspeed range (bundled catalog). With ESC dc_e_22 COBYLA ended 8.8e-7 outside a constraint
// and the evaluator fell back to its coarse grid's start, 32.16 Wh at 3.5 Ah, above the 30.90 Wh
// of dc_e_21, an ESC dc_e_22 dominates (R5: it may score no better). The last feasible point
// towards COBYLA's answer keeps the order R5 relies on.
TEST(MissionEvalManyFreeTest, AnOptimumOnAFeasibilityBoundaryIsKeptAndDominanceHolds) {
  const QuadplaneWithRanges q(8.0, 14.0, 24.0);
  const Catalog& cat = q.cat;
  auto solve = [&](const char* esc) { return MissionEvaluator(q.m, q.With(esc)).Solve(); };
  ASSERT_TRUE(search_internal::EscDominates(cat.esc("dc_e_22"), cat.esc("dc_e_21")));
  const MissionResult dominated = solve("dc_e_21");
  const MissionResult dominating = solve("dc_e_22");
  ASSERT_TRUE(dominated.feasible);
  ASSERT_TRUE(dominating.feasible);
  EXPECT_LE(dominating.score, dominated.score);
  // Both end on the boundary near the smallest feasible pack, not on the grid's 3.5 Ah.
  EXPECT_LT(dominating.capacity_ah, 3.0);
}

// A feasible corner the 5 x 5 grid misses: the quadplane example's pusher, capacity [2, 10] Ah,
// airspeed [12, 26] m/s, lift dc_m_550 + GWS 9x5. With these ESCs no grid point is feasible and
// COBYLA, started outside, ended 1.1e-6 outside a constraint (fu_e_60: reported infeasible,
// though it flies near 3 Ah and 12 m/s), at its iteration limit (dc_e_113: 34.60 Wh at 3.67 Ah)
// or at a local answer (dc_e_2: 34.20 Wh at 12.8 m/s), each above a dense grid's best (41 x 29
// points: 33.74, 33.56, 34.05 Wh). The 1-D searches along each variable from COBYLA's answer
// find each feasible, at or below the dense grid's best.
TEST(MissionEvalManyFreeTest, AFeasibleCornerTheGridMissesIsFound) {
  const QuadplaneWithRanges q(10.0, 12.0, 26.0);
  const Mission& m = q.m;
  for (const char* esc : {"fu_e_60", "dc_e_113", "dc_e_2"}) {
    SCOPED_TRACE(esc);
    const Combination c = q.With(esc);
    const MissionResult r = MissionEvaluator(m, c).Solve();
    double dense_best = std::numeric_limits<double>::infinity();
    for (int a = 0; a <= 40; ++a) {
      for (int b = 0; b <= 28; ++b) {
        Mission f = m;
        const double cap = 2.0 + 8.0 * a / 40, v = 12.0 + 14.0 * b / 28;
        f.battery.capacity_ah = Range{cap, cap};
        for (Segment& s : f.segments) {
          if (s.type == SegmentType::kCruise) s.airspeed_m_s = Range{v, v};
        }
        const MissionResult g = MissionEvaluator(f, c).Solve();
        if (g.feasible) dense_best = std::min(dense_best, g.score);
      }
    }
    ASSERT_TRUE(std::isfinite(dense_best)) << "the dense grid flies it";
    ASSERT_TRUE(r.feasible) << r.solver;
    // The solver's tolerance, 1e-6 of the range, against a grid of 0.2 Ah and 0.5 m/s steps.
    EXPECT_LE(r.score, dense_best * (1 + 1e-6)) << r.solver;
  }
}

}  // namespace
}  // namespace dynosize
