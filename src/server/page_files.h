// The page's files (web/: index.html, app.js, style.css and Chart.js, copied into the build or
// install tree) as `dynosize serve` serves them: read once at start into memory, served only by
// their exact names. A request's path is looked up in that list, never joined to a folder, so no
// path (../, %2e%2e, symlinks, absolute paths) can reach a file outside the page's folder.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace dynosize::server {

struct PageFile {
  std::string content;
  std::string content_type;
};

class PageFiles {
 public:
  // Reads every regular file under `dir` (not following symlinked folders). Throws NoInputError
  // when `dir` is not a folder holding index.html.
  static PageFiles Load(const std::string& dir);
  // The file served at a request path ("/" is "/index.html"); null when there is none.
  const PageFile* Find(const std::string& path) const;
  std::size_t size() const { return files_.size(); }
  // The names (without ".json") of the example missions, the files under /examples/, sorted.
  std::vector<std::string> ExampleNames() const;

 private:
  std::map<std::string, PageFile> files_;  // "/app.js" -> file
};

// The content type of a file name by its extension (text types in UTF-8); application/octet-stream
// for any other.
std::string ContentTypeOf(const std::string& name);

// The page's folder when the user names none, the first that holds index.html of:
//   1. $DYNOSIZE_WEB_DIR when set and not empty;
//   2. <dir of the running program>/../share/dynosize/web (an installed dynosize);
//   3. <dir of the running program>/web (the build tree: CMake copies web/ there).
// "" when none does.
std::string DefaultPageDir();

}  // namespace dynosize::server
