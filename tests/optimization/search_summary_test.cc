// The search's options check (SearchOptions::IsValid) and its Summary: the counts it reports
// are the search's, the gap is the N-th best's distance to the bound of what is left.
#include "optimization/search.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <string>

#include "catalog/catalog.h"
#include "cli_runner.h"
#include "common/error.h"

namespace dynosize {
namespace {

const std::string kSourceDir = DYNOSIZE_SOURCE_DIR;

TEST(SearchOptionsTest, IsValidSaysWhichOptionBreaksWhichRule) {
  SearchOptions o;
  std::string why = "stale";
  EXPECT_TRUE(o.IsValid(&why));
  EXPECT_EQ(why, "");
  o.top_n = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(why, "--top 0: must be >= 1");
  EXPECT_FALSE(o.IsValid(nullptr));
}

// The search refuses invalid options with IsValid's message (a UsageError, exit 2 in the CLI).
TEST(SearchOptionsTest, TheSearchRefusesInvalidOptionsWithTheSameMessage) {
  const Catalog cat = Catalog::Load(kSourceDir + "/catalog");
  const Mission m = ReadMission(kSourceDir + "/examples/missions/quadcopter_1p5kg.json");
  SearchOptions o;
  o.top_n = -2;
  try {
    SearchCatalog(m, cat, o);
    FAIL() << "no UsageError";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()), "--top -2: must be >= 1");
  }
}

TEST(SearchSummaryTest, ReportsTheCountsOfTheSearch) {
  const Catalog cat = Catalog::Load(kSourceDir + "/catalog");
  const Mission m = ReadMission(kSourceDir + "/examples/missions/quadcopter_1p5kg.json");
  SearchOptions o;
  o.top_n = 3;
  const SearchResult r = SearchCatalog(m, cat, o);
  const SearchSummary s = SearchSummary::From(r);
  EXPECT_EQ(s.results, 3);
  EXPECT_EQ(s.combinations, r.combinations);
  EXPECT_EQ(s.candidate_pairs, r.candidate_pairs);
  EXPECT_GT(s.candidate_pairs, 0);
  EXPECT_EQ(s.solved, r.searched);
  EXPECT_EQ(s.pruned, r.pruned);
  EXPECT_EQ(s.pruned_by, r.pruned_by);
  EXPECT_EQ(s.solved + s.pruned, s.combinations);  // finished: every combination settled
  EXPECT_FALSE(s.interrupted);
  EXPECT_EQ(s.Gap(), 0.0);
  const std::string brief = s.BriefReport();
  EXPECT_EQ(brief.find('\n'), std::string::npos) << brief;
  EXPECT_NE(brief.find(std::to_string(r.combinations) + " combinations"), std::string::npos) << brief;
  EXPECT_NE(brief.find(std::to_string(r.candidate_pairs) + " candidate pairs bounded"), std::string::npos) << brief;
  EXPECT_NE(brief.find(std::to_string(r.searched) + " solved exactly"), std::string::npos) << brief;
  EXPECT_NE(brief.find(", done"), std::string::npos) << brief;
  const std::string full = s.FullReport();
  for (const auto& [rule, n] : r.pruned_by) {
    if (n == 0) continue;
    EXPECT_NE(full.find(rule), std::string::npos) << rule << "\n" << full;
    EXPECT_NE(full.find(std::to_string(n)), std::string::npos) << rule << "\n" << full;
  }
  EXPECT_NE(full.find("every combination settled"), std::string::npos) << full;
}

// A search stopped by its evaluation budget (a count, so where it stops does not depend on
// timing) reports the stop, what is left and a gap that is not negative.
TEST(SearchSummaryTest, ReportsAnInterruptedSearchWithItsGap) {
  const Catalog cat = Catalog::Load(kSourceDir + "/catalog");
  const Mission m = ReadMission(kSourceDir + "/examples/missions/quadcopter_1p5kg.json");
  SearchOptions o;
  o.top_n = 3;
  o.evaluation_budget = 50;
  const SearchResult r = SearchCatalog(m, cat, o);
  ASSERT_TRUE(r.interrupted);
  const SearchSummary s = SearchSummary::From(r);
  EXPECT_TRUE(s.interrupted);
  EXPECT_EQ(s.unsettled, r.unsettled);
  EXPECT_GT(s.unsettled, 0);
  EXPECT_GE(s.Gap(), 0.0);
  EXPECT_NE(s.BriefReport().find("interrupted (gap "), std::string::npos) << s.BriefReport();
  EXPECT_NE(s.FullReport().find(std::to_string(r.unsettled) + " combinations not settled"), std::string::npos)
      << s.FullReport();
}

TEST(SearchSummaryTest, TheGapIsTheNthBestAboveTheBoundOfWhatIsLeft) {
  SearchSummary s;
  s.nth_best_score = -5.0;
  s.unsettled_bound_score = -7.5;
  EXPECT_EQ(s.Gap(), 0.0);  // finished: proven
  s.interrupted = true;
  EXPECT_DOUBLE_EQ(s.Gap(), 2.5);
  s.unsettled_bound_score = -std::numeric_limits<double>::infinity();  // no bound (max_efficiency)
  EXPECT_TRUE(std::isinf(s.Gap()));
  EXPECT_NE(s.BriefReport().find("gap unknown"), std::string::npos) << s.BriefReport();
  s.unsettled_bound_score = -4.0;  // what is left cannot beat the N-th best
  EXPECT_EQ(s.Gap(), 0.0);
}

// The joint search's inner searches put back over their budget solve real combinations whose
// results can be shown on a stop while the combinations stay unsettled: the reports say where
// those solves are counted (else "0 solved exactly" beside shown results reads as a bug).
TEST(SearchSummaryTest, SolvesOfPutBackSearchesAreNamed) {
  SearchSummary s;
  s.virtual_evaluations = 120;
  EXPECT_EQ(s.BriefReport().find("put back"), std::string::npos) << s.BriefReport();
  s.put_back_solves = 100;
  EXPECT_NE(s.BriefReport().find("(120 virtual-ESC solves besides, 100 of them in inner searches put back over their budget)"),
            std::string::npos)
      << s.BriefReport();
  EXPECT_NE(s.FullReport().find("120 (100 in inner searches put back over their budget)"), std::string::npos)
      << s.FullReport();
}

// optimize --stats prints the summary's brief report, one line on stderr, and leaves stdout alone.
TEST(SearchSummaryTest, OptimizeStatsPrintsTheBriefReport) {
  const std::string mission = kSourceDir + "/examples/missions/fpv_5in.json";
  const testing_util::CliRun r = testing_util::RunCli("optimize " + mission + " --top 1 --json --stats");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("search: 1 results, ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(" candidate pairs bounded, "), std::string::npos) << r.err;
  ASSERT_GE(r.err.size(), 7u);
  EXPECT_EQ(r.err.substr(r.err.size() - 7), ", done\n") << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  const testing_util::CliRun plain = testing_util::RunCli("optimize " + mission + " --top 1 --json");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(plain.err, "");
}

// The joint search's phases: one more line in both reports (where a slow both-free search spends
// its time), none for a one-group search.
TEST(SearchSummaryTest, TheJointSearchsPhasesAreReportedOnlyForAJointSearch) {
  SearchSummary s;
  EXPECT_EQ(s.BriefReport().find("joint search"), std::string::npos) << s.BriefReport();
  EXPECT_EQ(s.FullReport().find("joint search"), std::string::npos) << s.FullReport();
  s.joint.setup_s = 0.5;
  s.joint.outer_pairs_s = 0.25;
  s.joint.class_searches = 3;
  s.joint.class_searches_s = 1.5;
  s.joint.triple_searches = 2;
  s.joint.triple_searches_s = 0.125;
  const std::string line =
      "joint search: bounds set up 0.500 s, first pass over the outer pairs 0.250 s, 3 class searches (virtual ESC) "
      "1.500 s, 2 triple searches 0.125 s";
  EXPECT_NE(s.BriefReport().find("\n" + line), std::string::npos) << s.BriefReport();
  EXPECT_NE(s.FullReport().find("  " + line + "\n"), std::string::npos) << s.FullReport();
  // The pairs bounded below the final N-th best, when the search knows them.
  s.joint.outer_pairs_below_final = 42;
  EXPECT_NE(s.BriefReport().find(line + ", 42 outer pairs bounded below the N-th best"), std::string::npos)
      << s.BriefReport();
}

}  // namespace
}  // namespace dynosize
