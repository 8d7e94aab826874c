// Error types of dynosize and the exit codes the CLI maps them to.
//
// Three tiers, as in Drake: bad user input throws one of the classes below with a message
// that names the file, row or JSON path, the value and the rule; a broken internal invariant
// is a bug (InternalError, exit 70); a numerical outcome (infeasible, not converged) is a
// status in a result struct, never an exception.
//
// Exit codes follow sysexits.h (docs/usage.md lists them).
#pragma once

#include <stdexcept>
#include <string>

namespace dynosize {

enum class ExitCode : int {
  kOk = 0,
  kUsage = 64,        // EX_USAGE: bad command line (unknown flag, value out of range)
  kDataError = 65,    // EX_DATAERR: bad input data (catalog, log, mission)
  kNoInput = 66,      // EX_NOINPUT: an input file or folder does not exist / cannot be read
  kUnavailable = 69,  // EX_UNAVAILABLE: a solver backend this build left out (solvers/solver.h)
  kInternal = 70,     // EX_SOFTWARE: a bug
  kCantCreate = 73,   // EX_CANTCREAT: an output file cannot be written
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

// A value on the command line (or passed to the library by a caller) breaks a rule.
class UsageError : public Error {
 public:
  explicit UsageError(const std::string& m) : Error(ExitCode::kUsage, m) {}
};

// An input file's content breaks a rule (catalog JSON, a log, a mission).
class DataError : public Error {
 public:
  explicit DataError(const std::string& m) : Error(ExitCode::kDataError, m) {}
};

// An input file or folder is missing or unreadable.
class NoInputError : public Error {
 public:
  explicit NoInputError(const std::string& m) : Error(ExitCode::kNoInput, m) {}
};

// An output file cannot be created or renamed into place.
class CantCreateError : public Error {
 public:
  explicit CantCreateError(const std::string& m) : Error(ExitCode::kCantCreate, m) {}
};

// A feature this build of dynosize left out: a solver backend switched off at configure time
// (-DDYNOSIZE_WITH_IPOPT=OFF or -DDYNOSIZE_WITH_NLOPT=OFF, solvers/solver.h).
class UnavailableError : public Error {
 public:
  explicit UnavailableError(const std::string& m) : Error(ExitCode::kUnavailable, m) {}
};

// A broken internal invariant: a bug in dynosize, not in the input.
class InternalError : public Error {
 public:
  explicit InternalError(const std::string& m) : Error(ExitCode::kInternal, m) {}
};

}  // namespace dynosize
