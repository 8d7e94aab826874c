// The catalog search against exhaustive evaluation on a small catalog, the per-segment optimum
// against a dense grid, infeasible missions, and every printed point reproduced by `simulate`.
#include "optimization/search.h"
#include "optimization/joint_search.h"
#include "optimization/search_stages.h"

#include <initializer_list>

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "catalog/catalog.h"
#include "cli_runner.h"
#include "common/error.h"
#include "common/json_file.h"
#include "mission/flight.h"
#include "optimization/mission_eval.h"
#include "optimization/small_catalog.h"
#include "solver_backends.h"

namespace dynosize {
namespace {

namespace fs = std::filesystem;
using testing_util::ForEachCombination;
using testing_util::kQuad;

class SearchTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = testing_util::WriteSmallCatalog("search");
    std::ofstream(dir_ / "quad.json") << kQuad;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
};
fs::path SearchTest::dir_;

const char* kLiftCruise = R"({
  "name": "test lift + cruise",
  "vehicle": {"mass_kg": 0.6, "rotors": 5, "drag_area_m2": 0.03, "drag_coefficient": 1.0, "avionics_power_w": 4},
  "battery": {"id": "dc_b_361", "cells": [3, 4], "reserve_soc": 0.25},
  "objective": {"type": "min_energy"},
  "segments": [
    {"name": "up", "type": "climb", "rate_m_s": 1.5, "distance_m": 20, "rotors": 4},
    {"name": "hover", "type": "hover", "duration_s": 30, "rotors": 4},
    {"name": "cruise", "type": "cruise", "airspeed_m_s": 12, "lift_to_drag": 6, "distance_m": 3000, "rotors": 1},
    {"name": "down", "type": "climb", "rate_m_s": -1, "distance_m": 20, "rotors": 4}
  ]
})";

std::string Name(const Combination& c) {
  return c.motor->id + "|" + c.esc->id + "|" + c.prop->id + "|" + std::to_string(c.cells);
}

// kLiftCruise in two propulsion groups: the 4-rotor segments fly the "lift" group (free), the
// others a 1-rotor "pusher" fixed to pick's motor, ESC and propeller.
Json LiftAndFixedPusher(const Combination& pick) {
  Json j = ParseJsonText(kLiftCruise, "lift");
  j["vehicle"].erase("rotors");
  j["propulsion"] = {{"lift", {{"rotors", 4}}},
                     {"pusher", {{"rotors", 1}, {"motor", pick.motor->id}, {"esc", pick.esc->id}, {"prop", pick.prop->id}}}};
  for (Json& sg : j["segments"]) {
    sg["group"] = sg["rotors"].get<int>() == 4 ? "lift" : "pusher";
    sg.erase("rotors");
  }
  return j;
}

// Every feasible combination solved without and then with cutoffs full.score * factor (until
// max_checks solves with a cutoff): a "bounded out" answer only where the true score does not
// beat the cutoff, any other feasible answer the full one; some cutoff must be bounded out.
void ExpectCutoffsBoundOutOnlyWhatCannotBeatThem(const Catalog& cat, const Mission& m, int max_checks,
                                                 std::initializer_list<double> factors) {
  int bounded = 0, checked = 0;
  ForEachCombination(cat, [&](const Combination& c) {
    if (checked >= max_checks) return;
    const MissionResult full = MissionEvaluator(m, c).Solve();
    if (!full.feasible) return;
    for (const double factor : factors) {
      const double cutoff = full.score * factor;
      const MissionResult cut = MissionEvaluator(m, c).Solve(cutoff);
      if (cut.bounded_out) {
        ++bounded;
        EXPECT_GE(full.score, cutoff) << Name(c) << " factor " << factor;
      } else {  // an infeasibility exit (a proof over the whole range) cannot refuse a feasible one
        EXPECT_TRUE(cut.feasible) << Name(c) << " factor " << factor;
        EXPECT_EQ(cut.score, full.score) << Name(c) << " factor " << factor;
      }
      ++checked;
    }
  });
  EXPECT_GE(checked, 9);
  EXPECT_GT(bounded, 0) << "no cutoff was bounded out: the bounds were not exercised";
}

// The search's top N against every combination evaluated. Returns how many combinations were
// feasible.
std::size_t CheckAgainstExhaustive(const Catalog& cat, const Mission& m) {
  std::vector<std::pair<double, std::string>> all;
  ForEachCombination(cat, [&](const Combination& c) {
    const MissionResult r = MissionEvaluator(m, c).Solve();
    if (r.feasible) all.emplace_back(r.score, Name(c));
  });
  std::sort(all.begin(), all.end());
  SearchOptions so;
  so.top_n = 3;
  const SearchResult s = SearchCatalog(m, cat, so);
  EXPECT_EQ(s.best.size(), std::min<std::size_t>(3, all.size()));
  for (std::size_t i = 0; i < s.best.size() && i < all.size(); ++i) {
    EXPECT_EQ(Name(s.best[i].combination), all[i].second) << i;
    EXPECT_EQ(s.best[i].result.score, all[i].first) << i;  // same code path, bit for bit
  }
  EXPECT_EQ(s.searched + s.pruned, s.combinations);
  EXPECT_GT(s.pruned, 0);
  // Each pruned combination is counted under one rule (one free group: the joint search's
  // counts are per outer choice).
  long long by_rule = 0;
  for (const auto& [rule, n] : s.pruned_by) by_rule += n;
  if (FreeGroupCount(m) <= 1) {
    EXPECT_EQ(by_rule, s.pruned);
  }
  return all.size();
}

TEST_F(SearchTest, MinEnergyLiftCruiseEqualsExhaustiveEvaluation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  const Mission m = ParseMission(ParseJsonText(kLiftCruise, "lift"), "lift");
  EXPECT_GE(CheckAgainstExhaustive(cat, m), 1u) << "the small catalog must fly the mission";
}

// Propulsion groups: the lift group searched, the pusher fixed (to the best single-group pick,
// so that the mission flies). The search's bounds per group (G1) must not cut off the best:
// optimize equals exhaustive evaluation over the lift group's parts. With both groups given
// the same parts, the group mission flies exactly as the one-group mission with per-segment
// rotor counts.
TEST_F(SearchTest, PropulsionGroupsEqualExhaustiveEvaluation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  const Mission single = ParseMission(ParseJsonText(kLiftCruise, "lift"), "lift");
  SearchOptions so;
  so.top_n = 3;
  const SearchResult one = SearchCatalog(single, cat, so);
  ASSERT_FALSE(one.best.empty());
  const Combination& pick = one.best[0].combination;
  Json j = LiftAndFixedPusher(pick);
  const Mission m = ParseMission(j, "groups");
  const int lift = m.segments[0].group, pusher = m.segments[2].group;
  // Same parts in both groups: the same flight as the one-group mission.
  Combination same = pick;
  same.groups.assign(2, GroupParts{pick.motor, pick.esc, pick.prop});
  const MissionResult a = MissionEvaluator(single, pick).Solve();
  const MissionResult b = MissionEvaluator(m, same).Solve();
  ASSERT_TRUE(a.feasible);
  EXPECT_EQ(b.feasible, a.feasible);
  // 4*m + 1*m against 5*m in the mass: rounding of the last bit only.
  EXPECT_NEAR(b.objective, a.objective, 1e-9 * a.objective);
  // Exhaustive over the lift group's parts. On the way, G1's table: the pusher's segment power
  // bound read at the combination's own mass is at or below its mean terminal power.
  search_internal::SearchContext ctx;
  ctx.mission = &m;
  ctx.catalog = &cat;
  search_internal::ResolveGroups(&ctx);
  ctx.options = search_internal::BatteryOptions(m, cat);
  ctx.escs = search_internal::BuildEscTable(cat, ctx.options);
  search_internal::BuildPropGrids(m, cat, &ctx.grids, &ctx.models);
  search_internal::FixedGroupPowerBounds(&ctx);
  int g1_checked = 0;
  std::vector<std::pair<double, std::string>> all;
  ForEachCombination(cat, [&](Combination c) {
    c.groups.assign(2, GroupParts{});
    c.groups[lift] = GroupParts{c.motor, c.esc, c.prop};
    c.groups[pusher] = GroupParts{pick.motor, pick.esc, pick.prop};
    const MissionResult r = MissionEvaluator(m, c).Solve();
    if (r.feasible) all.emplace_back(r.score, Name(c));
    std::size_t o = 0;
    while (o < ctx.options.size() && !(ctx.options[o].entry == c.battery && ctx.options[o].cells == c.cells)) ++o;
    ASSERT_LT(o, ctx.options.size());
    for (std::size_t si = 0; si < r.segments.size(); ++si) {
      const SegmentResult& sr = r.segments[si];
      if (sr.group != pusher || !(sr.duration_s > 0) || sr.energy_j <= 0) continue;
      EXPECT_LE(search_internal::FixedPowerLowerBoundW(ctx, o, si, r.total_mass_kg), sr.energy_j / sr.duration_s)
          << Name(c) << " segment " << sr.name;
      ++g1_checked;
    }
  });
  EXPECT_GT(g1_checked, 0);
  std::sort(all.begin(), all.end());
  ASSERT_GE(all.size(), 1u);
  const SearchResult s = SearchCatalog(m, cat, so);
  ASSERT_EQ(s.best.size(), std::min<std::size_t>(3, all.size()));
  for (std::size_t i = 0; i < s.best.size(); ++i) {
    EXPECT_EQ(Name(s.best[i].combination), all[i].second) << i;
    EXPECT_EQ(s.best[i].result.score, all[i].first) << i;
    EXPECT_EQ(s.best[i].combination.Parts(pusher).motor, pick.motor);
  }
  EXPECT_EQ(s.searched + s.pruned, s.combinations);
  // Two free groups: the joint search (G2), tested in joint_search_test.cc.
  // A fixed id not in the catalog: the JSON path and the id.
  Json bad = j;
  bad["propulsion"]["pusher"]["motor"] = "no_such_motor";
  try {
    SearchCatalog(ParseMission(bad, "bad"), cat, so);
    ADD_FAILURE() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("$.propulsion.pusher.motor: \"no_such_motor\": not in the catalog"), std::string::npos)
        << e.what();
  }
  // evaluate --pick: the search's #1 reproduced through the CLI; bad picks are usage errors.
  std::ofstream(dir_ / "groups.json") << DumpJson(j);
  const std::string base = "evaluate " + (dir_ / "groups.json").string() + " --catalog " + (dir_ / "catalog").string() +
                           " --battery dc_b_361 --cells " + std::to_string(s.best[0].combination.cells);
  const Combination& top = s.best[0].combination;
  const auto ok = testing_util::RunCli(base + " --pick lift=" + top.motor->id + "," + top.esc->id + "," + top.prop->id + " --json");
  ASSERT_EQ(ok.code, 0) << ok.err;
  const Json out = Json::parse(ok.out);
  EXPECT_EQ(out["objective"].get<double>(), s.best[0].result.objective);
  EXPECT_EQ(out["groups"]["pusher"]["motor"], pick.motor->id);
  EXPECT_EQ(out["segments"][2]["group"], "pusher");
  const auto wing = testing_util::RunCli(base + " --pick wing=" + top.motor->id + "," + top.esc->id + "," + top.prop->id);
  EXPECT_EQ(wing.code, 64);
  EXPECT_NE(wing.err.find("--pick \"wing="), std::string::npos) << wing.err;
  EXPECT_NE(wing.err.find("no propulsion group 'wing'"), std::string::npos) << wing.err;
  const auto none = testing_util::RunCli(base);
  EXPECT_EQ(none.code, 64);
  EXPECT_NE(none.err.find("group 'lift' has no parts"), std::string::npos) << none.err;
  const auto malformed = testing_util::RunCli(base + " --pick lift=" + top.motor->id);
  EXPECT_EQ(malformed.code, 64);
  EXPECT_NE(malformed.err.find("must be GROUP=MOTOR,ESC,PROP"), std::string::npos) << malformed.err;
}

TEST_F(SearchTest, OptimizeEqualsTheBestOfExhaustiveEvaluation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  const Mission m = ParseMission(ParseJsonText(kQuad, "quad"), "quad");
  EXPECT_GE(CheckAgainstExhaustive(cat, m), 3u);
}

// The default ranking (credible data: propeller FM held to the measured class envelope,
// credibility.h), the data as given, folding propellers refused and unrated motors excluded:
// each is a different score, and the search must stay exact for each.
TEST_F(SearchTest, EveryRankingEqualsExhaustiveEvaluation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  Json j = ParseJsonText(kQuad, "quad");  // allows the folding 18 in AeroCarbon (dc_p_173)
  const Mission credible = ParseMission(j, "quad");
  EXPECT_EQ(credible.objective.ranking, DataScenario::kCredible);
  EXPECT_GE(CheckAgainstExhaustive(cat, credible), 3u);
  j["objective"]["ranking"] = "as_given";
  const Mission given = ParseMission(j, "quad");
  EXPECT_GE(CheckAgainstExhaustive(cat, given), 3u);
  j["objective"]["ranking"] = "credible";
  j["constraints"]["allow_folding_props_for_lift"] = false;
  j["constraints"]["unrated_motors"] = "exclude";
  const Mission strict = ParseMission(j, "quad");
  EXPECT_GE(CheckAgainstExhaustive(cat, strict), 3u);
  SearchOptions so;
  so.top_n = 1;
  const SearchResult sc = SearchCatalog(credible, cat, so), sg = SearchCatalog(given, cat, so);
  const SearchResult ss = SearchCatalog(strict, cat, so);
  ASSERT_EQ(sc.best.size(), 1u);
  ASSERT_EQ(sg.best.size(), 1u);
  ASSERT_EQ(ss.best.size(), 1u);
  // The DriveCalc laws of this catalog promise more than the measured props of their class.
  EXPECT_LT(sc.best[0].result.objective, sg.best[0].result.objective);
  EXPECT_GT(ss.pruned_by.count("prop_folding") ? ss.pruned_by.at("prop_folding") : 0, 0);
  EXPECT_NE(ss.best[0].combination.prop->id, "dc_p_173");
  for (const SearchResult* s : {&sc, &sg, &ss}) {
    const ObjectiveRange& g = s->best[0].result.range;
    EXPECT_TRUE(g.computed);
    EXPECT_LE(g.low, s->best[0].result.objective);
    EXPECT_GE(g.high, s->best[0].result.objective);
  }
}

// A capacity range: the evaluator's bounds (bisected over the range, the other segments'
// energy subtracted from the budget) and the search's must not cut off the best combinations.
TEST_F(SearchTest, CapacityRangeEqualsExhaustiveEvaluation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  Json j = ParseJsonText(kQuad, "quad");
  j["battery"]["capacity_ah"] = {2.0, 6.0};
  const Mission m = ParseMission(j, "quad");
  EXPECT_GE(CheckAgainstExhaustive(cat, m), 3u);
}

// min_hover_throttle is the one constraint a heavier, more resistive ESC helps: the search must
// not let a failing ESC (or the virtual one) rule out the ESCs it dominates.
TEST_F(SearchTest, MinHoverThrottleEqualsExhaustiveEvaluation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  Json j = ParseJsonText(kQuad, "quad");
  const Mission free_m = ParseMission(j, "quad");
  j["constraints"]["min_hover_throttle"] = 0.4;
  const Mission m = ParseMission(j, "quad");
  SearchOptions so;
  so.top_n = 3;
  const SearchResult unconstrained = SearchCatalog(free_m, cat, so);
  ASSERT_FALSE(unconstrained.best.empty());
  const MissionResult r = MissionEvaluator(m, unconstrained.best[0].combination).Solve();
  ASSERT_FALSE(r.feasible) << "the limit must bind on this catalog";
  bool named = false;
  for (const Violation& v : r.violations) named |= v.constraint == "min_hover_throttle";
  EXPECT_TRUE(named);
  EXPECT_GE(CheckAgainstExhaustive(cat, m), 3u);
}

// The propeller data window (mission.h; docs/search.md#r12): the search equals exhaustive evaluation
// when the window binds (the defaults, and a tight one), and with it off no combination names it.
TEST_F(SearchTest, PropDataWindowEqualsExhaustiveEvaluation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  for (const auto& [below, above] : {std::pair<double, double>{0.6, 1.5}, {0.9, 1.1}, {0.0, 0.0}}) {
    for (const bool capacity_range : {false, true}) {
      Json j = ParseJsonText(kQuad, "quad");
      if (capacity_range) j["battery"]["capacity_ah"] = {2.0, 6.0};
      j["constraints"]["prop_below_data_factor"] = below;
      j["constraints"]["prop_above_data_factor"] = above;
      const Mission m = ParseMission(j, "quad");
      int named = 0, feasible = 0;
      ForEachCombination(cat, [&](const Combination& c) {
        const MissionResult r = MissionEvaluator(m, c).Solve();
        feasible += r.feasible;
        for (const Violation& v : r.violations) {
          named += v.constraint == "prop_below_data" || v.constraint == "prop_above_data";
        }
      });
      if (below > 0) {
        EXPECT_GE(named, 1) << below << " " << capacity_range << ": the window must bind on this catalog";
      } else {
        EXPECT_EQ(named, 0);
      }
      if (feasible > 0) CheckAgainstExhaustive(cat, m);
    }
  }
}

// DataWindowRefuses (before a solve, and Solve's early exit) refuses only combinations whose full
// solve breaks the same constraint.
TEST_F(SearchTest, DataWindowRefusesOnlyInfeasibleCombinations) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  for (const bool capacity_range : {false, true}) {
    Json j = ParseJsonText(kQuad, "quad");
    if (capacity_range) j["battery"]["capacity_ah"] = {2.0, 6.0};
    j["constraints"]["prop_below_data_factor"] = 0.9;
    j["constraints"]["prop_above_data_factor"] = 1.1;
    const Mission m = ParseMission(j, "quad");
    int refused = 0;
    ForEachCombination(cat, [&](const Combination& c) {
      const MissionEvaluator eval(m, c);
      MissionResult w;
      if (!eval.DataWindowRefuses(true, &w)) return;
      ++refused;
      ASSERT_EQ(w.violations.size(), 1u);
      const MissionResult full = eval.Solve();
      EXPECT_FALSE(full.feasible) << Name(c);
      bool named = false;
      for (const Violation& v : full.violations) named |= v.constraint == w.violations[0].constraint;
      EXPECT_TRUE(named) << Name(c) << " " << w.violations[0].constraint;
    });
    EXPECT_GE(refused, 1) << "capacity range " << capacity_range;
  }
}

// Thrust-to-weight at its default (2.0): more mass and more ESC resistance only lower it, so the
// virtual ESC and ESC dominance (R5) stay bounds; the search must still equal exhaustive
// evaluation.
TEST_F(SearchTest, ThrustToWeightEqualsExhaustiveEvaluation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  Json j = ParseJsonText(kQuad, "quad");
  j["constraints"].erase("min_thrust_to_weight");
  const Mission m = ParseMission(j, "quad");
  ASSERT_EQ(m.constraints.min_thrust_to_weight, 2.0);
  EXPECT_GE(CheckAgainstExhaustive(cat, m), 1u);
  for (const bool capacity_range : {true}) {
    if (capacity_range) j["battery"]["capacity_ah"] = {2.0, 6.0};
    EXPECT_GE(CheckAgainstExhaustive(cat, ParseMission(j, "quad")), 1u);
  }
}

// A thrust-to-weight no combination reaches: the answer is the best combinations without that
// limit, each marked infeasible with its thrust-to-weight, not an empty list.
TEST_F(SearchTest, UnreachableThrustToWeightGivesResultsWithTheViolation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  Json j = ParseJsonText(kQuad, "quad");
  j["constraints"]["min_thrust_to_weight"] = 40.0;
  const Mission m = ParseMission(j, "quad");
  SearchOptions so;
  so.top_n = 2;
  const SearchResult s = SearchCatalog(m, cat, so);
  ASSERT_EQ(s.best.size(), 2u);
  EXPECT_EQ(s.relaxed_constraint, "min_thrust_to_weight");
  for (const RankedCombination& b : s.best) {
    EXPECT_FALSE(b.result.feasible);
    bool named = false;
    for (const Violation& v : b.result.violations) {
      if (v.constraint != "min_thrust_to_weight") continue;
      named = true;
      EXPECT_LT(v.value, 40.0);
      EXPECT_GT(v.value, 0.5);
      EXPECT_NEAR(v.value, b.result.thrust_to_weight, 0.0);
    }
    EXPECT_TRUE(named);
  }
  // The same order as the search without the limit.
  j["constraints"]["min_thrust_to_weight"] = 0.0;
  const SearchResult free_s = SearchCatalog(ParseMission(j, "quad"), cat, so);
  ASSERT_EQ(free_s.best.size(), 2u);
  EXPECT_EQ(Name(free_s.best[0].combination), Name(s.best[0].combination));
  // The CLI says so in one line and lists them.
  std::ofstream(dir_ / "tw.json") << DumpJson(ParseJsonText(DumpJson([&] { Json k = j; k["constraints"]["min_thrust_to_weight"] = 40.0; return k; }()), "x"));
  const auto cli = testing_util::RunCli("optimize " + (dir_ / "tw.json").string() + " --catalog " +
                                        (dir_ / "catalog").string() + " --top 2");
  EXPECT_EQ(cli.code, 0) << cli.err;
  EXPECT_NE(cli.out.find("no combination reaches min_thrust_to_weight"), std::string::npos) << cli.out;
  EXPECT_NE(cli.out.find("fails min_thrust_to_weight"), std::string::npos) << cli.out;
}

// The evaluator's early exits are proofs: for every combination, a cutoff just worse than its
// true score must neither be "bounded out" nor "infeasible" (a bound below the true endurance,
// or a screening rule that is not monotone, would fail here).
TEST_F(SearchTest, EarlyExitsNeverCutOffAFeasibleScore) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  for (const int variant : {0, 1, 2}) {  // fixed capacity without, with min_hover_throttle; a range
    const bool capacity_range = variant == 2;
    Json j = ParseJsonText(kQuad, "quad");
    if (capacity_range) j["battery"]["capacity_ah"] = {2.0, 6.0};
    if (variant > 0) j["constraints"]["min_hover_throttle"] = 0.3;
    const Mission m = ParseMission(j, "quad");
    int checked = 0;
    ForEachCombination(cat, [&](const Combination& c) {
      const MissionResult full = MissionEvaluator(m, c).Solve();
      if (!full.feasible) return;
      // A valid early exit proves score >= cutoff, impossible here; the 1e-6 (relative)
      // margin keeps a bound that is exactly tight from counting as a failure.
      const double cutoff = full.score + 1e-6 * std::fabs(full.score);
      const MissionResult cut = MissionEvaluator(m, c).Solve(cutoff);
      EXPECT_FALSE(cut.bounded_out) << Name(c);
      EXPECT_TRUE(cut.feasible) << Name(c);
      EXPECT_EQ(cut.score, full.score) << Name(c);
      ++checked;
    });
    EXPECT_GE(checked, 3) << "variant " << variant;
  }
}

// The same with an ESC whose DC current has a large part proportional to the phase current
// alone (C0 = 0.6, C1 = 0.6: PDC = C1*U*I/kv + C0*VDC*I, eqs 57, 59), whose power falls as the
// pack's voltage sags: the evaluator's endurance bound must not take the stretch's power at
// its start for its least, with a fixed capacity and with a range.
TEST_F(SearchTest, EarlyExitsHoldWhenTheEscPowerFallsWithTheVoltage) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  EscEntry esc = cat.esc("dc_e_56");
  esc.id = "c0_heavy";
  esc.params.c1 = 0.6;
  esc.params.c0 = 0.6;
  for (const bool capacity_range : {false, true}) {
    Json j = ParseJsonText(kQuad, "quad");
    if (capacity_range) j["battery"]["capacity_ah"] = {2.0, 6.0};
    // The hover alone: no other segment's energy hides the stretch's own (the bound is tight).
    j["segments"] = Json::parse(R"([{"name": "loiter", "type": "hover", "duration_s": 60}])");
    const Mission m = ParseMission(j, "quad");
    int checked = 0;
    for (const auto& mo : cat.motors()) {
      if (!mo.mass_kg) continue;
      for (const auto& p : cat.props()) {
        for (int cells : {3, 4}) {
          const Combination c{&mo, &esc, &p, &cat.battery("dc_b_361"), cells};
          const MissionResult full = MissionEvaluator(m, c).Solve();
          if (!full.feasible) continue;
          const double cutoff = full.score + 1e-6 * std::fabs(full.score);
          const MissionResult cut = MissionEvaluator(m, c).Solve(cutoff);
          EXPECT_FALSE(cut.bounded_out) << Name(c) << (capacity_range ? " (capacity range)" : "");
          EXPECT_EQ(cut.score, full.score) << Name(c);
          ++checked;
        }
      }
    }
    EXPECT_GE(checked, 3) << "capacity range " << capacity_range;
  }
}

// Solve's decide (the virtual ESC's question, R5: does the score beat the cutoff?) gives the
// same answer as the full solve at cutoffs on both sides of the true score, with the stretch
// alone free, with a capacity range, and with a free cruise airspeed; a "yes" comes with a
// feasible point that beats the cutoff, and some answers must stop early (else the test would
// not exercise it).
TEST_F(SearchTest, DecideAnswersAsTheFullSolve) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("nlopt_cobyla");  // free continuous variables (mission_eval.h)
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  std::vector<Mission> missions;
  Json q = ParseJsonText(kQuad, "quad");
  missions.push_back(ParseMission(q, "quad"));
  q["battery"]["capacity_ah"] = {2.0, 6.0};
  missions.push_back(ParseMission(q, "quad"));
  Json l = ParseJsonText(kLiftCruise, "lift");
  l["battery"]["capacity_ah"] = {2.0, 6.0};
  l["segments"][2]["airspeed_m_s"] = {9.0, 16.0};
  missions.push_back(ParseMission(l, "lift"));
  for (const Mission& m : missions) {
    int checked = 0, early = 0;
    ForEachCombination(cat, [&](const Combination& c) {
      if (checked >= 40) return;
      const MissionResult full = MissionEvaluator(m, c).Solve();
      if (!full.feasible) return;
      // The cutoff's side of the true score: 0.7 and 0.97 of it are harder to beat for
      // min_energy, easier for max_endurance (score = -endurance); 1.03 and 1.3 the opposite.
      for (const double factor : {0.7, 0.97, 1.03, 1.3}) {
        const double cutoff = full.score * factor;
        const MissionResult cut = MissionEvaluator(m, c).Solve(cutoff, false);
        const MissionResult dec = MissionEvaluator(m, c).Solve(cutoff, false, true);
        const bool beats = cut.feasible && !cut.bounded_out && cut.score < cutoff;
        EXPECT_EQ(dec.feasible && !dec.bounded_out && dec.score < cutoff, beats) << Name(c) << " " << factor;
        EXPECT_EQ(beats, full.score < cutoff) << Name(c) << " " << factor;
        if (beats && dec.score != full.score) ++early;
        ++checked;
      }
    });
    EXPECT_GE(checked, 8) << m.name;
    EXPECT_GT(early, 0) << m.name << ": no decision stopped early";
  }
}

// The hover-throttle exit (EarlyExit: the hover throttle at full charge below
// min_hover_throttle, with or without a capacity range) only refuses combinations that the
// full solve finds infeasible for that same limit; it must refuse some here (else the test
// would not exercise it).
TEST_F(SearchTest, HoverThrottleExitOnlyRefusesInfeasibleCombinations) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  for (const bool capacity_range : {false, true}) {
    Json j = ParseJsonText(kQuad, "quad");
    if (capacity_range) j["battery"]["capacity_ah"] = {2.0, 6.0};
    j["constraints"]["min_hover_throttle"] = 0.35;
    const Mission m = ParseMission(j, "quad");
    int refused = 0;
    ForEachCombination(cat, [&](const Combination& c) {
      // Any finite cutoff enables the exits; a huge one keeps the objective bounds from firing.
      const MissionResult cut = MissionEvaluator(m, c).Solve(1e300);
      if (cut.feasible || cut.violations.size() != 1 || cut.violations[0].constraint != "min_hover_throttle" ||
          !cut.segments.empty()) {
        return;  // not the exit (it returns no segments)
      }
      ++refused;
      const MissionResult full = MissionEvaluator(m, c).Solve();
      EXPECT_FALSE(full.feasible) << Name(c);
      bool named = false;
      for (const Violation& v : full.violations) named |= v.constraint == "min_hover_throttle";
      EXPECT_TRUE(named) << Name(c);
    });
    EXPECT_GE(refused, 1) << "capacity range " << capacity_range;
  }
}

// Solve's search flag: without a finite cutoff (the search before its top N is full) the exits
// that end in an infeasible result still run. The answer's feasibility and a feasible answer's
// score are the full solve's; some combinations must be decided by an exit (fewer segments than
// the full solve's answer: a screened run or no run), with and without a capacity range.
TEST_F(SearchTest, SearchSolvesWithoutACutoffScreenOnlyInfeasibleCombinations) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  for (const bool capacity_range : {false, true}) {
    Json j = ParseJsonText(kQuad, "quad");
    if (capacity_range) j["battery"]["capacity_ah"] = {2.0, 6.0};
    j["constraints"]["min_hover_throttle"] = 0.35;
    const Mission m = ParseMission(j, "quad");
    int screened = 0, feasible = 0;
    ForEachCombination(cat, [&](const Combination& c) {
      const MissionEvaluator ev(m, c);
      const MissionResult cut = ev.Solve(std::numeric_limits<double>::infinity(), false, false, true);
      const MissionResult full = ev.Solve(std::numeric_limits<double>::infinity(), false);
      ASSERT_EQ(cut.feasible, full.feasible) << Name(c);
      if (full.feasible) {
        EXPECT_EQ(cut.score, full.score) << Name(c);
        ++feasible;
      }
      if (cut.segments.size() < full.segments.size()) ++screened;  // an exit's shorter answer
    });
    EXPECT_GE(feasible, 1) << "capacity range " << capacity_range;
    EXPECT_GE(screened, 10) << "capacity range " << capacity_range;
  }
}

// The thrust-to-weight ceiling (MissionEvaluator::ThrustToWeightMassCeilingKg) is an upper
// bound: every solved combination, at capacities across a range, has a full-throttle thrust
// (thrust_to_weight x weight) at or below the ceiling's. And the exit built on it with the hover
// throttle (EarlyExit, HoverOrWeightRefuses: below min_hover_throttle up to C_h, too heavy above
// it) only refuses combinations whose full solve is infeasible; with limits set so that both
// bind, it must refuse some with C_h inside the range (else the test would not exercise it).
TEST_F(SearchTest, ThrustToWeightCeilingBoundsEveryRunAndItsExitOnlyRefusesInfeasible) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  int bounded = 0, tight = 0, refused = 0, inside = 0;
  // (min_hover_throttle, min_thrust_to_weight): pairs where the hover throttle passes only with
  // the larger packs and the thrust-to-weight only with the smaller ones (2-4 refusals each below
  // the top; 34-68 of the 336 combinations feasible).
  for (const auto& limits : {std::pair{0.30, 2.0}, std::pair{0.30, 2.4}, std::pair{0.35, 2.4}}) {
  // Plain copies: a lambda may not capture a structured binding (C++17; clang refuses it).
  const double hover = limits.first, tw = limits.second;
  Json j = ParseJsonText(kQuad, "quad");
  j["battery"]["capacity_ah"] = {2.0, 6.0};
  j["constraints"]["min_hover_throttle"] = hover;
  j["constraints"]["min_thrust_to_weight"] = tw;
  const Mission m = ParseMission(j, "quad");
  ForEachCombination(cat, [&](const Combination& c) {
    const MissionEvaluator ev(m, c);
    const double ceiling_kg = ev.ThrustToWeightMassCeilingKg();
    for (const double capacity_ah : {2.0, 4.0, 6.0}) {
      ContinuousVars v;
      v.capacity_ah = capacity_ah;
      const MissionResult r = ev.Simulate(v);
      if (!(r.thrust_to_weight > 0)) continue;
      // thrust_to_weight = N*T/(m*g) and the ceiling N*T_ub*(1 + 1e-6)/(g*limit).
      const double thrust_kg = r.thrust_to_weight * r.total_mass_kg;
      EXPECT_LE(thrust_kg, ceiling_kg * tw) << Name(c) << " at " << capacity_ah << " Ah";
      ++bounded;
      if (thrust_kg > 0.9 * ceiling_kg * tw) ++tight;  // the sag is a few per cent
    }
    const MissionResult cut = ev.Solve(std::numeric_limits<double>::infinity(), false, false, true);
    if (cut.feasible || !cut.segments.empty() || cut.violations.size() != 1) return;  // not an exit
    const std::string& why = cut.violations[0].constraint;
    if (why != "min_hover_throttle" && why != "min_thrust_to_weight") return;
    ++refused;
    if (why == "min_hover_throttle" && cut.capacity_ah < 6.0) ++inside;
    const MissionResult full = ev.Solve();
    EXPECT_FALSE(full.feasible) << Name(c) << " refused for " << why << " (" << hover << ", " << tw << ")";
  });
  }
  EXPECT_GE(bounded, 20);
  EXPECT_GT(tight, 0) << "the ceiling should be within 10 % of some full-throttle thrust";
  EXPECT_GE(refused, 1);
  EXPECT_GE(inside, 1) << "no refusal through the hover throttle below the range's top";
}

// The other side of the early exits (EnduranceUpperBound with its throttle floor, the bound
// over the golden section's bracket after the capacity grid): at cutoffs around the true
// score, a "bounded out" answer is only given when the true score does not beat the cutoff,
// and any other answer is the full one. Cutoffs better than the true score must let some
// combinations be bounded out (else the test would not exercise the bounds).
TEST_F(SearchTest, EarlyExitsBoundOutOnlyWhatCannotBeatTheCutoff) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  Json j = ParseJsonText(kQuad, "quad");
  j["battery"]["capacity_ah"] = {2.0, 6.0};
  const Mission m = ParseMission(j, "quad");
  // score = -endurance: 1.10 asks for 10 % more; eight feasible combinations (a test of seconds).
  ExpectCutoffsBoundOutOnlyWhatCannotBeatThem(cat, m, 24, {1.10, 1.02, 0.98});
}

// The same for min_energy with a capacity range and a free wing-borne cruise airspeed (the
// energy pre-check at the smallest capacity, with the momentum bound of the free cruise), and
// the search equals exhaustive evaluation there (G1's free-cruise table: the pusher fixed).
TEST_F(SearchTest, FreeCruiseEnergyBoundsAreBounds) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("nlopt_cobyla");  // free continuous variables (mission_eval.h)
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  Json j = ParseJsonText(kLiftCruise, "lift");
  j["battery"]["capacity_ah"] = {2.0, 6.0};
  j["segments"][2]["airspeed_m_s"] = {9.0, 16.0};
  // The wing's L/D: the body's drag is added, so the thrust rises with the airspeed (flight.h)
  // and the bounds must take its least value over the range.
  j["segments"][2]["lift_to_drag_of"] = "wing";
  const Mission m = ParseMission(j, "lift");
  // min_energy: 0.90 asks for 10 % less; ten feasible combinations (a test of seconds).
  ExpectCutoffsBoundOutOnlyWhatCannotBeatThem(cat, m, 30, {0.5, 0.90, 1.0 + 1e-6});
}

// R15 in the evaluator's min_energy early exit (mission_eval_early_exits.cc): the energy bound
// at the smallest capacity of a wide range, raised to the capacity that energy needs above the
// reserve, is still a bound, with the capacity alone free and with a cruise airspeed too.
// Without a free airspeed the bound at the raised capacity is nearly the energy itself, so a
// needed capacity taken 1.3 times too large bounds out feasible combinations here; the
// infeasibility exit at the smallest pack (BreaksBeforeFreeAirspeeds) refuses feasible ones
// when it reads a constraint that a larger pack can cure (the reserve, the cut-off).
TEST_F(SearchTest, MinEnergyEarlyExitAtTheNeededCapacityIsABound) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("nlopt_cobyla");  // two free variables (mission_eval.h)
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  for (const bool airspeed_free : {false, true}) {
    Json j = ParseJsonText(kQuad, "quad");
    j["objective"] = {{"type", "min_energy"}};
    j["battery"]["capacity_ah"] = {0.3, 6.0};  // 0.3 Ah: far below what any combination needs
    if (airspeed_free) {  // a wing-borne cruise: its bound reads the propeller (prop_bounds.h)
      j["segments"][1]["airspeed_m_s"] = {6.0, 14.0};
      j["segments"][1]["lift_to_drag"] = 6.0;
    }
    const Mission m = ParseMission(j, "quad");
    ExpectCutoffsBoundOutOnlyWhatCannotBeatThem(cat, m, 30, {0.9, 0.99, 1.0 + 1e-6});
  }
}

// A search's evaluation (Solve's `search`) settles min_thrust_to_weight from a floor of the
// full-throttle thrust where the floor meets the limit with the run's least slack to spare
// (FinishRun, ThrustFloorN): the score, the feasibility, the least slack and the violations
// must be those of the full solve, with the capacity free and with a cruise airspeed too, and
// with a limit the floors settle and one close to the thrust they bound. A floor taken 20 %
// too high changes the feasibility of combinations here.
TEST_F(SearchTest, SearchEvaluationsSettleThrustToWeightAsTheFullSolve) {
  DYNOSIZE_SKIP_UNLESS_AVAILABLE("nlopt_cobyla");  // two free variables (mission_eval.h)
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  int settled_differently = 0, checked = 0;
  for (const double tw : {1.5, 2.5}) {
    for (const bool airspeed_free : {false, true}) {
      Json j = ParseJsonText(kQuad, "quad");
      j["objective"] = {{"type", "min_energy"}};
      j["battery"]["capacity_ah"] = {1.0, 6.0};
      j["constraints"]["min_thrust_to_weight"] = tw;
      if (airspeed_free) {
        j["segments"][1]["airspeed_m_s"] = {6.0, 14.0};
        j["segments"][1]["lift_to_drag"] = 6.0;
      }
      const Mission m = ParseMission(j, "quad");
      ForEachCombination(cat, [&](const Combination& c) {
        const MissionEvaluator eval(m, c);
        const double no_cutoff = std::numeric_limits<double>::infinity();
        const MissionResult full = eval.Solve(no_cutoff, false);
        const MissionResult search = eval.Solve(no_cutoff, false, false, true);
        EXPECT_EQ(search.feasible, full.feasible) << Name(c) << " tw " << tw;
        EXPECT_EQ(search.score, full.score) << Name(c) << " tw " << tw;
        // An infeasibility exit (EarlyExit: a proof over the ranges) names the one violation it
        // rests on; the solves' own runs are compared.
        if (search.violations_everywhere) return;
        ++checked;
        EXPECT_EQ(search.min_slack, full.min_slack) << Name(c) << " tw " << tw;
        EXPECT_EQ(search.violations.size(), full.violations.size()) << Name(c) << " tw " << tw;
        settled_differently += search.thrust_to_weight != full.thrust_to_weight;
      });
    }
  }
  EXPECT_GE(checked, 20);
  EXPECT_GT(settled_differently, 0) << "no run settled the limit from its floor: the floors were not exercised";
}

// G1 with a free wing-borne cruise airspeed flown by a fixed pusher: the table's power at a
// combination's mass times the shortest duration is at or below the cruise energy at the
// airspeed the evaluator picks, and the bound from the pusher's own data (M4) is tight.
TEST_F(SearchTest, FixedGroupFreeCruiseBoundIsBelowTheEnergy) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  const Mission single = ParseMission(ParseJsonText(kLiftCruise, "lift"), "lift");
  SearchOptions so;
  so.top_n = 1;
  const SearchResult one = SearchCatalog(single, cat, so);
  ASSERT_FALSE(one.best.empty());
  const Combination& pick = one.best[0].combination;
  Json j = LiftAndFixedPusher(pick);
  j["segments"][2]["airspeed_m_s"] = {9.0, 16.0};
  // Stopped lift rotors in the cruise: a thrust that rises with the airspeed (flight.h).
  j["propulsion"]["lift"]["idle_drag_area_m2"] = 0.004;
  const Mission m = ParseMission(j, "groups");
  const int lift = m.segments[0].group, pusher = m.segments[2].group;
  search_internal::SearchContext ctx;
  ctx.mission = &m;
  ctx.catalog = &cat;
  search_internal::ResolveGroups(&ctx);
  ctx.options = search_internal::BatteryOptions(m, cat);
  ctx.escs = search_internal::BuildEscTable(cat, ctx.options);
  search_internal::BuildPropGrids(m, cat, &ctx.grids, &ctx.models);
  search_internal::FixedGroupPowerBounds(&ctx);
  int checked = 0, above_avionics = 0, from_data = 0;
  ForEachCombination(cat, [&](Combination c) {
    if (checked >= 40) return;
    c.groups.assign(2, GroupParts{});
    c.groups[lift] = GroupParts{c.motor, c.esc, c.prop};
    c.groups[pusher] = GroupParts{pick.motor, pick.esc, pick.prop};
    const MissionResult r = MissionEvaluator(m, c).Solve();
    if (!r.feasible) return;
    std::size_t o = 0;
    while (o < ctx.options.size() && !(ctx.options[o].entry == c.battery && ctx.options[o].cells == c.cells)) ++o;
    ASSERT_LT(o, ctx.options.size());
    const double p_lb = search_internal::FixedPowerLowerBoundW(ctx, o, 2, r.total_mass_kg);
    const double e_lb = p_lb * SegmentDurationS(m.segments[2], m.segments[2].airspeed_m_s.hi);
    EXPECT_LE(e_lb, r.segments[2].energy_j) << Name(c) << " at " << r.segments[2].airspeed_m_s << " m/s";
    if (p_lb > m.vehicle.avionics_power_w) ++above_avionics;
    // Momentum theory alone reaches 0.65-0.68 of these energies; the pusher's own data (M4)
    // about 0.9.
    if (e_lb > 0.8 * r.segments[2].energy_j) ++from_data;
    ++checked;
  });
  EXPECT_GE(checked, 3);
  EXPECT_GT(above_avionics, 0) << "the free-cruise bound should add to the avionics";
  EXPECT_GT(from_data, 0) << "the bound from the pusher's own data should grip";
}

// An entry the catalog marks "exclude" (catalog.h) is never searched: the pick's motor and
// propeller, excluded, leave the search (catalog_exclude) and the next best wins.
TEST_F(SearchTest, CatalogExcludedEntriesAreNotSearched) {
  const Mission m = ParseMission(ParseJsonText(kQuad, "quad"), "quad");
  SearchOptions so;
  so.top_n = 1;
  const Catalog full = Catalog::Load((dir_ / "catalog").string());
  const SearchResult before = SearchCatalog(m, full, so);
  ASSERT_EQ(before.best.size(), 1u);
  const std::string motor = before.best[0].combination.motor->id, prop = before.best[0].combination.prop->id;
  EXPECT_EQ(before.pruned_by.count("catalog_exclude"), 0u);
  Json doc = ReadJsonFile((dir_ / "catalog" / "small.json").string());
  for (Json& e : doc["motors"]) {
    if (e["id"] == motor) e["exclude"] = "test: excluded";
  }
  for (Json& e : doc["props"]) {
    if (e["id"] == prop) e["exclude"] = "test: excluded";
  }
  fs::create_directories(dir_ / "excluded");
  std::ofstream(dir_ / "excluded" / "small.json") << DumpJson(doc);
  const Catalog cat = Catalog::Load((dir_ / "excluded").string());
  const SearchResult after = SearchCatalog(m, cat, so);
  ASSERT_EQ(after.best.size(), 1u);
  EXPECT_NE(after.best[0].combination.motor->id, motor);
  EXPECT_NE(after.best[0].combination.prop->id, prop);
  ASSERT_EQ(after.pruned_by.count("catalog_exclude"), 1u);
  EXPECT_GT(after.pruned_by.at("catalog_exclude"), 0);
  EXPECT_EQ(after.searched + after.pruned, after.combinations);
  // evaluate still flies an excluded entry when asked by id, and says so.
  const Combination& b = before.best[0].combination;
  const Combination c{&cat.motor(motor), &cat.esc(b.esc->id), &cat.prop(prop), &cat.battery(b.battery->id), b.cells};
  const MissionResult r = MissionEvaluator(m, c).Solve();
  bool said = false;
  for (const std::string& w : r.warnings) said |= w.find("excluded from searches by the catalog") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST_F(SearchTest, FreeAirspeedOptimumBeatsADenseGrid) {
  Json j = ParseJsonText(kQuad, "quad");
  // On the data as given: the credible propeller power (credibility.h) breaks this motor's
  // current rating.
  j["objective"] = {{"type", "min_energy"}, {"ranking", "as_given"}};
  j["segments"][1]["airspeed_m_s"] = {4.0, 20.0};
  const Mission m = ParseMission(j, "quad");
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  const Combination c{&cat.motor("dc_m_1020"), &cat.esc("dc_e_56"), &cat.prop("dc_p_173"), &cat.battery("dc_b_361"), 4};
  const MissionEvaluator ev(m, c);
  const MissionResult r = ev.Solve();
  ASSERT_TRUE(r.feasible);
  double grid_best = 1e300, v_best = 0;
  for (int i = 0; i <= 400; ++i) {
    ContinuousVars v;
    v.airspeed_m_s.assign(m.segments.size(), 0.0);
    v.airspeed_m_s[1] = 4.0 + 16.0 * i / 400.0;
    const MissionResult g = ev.Simulate(v);
    if (g.feasible && g.objective < grid_best) { grid_best = g.objective; v_best = v.airspeed_m_s[1]; }
  }
  // COBYLA stops at relative_tolerance 1e-6 in the scaled airspeed; the energy is flat at the
  // optimum, so it matches the grid's best (step 0.04 m/s) to 1e-5 relative or beats it.
  EXPECT_LE(r.objective, grid_best * (1 + 1e-5));
  EXPECT_NEAR(r.segments[1].airspeed_m_s, v_best, 0.5);
}

TEST_F(SearchTest, FreeCapacityOptimumBeatsADenseGrid) {
  Json j = ParseJsonText(kQuad, "quad");
  j["battery"]["capacity_ah"] = {1.5, 9.0};
  const Mission m = ParseMission(j, "quad");
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  const Combination c{&cat.motor("dc_m_1020"), &cat.esc("dc_e_56"), &cat.prop("dc_p_173"), &cat.battery("dc_b_361"), 4};
  const MissionEvaluator ev(m, c);
  const MissionResult r = ev.Solve();
  ASSERT_TRUE(r.feasible) << r.solver;
  double grid_best = 0, c_best = 0;
  for (int i = 0; i <= 300; ++i) {
    ContinuousVars v;
    v.capacity_ah = 1.5 + 7.5 * i / 300.0;
    v.airspeed_m_s.assign(m.segments.size(), 0.0);
    const MissionResult g = ev.Simulate(v);
    if (g.feasible && g.objective > grid_best) { grid_best = g.objective; c_best = v.capacity_ah; }
  }
  // Endurance found by regula falsi to 1e-6 relative per capacity, and COBYLA on the capacity
  // to 1e-6 of its range: within 1e-4 of the grid's best (step 0.025 A*h) or better.
  EXPECT_GE(r.objective, grid_best * (1 - 1e-4)) << r.solver;
  EXPECT_NEAR(r.capacity_ah, c_best, 0.3) << r.solver;
}

TEST_F(SearchTest, InfeasibleMissionSaysWhichConstraintAndByHowMuch) {
  Json j = ParseJsonText(kQuad, "quad");
  j["vehicle"]["mass_kg"] = 12.0;  // far too heavy for these components
  const Mission m = ParseMission(j, "quad");
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  const SearchResult s = SearchCatalog(m, cat);
  EXPECT_TRUE(s.best.empty());
  const Combination c{&cat.motor("dc_m_1020"), &cat.esc("dc_e_56"), &cat.prop("dc_p_173"), &cat.battery("dc_b_361"), 4};
  const MissionResult r = MissionEvaluator(m, c).Solve();
  EXPECT_FALSE(r.feasible);
  ASSERT_FALSE(r.violations.empty());
  for (const Violation& v : r.violations) EXPECT_GT(v.excess(), 0.0) << v.constraint;
  // The CLI says it in one line per failing constraint, with the amount.
  std::ofstream(dir_ / "heavy.json") << DumpJson(j);
  const auto cli = testing_util::RunCli("evaluate " + (dir_ / "heavy.json").string() + " --catalog " +
                                        (dir_ / "catalog").string() +
                                        " --motor dc_m_1020 --esc dc_e_56 --prop dc_p_173 --battery dc_b_361 --cells 4");
  EXPECT_EQ(cli.code, 0) << cli.err;  // an infeasible combination is a result, not an error
  EXPECT_NE(cli.out.find("INFEASIBLE"), std::string::npos) << cli.out;
  EXPECT_NE(cli.out.find("fails " + r.violations.front().constraint), std::string::npos) << cli.out;
  EXPECT_NE(cli.out.find("(by "), std::string::npos) << cli.out;
}

// Outputs that agree with themselves. A result that cannot fly its mission
// shows no credible value (its objective is what it flew before it broke a limit), a design
// that cannot hover has no hover endurance, and a range's end that cannot fly is null.
TEST_F(SearchTest, OutputsAgreeWithThemselves) {
  Json j = ParseJsonText(kQuad, "quad");
  j["vehicle"]["mass_kg"] = 12.0;  // far too heavy for these components: cannot hover
  std::ofstream(dir_ / "heavy2.json") << DumpJson(j);
  const std::string args = "evaluate " + (dir_ / "heavy2.json").string() + " --catalog " + (dir_ / "catalog").string() +
                           " --motor dc_m_1020 --esc dc_e_56 --prop dc_p_173 --battery dc_b_361 --cells 4";
  const auto js = testing_util::RunCli(args + " --json");
  ASSERT_EQ(js.code, 0) << js.err;
  const Json r = Json::parse(js.out);
  ASSERT_FALSE(r["feasible"].get<bool>());
  EXPECT_FALSE(r["objective_in_range"].get<bool>());
  if (r.contains("summary")) {
    EXPECT_FALSE(r["summary"]["can_hover"].get<bool>());
    EXPECT_TRUE(r["summary"]["hover_endurance_s"].is_null());
    EXPECT_TRUE(r["summary"]["full_throttle_endurance_s"].is_null());
  }
  for (const Json& end : r["objective_range"]) EXPECT_TRUE(end.is_null() || end.is_number());
  if (!r["objective_range_complete"].get<bool>()) {
    EXPECT_TRUE(r["objective_range"][0].is_null() || r["objective_range"][1].is_null());
  }
  const auto tx = testing_util::RunCli(args);
  ASSERT_EQ(tx.code, 0) << tx.err;
  EXPECT_NE(tx.out.find("credible infeasible;"), std::string::npos) << tx.out;
  EXPECT_NE(tx.out.find("it cannot hover"), std::string::npos) << tx.out;
  EXPECT_EQ(tx.out.find(" min, full throttle "), std::string::npos) << tx.out;  // no endurances
  // A feasible result lies inside its range.
  const auto ok = testing_util::RunCli("evaluate " + (dir_ / "quad.json").string() + " --catalog " +
                                       (dir_ / "catalog").string() +
                                       " --motor dc_m_1020 --esc dc_e_56 --prop dc_p_173 --battery dc_b_361 --cells 4 --json");
  ASSERT_EQ(ok.code, 0) << ok.err;
  const Json f = Json::parse(ok.out);
  if (f["feasible"].get<bool>()) {
    EXPECT_TRUE(f["objective_in_range"].get<bool>());
    const Json& g = f["objective_range"];
    if (g[0].is_number()) {
      EXPECT_LE(g[0].get<double>(), f["objective"].get<double>());
    }
    if (g[1].is_number()) {
      EXPECT_GE(g[1].get<double>(), f["objective"].get<double>());
    }
  }
}

TEST_F(SearchTest, EverySegmentPointIsReproducedBySimulate) {
  const std::string cat = "--catalog " + (dir_ / "catalog").string();
  // On the data as given: the credible propeller power breaks this motor's current rating.
  Json given = ParseJsonText(kQuad, "quad");
  given["objective"]["ranking"] = "as_given";
  std::ofstream(dir_ / "quad_given.json") << DumpJson(given);
  const auto ev = testing_util::RunCli("evaluate " + (dir_ / "quad_given.json").string() + " " + cat +
                                       " --motor dc_m_1020 --esc dc_e_56 --prop dc_p_173 --battery dc_b_361 --cells 4 --json");
  ASSERT_EQ(ev.code, 0) << ev.err;
  const Json j = Json::parse(ev.out);
  ASSERT_TRUE(j["feasible"].get<bool>());
  ASSERT_EQ(j["segments"].size(), 4u);
  for (const Json& s : j["segments"]) {
    char args[512];
    std::snprintf(args, sizeof args, "simulate %s --motor dc_m_1020 --esc dc_e_56 --vdc %.17g --throttle %.17g --torque %.17g --json",
                  cat.c_str(), s["vdc_v"].get<double>(), s["throttle"].get<double>(), s["torque_nm"].get<double>());
    const auto sim = testing_util::RunCli(args);
    ASSERT_EQ(sim.code, 0) << sim.err;
    const Json p = Json::parse(sim.out);
    // The forward model inverts the inverse to rounding (a quadratic's root, 1e-12 relative).
    for (const char* key : {"rpm", "irms_a", "idc_a", "pdc_w", "pesc_w", "eta_motor", "eta_esc", "eta_system"}) {
      EXPECT_NEAR(p[key].get<double>(), s[key].get<double>(), 1e-9 * std::fabs(s[key].get<double>()))
          << s["name"] << " " << key;
    }
  }
  // The optimize CLI prints the same numbers as evaluate for its top pick.
  const auto opt = testing_util::RunCli("optimize " + (dir_ / "quad.json").string() + " " + cat + " --top 1 --json");
  ASSERT_EQ(opt.code, 0) << opt.err;
  const Json o = Json::parse(opt.out);
  ASSERT_EQ(o["results"].size(), 1u);
  const Json& best = o["results"][0];
  const auto ev2 = testing_util::RunCli("evaluate " + (dir_ / "quad.json").string() + " " + cat + " --motor " +
                                        best["motor"].get<std::string>() + " --esc " + best["esc"].get<std::string>() +
                                        " --prop " + best["prop"].get<std::string>() + " --battery " +
                                        best["battery"].get<std::string>() + " --cells " +
                                        std::to_string(best["cells"].get<int>()) + " --json");
  ASSERT_EQ(ev2.code, 0) << ev2.err;
  EXPECT_EQ(Json::parse(ev2.out)["objective"], best["objective"]);
  EXPECT_EQ(o["searched"].get<long long>() + o["pruned"].get<long long>(), o["combinations"].get<long long>());
}

// The answer and every count do not depend on the number of threads, on the bundled catalog and
// the quadcopter example (its later stage 4 batches are bounded against the threshold of the
// moment they are drawn, and the rules count what they remove then); the counts add up to the
// combinations.
TEST(SearchThreadsTest, TheAnswerAndTheCountsDoNotDependOnTheThreads) {
  const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  const Mission m = ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
  SearchResult r[2];
  for (int t = 0; t < 2; ++t) {
    SearchOptions o;
    o.top_n = 3;
    o.threads = t + 1;
    r[t] = SearchCatalog(m, cat, o);
  }
  ASSERT_EQ(r[0].best.size(), 3u);
  ASSERT_EQ(r[1].best.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(r[0].best[i].combination.motor, r[1].best[i].combination.motor) << i;
    EXPECT_EQ(r[0].best[i].combination.esc, r[1].best[i].combination.esc) << i;
    EXPECT_EQ(r[0].best[i].combination.prop, r[1].best[i].combination.prop) << i;
    EXPECT_EQ(r[0].best[i].result.score, r[1].best[i].result.score) << i;
  }
  EXPECT_EQ(r[0].pruned_by, r[1].pruned_by);
  EXPECT_EQ(r[0].searched, r[1].searched);
  EXPECT_EQ(r[0].candidate_pairs, r[1].candidate_pairs);
  EXPECT_EQ(r[0].virtual_evaluations, r[1].virtual_evaluations);
  long long pruned = 0;
  for (const auto& [rule, n] : r[0].pruned_by) pruned += n;
  EXPECT_EQ(r[0].searched + pruned, r[0].combinations);
}

}  // namespace
}  // namespace dynosize
