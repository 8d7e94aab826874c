// Internal to solvers/: what solver.cc needs from each backend. Includes no solver header.
#pragma once

#include <exception>
#include <string>

#include "solvers/problem.h"
#include "solvers/solver.h"

namespace dynosize {
namespace solvers_internal {

// Wraps the user's functions for a backend: counts evaluations, and stores the first exception
// a callback throws so the backend can be stopped and the exception rethrown after it returns
// (an exception must never unwind through Ipopt's or NLopt's C/Fortran frames).
struct CallbackGuard {
  const Problem& problem;
  int objective_evaluations = 0;
  int constraint_evaluations = 0;
  std::exception_ptr error;

  explicit CallbackGuard(const Problem& p) : problem(p) {}
  void RethrowIfAny() const {
    if (error) std::rethrow_exception(error);
  }
};

// Whether each backend is built in: defined by ipopt_solver.cc / nlopt_solver.cc (true) or, when
// CMake leaves a backend out (DYNOSIZE_WITH_IPOPT / DYNOSIZE_WITH_NLOPT OFF), by no_ipopt.cc /
// no_nlopt.cc (false), whose Run* throw UnavailableError with NotBuiltMessage.
bool IpoptBuilt();
bool NloptBuilt();
// "dynosize was not built with <backend> (-D<option>=OFF), which algorithm '<algorithm>' needs; ..."
std::string NotBuiltMessage(const char* backend, const char* option, const std::string& algorithm);

// A backend run: status as the backend reports it (the wrapper re-checks feasibility later),
// x, iterations, evaluation counts and message. Rethrows a callback's exception.
SolverResult RunIpopt(const Problem& problem, const SolverOptions& options);
SolverResult RunNlopt(const Problem& problem, const SolverOptions& options, const std::string& algorithm);

}  // namespace solvers_internal
}  // namespace dynosize
