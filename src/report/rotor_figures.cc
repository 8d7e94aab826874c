#include "report/rotor_figures.h"

#include "common/text_format.h"
#include "report/gnuplot.h"

namespace dynosize {

void WriteRotorValidationFigure(const LeaveFamilyOutReport& r, const std::string& png_path) {
  // Columns: measured, model (static CT; static CP; sweep efficiency).
  std::vector<std::vector<double>> ct(2), cp(2), eta(2);
  for (const CasePrediction& p : r.left_out_points) {
    if (p.measured.j == 0.0) {
      ct[0].push_back(p.measured.ct);
      ct[1].push_back(p.model.ct);
      cp[0].push_back(p.measured.cp);
      cp[1].push_back(p.model.cp);
    } else {
      eta[0].push_back(p.measured.eta);
      eta[1].push_back(p.model.efficiency);
    }
  }
  const std::vector<DataBlock> blocks = {{"ct", {ct}, false}, {"cp", {cp}, false}, {"eta", {eta}, false}};
  const std::string body =
      "set multiplot layout 1,3 title \"UIUC propellers from their geometry, each family predicted by the polar "
      "fitted without it\\nmedian error: static CT " + PercentText(r.left_out.ct_median) + ", CP " +
      PercentText(r.left_out.cp_median) + ", sweep efficiency " + FixedText(r.left_out.eta_median, 3) + "\"\n"
      "set grid\nset key inside top left box opaque\n"
      "set xlabel 'measured CT (static)'\nset ylabel 'model CT'\nset xrange [0:0.25]\nset yrange [0:0.25]\n"
      "plot $ct using 1:2 with points pt 7 ps 0.4 lc rgb '#1f77b4' title 'static points', x lc rgb 'black' title 'exact', "
      "1.1*x dt 2 lc rgb 'gray' title '+-10 %', 0.9*x dt 2 lc rgb 'gray' notitle\n"
      "set xlabel 'measured CP (static)'\nset ylabel 'model CP'\nset xrange [0:0.15]\nset yrange [0:0.15]\n"
      "plot $cp using 1:2 with points pt 7 ps 0.4 lc rgb '#d62728' title 'static points', x lc rgb 'black' title 'exact', "
      "1.1*x dt 2 lc rgb 'gray' title '+-10 %', 0.9*x dt 2 lc rgb 'gray' notitle\n"
      "set xlabel 'measured efficiency (J sweeps)'\nset ylabel 'model efficiency'\nset xrange [0:1]\nset yrange [0:1]\n"
      "plot $eta using 1:2 with points pt 7 ps 0.4 lc rgb '#2ca02c' title 'sweep points', x lc rgb 'black' title 'exact', "
      "x+0.05 dt 2 lc rgb 'gray' title '+-0.05', x-0.05 dt 2 lc rgb 'gray' notitle\n"
      "unset multiplot\n";
  RenderPng(png_path, blocks, body, 1500, 600);
}

}  // namespace dynosize
