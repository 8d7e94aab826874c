// Folders of the user's own parts read on top of a catalog (catalog/catalog_path.h,
// Catalog::Load(CatalogFolders)): clashing ids, --override, DYNOSIZE_CATALOG_PATH, the bundled
// catalog's location.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "catalog/catalog.h"
#include "catalog/catalog_path.h"
#include "common/error.h"

namespace dynosize {
namespace {

namespace fs = std::filesystem;

std::string Motor(const std::string& id, double rm_ohm) {
  return R"({"id": ")" + id + R"(", "name": "Test motor", "type": "bldc", "kv_rpm_per_v": 1000, "rm_ohm": )" +
         std::to_string(rm_ohm) + R"(, "io_a": 0.4, "source": {"dataset": "unit test"}})";
}
std::string Esc(const std::string& id) {
  return R"({"id": ")" + id + R"(", "name": "Test ESC", "resc_ohm": 0.01, "c1": 1.15, "c0": 0.02,
    "tr_sat": 0.9, "sat_slope": 0.6, "source": {"dataset": "unit test"}})";
}

// A fresh folder per test under the temporary directory, removed at the end.
class AddedCatalogFolders : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("dynosize_catalog_folders_" + std::to_string(getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
  }
  void TearDown() override {
    fs::remove_all(root_);
    unsetenv("DYNOSIZE_CATALOG_PATH");
  }
  // Writes {"motors": [...], "escs": [...]} to root/dir/file and returns root/dir.
  std::string Write(const std::string& dir, const std::string& file, const std::string& motors,
                    const std::string& escs = "") {
    fs::create_directories(root_ / dir);
    std::ofstream(root_ / dir / file) << R"({"motors": [)" << motors << R"(], "escs": [)" << escs << "]}";
    return (root_ / dir).string();
  }
  fs::path root_;
};

TEST_F(AddedCatalogFolders, AddedFolderJoinsTheBase) {
  const std::string base = Write("base", "a.json", Motor("m1", 0.1), Esc("e1"));
  const std::string mine = Write("mine", "b.json", Motor("m2", 0.2));
  const Catalog c = Catalog::Load(CatalogFolders{base, {mine}, false});
  EXPECT_EQ(c.motors().size(), 2u);
  EXPECT_EQ(c.motor("m2").file, mine + "/b.json");
  EXPECT_EQ(c.motor("m1").file, base + "/a.json");
}

TEST_F(AddedCatalogFolders, ClashingIdIsAnErrorNamingBothFiles) {
  const std::string base = Write("base", "a.json", Motor("m1", 0.1), Esc("e1"));
  const std::string mine = Write("mine", "b.json", Motor("m1", 0.2));
  try {
    Catalog::Load(CatalogFolders{base, {mine}, false});
    FAIL() << "a clashing id was accepted";
  } catch (const DataError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(mine + "/b.json: motors[0] id=m1: key 'id'"), std::string::npos) << m;
    EXPECT_NE(m.find("clashes with " + base + "/a.json: motors[0] id=m1"), std::string::npos) << m;
    EXPECT_NE(m.find("--override"), std::string::npos) << m;
    EXPECT_EQ(e.code(), ExitCode::kDataError);
  }
  // Validate lists the same problem.
  const auto problems = Catalog::Validate(CatalogFolders{base, {mine}, false});
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("clashes with"), std::string::npos);
}

TEST_F(AddedCatalogFolders, OverrideLetsTheAddedEntryWin) {
  const std::string base = Write("base", "a.json", Motor("m1", 0.1) + "," + Motor("m0", 0.3), Esc("e1"));
  const std::string first = Write("first", "b.json", Motor("m1", 0.2));
  const std::string second = Write("second", "c.json", Motor("m1", 0.25));
  const Catalog one = Catalog::Load(CatalogFolders{base, {first}, true}, /*in_system_law=*/false);
  EXPECT_EQ(one.motors().size(), 2u);  // replaced, not added
  EXPECT_EQ(one.motor("m1").params.rm_ohm, 0.2);
  EXPECT_EQ(one.motor("m1").file, first + "/b.json");
  EXPECT_EQ(one.motor("m0").params.rm_ohm, 0.3);  // the others untouched
  // A later added folder wins over an earlier one.
  const Catalog two = Catalog::Load(CatalogFolders{base, {first, second}, true}, false);
  EXPECT_EQ(two.motor("m1").params.rm_ohm, 0.25);
  EXPECT_EQ(two.motors().size(), 2u);
}

TEST_F(AddedCatalogFolders, OverrideKeepsTheOtherRules) {
  const std::string base = Write("base", "a.json", Motor("m1", 0.1), Esc("e1"));
  // Another kind under the same id: still an error.
  const std::string kind = Write("kind", "b.json", "", Esc("m1"));
  try {
    Catalog::Load(CatalogFolders{base, {kind}, true});
    FAIL() << "an ESC replaced a motor";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot override " + base + "/a.json: motors[0] id=m1: motor there, ESC "
                                         "here (an override must be of the same kind)"),
              std::string::npos)
        << e.what();
  }
  // Twice in one added folder: a duplicate, whatever --override says.
  const std::string dup = Write("dup", "b.json", Motor("m2", 0.1) + "," + Motor("m2", 0.2));
  EXPECT_THROW(Catalog::Load(CatalogFolders{base, {dup}, true}), DataError);
  // An added entry that breaks a rule does not replace the base entry.
  const std::string bad = Write("bad", "b.json", Motor("m1", -1.0));
  const auto problems = Catalog::Validate(CatalogFolders{base, {bad}, true});
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("key 'rm_ohm'"), std::string::npos) << problems[0];
}

TEST_F(AddedCatalogFolders, MissingOrEmptyAddedFolderIsReported) {
  const std::string base = Write("base", "a.json", Motor("m1", 0.1), Esc("e1"));
  try {
    Catalog::Load(CatalogFolders{base, {(root_ / "nope").string()}, false});
    FAIL();
  } catch (const NoInputError& e) {
    EXPECT_NE(std::string(e.what()).find((root_ / "nope").string() + ": no such catalog folder"), std::string::npos);
  }
  fs::create_directories(root_ / "empty");
  try {
    Catalog::Load(CatalogFolders{base, {(root_ / "empty").string()}, false});
    FAIL();
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("empty: the catalog folder holds no .json file"), std::string::npos);
  }
}

TEST(CatalogPath, SplitSkipsEmptyElements) {
  EXPECT_EQ(SplitCatalogPath(""), std::vector<std::string>{});
  EXPECT_EQ(SplitCatalogPath("a"), std::vector<std::string>{"a"});
  EXPECT_EQ(SplitCatalogPath(":a::b c:"), (std::vector<std::string>{"a", "b c"}));
}

TEST_F(AddedCatalogFolders, EnvironmentFoldersComeBeforeTheCommandLine) {
  setenv("DYNOSIZE_CATALOG_PATH", "/x:/y", 1);
  const CatalogFolders f = ResolveCatalogFolders("/base", {"/z"}, true);
  EXPECT_EQ(f.base, "/base");
  EXPECT_EQ(f.added, (std::vector<std::string>{"/x", "/y", "/z"}));
  EXPECT_TRUE(f.override_ids);
  unsetenv("DYNOSIZE_CATALOG_PATH");
  EXPECT_EQ(ResolveCatalogFolders("/base", {}, false).added, std::vector<std::string>{});
}

TEST(CatalogPath, TheBuildTreeFindsTheSourceCatalog) {
  // The test binary lives in the build tree: the bundled catalog is the source tree's.
  if (const char* env = std::getenv("DYNOSIZE_CATALOG"); env && *env) GTEST_SKIP() << "DYNOSIZE_CATALOG is set";
  EXPECT_TRUE(fs::equivalent(BundledCatalogDir(), fs::path(DYNOSIZE_SOURCE_DIR) / "catalog"))
      << BundledCatalogDir();
  EXPECT_TRUE(fs::equivalent(ResolveCatalogFolders("", {}, false).base, fs::path(DYNOSIZE_SOURCE_DIR) / "catalog"));
  // An installed package's catalog (step 4) comes after the build tree's own.
  SetPackageCatalogDir(fs::temp_directory_path().string());
  EXPECT_TRUE(fs::equivalent(BundledCatalogDir(), fs::path(DYNOSIZE_SOURCE_DIR) / "catalog"));
  SetPackageCatalogDir("");
}

}  // namespace
}  // namespace dynosize
