#include "report/diagnosis_figures.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "common/text_file.h"
#include "common/units.h"
#include "report/column_axis.h"
#include "report/gnuplot.h"

namespace dynosize {

namespace {

using logs::Column;


std::string Quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\\\"") : std::string(1, c);
  return q + "\"";
}

std::string BaseName(const std::string& p) {
  const std::size_t slash = p.find_last_of('/');
  std::string b = slash == std::string::npos ? p : p.substr(slash + 1);
  return b.size() > 80 ? b.substr(0, 77) + "..." : b;
}

std::string Causes(const diagnosis::DiagnoseResult& r) {
  if (r.findings.empty()) return "no finding";
  std::string s;
  for (const auto& f : r.findings) s += (s.empty() ? "" : " + ") + std::string(diagnosis::CauseId(f.cause));
  return s;
}

double MedianAbs(std::vector<double> v) {
  if (v.empty()) return 0.0;
  for (double& x : v) x = std::fabs(x);
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// 1. Residuals against each logged variable: one panel per predicted column.
void WriteResidualFigures(const std::string& dir, const logs::SteadyTable& t, const diagnosis::DiagnoseResult& r,
                          const std::vector<Column>& cols, const std::string& file, const std::string& sub,
                          std::vector<std::string>* written) {
  std::vector<Column> vars;
  for (Column c : {Column::kThrottle, Column::kOmegaRadS, Column::kIdcA, Column::kVdcV, Column::kTorqueNm,
                   Column::kTimeS, Column::kTempC}) {
    if (t.Has(c)) vars.push_back(c);
  }
  for (Column var : vars) {
    const ColumnAxis ax = DescribeColumn(var);
    std::vector<DataBlock> blocks;
    std::ostringstream g;
    g << "set multiplot layout 1," << cols.size() << " title "
      << Quote("residuals vs " + std::string(ax.label) + ": " + file + "\\n" + sub) << "\n"
      << "set grid\nset key top left\nset xtics rotate by -35\nset xlabel '" << ax.label << " [" << ax.unit << "]'\n"
      << "set ylabel 'held-out error (pred - meas)/meas [%]'\n";
    for (std::size_t k = 0; k < cols.size(); ++k) {
      const Column c = cols[k];
      std::vector<double> x, eb, ee;
      const auto& pb = r.baseline_cv_prediction.at(c);
      const auto& pe = r.extended_cv_prediction.at(c);
      for (std::size_t i = 0; i < t.rows(); ++i) {
        const double m = t.Get(c)[i];
        if (!r.row_used[i] || !std::isfinite(pb[i]) || m == 0.0) continue;
        x.push_back(t.Get(var)[i] * ax.scale);
        eb.push_back((pb[i] - m) / m * 100.0);
        ee.push_back(std::isfinite(pe[i]) ? (pe[i] - m) / m * 100.0 : std::nan(""));
      }
      DataBlock b;
      b.name = "r" + std::to_string(k);
      b.series.push_back({x, eb, ee});
      blocks.push_back(b);
      g << "set title '" << DescribeColumn(c).label << "'\n"
        << "plot $" << b.name << " using 1:2 with points pt 7 ps 0.7 lc rgb '#d95f0e' title 'first-order', "
        << "$" << b.name << " using 1:3 with points pt 9 ps 0.8 lc rgb '#1f3b99' title 'extended', "
        << "0 with lines lc rgb 'gray' notitle\n";
    }
    g << "unset multiplot\n";
    const std::string path = dir + "/residuals_vs_" + logs::ColumnName(var) + ".png";
    RenderPng(path, blocks, g.str(), std::max<int>(700, 520 * static_cast<int>(cols.size())), 520);
    written->push_back(path);
  }
}

// 2. Measured vs predicted.
void WriteMeasuredVsPredicted(const std::string& dir, const logs::SteadyTable& t,
                              const diagnosis::DiagnoseResult& r, const std::vector<Column>& cols,
                              const std::string& file, const std::string& sub, std::vector<std::string>* written) {
  std::vector<DataBlock> blocks;
  std::ostringstream g;
  g << "set multiplot layout 1," << cols.size() << " title "
    << Quote("measured vs predicted (held-out): " + file + "\\n" + sub) << "\n"
    << "set grid\nset key top left\nset xtics rotate by -35\n";
  for (std::size_t k = 0; k < cols.size(); ++k) {
    const Column c = cols[k];
    const ColumnAxis ax = DescribeColumn(c);
    std::vector<double> m, pb, pe;
    for (std::size_t i = 0; i < t.rows(); ++i) {
      const double mv = t.Get(c)[i];
      const double b = r.baseline_cv_prediction.at(c)[i];
      if (!r.row_used[i] || !std::isfinite(b)) continue;
      m.push_back(mv * ax.scale);
      pb.push_back(b * ax.scale);
      pe.push_back(r.extended_cv_prediction.at(c)[i] * ax.scale);
    }
    DataBlock b;
    b.name = "m" + std::to_string(k);
    b.series.push_back({m, pb, pe});
    blocks.push_back(b);
    g << "set title '" << ax.label << "'\nset xlabel 'measured [" << ax.unit << "]'\nset ylabel 'predicted ["
      << ax.unit << "]'\n"
      << "plot $" << b.name << " using 1:2 with points pt 7 ps 0.7 lc rgb '#d95f0e' title 'first-order', "
      << "$" << b.name << " using 1:3 with points pt 9 ps 0.8 lc rgb '#1f3b99' title 'extended', "
      << "x with lines dt 2 lc rgb 'gray' title '1:1'\n";
  }
  g << "unset multiplot\n";
  const std::string path = dir + "/measured_vs_predicted.png";
  RenderPng(path, blocks, g.str(), std::max<int>(700, 520 * static_cast<int>(cols.size())), 520);
  written->push_back(path);
}

// Series: sweeps (consecutive rows while the x variable does not fall), the way stand
// logs are taken; more than 8 sweeps are grouped by supply voltage (0.5 V bins) instead.
// Returns the rows of each series (used rows with a baseline prediction of column c, against
// xcol) and their titles (mean supply voltage).
std::vector<std::vector<std::size_t>> CurveSeries(const logs::SteadyTable& t, const diagnosis::DiagnoseResult& r,
                                                  Column c, Column xcol, std::vector<std::string>* titles) {
  std::vector<std::vector<std::size_t>> groups;
  double last = -1e300;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (!r.row_used[i] || !std::isfinite(r.baseline_cv_prediction.at(c)[i])) continue;
    const double x = t.Get(xcol)[i];
    if (groups.empty() || x < last) groups.emplace_back();
    groups.back().push_back(i);
    last = x;
  }
  if (groups.size() > 8) {
    std::map<long, std::vector<std::size_t>> by_v;
    for (const auto& gr : groups) {
      for (std::size_t i : gr) by_v[std::lround(t.Get(Column::kVdcV)[i] * 2.0)].push_back(i);
    }
    groups.clear();
    for (auto& [vkey, rows] : by_v) {
      std::sort(rows.begin(), rows.end(), [&](std::size_t a, std::size_t bb) {
        return t.Get(xcol)[a] < t.Get(xcol)[bb];
      });
      groups.push_back(rows);
    }
  }
  for (const auto& gr : groups) {
    double v = 0.0;
    for (std::size_t i : gr) v += t.Get(Column::kVdcV)[i];
    std::ostringstream tt;
    tt.precision(3);
    tt << v / static_cast<double>(gr.size()) << " V";
    titles->push_back(tt.str());
  }
  return groups;
}

// 3. Paper-style curves: each column against throttle (or speed), one series per supply
// voltage (rounded to 0.5 V); the points the first-order model misses (held-out error above
// three times the median) ringed.
void WriteCurves(const std::string& dir, const logs::SteadyTable& t, const diagnosis::DiagnoseResult& r,
                 const std::vector<Column>& cols, const std::string& file, std::vector<std::string>* written) {
  const Column xcol = t.Has(Column::kThrottle) ? Column::kThrottle : Column::kOmegaRadS;
  const ColumnAxis xa = DescribeColumn(xcol);
  std::vector<DataBlock> blocks;
  std::ostringstream g;
  g << "set multiplot layout 1," << cols.size() << " title "
    << Quote("measured (points), first-order (dashed) and extended (solid) model, held-out: " + file +
             "\\nringed: points the first-order model misses (error > 3x median)")
    << "\nset grid\nset key top left font ',8'\nset xlabel '" << xa.label << " [" << xa.unit << "]'\n";
  for (std::size_t k = 0; k < cols.size(); ++k) {
    const Column c = cols[k];
    if (c == xcol) continue;
    const ColumnAxis ax = DescribeColumn(c);
    std::vector<double> errs;
    for (std::size_t i = 0; i < t.rows(); ++i) {
      const double b = r.baseline_cv_prediction.at(c)[i];
      if (r.row_used[i] && std::isfinite(b) && t.Get(c)[i] != 0.0) errs.push_back((b - t.Get(c)[i]) / t.Get(c)[i] * 100.0);
    }
    const double miss = std::max(3.0 * MedianAbs(errs), 1.0);
    std::vector<std::string> titles;
    const std::vector<std::vector<std::size_t>> groups = CurveSeries(t, r, c, xcol, &titles);
    DataBlock b;
    b.name = "c" + std::to_string(k);
    for (const auto& rows : groups) {
      std::vector<double> x, m, pb, pe, missed;
      for (std::size_t i : rows) {
        const double mv = t.Get(c)[i];
        const double bv = r.baseline_cv_prediction.at(c)[i];
        x.push_back(t.Get(xcol)[i] * xa.scale);
        m.push_back(mv * ax.scale);
        pb.push_back(bv * ax.scale);
        pe.push_back(r.extended_cv_prediction.at(c)[i] * ax.scale);
        missed.push_back(mv != 0.0 && std::fabs((bv - mv) / mv * 100.0) > miss ? mv * ax.scale : std::nan(""));
      }
      b.series.push_back({x, m, pb, pe, missed});
    }
    blocks.push_back(b);
    g << "set title '" << ax.label << "'\nset ylabel '" << ax.label << " [" << ax.unit << "]'\nplot ";
    for (std::size_t s = 0; s < titles.size(); ++s) {
      const int lc = static_cast<int>(s % 8) + 1;
      g << (s ? ", " : "") << "$" << b.name << " index " << s << " using 1:2 with points pt 7 ps 0.6 lc "
        << lc << " title '" << titles[s] << "', "
        << "$" << b.name << " index " << s << " using 1:3 with lines dt 2 lc " << lc << " notitle, "
        << "$" << b.name << " index " << s << " using 1:4 with lines lw 1.5 lc " << lc << " notitle, "
        << "$" << b.name << " index " << s << " using 1:5 with points pt 6 ps 2.0 lc rgb 'red' "
        << (s == 0 ? "title 'missed'" : "notitle");
    }
    g << "\n";
  }
  g << "unset multiplot\n";
  const std::string path = dir + "/curves.png";
  RenderPng(path, blocks, g.str(), std::max<int>(800, 560 * static_cast<int>(cols.size())), 560);
  written->push_back(path);
}

}  // namespace

std::vector<std::string> WriteDiagnosisFigures(const std::string& dir, const logs::SteadyTable& t,
                                               const diagnosis::DiagnoseResult& r) {
  MakeOutputDir(dir);
  std::vector<std::string> written;
  const std::string file = BaseName(r.file);
  std::ostringstream sub;
  sub.precision(3);
  sub << "cross-validated: first-order " << r.baseline_cv_rms_percent << " % rms -> extended ("
      << Causes(r) << ") " << r.extended_cv_rms_percent << " %";
  std::vector<Column> cols;
  for (const auto& c : r.baseline_cv) cols.push_back(c.column);
  WriteResidualFigures(dir, t, r, cols, file, sub.str(), &written);
  WriteMeasuredVsPredicted(dir, t, r, cols, file, sub.str(), &written);
  WriteCurves(dir, t, r, cols, file, &written);
  return written;
}

}  // namespace dynosize
