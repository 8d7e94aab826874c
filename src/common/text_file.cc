#include "common/text_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace dynosize {

std::string ReadTextFile(const std::string& path, std::size_t max_bytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    throw NoInputError(path + ": no such file");
  }
  if (std::filesystem::is_directory(status)) {
    throw NoInputError(path + ": is a folder, expected a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw NoInputError(path + ": cannot open: " + std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw NoInputError(path + ": cannot read its size");
  if (static_cast<std::size_t>(size) > max_bytes) {
    throw DataError(path + ": " + std::to_string(size) + " bytes: larger than the limit of " +
                    std::to_string(max_bytes) + " bytes for this kind of file");
  }
  in.seekg(0, std::ios::beg);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (size > 0 && !in.read(&text[0], size)) throw NoInputError(path + ": read failed");
  return text;
}

void WriteFileAtomic(const std::string& path, const std::string& content) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string tmpl = (dir / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = mkstemp(&tmpl[0]);
  if (fd < 0) {
    throw CantCreateError(path + ": cannot create a temporary file in " + dir.string() + ": " +
                          std::strerror(errno));
  }
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string reason = std::strerror(errno);
      ::close(fd);
      ::unlink(tmpl.c_str());
      throw CantCreateError(path + ": write failed: " + reason);
    }
    written += static_cast<std::size_t>(n);
  }
  // mkstemp creates 0600; give the file the usual permissions (subject to umask).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(tmpl.c_str());
    throw CantCreateError(path + ": cannot flush to disk: " + reason);
  }
  if (std::rename(tmpl.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(tmpl.c_str());
    throw CantCreateError(path + ": cannot rename the temporary file into place: " + reason);
  }
}

FileLock::FileLock(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const std::string lock_path =
      (target.parent_path() / ("." + target.filename().string() + ".lock")).string();
  fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd_ < 0) {
    throw CantCreateError(lock_path + ": cannot create the lock file: " + std::strerror(errno));
  }
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno == EINTR) continue;
    const std::string reason = std::strerror(errno);
    ::close(fd_);
    throw CantCreateError(lock_path + ": cannot lock: " + reason);
  }
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

void MakeOutputDir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw CantCreateError(dir + ": cannot create output folder: " +
                          (ec ? ec.message() : std::string("not a folder")));
  }
}

}  // namespace dynosize
