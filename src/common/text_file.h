// Whole-file reads and atomic writes. Every file dynosize writes (catalog entries, reports,
// figures, CSV results) goes to a temporary file in the same folder that is renamed into place,
// so that a killed or failed run leaves the earlier file intact.
#pragma once

#include <cstddef>
#include <string>

namespace dynosize {

// Reads a whole file. Throws NoInputError when it is missing or unreadable (naming the path and
// the system's reason), DataError when it is larger than max_bytes.
std::string ReadTextFile(const std::string& path, std::size_t max_bytes);

// Writes `content` to `path` atomically: a temporary file beside it, flushed and fsynced, then
// rename(2). Throws CantCreateError naming the path and the reason.
void WriteFileAtomic(const std::string& path, const std::string& content);

// Creates a folder (and its parents) for output; CantCreateError when impossible.
void MakeOutputDir(const std::string& dir);

// An exclusive advisory lock (flock(2)) on ".<name>.lock" beside `path`, held for the object's lifetime, for
// read-modify-write of a shared file (calibrate --out adding entries to one catalog): runs
// that write the same file take turns instead of losing each other's entries. The lock file
// stays (removing it would race with a waiting run); the kernel releases the lock when the
// process ends, however it ends. Throws CantCreateError when the lock file cannot be created.
class FileLock {
 public:
  explicit FileLock(const std::string& path);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace dynosize
