// Tests that need a solver backend skip, with the reason, in a build that left it out
// (-DDYNOSIZE_WITH_IPOPT=OFF, -DDYNOSIZE_WITH_NLOPT=OFF: solvers/solver.h IsAlgorithmAvailable).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "solvers/solver.h"

// Use at the top of a test body: DYNOSIZE_SKIP_UNLESS_AVAILABLE("ipopt");
#define DYNOSIZE_SKIP_UNLESS_AVAILABLE(algorithm)                                \
  do {                                                                           \
    std::string dynosize_unavailable_why;                                        \
    if (!::dynosize::IsAlgorithmAvailable(algorithm, &dynosize_unavailable_why)) \
      GTEST_SKIP() << dynosize_unavailable_why;                                  \
  } while (0)
