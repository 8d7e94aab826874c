// The figure of docs/in-system-law.md: every KDE sheet point's measured DC current against the
// prediction from the motor's datasheet values as they are (the plain DC model) and through the
// in-system law fitted without that motor, with the p10-p90 range (stand/in_system_fit.h).
#pragma once

#include <string>
#include <vector>

#include "stand/in_system_fit.h"

namespace dynosize {

// Writes png_path (and its .gp script); throws CantCreateError when gnuplot fails.
void WriteInSystemLawFigure(const std::vector<stand::LawMotor>& motors, const stand::LawReport& report,
                            const std::string& png_path);

}  // namespace dynosize
