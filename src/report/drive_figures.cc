#include "report/drive_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/numbers.h"
#include "common/text_file.h"
#include "common/text_format.h"
#include "common/units.h"
#include "model/sweep.h"
#include "report/gnuplot.h"

namespace dynosize {

namespace {

constexpr int kPointsPerLine = 60;

// The torque range drawn for one throttle: from no load to the smaller of the stall torque and
// the torque at the current limit.
double MaxTorque(const Drive& d, double vdc_v, double throttle, double i_limit_a) {
  const double q_limit = d.motor().kt_nm_per_a * (i_limit_a - d.motor().io_a);
  return std::max(0.0, std::min(d.StallTorque(vdc_v, throttle), q_limit));
}

// One series per throttle, columns from `columns(point)`.
template <typename Columns>
DataBlock ThrottleLines(const Drive& d, const DriveFigureOptions& o, const std::string& name,
                        int ncols, Columns columns) {
  DataBlock b;
  b.name = name;
  for (int k = 1; k <= o.throttle_steps; ++k) {
    const double tr = static_cast<double>(k) / o.throttle_steps;
    const double q_max = MaxTorque(d, o.vdc_v, tr, o.current_limit_a);
    std::vector<std::vector<double>> cols(static_cast<std::size_t>(ncols));
    for (int i = 0; i <= kPointsPerLine; ++i) {
      const OperatingPoint p = d.AtTorque(o.vdc_v, tr, q_max * i / kPointsPerLine);
      const std::vector<double> row = columns(p);
      for (int c = 0; c < ncols; ++c) cols[static_cast<std::size_t>(c)].push_back(row[static_cast<std::size_t>(c)]);
    }
    b.series.push_back(std::move(cols));
  }
  return b;
}

// The largest finite value of the given columns over all series (0 when none).
double MaxFinite(const DataBlock& b, const std::vector<std::size_t>& columns) {
  double m = 0.0;
  for (const auto& series : b.series) {
    for (std::size_t c : columns) {
      for (double v : series[c]) {
        if (std::isfinite(v)) m = std::max(m, v);
      }
    }
  }
  return m;
}

// "plot for [k=0:N-1] $x index k using ... title sprintf('%d %%', 10*(k+1))".
std::string ForEachThrottle(const DriveFigureOptions& o, const std::string& block,
                            const std::string& using_clause) {
  std::ostringstream s;
  s << "for [k=0:" << o.throttle_steps - 1 << "] $" << block << " index k using " << using_clause
    << " with lines lw 2 lc palette frac (k+1.0)/" << o.throttle_steps
    << " title sprintf('TR %d %%', (k+1)*" << 100 / o.throttle_steps << ")";
  return s.str();
}

// A two-line gnuplot title: the pair and voltage, then what the figure shows.
std::string Title(const DriveFigureOptions& o, const std::string& what) {
  std::string t = o.title + " at VDC = " + SignificantText(o.vdc_v, 3) + " V\\n" + what;
  std::string q;
  for (char c : t) {
    if (c == '"') q += "\\\""; else q += c;
  }
  return "\"" + q + "\"";
}

// System efficiency map over torque and speed (inverse model), with the per-throttle
// maximum-efficiency points (analogue of eq 14) and the full-throttle line; returns the PNG path.
std::string EfficiencyMapFigure(const Drive& d, const DriveFigureOptions& o, const std::string& dir) {
  const double w_max = d.NoLoadSpeed(o.vdc_v, 1.0);
  const double q_max = MaxTorque(d, o.vdc_v, 1.0, o.current_limit_a);
  DataBlock map;
  map.name = "map";
  map.grid = true;
  const int n = 120;
  for (int i = 0; i <= n; ++i) {
    const double w = w_max * i / n;
    std::vector<double> rpm, q, eta;
    for (int j = 0; j <= n; ++j) {
      const double torque = q_max * j / n;
      const OperatingPoint p = d.Inverse(o.vdc_v, torque, w);
      const bool ok = p.throttle >= 0.0 && p.throttle <= 1.0 && p.irms_a <= o.current_limit_a;
      rpm.push_back(p.rpm);
      q.push_back(torque);
      eta.push_back(ok ? 100 * p.eta_system : kNaN);
    }
    map.series.push_back({rpm, q, eta});
  }
  // Not clipped at 100 % (as figure 4).
  const double map_max = MaxFinite(map, {2});
  const bool map_above = map_max > 100.0;
  DataBlock best;
  best.name = "best";
  std::vector<double> br, bq;
  for (const auto& row : SummarizeThrottles(d, o.vdc_v, o.throttle_steps)) {
    if (row.at_max_efficiency.irms_a > o.current_limit_a) continue;
    br.push_back(row.max_efficiency_rpm);
    bq.push_back(row.at_max_efficiency.torque_nm);
  }
  best.series.push_back({br, bq});
  const DataBlock full = ThrottleLines(d, o, "unused", 2, [](const OperatingPoint& p) {
    return std::vector<double>{p.rpm, p.torque_nm};
  });
  DataBlock top;
  top.name = "full";
  top.series.push_back(full.series.back());
  std::ostringstream s;
  s << "set title " << Title(o, "system efficiency Pmech/PDC [%] over torque and speed (inverse model)") << "\n"
    << "set xlabel 'speed [rpm]'\nset ylabel 'torque [N m]'\nset view map\n"
    << "set palette defined (0 '#2b083b', 0.35 '#3b528b', 0.6 '#21918c', 0.8 '#5ec962', 1 '#fde725')\n"
    << "set cbrange [0:" << (map_above ? SignificantText(map_max, 4) : "100") << "]\n"
    << "set cblabel 'eta system [%]" << (map_above ? " (above 100: creates energy)" : "") << "'\n"
    << "set key outside bottom center horizontal\n"
    << "set contour base\nset cntrparam levels discrete 40,60,70,80,85,90" << (map_above ? ",100" : "")
    << "\nset cntrlabel onecolor\n"
    << "set xrange [0:" << RadPerSecToRpm(w_max) << "]\nset yrange [0:" << q_max << "]\n"
    << "unset surface\nset table $contours\nsplot $map using 1:2:3 with lines\nunset table\n"
    << "unset contour\nset surface\n"
    << "plot $map using 1:2:3 with image notitle, "
    << "$contours using 1:2 with lines lc rgb 'white' lw 1 title 'contours 40/60/70/80/85/90"
    << (map_above ? "/100" : "") << " %', "
    << "$full using 1:2 with lines lw 2 lc rgb 'black' title 'full throttle', "
    << "$best using 1:2 with linespoints pt 7 ps 1 lc rgb 'red' title 'max efficiency per throttle (eq 14 analogue)'\n";
  const std::string path = dir + "/efficiency_map.png";
  RenderPng(path, {map, best, top}, s.str(), 1000, 800);
  return path;
}

}  // namespace

std::vector<std::string> WriteDriveFigures(const Drive& d, const DriveFigureOptions& opt,
                                           const std::string& dir) {
  DriveFigureOptions o = opt;
  if (!(o.current_limit_a > 0.0)) o.current_limit_a = CurrentLimit(d, o.vdc_v);
  MakeOutputDir(dir);
  std::vector<std::string> written;
  const std::string palette =
      "set palette defined (0 '#1f3b99', 0.5 '#2ca25f', 1 '#d95f0e')\nunset colorbox\n";
  const std::string limit_note =
      "lines end at the stall torque or the current limit " + SignificantText(o.current_limit_a, 3) + " A";
  const bool saturates = d.esc().tr_sat < 1.0;
  const std::string sat_note = saturates ? "; ESC saturates above TR " + SignificantText(100 * d.esc().tr_sat, 3) +
                                               " % (slope " + SignificantText(d.esc().sat_slope, 2) + ")"
                                         : "";

  // 1. Torque and mechanical power vs rpm per throttle (the paper's Fig. 25, eqs 49-50).
  {
    const DataBlock b = ThrottleLines(d, o, "ts", 3, [](const OperatingPoint& p) {
      return std::vector<double>{p.rpm, p.torque_nm, p.pmech_w};
    });
    std::ostringstream s;
    s << palette << "set multiplot layout 2,1 title "
      << Title(o, "torque and power vs speed (eqs 49, 50); " + limit_note + sat_note) << "\n"
      << "set ylabel 'torque Q [N m]'\nset xlabel 'speed [rpm]'\nset yrange [0:*]\n"
      << "plot " << ForEachThrottle(o, "ts", "1:2") << "\n"
      << "set ylabel 'mechanical power Pm [W]'\n"
      << "plot " << ForEachThrottle(o, "ts", "1:3") << "\nunset multiplot\n";
    const std::string path = dir + "/torque_power_vs_rpm.png";
    RenderPng(path, {b}, s.str(), 1000, 900);
    written.push_back(path);
  }
  // 2. VLL,rms vs Irms per throttle (Fig. 22, eq 47).
  {
    const DataBlock b = ThrottleLines(d, o, "vi", 2, [](const OperatingPoint& p) {
      return std::vector<double>{p.irms_a, p.vll_rms_v};
    });
    std::ostringstream s;
    s << palette << "set title " << Title(o, "line-line rms voltage vs rms current (eq 47)" + sat_note)
      << "\nset xlabel 'Irms [A]'\nset ylabel 'VLL,rms [V]'\n"
      << "set arrow from graph 0, first " << o.vdc_v << " to graph 1, first " << o.vdc_v
      << " nohead dt 2 lc rgb 'gray'\n"
      << "set label 'VDC' at graph 0.02, first " << o.vdc_v << " offset 0,0.6 tc rgb 'gray'\n"
      << "set yrange [0:" << 1.08 * o.vdc_v << "]\n"
      << "plot " << ForEachThrottle(o, "vi", "1:2") << "\n";
    const std::string path = dir + "/vll_rms_vs_irms.png";
    RenderPng(path, {b}, s.str());
    written.push_back(path);
  }
  // 3. IDC/Irms vs throttle: the ESC line (eq 57, with saturation) and the ideal ESC (eq 56).
  {
    DataBlock b;
    b.name = "ratio";
    std::vector<double> tr, model, ideal, timing;
    for (int i = 0; i <= 100; ++i) {
      const double t = i / 100.0;
      const double te = d.EffectiveThrottle(t);
      tr.push_back(100.0 * t);
      model.push_back(d.esc().c1 * te + d.esc().c0);
      ideal.push_back(kIdealIdcPerIrmsPerThrottle * t);
      timing.push_back(d.EscTimingFigure(t));
    }
    b.series.push_back({tr, model, ideal, timing});
    std::ostringstream s;
    s << "set title '" << o.esc_name << ": DC/AC current ratio vs throttle (eqs 56, 57, 62)'\n"
      << "set xlabel 'throttle TR [%]'\nset ylabel 'IDC / Irms'\nset key left top inside\n"
      << "plot $ratio using 1:2 with lines lw 2 lc rgb '#d95f0e' title sprintf('ESC: %.3f TR_eff + %.3f', "
      << d.esc().c1 << ", " << d.esc().c0 << "), "
      << "$ratio using 1:3 with lines lw 2 dt 2 lc rgb '#1f3b99' title 'ideal ESC (3/pi) sqrt(27/20) TR', "
      << "$ratio using 1:4 with lines lw 1 lc rgb '#2ca25f' title 'timing figure (t_on+t_off) f_sw (eq 62)'\n";
    const std::string path = dir + "/idc_over_irms_vs_throttle.png";
    RenderPng(path, {b}, s.str());
    written.push_back(path);
  }
  // 4. Efficiencies vs rpm at selected throttles (Fig. 7 for the combined model).
  {
    const DataBlock b = ThrottleLines(d, o, "eta", 4, [](const OperatingPoint& p) {
      return std::vector<double>{p.rpm, 100 * p.eta_motor, 100 * p.eta_esc, 100 * p.eta_system};
    });
    // Efficiencies above 100 % are drawn, not clipped: a point above the dashed
    // 100 % line creates energy (docs/model.md section 10) and must be seen.
    const double eta_max = MaxFinite(b, {1, 2, 3});
    const bool above = eta_max > 100.0;
    std::ostringstream s;
    s << palette << "set multiplot layout 3,1 title "
      << Title(o, "efficiencies vs speed per throttle; " + limit_note +
                      (above ? "\\nABOVE 100 %: these parameters create energy (model.md section 10)" : ""))
      << "\n"
      << "set xlabel 'speed [rpm]'\nset yrange [0:" << (above ? SignificantText(1.05 * eta_max, 4) : "105") << "]\n"
      << "set arrow from graph 0, first 100 to graph 1, first 100 nohead dt 2 lw 2 lc rgb 'red'\n"
      << "set ylabel 'motor [%]'\nplot " << ForEachThrottle(o, "eta", "1:2") << "\n"
      << "set ylabel 'ESC [%]'\nplot " << ForEachThrottle(o, "eta", "1:3") << "\n"
      << "set ylabel 'system [%]'\nplot " << ForEachThrottle(o, "eta", "1:4") << "\n"
      << "unset multiplot\n";
    const std::string path = dir + "/efficiency_vs_rpm.png";
    RenderPng(path, {b}, s.str(), 1000, 1100);
    written.push_back(path);
  }
  // 5. System efficiency map over torque and speed (inverse model).
  written.push_back(EfficiencyMapFigure(d, o, dir));
  return written;
}

}  // namespace dynosize
