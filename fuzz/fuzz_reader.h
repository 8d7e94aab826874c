// The template of every dynosize fuzz target: libFuzzer hands us bytes, the reader under test
// gets them as a file (the readers take paths, as the CLI does), and the only acceptable
// outcomes are a result or a dynosize::Error (bad input: one line, a documented exit code).
// Anything else is a finding: a crash or a sanitizer report (ASan/UBSan abort the process), an
// exception of another type (the CLI would report it as "internal error", exit 70: abort here),
// an empty error message, or a message that spans lines.
//
// A new reader is one file, fuzz/<name>_fuzz.cc:
//
//   #include "fuzz_reader.h"
//   #include "mission/mission.h"
//   DYNOSIZE_FUZZ_READER(".json", { (void)dynosize::ReadMission(path); })
//
// CMake builds every fuzz/*_fuzz.cc with -DDYNOSIZE_FUZZ=ON (clang); scripts/fuzz.sh runs it,
// seeded from ../shared/data and examples/ (scripts/fuzz_seeds.txt).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "common/error.h"

namespace dynosize::fuzz {

// A per-process file in $TMPDIR (libFuzzer -jobs/-workers run several processes).
inline std::string InputPath(const char* suffix) {
  const char* tmp = std::getenv("TMPDIR");
  return std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/dynosize_fuzz_" +
         std::to_string(getpid()) + suffix;
}

inline void WriteInput(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
}

template <typename Read>
int RunReader(const char* suffix, const std::uint8_t* data, std::size_t size, Read read) {
  static const std::string path = InputPath(suffix);
  WriteInput(path, data, size);
  try {
    read(path);
  } catch (const dynosize::Error& e) {
    const std::string m = e.what();
    if (m.empty() || m.find('\n') != std::string::npos) {
      std::fprintf(stderr, "fuzz: error message empty or not one line:\n%s\n", m.c_str());
      std::abort();
    }
    if (e.code() == dynosize::ExitCode::kInternal) {
      std::fprintf(stderr, "fuzz: InternalError (a bug) on input: %s\n", m.c_str());
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: exception outside dynosize::Error: %s\n", e.what());
    std::abort();
  }
  return 0;
}

}  // namespace dynosize::fuzz

// Defines LLVMFuzzerTestOneInput: the body (a braced block, commas allowed) sees
// `const std::string& path` (the input file).
#define DYNOSIZE_FUZZ_READER(SUFFIX, ...)                                              \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    return dynosize::fuzz::RunReader(SUFFIX, data, size,                              \
                                     [](const std::string& path) __VA_ARGS__);        \
  }
