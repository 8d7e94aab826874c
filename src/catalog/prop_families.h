// The catalog's "prop_families" (catalog/catalog.h): propeller families offered to the search with
// their sizes free (rotor/family.h PropSizing, issue 52 item 5). One entry:
//
//   {"id": "fam_multirotor_carbon", "name": "...", "family": "multirotor",
//    "diameter_m": [0.508, 1.575], "pitch_ratio": [0.30, 0.45], "blades": [2],
//    "source": {"dataset": "...", "reference": "...", "note": "..."}}
//
// Strict like the rest of the catalog: unknown keys, missing keys, wrong types, ranges out of
// bounds (CheckPropSizing), an unknown family and a repeated id are problems naming the file, the
// entry and the rule.
#pragma once

#include <string>
#include <vector>

#include "common/json_file.h"
#include "rotor/family.h"

namespace dynosize {

// Appends the valid entries of `arr` (the document's "prop_families") to *out (an id already in
// *out is a problem) and one line per problem to *problems.
void ReadPropFamilies(const Json& arr, const std::string& file, std::vector<PropSizing>* out,
                      std::vector<std::string>* problems);

}  // namespace dynosize
