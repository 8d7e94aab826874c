// identification/knee_profile.h: the knee profile fits at every knee of the grid in order,
// reports the cost curve, keeps the lowest cost (the first of equal ones), skips failed fits, and
// says when every fit failed.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "identification/knee_profile.h"

namespace dynosize::identification {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Fit {
  double knee = -1.0;  // -1: a default (no fit)
  double cost = kInf;
};

TEST(KneeProfile, KeepsTheLowestCostAndReportsTheCurve) {
  const std::vector<double> grid = {0.5, 0.6, 0.7, 0.8, 0.9};
  std::vector<std::size_t> order;
  const auto fit_at = [&](double knee, std::size_t j) {
    order.push_back(j);
    return Fit{knee, (knee - 0.72) * (knee - 0.72)};
  };
  const KneeProfile<Fit> p = ProfileKnee<Fit>(grid, fit_at, [](const Fit& f) { return f.cost; });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  ASSERT_TRUE(p.found());
  EXPECT_EQ(p.best, 2u);
  EXPECT_EQ(p.best_fit.knee, 0.7);
  EXPECT_EQ(p.knees, grid);
  ASSERT_EQ(p.costs.size(), grid.size());
  for (std::size_t j = 0; j < grid.size(); ++j) EXPECT_EQ(p.costs[j], (grid[j] - 0.72) * (grid[j] - 0.72));
}

TEST(KneeProfile, FirstOfEqualCostsAndFailedFitsSkipped) {
  const std::vector<double> grid = {0.5, 0.6, 0.7, 0.8};
  const std::vector<double> cost = {kInf, 2.0, std::nan(""), 2.0};
  const auto fit_at = [&](double knee, std::size_t j) { return Fit{knee, cost[j]}; };
  const KneeProfile<Fit> p = ProfileKnee<Fit>(grid, fit_at, [](const Fit& f) { return f.cost; });
  ASSERT_TRUE(p.found());
  EXPECT_EQ(p.best, 1u);
  EXPECT_EQ(p.best_fit.knee, 0.6);
  EXPECT_EQ(p.costs[2], kInf);  // a NaN cost is a failed fit on the curve
}

TEST(KneeProfile, EveryFitFailedGivesTheDefaultOutcome) {
  const auto fit_at = [](double knee, std::size_t) { return Fit{knee, kInf}; };
  const KneeProfile<Fit> p = ProfileKnee<Fit>({0.5, 0.7}, fit_at, [](const Fit& f) { return f.cost; });
  EXPECT_FALSE(p.found());
  EXPECT_EQ(p.best_fit.knee, -1.0);
  const KneeProfile<Fit> empty = ProfileKnee<Fit>({}, fit_at, [](const Fit& f) { return f.cost; });
  EXPECT_FALSE(empty.found());
  EXPECT_TRUE(empty.costs.empty());
}

}  // namespace
}  // namespace dynosize::identification
