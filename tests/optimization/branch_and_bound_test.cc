// Distinct designs (docs/ranking.md) against exhaustive evaluation: the N designs of least best
// score and, inside each, every other combination scoring below the N-th design's best. R14
// (docs/search.md#r14) solves a known design's other ESCs against the design's best and solves
// those it defers again at the end; a deferred combination left unsolved drops an alternative.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/mission_eval.h"
#include "optimization/search.h"
#include "optimization/small_catalog.h"

namespace dynosize {
namespace {

namespace fs = std::filesystem;

class DistinctDesignsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = testing_util::WriteSmallCatalog("distinct_designs"); }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
};
fs::path DistinctDesignsTest::dir_;

std::string Design(const Combination& c) { return c.motor->id + "|" + c.prop->id; }
std::string Variant(const Combination& c) { return c.esc->id + "|" + std::to_string(c.cells); }

// (score, ESC|cells), ascending (ties by name: the search lists ties in the order it met them).
using Scored = std::vector<std::pair<double, std::string>>;

// The top n designs and their alternatives by exhaustive evaluation, as the search must list
// them; the number of alternatives in *alternatives.
void CheckDistinctDesigns(const Catalog& cat, const Mission& m, int n, int* alternatives) {
  std::map<std::string, Scored> per_design;
  testing_util::ForEachCombination(cat, [&](const Combination& c) {
    const MissionResult r = MissionEvaluator(m, c).Solve();
    if (r.feasible) per_design[Design(c)].emplace_back(r.score, Variant(c));
  });
  std::vector<std::pair<double, std::string>> designs;  // (best score, design)
  for (auto& [d, v] : per_design) {
    std::sort(v.begin(), v.end());
    designs.emplace_back(v.front().first, d);
  }
  std::sort(designs.begin(), designs.end());
  const std::size_t top = std::min<std::size_t>(static_cast<std::size_t>(n), designs.size());
  const double threshold = designs.size() >= static_cast<std::size_t>(n) ? designs[top - 1].first
                                                                         : std::numeric_limits<double>::infinity();
  SearchOptions so;
  so.top_n = n;
  so.distinct_designs = true;
  const SearchResult s = SearchCatalog(m, cat, so);
  ASSERT_EQ(s.best.size(), top);
  *alternatives = 0;
  for (std::size_t i = 0; i < top; ++i) {
    const RankedCombination& b = s.best[i];
    EXPECT_EQ(Design(b.combination), designs[i].second) << i;
    EXPECT_EQ(b.result.score, designs[i].first) << i;  // the same code path, bit for bit
    const Scored& all = per_design[designs[i].second];
    Scored expected;  // after the design's best (the result itself), those below the threshold
    for (std::size_t k = 1; k < all.size(); ++k) {
      if (all[k].first < threshold) expected.push_back(all[k]);
    }
    Scored listed;
    for (const Alternative& a : b.alternatives) listed.emplace_back(a.score, Variant(a.combination));
    std::sort(listed.begin(), listed.end());
    // The best may tie with an alternative (which of them is listed as the best): scores only.
    ASSERT_EQ(listed.size(), expected.size()) << "design " << designs[i].second;
    for (std::size_t k = 0; k < listed.size(); ++k) EXPECT_EQ(listed[k].first, expected[k].first) << i << " " << k;
    *alternatives += static_cast<int>(listed.size());
  }
  EXPECT_EQ(s.searched + s.pruned, s.combinations);
  long long by_rule = 0;
  for (const auto& [rule, count] : s.pruned_by) by_rule += count;
  EXPECT_EQ(by_rule, s.pruned);
}

// The fixed-capacity quad lists no alternative on the small catalog (its designs' other ESCs
// score above the N-th design); with a capacity range the first design lists several.
TEST_F(DistinctDesignsTest, DesignsAndAlternativesEqualExhaustiveEvaluation) {
  const Catalog cat = Catalog::Load((dir_ / "catalog").string());
  Json ranged = ParseJsonText(testing_util::kQuad, "quad");
  ranged["battery"]["capacity_ah"] = {2.0, 6.0};
  int listed = 0;
  for (const Json& j : {ParseJsonText(testing_util::kQuad, "quad"), ranged}) {
    for (int n : {1, 3}) {
      int alternatives = 0;
      CheckDistinctDesigns(cat, ParseMission(j, "quad"), n, &alternatives);
      listed += alternatives;
    }
  }
  EXPECT_GT(listed, 0) << "no design lists an alternative: the test proves nothing";
}

}  // namespace
}  // namespace dynosize
