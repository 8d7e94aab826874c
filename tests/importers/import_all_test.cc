// Regenerating the committed catalog: `build/dynosize catalog import --shared ../shared/data
// --out catalog`, or without the CLI:
//   build/dynosize_tests --gtest_also_run_disabled_tests --gtest_filter='*RegenerateCatalog*'
#include <filesystem>
#include <iostream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "catalog/catalog.h"
#include "common/text_file.h"
#include "importers/importers.h"

namespace dynosize {
namespace {

const std::string kShared = DYNOSIZE_SHARED_DIR "/data";
const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";

bool HaveShared() { return std::filesystem::is_directory(kShared + "/drivecalc"); }

TEST(ImportAllTest, DISABLED_RegenerateCatalog) {
  if (!HaveShared()) GTEST_SKIP() << "no ../shared/data: cannot regenerate the catalog";
  const ImportReport report = ImportAll(kShared, kCatalog);
  std::cout << report.FullReport();
}

// Re-running the importers reproduces the committed files byte for byte.
TEST(ImportAllTest, ReproducesCommittedCatalogByteForByte) {
  if (!HaveShared()) GTEST_SKIP() << "no ../shared/data: the importers cannot run";
  const std::string tmp = ::testing::TempDir() + "/dynosize_catalog_repro_" + std::to_string(getpid());
  std::filesystem::remove_all(tmp);
  const ImportReport report = ImportAll(kShared, tmp);
  for (const auto& d : report.datasets) {
    const std::string fresh = ReadTextFile(tmp + "/" + d.output_file, 64u << 20);
    const std::string committed = ReadTextFile(kCatalog + "/" + d.output_file, 64u << 20);
    EXPECT_TRUE(fresh == committed) << d.output_file << " differs from the committed file: "
                                    << "re-run the DISABLED_RegenerateCatalog driver";
  }
  std::filesystem::remove_all(tmp);
}

}  // namespace
}  // namespace dynosize
