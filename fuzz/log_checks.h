// What a log read must give whenever it does not refuse (logs/log_reader.h): a table of at
// least 2 rows whose present columns all have one finite value per row, and no values in the
// absent ones. A violation aborts the fuzz target (a finding).
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "logs/log_reader.h"

namespace dynosize::fuzz {

inline void CheckTable(const logs::SteadyTable& t) {
  auto fail = [](const char* what, int column) {
    std::fprintf(stderr, "fuzz: log table invariant broken: %s (column %d)\n", what, column);
    std::abort();
  };
  if (t.rows() < 2) fail("fewer than 2 rows returned", -1);
  if (t.samples.size() != t.rows()) fail("samples size", -1);
  for (int c = 0; c < logs::kColumnCount; ++c) {
    const auto& v = t.columns[c];
    if (!t.info[c].present) {
      if (!v.empty()) fail("values in an absent column", c);
      continue;
    }
    if (v.size() != t.rows()) fail("column size differs from rows()", c);
    for (const double x : v) {
      if (!std::isfinite(x)) fail("non-finite value", c);
    }
  }
}

}  // namespace dynosize::fuzz
