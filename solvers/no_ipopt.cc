// Built instead of ipopt_solver.cc when CMake is configured with -DDYNOSIZE_WITH_IPOPT=OFF
// (Drake's no_ipopt.cc pattern): the algorithm "ipopt" is known but not available.
#include "common/error.h"
#include "solvers/backends.h"

namespace dynosize {
namespace solvers_internal {

bool IpoptBuilt() { return false; }

SolverResult RunIpopt(const Problem&, const SolverOptions&) {
  throw UnavailableError(NotBuiltMessage("Ipopt", "DYNOSIZE_WITH_IPOPT", "ipopt"));
}

}  // namespace solvers_internal
}  // namespace dynosize
