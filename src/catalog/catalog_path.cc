#include "catalog/catalog_path.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace dynosize {

namespace {

namespace fs = std::filesystem;

bool IsFolder(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

// The running program's folder ("" when the system does not say: /proc/self/exe is Linux's).
fs::path ProgramDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

// Whether `dir` is `root` or below it (both made absolute and normal).
bool IsBelow(const fs::path& dir, const fs::path& root) {
  std::error_code ec;
  const fs::path d = fs::weakly_canonical(dir, ec);
  if (ec) return false;
  const fs::path r = fs::weakly_canonical(root, ec);
  if (ec) return false;
  const auto mismatch = std::mismatch(r.begin(), r.end(), d.begin(), d.end());
  return mismatch.first == r.end();
}

std::string& PackageCatalogDir() {
  static std::string dir;
  return dir;
}

}  // namespace

void SetPackageCatalogDir(const std::string& dir) { PackageCatalogDir() = dir; }

std::string BundledCatalogDir() {
  if (const char* env = std::getenv("DYNOSIZE_CATALOG"); env && *env) return env;
  const fs::path source_catalog = DYNOSIZE_SOURCE_CATALOG;
  const fs::path program_dir = ProgramDir();
  if (!program_dir.empty()) {
    const fs::path installed = program_dir.parent_path() / "share" / "dynosize" / "catalog";
    if (IsFolder(installed)) return installed.string();
    if (IsBelow(program_dir, DYNOSIZE_BUILD_DIR) && IsFolder(source_catalog)) return source_catalog.string();
  }
  if (const std::string& package = PackageCatalogDir(); !package.empty() && IsFolder(package)) return package;
  if (IsFolder(DYNOSIZE_INSTALL_CATALOG)) return DYNOSIZE_INSTALL_CATALOG;
  if (IsFolder(source_catalog)) return source_catalog.string();
  return "catalog";
}

std::vector<std::string> SplitCatalogPath(const std::string& path) {
  std::vector<std::string> folders;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    std::size_t end = path.find(':', begin);
    if (end == std::string::npos) end = path.size();
    if (end > begin) folders.push_back(path.substr(begin, end - begin));
    begin = end + 1;
  }
  return folders;
}

CatalogFolders ResolveCatalogFolders(const std::string& base_dir, const std::vector<std::string>& added,
                                     bool override_ids) {
  CatalogFolders f;
  f.base = base_dir.empty() ? BundledCatalogDir() : base_dir;
  if (const char* env = std::getenv("DYNOSIZE_CATALOG_PATH"); env) f.added = SplitCatalogPath(env);
  f.added.insert(f.added.end(), added.begin(), added.end());
  f.override_ids = override_ids;
  return f;
}

}  // namespace dynosize
