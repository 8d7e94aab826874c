// The paper's figures for one motor + ESC pair at one supply voltage, as PNG files:
//   torque_power_vs_rpm.png        Q and Pm vs rpm per throttle (Fig. 25; eqs 49, 50)
//   vll_rms_vs_irms.png            VLL,rms vs Irms per throttle (Fig. 22; eq 47)
//   idc_over_irms_vs_throttle.png  IDC/Irms vs throttle, ESC vs ideal (Figs. 28-30; eqs 56, 57, 62)
//   efficiency_vs_rpm.png          motor, ESC and system efficiency vs rpm (Fig. 7 analogue)
//   efficiency_map.png             system efficiency over torque and rpm with the optimum line
// Efficiencies are never clipped: values above 100 % (parameters that create energy, docs/model.md
// section 10) widen the axis / colour range and are marked against a dashed 100 % line.
#pragma once

#include <string>
#include <vector>

#include "model/drive.h"

namespace dynosize {

struct DriveFigureOptions {
  double vdc_v = 0.0;
  std::string title;     // e.g. "EMAX 1900 KV + MultiStar 30 A"
  std::string esc_name;  // for the ESC-only figure
  int throttle_steps = 10;
  // Curves stop at this current; <= 0 means CurrentLimit() of model/sweep.h.
  double current_limit_a = 0.0;
};

// Writes the figures (and their gnuplot scripts) into `dir`, creating it; returns the PNG paths.
std::vector<std::string> WriteDriveFigures(const Drive& drive, const DriveFigureOptions& options,
                                           const std::string& dir);

}  // namespace dynosize
