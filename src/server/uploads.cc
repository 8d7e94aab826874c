#include "server/uploads.h"

#include <stdlib.h>  // mkdtemp (POSIX)

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "common/error.h"

namespace dynosize::server {

namespace fs = std::filesystem;

std::string CheckedLogName(const std::string& name, const std::string& what) {
  const auto allowed = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::string("._- ()+,").find(c) != std::string::npos;
  };
  if (name.empty() || name.size() > 200 || name.front() == '.' || !std::all_of(name.begin(), name.end(), allowed)) {
    throw UsageError(what + " \"" + name.substr(0, 60) +
                     "\": a log's name must be 1-200 letters, digits, '.', '_', '-', ' ', '(', ')', '+', ',' "
                     "not starting with '.' (a file name without folders)");
  }
  return name;
}

std::string DecodeBase64(const std::string& text, const std::string& what) {
  std::string out;
  out.reserve(text.size() * 3 / 4);
  unsigned int bits = 0;
  int count = 0;
  bool padded = false;
  for (char c : text) {
    int v = -1;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    if (c >= '0' && c <= '9') v = c - '0' + 52;
    if (c == '+') v = 62;
    if (c == '/') v = 63;
    if (c == '=') {
      padded = true;
      continue;
    }
    if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    if (v < 0 || padded) throw UsageError(what + ": not base64 (a character '" + std::string(1, c) + "')");
    bits = (bits << 6) | static_cast<unsigned int>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<char>((bits >> count) & 0xFFu));
    }
  }
  return out;
}

UploadFolder::UploadFolder() {
  std::error_code ec;
  std::string pattern = (fs::temp_directory_path(ec) / "dynosize-serve-XXXXXX").string();
  if (ec || mkdtemp(pattern.data()) == nullptr) {
    throw CantCreateError("serve: cannot create a temporary folder for the uploaded logs (" + pattern + ")");
  }
  dir_ = pattern;
}

UploadFolder::~UploadFolder() {
  std::error_code ec;
  fs::remove_all(dir_, ec);  // nothing to do about a failure here: the folder is private
}

std::string UploadFolder::Write(const UploadedLog& log) {
  if (std::find(names_.begin(), names_.end(), log.name) != names_.end()) {
    throw UsageError("logs: two logs named '" + log.name + "': give each its own name");
  }
  names_.push_back(log.name);
  const std::string path = dir_ + "/" + log.name;
  std::ofstream out(path, std::ios::binary);
  out << log.bytes;
  out.close();
  if (!out) throw CantCreateError("serve: cannot write the uploaded log '" + log.name + "' to " + dir_);
  return path;
}

std::string UploadFolder::Strip(std::string text) const {
  const std::string prefix = dir_ + "/";
  for (auto at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at)) text.erase(at, prefix.size());
  return text;
}

}  // namespace dynosize::server
