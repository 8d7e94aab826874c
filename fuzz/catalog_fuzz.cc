// Fuzz target: the strict catalog reader (common/json_file.h + catalog/catalog.h AddDocument),
// exactly the path `Catalog::Load` takes per file.
#include "catalog/catalog.h"
#include "fuzz_reader.h"

DYNOSIZE_FUZZ_READER(".json", {
  dynosize::JsonReadOptions jo;
  jo.max_bytes = 1 << 20;
  const dynosize::Json doc = dynosize::ReadJsonFile(path, jo);
  dynosize::Catalog c;
  std::vector<std::string> problems;
  c.AddDocument(doc, path, &problems);
})
