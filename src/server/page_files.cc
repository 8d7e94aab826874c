#include "server/page_files.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "common/error.h"

namespace dynosize::server {

namespace fs = std::filesystem;

namespace {

bool HoldsIndex(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "index.html", ec);
}

}  // namespace

std::string ContentTypeOf(const std::string& name) {
  const std::string ext = fs::path(name).extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".ico") return "image/x-icon";
  return "application/octet-stream";
}

PageFiles PageFiles::Load(const std::string& dir) {
  if (dir.empty() || !HoldsIndex(dir)) {
    throw NoInputError("the web page's folder " + (dir.empty() ? std::string("(none found)") : "'" + dir + "'") +
                       " does not hold index.html: build the target dynosize (it copies web/ beside the "
                       "program), or name the folder with --web-dir or $DYNOSIZE_WEB_DIR");
  }
  PageFiles out;
  std::error_code ec;
  const fs::path root = fs::path(dir);
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (!it->is_regular_file(ec) || it->is_symlink(ec)) continue;
    std::ifstream in(it->path(), std::ios::binary);
    if (!in) throw NoInputError(it->path().string() + ": cannot be read");
    std::ostringstream text;
    text << in.rdbuf();
    const std::string rel = "/" + it->path().lexically_relative(root).generic_string();
    out.files_[rel] = PageFile{text.str(), ContentTypeOf(rel)};
  }
  if (ec) throw NoInputError(dir + ": cannot be listed: " + ec.message());
  return out;
}

const PageFile* PageFiles::Find(const std::string& path) const {
  const auto it = files_.find(path == "/" ? "/index.html" : path);
  return it == files_.end() ? nullptr : &it->second;
}

std::vector<std::string> PageFiles::ExampleNames() const {
  const std::string prefix = "/examples/", suffix = ".json";
  std::vector<std::string> names;
  for (const auto& [path, file] : files_) {
    if (path.rfind(prefix, 0) != 0 || path.size() <= prefix.size() + suffix.size()) continue;
    if (path.compare(path.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    const std::string name = path.substr(prefix.size(), path.size() - prefix.size() - suffix.size());
    if (name.find('/') == std::string::npos) names.push_back(name);
  }
  return names;  // in the map's order: sorted
}

std::string DefaultPageDir() {
  if (const char* env = std::getenv("DYNOSIZE_WEB_DIR"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);  // Linux's name of the running program
  if (ec) return "";
  for (const fs::path& dir : {exe.parent_path().parent_path() / "share" / "dynosize" / "web", exe.parent_path() / "web"}) {
    if (HoldsIndex(dir)) return dir.string();
  }
  return "";
}

}  // namespace dynosize::server
