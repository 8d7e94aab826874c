// The top N as distinct designs (each with its alternatives) against
// exhaustive evaluation on the small catalog, one free group and two; and a search stopped by
// its stop flag or deadline, which returns the best found so far with a proven bound.
#include "optimization/top_results.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "mission/flight.h"
#include "optimization/joint_search.h"
#include "optimization/mission_eval.h"
#include "optimization/search.h"
#include "optimization/small_catalog.h"
#include "prop/prop_model.h"

namespace dynosize::search_internal {
namespace {

namespace fs = std::filesystem;
using testing_util::kFreeQuadplane;
using testing_util::kQuad;
constexpr double kInf = std::numeric_limits<double>::infinity();

class TopResultsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = testing_util::WriteSmallCatalog("top_results");
    cat_ = std::make_unique<Catalog>(Catalog::Load((dir_ / "catalog").string()));
  }
  static void TearDownTestSuite() {
    cat_.reset();
    fs::remove_all(dir_);
  }
  static fs::path dir_;
  static std::unique_ptr<Catalog> cat_;
};
fs::path TopResultsTest::dir_;
std::unique_ptr<Catalog> TopResultsTest::cat_;

struct Scored {
  double score;
  std::string design, name;  // design: motor and prop of every group; name: every part and the cells
};

std::string DesignName(const Combination& c) {
  std::string s;
  for (int g = 0; g < std::max<int>(1, static_cast<int>(c.groups.size())); ++g) {
    s += c.Parts(g).motor->id + "," + c.Parts(g).prop->id + ";";
  }
  return s;
}
std::string FullName(const Combination& c) {
  std::string s;
  for (int g = 0; g < std::max<int>(1, static_cast<int>(c.groups.size())); ++g) s += c.Parts(g).esc->id + ",";
  return DesignName(c) + s + std::to_string(c.cells);
}

// Every feasible combination of the small catalog (motors without mass left out, as the search
// does) for a mission without groups.
std::vector<Scored> ExhaustiveOneGroup(const Catalog& cat, const Mission& m) {
  std::vector<Scored> all;
  testing_util::ForEachCombination(cat, [&](const Combination& c) {
    const MissionResult r = MissionEvaluator(m, c).Solve();
    if (r.feasible) all.push_back({r.score, DesignName(c), FullName(c)});
  });
  return all;
}

// The same for kFreeQuadplane's two free groups.
std::vector<Scored> ExhaustiveTwoGroups(const Catalog& cat, const Mission& m) {
  std::vector<std::unique_ptr<PropModel>> models;
  for (const PropEntry& p : cat.props()) models.push_back(std::make_unique<PropModel>(p));
  std::vector<const PropModel*> group_models(2, nullptr);
  std::vector<Scored> all;
  for (const MotorEntry& ml : cat.motors()) {
    for (const EscEntry& el : cat.escs()) {
      for (std::size_t pl = 0; pl < cat.props().size(); ++pl) {
        for (const MotorEntry& mp : cat.motors()) {
          for (const EscEntry& ep : cat.escs()) {
            for (std::size_t pp = 0; pp < cat.props().size(); ++pp) {
              if (!ml.mass_kg || !mp.mass_kg) continue;
              for (int cells : {3, 4}) {
                Combination c{&ml, &el, &cat.props()[pl], &cat.battery("dc_b_361"), cells, {}};
                c.groups = {GroupParts{&ml, &el, &cat.props()[pl]}, GroupParts{&mp, &ep, &cat.props()[pp]}};
                group_models = {models[pl].get(), models[pp].get()};
                const MissionResult r = MissionEvaluator(m, c, models[pl].get(), &group_models).Solve();
                if (r.feasible) all.push_back({r.score, DesignName(c), FullName(c)});
              }
            }
          }
        }
      }
    }
  }
  return all;
}

// The search's distinct designs equal exhaustive evaluation's: the best n designs (each at its
// best combination, name and score bit for bit: the same code path) and, inside each, every
// other combination of the design scoring below the n-th design's best. Returns the alternatives
// listed (the check must see some).
std::size_t ExpectDistinctDesignsOfExhaustive(const Catalog& cat, const Mission& m, std::vector<Scored> all, int n) {
  std::stable_sort(all.begin(), all.end(), [](const Scored& a, const Scored& b) { return a.score < b.score; });
  std::vector<const Scored*> designs;  // each design's best, best first
  std::set<std::string> seen;
  for (const Scored& s : all) {
    if (seen.insert(s.design).second) designs.push_back(&s);
  }
  const double threshold = static_cast<int>(designs.size()) >= n ? designs[static_cast<std::size_t>(n - 1)]->score : kInf;
  SearchOptions so;
  so.top_n = n;
  so.distinct_designs = true;
  const SearchResult s = SearchCatalog(m, cat, so);
  EXPECT_FALSE(s.interrupted);
  EXPECT_EQ(s.best.size(), std::min<std::size_t>(static_cast<std::size_t>(n), designs.size()));
  std::size_t listed = 0;
  for (std::size_t i = 0; i < s.best.size() && i < designs.size(); ++i) {
    EXPECT_EQ(FullName(s.best[i].combination), designs[i]->name) << i;
    EXPECT_EQ(s.best[i].result.score, designs[i]->score) << i;
    std::vector<std::pair<double, std::string>> want, got;
    for (const Scored& x : all) {
      if (x.design == designs[i]->design && x.name != designs[i]->name && x.score < threshold) want.emplace_back(x.score, x.name);
    }
    for (const Alternative& a : s.best[i].alternatives) got.emplace_back(a.score, FullName(a.combination));
    EXPECT_TRUE(std::is_sorted(got.begin(), got.end(), [](const auto& a, const auto& b) { return a.first < b.first; }));
    std::sort(want.begin(), want.end());
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want) << "alternatives of #" << i + 1;
    listed += got.size();
  }
  return listed;
}

TEST_F(TopResultsTest, DistinctDesignsEqualExhaustiveEvaluation) {
  const Mission m = ParseMission(ParseJsonText(kQuad, "quad"), "quad");
  const std::vector<Scored> all = ExhaustiveOneGroup(*cat_, m);
  ASSERT_GE(all.size(), 6u) << "the small catalog must fly the mission";
  std::size_t listed = 0;
  // With 6, the third design's other ESCs score better than the sixth design (the small catalog).
  for (int n : {1, 3, 6}) listed += ExpectDistinctDesignsOfExhaustive(*cat_, m, all, n);
  EXPECT_GT(listed, 0u) << "no design had an alternative: the check was not exercised";
}

TEST_F(TopResultsTest, DistinctDesignsWithTwoFreeGroupsEqualExhaustiveEvaluation) {
  const Mission m = ParseMission(ParseJsonText(kFreeQuadplane, "free"), "free");
  ASSERT_EQ(FreeGroupCount(m), 2);
  ASSERT_EQ(m.groups[0].name, "lift");  // ExhaustiveTwoGroups's order
  const std::vector<Scored> all = ExhaustiveTwoGroups(*cat_, m);
  ASSERT_GE(all.size(), 6u);
  EXPECT_GT(ExpectDistinctDesignsOfExhaustive(*cat_, m, all, 2), 0u);
}

// The threshold rule on its own: designs count once, at their best; combinations each.
TEST(TopScoresTest, DesignsCountOnceAtTheirBest) {
  TopScores designs(2, true, 10.0), combos(2, false, 10.0);
  const EntryKey a = {1, 2}, a2 = {1, 2}, b = {3, 4}, c = {5, 6};
  EXPECT_EQ(designs.Threshold(), 10.0);  // the cutoff while fewer than 2
  for (TopScores* t : {&designs, &combos}) {
    EXPECT_TRUE(t->Add(a, 3.0));
    EXPECT_TRUE(t->Add(t == &designs ? a2 : EntryKey{1, 2, 9}, 2.0));  // the same design, better
  }
  EXPECT_EQ(designs.Threshold(), 10.0) << "one design so far";
  EXPECT_EQ(combos.Threshold(), 3.0);
  EXPECT_TRUE(designs.Add(b, 4.0));
  EXPECT_EQ(designs.Threshold(), 4.0);
  EntryKey evicted;
  EXPECT_TRUE(designs.Add(c, 1.0, &evicted));
  EXPECT_EQ(evicted, b);
  EXPECT_EQ(designs.Threshold(), 2.0);
  EXPECT_FALSE(designs.Add(b, 2.0)) << "not below the threshold";
}

// Stopped after k chunks: what is left unsettled is bounded, and every combination better than
// both that bound and the N-th best found is among the results (nothing below the bound was lost).
void ExpectStoppedSearchIsValid(const SearchResult& s, const std::vector<Scored>& all, int n, const std::string& what) {
  ASSERT_TRUE(s.interrupted) << what;
  EXPECT_LE(static_cast<int>(s.best.size()), n) << what;
  EXPECT_FALSE(std::isnan(s.unsettled_bound_score)) << what;
  EXPECT_GT(s.unsettled, 0) << what;
  EXPECT_EQ(s.searched + s.pruned + s.unsettled, s.combinations) << what;
  std::set<std::string> found;
  for (const RankedCombination& b : s.best) {
    EXPECT_TRUE(b.result.feasible) << what;
    found.insert(FullName(b.combination));
  }
  const double settled_below = std::min(s.unsettled_bound_score, s.nth_best_score);
  int below = 0;
  for (const Scored& x : all) {
    if (!(x.score < settled_below)) continue;
    ++below;
    EXPECT_TRUE(found.count(x.name)) << what << ": " << x.name << " scores " << x.score << " below the bound "
                                     << s.unsettled_bound_score << " and the N-th best " << s.nth_best_score;
  }
  // The bound is a bound: nothing unsettled beats it, so the best of all is found or not below it.
  if (!all.empty() && !found.count(std::min_element(all.begin(), all.end(), [](const Scored& a, const Scored& b) {
                                      return a.score < b.score;
                                    })->name)) {
    for (const Scored& x : all) EXPECT_GE(x.score, s.unsettled_bound_score) << what << " " << x.name;
  }
}

SearchResult StopAfter(const Mission& m, const Catalog& cat, int n, int calls, bool distinct) {
  std::atomic<bool> stop{false};
  int seen = 0;
  SearchOptions so;
  so.top_n = n;
  so.distinct_designs = distinct;
  so.stop = &stop;
  // The progress callback runs between chunks, just before the stop check.
  so.progress = [&](const SearchProgress&) {
    if (++seen >= calls) stop = true;
  };
  return SearchCatalog(m, cat, so);
}

TEST_F(TopResultsTest, StoppedSearchReturnsTheBestSoFarWithAValidBound) {
  const Mission m = ParseMission(ParseJsonText(kQuad, "quad"), "quad");
  const std::vector<Scored> all = ExhaustiveOneGroup(*cat_, m);
  int interrupted_with_results = 0;
  for (bool distinct : {false, true}) {
    for (int calls = 1; calls <= 4; ++calls) {
      const SearchResult s = StopAfter(m, *cat_, 3, calls, distinct);
      if (!s.interrupted) continue;  // the search had ended before the stop
      ExpectStoppedSearchIsValid(s, all, 3, "after " + std::to_string(calls) + " chunks");
      if (!s.best.empty() && std::isfinite(s.nth_best_score)) {
        ++interrupted_with_results;
        EXPECT_LT(s.unsettled_bound_score, s.nth_best_score) << "a gap is left (else the search would be done)";
      }
    }
  }
  EXPECT_GT(interrupted_with_results, 0) << "no stop came after results: the gap was not exercised";
}

TEST_F(TopResultsTest, StopBeforeAnythingIsFoundIsAnEmptyInterruptedResult) {
  const Mission m = ParseMission(ParseJsonText(kQuad, "quad"), "quad");
  const std::vector<Scored> all = ExhaustiveOneGroup(*cat_, m);
  SearchOptions so;
  so.deadline = std::chrono::steady_clock::now();  // already passed
  const SearchResult s = SearchCatalog(m, *cat_, so);
  EXPECT_TRUE(s.best.empty());
  EXPECT_TRUE(s.relaxed_constraint.empty()) << "no search without the thrust-to-weight after a stop";
  ExpectStoppedSearchIsValid(s, all, so.top_n, "deadline passed");
  EXPECT_TRUE(std::isfinite(s.unsettled_bound_score));
  for (const Scored& x : all) EXPECT_GE(x.score, s.unsettled_bound_score) << x.name;
  // A deadline far ahead: the whole search.
  so.deadline = std::chrono::steady_clock::now() + std::chrono::hours(1);
  EXPECT_FALSE(SearchCatalog(m, *cat_, so).interrupted);
}

TEST_F(TopResultsTest, StoppedJointSearchStopsItsInnerSearchesToo) {
  const Mission m = ParseMission(ParseJsonText(kFreeQuadplane, "free"), "free");
  const std::vector<Scored> all = ExhaustiveTwoGroups(*cat_, m);
  int stopped = 0;
  for (int calls : {1, 2, 3, 5}) {
    const SearchResult s = StopAfter(m, *cat_, 3, calls, true);
    if (!s.interrupted) continue;
    ++stopped;
    ExpectStoppedSearchIsValid(s, all, 3, "joint, after " + std::to_string(calls) + " progress calls");
  }
  EXPECT_GT(stopped, 0);
}

// A stop can come in the middle of a chunk of candidates (the workers check it before taking
// each one): the candidates not taken stay unsettled, so every count and the bound still hold.
// The stop comes from another thread after a delay; whatever the moment, the checks must hold.
// The bundled catalog's quadcopter: its search takes about 0.15 s, much of it in chunks of
// solves (the small catalog's is mostly set-up, so a stop seldom lands in a chunk); the stops
// come at fractions of the time the whole search took on this build (ten times more under the
// sanitizers). With two
// threads one of them draws the next chunk while the other solves, so a stop lands among a
// chunk's solves mostly with one.
TEST(TopResultsStopTest, StopInTheMiddleOfAChunkLeavesTheCountsAndTheBoundValid) {
  const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  const Mission m = ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
  SearchOptions so;
  so.top_n = 3;
  so.threads = 1;
  const auto t0 = std::chrono::steady_clock::now();
  const SearchResult full = SearchCatalog(m, cat, so);
  const auto whole = std::chrono::steady_clock::now() - t0;  // scales with the build (sanitizers)
  ASSERT_FALSE(full.best.empty());
  const RankedCombination& best = full.best.front();
  int with_solves = 0;
  for (int k = 1; k <= 20; ++k) {  // stops at 5 %, 10 %, ..., 100 % of the whole search's time
    std::atomic<bool> stop{false};
    so.stop = &stop;
    // One thread draws and solves in turn, so a stop lands among the solves more often.
    so.threads = k % 2 == 0 ? 2 : 1;
    const auto delay = whole * k / 20;
    std::thread stopper([&stop, delay] {
      std::this_thread::sleep_for(delay);
      stop = true;
    });
    const SearchResult s = SearchCatalog(m, cat, so);
    stopper.join();
    const std::string what = "stopped at " + std::to_string(5 * k) + " % of the search's time";
    if (!s.interrupted) continue;
    if (s.searched > 0) ++with_solves;
    EXPECT_GT(s.unsettled, 0) << what;
    // `pruned` is what the others leave; the rules' own counts must add up to it (a candidate
    // neither solved nor counted as unsettled would be missing from them).
    long long by_rule = 0;
    for (const auto& [rule, n] : s.pruned_by) by_rule += n;
    EXPECT_EQ(s.searched + by_rule + s.unsettled, s.combinations) << what;
    ASSERT_TRUE(std::isfinite(s.unsettled_bound_score)) << what;
    bool found = false;
    for (const RankedCombination& b : s.best) found = found || FullName(b.combination) == FullName(best.combination);
    if (!found) {
      EXPECT_GE(best.result.score, s.unsettled_bound_score) << what << ": the best was lost below the bound";
    }
  }
  EXPECT_GT(with_solves, 0) << "no stop came after the first solves";
}

// Distinct designs keep search.h's promise: the answer and the counts do not depend on the threads.
TEST(TopResultsThreadsTest, DistinctDesignsDoNotDependOnTheThreads) {
  const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  const Mission m = ReadMission(std::string(DYNOSIZE_SOURCE_DIR) + "/examples/missions/quadcopter_1p5kg.json");
  SearchResult r[2];
  for (int t = 0; t < 2; ++t) {
    SearchOptions o;
    o.top_n = 3;
    o.threads = t + 1;
    o.distinct_designs = true;
    r[t] = SearchCatalog(m, cat, o);
  }
  ASSERT_EQ(r[0].best.size(), 3u);
  ASSERT_EQ(r[1].best.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(FullName(r[0].best[i].combination), FullName(r[1].best[i].combination)) << i;
    EXPECT_EQ(r[0].best[i].result.score, r[1].best[i].result.score) << i;
    ASSERT_EQ(r[0].best[i].alternatives.size(), r[1].best[i].alternatives.size()) << i;
    for (std::size_t k = 0; k < r[0].best[i].alternatives.size(); ++k) {
      EXPECT_EQ(FullName(r[0].best[i].alternatives[k].combination), FullName(r[1].best[i].alternatives[k].combination));
    }
    for (std::size_t k = 0; k < i; ++k) EXPECT_NE(DesignName(r[0].best[i].combination), DesignName(r[0].best[k].combination));
  }
  EXPECT_EQ(r[0].pruned_by, r[1].pruned_by);
  EXPECT_EQ(r[0].searched, r[1].searched);
}

}  // namespace
}  // namespace dynosize::search_internal
