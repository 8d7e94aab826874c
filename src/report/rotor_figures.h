// The figure of docs/validation.md's "Propellers from their geometry": every UIUC static point's
// measured CT and CP against the blade-element model's (rotor/validation.h), each family
// predicted by the polar fitted without it.
#pragma once

#include <string>

#include "rotor/validation.h"

namespace dynosize {

// Writes png_path (and its .gp script); throws CantCreateError when gnuplot fails.
void WriteRotorValidationFigure(const LeaveFamilyOutReport& report, const std::string& png_path);

}  // namespace dynosize
