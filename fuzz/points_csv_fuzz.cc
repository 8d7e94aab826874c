// Fuzz target: the batch point list of `dynosize simulate --batch` (io/points_csv.h).
#include "fuzz_reader.h"
#include "io/points_csv.h"

DYNOSIZE_FUZZ_READER(".csv", {
  for (const auto& r : dynosize::ReadPointsCsv(path)) (void)dynosize::CheckPointRequest(r);
})
