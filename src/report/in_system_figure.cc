#include "report/in_system_figure.h"

#include <cmath>

#include "report/gnuplot.h"

namespace dynosize {

void WriteInSystemLawFigure(const std::vector<stand::LawMotor>& motors, const stand::LawReport& report,
                            const std::string& png_path) {
  // Columns: measured IDC, predicted/measured, low/measured, high/measured.
  std::vector<std::vector<double>> ds(2), law(4);
  for (std::size_t m = 0; m < motors.size() && m < report.left_out.size(); ++m) {
    const InSystemLaw& l = report.left_out[m].law;
    for (const auto& p : motors[m].points) {
      if (!(std::isfinite(p.torque_nm) && p.torque_nm > 0.0 && p.idc_a > 0.0)) continue;
      // Predicted over measured: 1 is exact.
      ds[0].push_back(p.idc_a);
      ds[1].push_back(stand::PredictIdc(motors[m], InSystemLaw{}, p) / p.idc_a);
      law[0].push_back(p.idc_a);
      law[1].push_back(stand::PredictIdc(motors[m], l, p) / p.idc_a);
      law[2].push_back(stand::PredictIdc(motors[m], l, p, l.r_ratio_p10, l.io_ratio_p10) / p.idc_a);
      law[3].push_back(stand::PredictIdc(motors[m], l, p, l.r_ratio_p90, l.io_ratio_p90) / p.idc_a);
    }
  }
  const std::vector<DataBlock> blocks = {{"ds", {ds}, false}, {"law", {law}, false}};
  const std::string body =
      "set title \"KDE Direct stand sheets: DC current at the measured speed and torque\\n" +
      std::to_string(ds[0].size()) + " points of " + std::to_string(report.left_out.size()) +
      " motors, each predicted by a law fitted without it\"\n"
      "set xlabel 'measured IDC [A]'\nset ylabel 'predicted / measured IDC'\n"
      "set logscale x\nset xrange [0.4:150]\nset yrange [0.5:1.5]\nset grid\n"
      "set key inside bottom right box opaque\n"
      "plot 1 title 'exact' lc rgb 'black' lw 2, "
      "$ds using 1:2 with points pt 7 ps 0.5 lc rgb '#d62728' title 'datasheet values (plain DC model)', "
      "$law using 1:2:3:4 with yerrorbars pt 7 ps 0.5 lc rgb '#1f77b4' "
      "title 'in-system law (bars: p10-p90)'\n";
  RenderPng(png_path, blocks, body, 1000, 750);
}

}  // namespace dynosize
