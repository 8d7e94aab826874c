#include "report/stand_figures.h"

#include <algorithm>
#include <sstream>

#include "common/text_file.h"
#include "common/text_format.h"
#include "common/units.h"
#include "report/gnuplot.h"

namespace dynosize {

namespace {

// A gnuplot double-quoted string; "\\n" in `s` stays a line break.
std::string Quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '\\';
    q += c;
  }
  return q + "\"";
}

}  // namespace

std::string WriteThrottleTableFigure(const std::vector<ThrottleTableRow>& rows, const std::string& title,
                                     const std::string& dir) {
  MakeOutputDir(dir);
  DataBlock b;
  b.name = "tab";
  std::vector<double> tr, thrust_g, idc, rpm;
  for (const auto& r : rows) {
    tr.push_back(100.0 * r.throttle);
    thrust_g.push_back(r.thrust_n / kNewtonPerGramForce);
    idc.push_back(r.point.drive.idc_a);
    rpm.push_back(r.point.drive.rpm);
  }
  b.series.push_back({tr, thrust_g, idc, rpm});
  std::ostringstream s;
  s << "set multiplot layout 2,1 title " << Quote(title + "\\nthrust and DC current vs throttle (prop torque law, eqs 48-59)")
    << "\nset xlabel 'throttle [%]'\nset xrange [0:100]\nset grid\nset key left top inside\n"
    << "set lmargin 12\nset rmargin 12\n"
    << "set ylabel 'thrust [gf]'\nset y2label 'speed [rpm]'\nset ytics nomirror\nset y2tics\n"
    << "plot $tab using 1:2 with linespoints lw 2 pt 7 lc rgb '#d95f0e' title 'thrust', "
    << "$tab using 1:4 axes x1y2 with lines lw 1 dt 2 lc rgb 'gray40' title 'speed (right axis)'\n"
    << "unset y2label\nunset y2tics\nset ytics mirror\n"
    << "set ylabel 'DC current [A]'\n"
    << "plot $tab using 1:3 with linespoints lw 2 pt 7 lc rgb '#1f3b99' title 'IDC'\n"
    << "unset multiplot\n";
  const std::string path = dir + "/thrust_current_vs_throttle.png";
  RenderPng(path, {b}, s.str(), 900, 900);
  return path;
}

namespace {

struct Panel {
  std::string title, unit;
  int mode;
  std::vector<double> meas, pred[2];  // [StandModel]
};

// Collects the (measured, predicted) pairs of one column for both models.
Panel Collect(const stand::StandTable& t, const stand::StandResult& r, int mode, const std::string& column,
              const std::string& title, const std::string& unit) {
  Panel p{title, unit, mode, {}, {}};
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const stand::StandRow& row = t.rows[i];
    const auto& pd = r.rows[i].pred[mode];
    if (!pd[0].valid || !pd[1].valid) continue;
    double meas = 0.0, a = 0.0, b = 0.0;
    if (column == "idc_a" && row.idc_a) {
      meas = *row.idc_a, a = pd[0].idc_a, b = pd[1].idc_a;
    } else if (column == "thrust_n" && row.thrust_n && pd[0].thrust_n && pd[1].thrust_n) {
      meas = *row.thrust_n / kNewtonPerGramForce;
      a = *pd[0].thrust_n / kNewtonPerGramForce;
      b = *pd[1].thrust_n / kNewtonPerGramForce;
    } else if (column == "rpm" && row.omega_rad_s) {
      meas = RadPerSecToRpm(*row.omega_rad_s), a = pd[0].rpm, b = pd[1].rpm;
    } else {
      continue;
    }
    p.meas.push_back(meas);
    p.pred[0].push_back(a);
    p.pred[1].push_back(b);
  }
  return p;
}

std::string ErrorLabel(const stand::StandResult& r, int mode, const std::string& column) {
  const auto* a = stand::FindError(r, mode, stand::kDynosize, column);
  const auto* b = stand::FindError(r, mode, stand::kPlainDc, column);
  if (!a || !b) return "";
  return "MAE dynosize " + SignificantText(a->mae, 3) + " %, plain DC " + SignificantText(b->mae, 3) + " %";
}

}  // namespace

std::string WriteStandFigure(const stand::StandTable& t, const stand::StandResult& r,
                             const std::string& title, const std::string& dir) {
  MakeOutputDir(dir);
  using stand::kAtMeasuredRpm;
  using stand::kFromThrottle;
  const std::vector<std::pair<Panel, std::string>> candidates = {
      {Collect(t, r, kAtMeasuredRpm, "idc_a", "DC current at the measured rpm", "A"), "idc_a"},
      {Collect(t, r, kAtMeasuredRpm, "thrust_n", "thrust at the measured rpm", "gf"), "thrust_n"},
      {Collect(t, r, stand::kAtMeasuredTorque, "idc_a", "DC current at the measured rpm and torque", "A"), "idc_a"},
      {Collect(t, r, kFromThrottle, "rpm", "speed from the throttle", "rpm"), "rpm"},
      {Collect(t, r, kFromThrottle, "idc_a", "DC current from the throttle", "A"), "idc_a"},
  };
  std::vector<DataBlock> blocks;
  std::ostringstream s;
  int n = 0;
  for (const auto& c : candidates) n += c.first.meas.empty() ? 0 : 1;
  if (n == 0) return "";  // nothing measured that a model predicts
  const int cols = n > 1 ? 2 : 1, rows = (n + 1) / 2;
  s << "set multiplot layout " << std::max(rows, 1) << "," << cols << " title "
    << Quote(title + "\\nmeasured vs predicted: dynosize (rms model, eqs 42-59) and the plain DC model (label Kv, datasheet R and Io)")
    << "\nset grid\nset key left top inside\nset size ratio -1\n";
  int k = 0;
  for (const auto& [p, column] : candidates) {
    if (p.meas.empty()) continue;
    const std::string name = "p" + std::to_string(k++);
    DataBlock b;
    b.name = name;
    b.series.push_back({p.meas, p.pred[0], p.pred[1]});
    blocks.push_back(b);
    double hi = 0.0, lo = p.meas.front();
    for (const auto* v : {&p.meas, &p.pred[0], &p.pred[1]}) {
      hi = std::max(hi, *std::max_element(v->begin(), v->end()));
      lo = std::min(lo, *std::min_element(v->begin(), v->end()));
    }
    // From zero unless the points sit far from it (speeds), where zero would crowd them.
    lo = lo > 0.4 * hi ? 0.9 * lo : 0.0;
    hi *= 1.05;
    s << "set title " << Quote(p.title + "\\n" + ErrorLabel(r, p.mode, column)) << "\n"
      << "set xlabel 'measured [" << p.unit << "]'\nset ylabel 'predicted [" << p.unit << "]'\n"
      << "set xrange [" << lo << ":" << hi << "]\nset yrange [" << lo << ":" << hi << "]\n"
      << "plot x with lines lc rgb 'black' title '1:1', 1.1*x with lines dt 2 lc rgb 'gray50' title '+-10 %', "
      << "0.9*x with lines dt 2 lc rgb 'gray50' notitle, "
      // dynosize as large discs under small squares: where the two models agree (an ideal ESC makes
      // them the same model) both stay visible.
      << "$" << name << " using 1:2 with points pt 7 ps 1.9 lc rgb '#d95f0e' title 'dynosize', "
      << "$" << name << " using 1:3 with points pt 5 ps 0.7 lc rgb '#1f3b99' title 'plain DC'\n";
  }
  s << "unset multiplot\n";
  const std::string path = dir + "/stand_measured_vs_predicted.png";
  RenderPng(path, blocks, s.str(), cols == 2 ? 1200 : 700, std::max(rows, 1) * 600);
  return path;
}

}  // namespace dynosize
