// Fuzz target: the strict mission reader (mission/mission.h ReadMission), the path `evaluate`
// and `optimize` take for their MISSION argument.
#include "fuzz_reader.h"
#include "mission/mission.h"

DYNOSIZE_FUZZ_READER(".json", { (void)dynosize::ReadMission(path); })
