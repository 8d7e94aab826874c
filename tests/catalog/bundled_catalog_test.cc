// The bundled catalog (catalog/*.json) validates, every entry carries its source, and it loads
// quickly.
#include <algorithm>
#include <chrono>
#include <string>

#include <gtest/gtest.h>

#include "catalog/catalog.h"
#include "catalog/schema.h"
#include "common/error.h"

namespace dynosize {
namespace {

const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";

TEST(BundledCatalogTest, ValidatesWithoutProblems) {
  const auto problems = Catalog::Validate(kCatalog);
  std::string all;
  for (std::size_t i = 0; i < problems.size() && i < 20; ++i) all += problems[i] + "\n";
  EXPECT_TRUE(problems.empty()) << problems.size() << " problems, first:\n" << all;
}

TEST(BundledCatalogTest, HoldsHundredsOfEachKindWithSources) {
  const Catalog c = Catalog::Load(kCatalog);
  EXPECT_GT(c.motors().size(), 1000u);
  EXPECT_GT(c.escs().size(), 300u);
  EXPECT_GT(c.props().size(), 300u);
  EXPECT_GT(c.batteries().size(), 300u);
  auto check = [](const EntryBase& e) {
    ASSERT_TRUE(e.json.contains("source")) << e.id;
    EXPECT_FALSE(e.json["source"]["dataset"].get<std::string>().empty()) << e.id;
  };
  for (const auto& e : c.motors()) check(e);
  for (const auto& e : c.escs()) check(e);
  for (const auto& e : c.props()) check(e);
  for (const auto& e : c.batteries()) check(e);
}

// Every ESC without a dyno fit says that its eq (57) constants are assumed.
TEST(BundledCatalogTest, CatalogEscsMarkThePriorAsAssumed) {
  const Catalog c = Catalog::Load(kCatalog);
  for (const auto& e : c.escs()) {
    if (e.id.rfind("dc_e_", 0) != 0 && e.id.rfind("fu_e_", 0) != 0) continue;
    for (const char* key : {"c1", "c0", "tr_sat", "sat_slope"}) {
      EXPECT_NE(std::find(e.assumed_keys.begin(), e.assumed_keys.end(), key), e.assumed_keys.end())
          << e.id << " " << key;
    }
  }
}

// "Well under a second": a generous bound for a loaded CI machine; the median is measured by
// bench/catalog_bench.cc.
constexpr double kMaxLoadSeconds = 1.0;

TEST(BundledCatalogTest, LoadsWellUnderASecond) {
#if !defined(NDEBUG) || defined(__SANITIZE_ADDRESS__) || defined(DYNOSIZE_SANITIZED)
  GTEST_SKIP() << "timing is meaningful in an optimised, uninstrumented build only";
#endif
  const auto t0 = std::chrono::steady_clock::now();
  const Catalog c = Catalog::Load(kCatalog);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(s, kMaxLoadSeconds) << c.size() << " entries";
}

}  // namespace
}  // namespace dynosize
