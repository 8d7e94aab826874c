// R7 and R6 as vehicle mass floors (optimization/mass_floors.h) on real catalog propellers: every
// vehicle lighter than the floor fails the rule in the evaluator itself, and a search whose
// fixed pusher cannot pass prop_figure_of_merit at any mass refuses every lift choice without a
// solve (the fixed groups' floor, SearchContext::fixed_mass_floor).
#include "optimization/mass_floors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "optimization/mission_eval.h"
#include "optimization/search.h"
#include "optimization/search_stages.h"
#include "solver_backends.h"

namespace dynosize {
namespace {

using search_internal::MassFloor;
using search_internal::SegmentMassFloorKg;

const Catalog& Bundled() {
  static const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  return cat;
}

// The bundled catalog without its high-voltage controllers (catalog/hv_controllers.json). The
// fixed groups' floor refuses a pair whose vehicle, with the heaviest ESC the pack option admits,
// is below the floor (pair_bounds.cc FixedMassFloorRule); a 2-11 kg automotive controller rated
// for 4S (Sevcon Gen4 24 V) lifts that bound above the floor of every mass the scan proves, so
// the pairs are refused later, by other rules, instead (still without a solve: the test below
// on the whole catalog).
const Catalog& WithoutHvControllers() {
  static const Catalog cat = [] {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "dynosize_mass_floors_catalog";
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const auto& e : fs::directory_iterator(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog")) {
      if (e.path().extension() == ".json" && e.path().filename() != "hv_controllers.json") {
        fs::copy_file(e.path(), dir / e.path().filename());
      }
    }
    return Catalog::Load(dir.string());
  }();
  return cat;
}

// The quadplane example (cruise at 18 m/s, L/D 10) with its lift group fixed to the both-free
// search's pick and the pusher to fu_m_166 + dc_e_138 on `pusher_prop`. The figure-of-merit
// limit in axial flow is held at the static 0.8: no measured sweep reaches the default 0.95
// (docs/model.md section 11), and the rules under test need a limit the propellers break.
Json QuadplaneJson(const std::string& pusher_prop) {
  Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadplane_2kg.json");
  j["constraints"]["max_axial_figure_of_merit"] = 0.8;
  j["propulsion"]["lift"]["motor"] = "dc_m_550";
  j["propulsion"]["lift"]["esc"] = "dc_e_145";
  j["propulsion"]["lift"]["prop"] = "uiuc_v2_gwsdd_9.0x5.0_2";
  j["propulsion"]["pusher"]["motor"] = "fu_m_166";
  j["propulsion"]["pusher"]["esc"] = "dc_e_138";
  j["propulsion"]["pusher"]["prop"] = pusher_prop;
  return j;
}

// Every group's parts as the mission names them, with a pack of `cells` cells `battery`.
Combination FixedCombination(const Mission& m, int cells = 4, const char* battery = "dc_b_361") {
  Combination c;
  c.battery = &Bundled().battery(battery);
  c.cells = cells;
  for (int g = 0; g < GroupCount(m); ++g) c.groups.push_back(FixedGroupParts(m, Bundled(), g));
  return c;
}

// Whether the evaluator finds the quadplane with `pusher_prop`, its vehicle made heavier so that
// the whole weighs total_kg, to break prop_figure_of_merit in its cruise (flown at airspeed_m_s,
// or the example's 18 m/s when 0).
bool CruiseFailsFigureOfMerit(const std::string& pusher_prop, double total_kg, double base_total_kg,
                              double airspeed_m_s = 0.0) {
  Json j = QuadplaneJson(pusher_prop);
  if (airspeed_m_s > 0) j["segments"][1]["airspeed_m_s"] = airspeed_m_s;
  j["vehicle"]["mass_kg"] = j["vehicle"]["mass_kg"].get<double>() + (total_kg - base_total_kg);
  const Mission m = ParseMission(j, "quadplane");
  const Combination c = FixedCombination(m);
  const MissionResult r = MissionEvaluator(m, c).Solve();
  // The evaluator's mass is the same sum of catalog masses: rounding only.
  constexpr double kMassRoundingKg = 1e-9;
  EXPECT_NEAR(r.total_mass_kg, total_kg, kMassRoundingKg);
  return std::any_of(r.violations.begin(), r.violations.end(), [](const Violation& v) {
    return v.constraint == "prop_figure_of_merit" && v.segment == "cruise";
  });
}

// Propellers of UIUC's forward-flight tables a 10 in pusher might fly: some pass the figure of
// merit limit at 18 m/s, some fail it from the lightest vehicle up.
const char* const kPusherProps[] = {"uiuc_v1_apcsf_9.0x6.0_2", "uiuc_v1_apcsf_8.0x6.0_2", "uiuc_v3_ancf_10.0x6.0_2",
                                    "uiuc_v1_ance_8.5x7.0_2",  "uiuc_v3_ancf_10.0x8.0_2", "uiuc_v2_gwsdd_9.0x5.0_2"};

// For each of kPusherProps: the cruise's floor from kStartKg with the cruise airspeed
// `airspeed` (a number or a [lo, hi] range); where there is one, the evaluator flies the vehicle
// at kSamples masses from kStartKg up to the floor (at most checked_up_to_kg), each at every
// airspeed of `flown_at` (0: the example's), and finds prop_figure_of_merit broken in the
// cruise every time. Both kinds of propeller must be among them: with a floor and without.
// The vehicle weighs at least 1.6 kg with any lift choice (the joint search's lightest, about
// 1.62-1.74 kg).
void ExpectEveryPointBelowTheFloorFails(const Json& airspeed, const std::vector<double>& flown_at,
                                        double checked_up_to_kg, int samples) {
  constexpr double kStartKg = 1.6;
  int with_floor = 0, without = 0;
  for (const char* id : kPusherProps) {
    Json j = QuadplaneJson(id);
    j["segments"][1]["airspeed_m_s"] = airspeed;
    const Mission m = ParseMission(j, "quadplane");
    const PropEntry& p = Bundled().prop(id);
    const PropModel model(p);
    const MassFloor f = SegmentMassFloorKg(m, m.segments[1], p, model, /*monotone=*/true, kStartKg);
    // No floor (0, or the scan's start: nothing proven above it).
    if (f.kg <= kStartKg) {
      EXPECT_TRUE(f.kg == 0.0 || f.kg == kStartKg) << id << ": a floor below the scan's start, " << f.kg;
      ++without;
      continue;
    }
    ++with_floor;
    EXPECT_STREQ(f.rule, "prop_figure_of_merit") << id;
    const Mission fixed = ParseMission(QuadplaneJson(id), "quadplane");
    const double base_total_kg = MissionEvaluator(fixed, FixedCombination(fixed)).Solve().total_mass_kg;
    const double top_kg = std::min(f.kg, checked_up_to_kg);
    for (int k = 0; k < samples; ++k) {
      const double kg = kStartKg + (top_kg - kStartKg) * k / samples;
      for (double v : flown_at) {
        EXPECT_TRUE(CruiseFailsFigureOfMerit(id, kg, base_total_kg, v))
            << id << " at " << kg << " kg, " << v << " m/s (floor " << f.kg << ")";
      }
    }
  }
  EXPECT_GE(with_floor, 1);
  EXPECT_GE(without, 1);
}

// At the example's 18 m/s, up to 3.8 kg (a vehicle twice the example's).
TEST(MassFloorsTest, EveryVehicleBelowTheFloorFailsTheRuleInTheEvaluator) {
  ExpectEveryPointBelowTheFloorFails(18.0, {0.0}, 3.8, 24);
}

// The same over a free cruise airspeed in [14, 20] m/s (APC SF 9x6 breaks the limit at every
// airspeed up to 20 m/s and meets it at 24): a point (mass, airspeed) below the floor fails the
// rule (each sampled mass at five airspeeds, flown as a fixed one by the evaluator).
TEST(MassFloorsTest, WithAFreeAirspeedEveryPointBelowTheFloorFailsTheRule) {
  ExpectEveryPointBelowTheFloorFails(Json::array({14.0, 20.0}), {14.0, 15.5, 17.0, 18.5, 20.0}, 3.2, 8);
}

TEST(MassFloorsTest, AFixedPusherFailingEveryMassIsRefusedWithoutASolve) {
  // APC SF 9x6 at 18 m/s: its figure of merit rises with the thrust and is above 0.8 from the
  // lightest vehicle up (the test above); every lift choice is refused by the floor, before
  // any solve (before the floor, the joint search spent a whole inner search budget on it).
  Json j = QuadplaneJson("uiuc_v1_apcsf_9.0x6.0_2");
  j["propulsion"]["lift"].erase("motor");
  j["propulsion"]["lift"].erase("esc");
  j["propulsion"]["lift"].erase("prop");
  const Mission m = ParseMission(j, "quadplane");
  SearchOptions o;
  o.top_n = 3;
  const SearchResult whole = SearchCatalog(m, Bundled(), o);
  EXPECT_TRUE(whole.best.empty());
  EXPECT_EQ(whole.searched, 0);
  EXPECT_EQ(whole.virtual_evaluations, 0);
  const SearchResult r = SearchCatalog(m, WithoutHvControllers(), o);
  EXPECT_TRUE(r.best.empty());
  EXPECT_EQ(r.searched, 0);
  EXPECT_EQ(r.virtual_evaluations, 0);
  ASSERT_TRUE(r.pruned_by.count("prop_figure_of_merit"));
  EXPECT_GT(r.pruned_by.at("prop_figure_of_merit"), 0);
  // The evaluator agrees on lift choices of every weight: the lightest and heaviest motors of the
  // catalog that the example's lift propeller can carry.
  for (const char* motor : {"dc_m_550", "dc_m_242", "fu_m_167"}) {
    Json e = QuadplaneJson("uiuc_v1_apcsf_9.0x6.0_2");
    e["propulsion"]["lift"]["motor"] = motor;
    const Mission me = ParseMission(e, "quadplane");
    const MissionResult res = MissionEvaluator(me, FixedCombination(me)).Solve();
    EXPECT_FALSE(res.feasible) << motor;
  }
}

// R3 over a free airspeed (FreeCruiseRangeRule, docs/search.md#g1-torque-floor): a fixed
// pusher whose motor cannot carry the cruise's torque floor anywhere in the range refuses every
// lift choice before any solve. fu_m_118 is a 1.2 g maxon EC 4 (0.47 A) on a GWS 9x7: the floor
// is about 0.05 N*m, some 60 A. The joint search used to take such pushers first (their bound is
// the lightest) and spent a whole inner search budget on each.
TEST(MassFloorsTest, AFixedPusherThatCannotCarryTheCruiseTorqueIsRefusedWithoutASolve) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("nlopt_cobyla");  // a free airspeed (mission_eval.h)
  Json j = QuadplaneJson("uiuc_v1_gwssf_9.0x7.0_2");
  j["propulsion"]["pusher"]["motor"] = "fu_m_118";
  j["segments"][1]["airspeed_m_s"] = Json::array({14.0, 24.0});
  Json free = j;
  free["propulsion"]["lift"].erase("motor");
  free["propulsion"]["lift"].erase("esc");
  free["propulsion"]["lift"].erase("prop");
  SearchOptions o;
  o.top_n = 3;
  const SearchResult r = SearchCatalog(ParseMission(free, "quadplane"), Bundled(), o);
  EXPECT_TRUE(r.best.empty());
  EXPECT_EQ(r.searched, 0);
  EXPECT_EQ(r.virtual_evaluations, 0);
  ASSERT_TRUE(r.pruned_by.count("motor_current"));
  EXPECT_GT(r.pruned_by.at("motor_current"), 0);
  // Refused by the pusher's rule, not one lift pair at a time by the power its bound reads
  // (without the rule every pair's bound failed reserve_soc, throttle or prop_above_data).
  for (const char* rule : {"reserve_soc", "throttle", "prop_above_data"}) EXPECT_EQ(r.pruned_by.count(rule), 0u) << rule;
  // The evaluator agrees at every airspeed of the range, flown as a fixed one.
  for (double v = 14.0; v <= 24.0 + 1e-9; v += 2.5) {
    Json e = j;
    e["segments"][1]["airspeed_m_s"] = v;
    const Mission m = ParseMission(e, "quadplane");
    const MissionResult res = MissionEvaluator(m, FixedCombination(m)).Solve();
    EXPECT_TRUE(std::any_of(res.violations.begin(), res.violations.end(), [](const Violation& x) {
      return x.constraint == "motor_current" && x.segment == "cruise";
    })) << v << " m/s";
  }
}

// The fixed groups' mass ceiling (SearchContext::fixed_mass_ceiling, docs/search.md#g1-torque-floor):
// the eVTOL example's cruise on a GWS 9x7 with dc_m_335 and an 18 A ESC (dc_e_14), its airspeed
// free in [14, 24] m/s. Every vehicle at or above the ceiling breaks, at every airspeed of the
// range flown as a fixed one, the speed, merit or drive limits the rule stands for; the lift
// choices that leave the vehicle there are refused before any solve.
TEST(MassFloorsTest, EveryVehicleAtOrAboveTheCeilingFailsTheCruiseInTheEvaluator) {
  Json j = ReadJsonFile(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/evtol_lift_cruise.json");
  j["propulsion"]["cruise"]["motor"] = "dc_m_335";
  j["propulsion"]["cruise"]["esc"] = "dc_e_14";
  j["propulsion"]["cruise"]["prop"] = "uiuc_v1_gwssf_9.0x7.0_2";
  j["segments"][2]["airspeed_m_s"] = Json::array({14.0, 24.0});
  Json free = j;
  free["battery"]["capacity_ah"] = Json::array({2.0, 8.0});
  free["propulsion"]["lift"].erase("motor");
  free["propulsion"]["lift"].erase("esc");
  free["propulsion"]["lift"].erase("prop");
  const Mission m = ParseMission(free, "evtol");
  search_internal::SearchContext ctx;
  search_internal::PrepareStages(m, Bundled(), &ctx);
  search_internal::FixedGroupPowerBounds(&ctx);
  // The packs of dc_b_361 and dc_b_363 leave no vehicle light enough (a floor beyond any);
  // with dc_b_313 the vehicle may weigh from 2.89 kg (the lightest lift choice) to the ceiling.
  ASSERT_EQ(ctx.options.size(), 3u);
  ASSERT_EQ(ctx.options[2].entry->id, "dc_b_313");
  const MassFloor ceiling = ctx.fixed_mass_ceiling[2];
  ASSERT_NE(ceiling.rule, nullptr);
  EXPECT_STREQ(ceiling.rule, "esc_current");
  // Measured: 3.53 kg (2.92 kg with the axial figure-of-merit limit at the static 0.8, whose
  // refusals at the low airspeeds lowered it), against 3.6 kg with the example's lift pick.
  EXPECT_GT(ceiling.kg, ctx.fixed_mass_floor[2].kg);
  EXPECT_LT(ceiling.kg, 3.6);
  // The example's lift pick (dc_m_334 + dc_e_145 + dc_p_318), the vehicle made lighter or
  // heavier so that the whole weighs total_kg.
  j["propulsion"]["lift"]["motor"] = "dc_m_334";
  j["propulsion"]["lift"]["esc"] = "dc_e_145";
  j["propulsion"]["lift"]["prop"] = "dc_p_318";
  const char* const limits[] = {"prop_figure_of_merit", "prop_max_rpm", "prop_above_data", "max_throttle",
                                "motor_current",        "motor_power",  "esc_current"};
  for (const double total_kg : {ceiling.kg, 1.1 * ceiling.kg, 1.5 * ceiling.kg}) {
    for (double v = 14.0; v <= 24.0 + 1e-9; v += 2.5) {
      Json e = j;
      e["segments"][2]["airspeed_m_s"] = v;
      const Mission base = ParseMission(e, "evtol");
      const double base_kg = MissionEvaluator(base, FixedCombination(base, 6, "dc_b_313")).Solve().total_mass_kg;
      e["vehicle"]["mass_kg"] = e["vehicle"]["mass_kg"].get<double>() + (total_kg - base_kg);
      const Mission me = ParseMission(e, "evtol");
      const MissionResult r = MissionEvaluator(me, FixedCombination(me, 6, "dc_b_313")).Solve();
      EXPECT_TRUE(std::any_of(r.violations.begin(), r.violations.end(), [&](const Violation& x) {
        return x.segment == "cruise" &&
               std::any_of(std::begin(limits), std::end(limits), [&](const char* l) { return x.constraint == l; });
      })) << total_kg << " kg at " << v << " m/s";
    }
  }
}

}  // namespace
}  // namespace dynosize
