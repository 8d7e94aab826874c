// Built instead of nlopt_solver.cc when CMake is configured with -DDYNOSIZE_WITH_NLOPT=OFF
// (Drake's no_ipopt.cc pattern): the algorithms "nlopt_*" are known but not available.
#include "common/error.h"
#include "solvers/backends.h"

namespace dynosize {
namespace solvers_internal {

bool NloptBuilt() { return false; }

SolverResult RunNlopt(const Problem&, const SolverOptions&, const std::string& algorithm) {
  throw UnavailableError(NotBuiltMessage("NLopt", "DYNOSIZE_WITH_NLOPT", algorithm));
}

}  // namespace solvers_internal
}  // namespace dynosize
