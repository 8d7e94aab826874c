// Where the catalog is found when the user names none, and the folders of the user's own parts
// added on top of it (docs/catalog.md). One rule for the CLI and for programs that use the
// library.
#pragma once

#include <string>
#include <vector>

namespace dynosize {

// Where a catalog is read from: a base folder (the bundled catalog, or the one the user names
// instead) and folders of the user's own parts added on top of it, read in order. Ids are unique
// across all of them: an added entry whose id an earlier folder already holds is an error naming
// both files, unless override_ids lets the added entry replace the earlier one (same kind only;
// a later added folder wins over an earlier one). ResolveCatalogFolders below fills it from the
// command line and the environment; Catalog::Load reads it.
struct CatalogFolders {
  std::string base;
  std::vector<std::string> added;
  bool override_ids = false;
};

// The bundled catalog folder, the first of:
//   1. $DYNOSIZE_CATALOG when set and not empty (it replaces the bundled catalog);
//   2. <dir of the running program>/../share/dynosize/catalog: a program installed with the
//      package (the dynosize CLI, or a user's program installed into the same prefix);
//   3. the source tree's catalog/ when the running program lives in the build tree it was built in;
//   4. the catalog of the installed package the program was built against (SetPackageCatalogDir:
//      <dynosize/dynosize.h> sets it from the location find_package(dynosize) found);
//   5. <install prefix>/share/dynosize/catalog of the prefix the build was configured with;
//   6. the source tree's catalog/;
//   7. "catalog" (relative to the working directory).
// Only folders that exist are taken at steps 2-6.
std::string BundledCatalogDir();

// Step 4 of BundledCatalogDir. A program built against the installed package gets it from
// dynosizeConfig.cmake (the compile definition DYNOSIZE_PACKAGE_CATALOG_DIR of dynosize::dynosize)
// through <dynosize/dynosize.h>, before main; "" clears it.
void SetPackageCatalogDir(const std::string& dir);

// The folders of a colon-separated path (DYNOSIZE_CATALOG_PATH), in order; empty elements (a
// leading, trailing or doubled colon) are skipped.
std::vector<std::string> SplitCatalogPath(const std::string& path);

// The folders a command reads: `base_dir` (BundledCatalogDir() when empty), then the folders of
// $DYNOSIZE_CATALOG_PATH, then `added` (so that with override_ids the command line wins over the
// environment).
CatalogFolders ResolveCatalogFolders(const std::string& base_dir, const std::vector<std::string>& added,
                                     bool override_ids);

}  // namespace dynosize
