// Logs sent to `dynosize serve` (calibrate, diagnose) as files for the log readers, which read
// files: each request gets a private folder under the system's temporary folder (mkdtemp, mode
// 0700), removed with everything in it when the request ends. A log's name is the base name the
// user gave, checked (no folders, no leading dot), so that the answer names the file as the CLI
// would name a file of that name in the working directory.
#pragma once

#include <string>
#include <vector>

namespace dynosize::server {

// One uploaded log: its name and its bytes (the body's "text", or "base64" decoded).
struct UploadedLog {
  std::string name;
  std::string bytes;
};

// The name checked: 1-200 characters of letters, digits, '.', '_', '-', ' ', '(', ')', '+', ','
// not starting with '.'. Throws UsageError naming `what` otherwise.
std::string CheckedLogName(const std::string& name, const std::string& what);

// Standard base64 (RFC 4648, padding optional, whitespace ignored). Throws UsageError naming
// `what` for any other character.
std::string DecodeBase64(const std::string& text, const std::string& what);

class UploadFolder {
 public:
  UploadFolder();  // throws CantCreateError when the folder cannot be made
  ~UploadFolder();
  UploadFolder(const UploadFolder&) = delete;
  UploadFolder& operator=(const UploadFolder&) = delete;
  // Writes the log and returns its path. Throws UsageError for a name already written.
  std::string Write(const UploadedLog& log);
  // `text` with every occurrence of the folder's path and its '/' removed: messages and documents
  // name the logs as the user named them.
  std::string Strip(std::string text) const;

 private:
  std::string dir_;
  std::vector<std::string> names_;
};

}  // namespace dynosize::server
