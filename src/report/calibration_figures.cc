#include "report/calibration_figures.h"

#include <cmath>
#include <sstream>

#include "common/text_file.h"
#include "common/units.h"
#include "report/column_axis.h"
#include "report/gnuplot.h"

namespace dynosize {

namespace {

using logs::Column;


double Predicted(const calibration::RowPrediction& p, Column c) {
  switch (c) {
    case Column::kOmegaRadS: return p.omega_rad_s;
    case Column::kIdcA: return p.idc_a;
    case Column::kIrmsA: return p.irms_a;
    case Column::kVllRmsV: return p.vll_rms_v;
    case Column::kPacW: return p.pac_w;
    default: return std::nan("");
  }
}

std::string Quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\\\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::vector<std::string> WriteCalibrationFigures(const std::string& dir, const logs::SteadyTable& t,
                                                 const calibration::CalibrationResult& r) {
  MakeOutputDir(dir);
  std::vector<std::string> written;
  const bool thr = t.Has(Column::kThrottle);
  const bool current_input = thr && !t.Has(Column::kTorqueNm) && !(t.Has(Column::kVllRmsV) && t.Has(Column::kIrmsA));
  // Base names only: the titles stay one line for several logs.
  std::string file;
  {
    std::string rest = t.file;
    while (!rest.empty()) {
      const std::size_t comma = rest.find(", ");
      std::string one = rest.substr(0, comma);
      const std::size_t slash = one.find_last_of('/');
      if (slash != std::string::npos) one = one.substr(slash + 1);
      file += (file.empty() ? "" : ", ") + one;
      rest = comma == std::string::npos ? "" : rest.substr(comma + 2);
    }
  }
  if (file.size() > 90) file = file.substr(0, 87) + "...";
  for (const auto& f : r.fit) {
    const ColumnAxis s = DescribeColumn(f.column);
    std::vector<double> meas, pred, res, tr, rpm;
    for (std::size_t i = 0; i < t.rows(); ++i) {
      const auto p = calibration::PredictRow(t, i, r.motor, r.esc);
      // Logs without torque or AC columns predict the speed from the measured current (calibrate.h).
      const double pv = f.column == Column::kOmegaRadS && current_input ? p.omega_from_idc_rad_s : Predicted(p, f.column);
      const double mv = t.Get(f.column)[i];
      if (!std::isfinite(pv) || mv == 0.0) continue;
      meas.push_back(mv * s.scale);
      pred.push_back(pv * s.scale);
      res.push_back((pv - mv) / mv * 100.0);
      tr.push_back(thr ? 100.0 * t.Get(Column::kThrottle)[i] : std::nan(""));
      rpm.push_back(t.Get(Column::kOmegaRadS)[i] / kRadPerSecPerRpm);
    }
    if (meas.empty()) continue;
    DataBlock b;
    b.name = "pts";
    b.series.push_back({meas, pred, res, tr, rpm});
    std::ostringstream title;
    title.precision(3);
    title << s.label << ": " << file << "\\nfit (" << r.mode << "): rmse " << f.rmse_percent
          << " %, median |error| " << f.median_abs_percent << " %, " << f.points << " points";
    std::ostringstream g;
    g << "set multiplot layout 1," << (thr ? 3 : 2) << " title " << Quote(title.str()) << "\n"
      << "set grid\nset key bottom right\nset xtics rotate by -35\nset lmargin 10\n"
      << "set xlabel 'measured [" << s.unit << "]'\nset ylabel 'predicted [" << s.unit << "]'\n"
      << "plot $pts using 1:2 with points pt 7 ps 0.8 lc rgb '#1f3b99' title 'points', "
      << "x with lines dt 2 lc rgb 'gray' title '1:1'\n"
      << "set ylabel 'residual (pred - meas)/meas [%]'\n";
    if (thr) {
      g << "set xlabel 'throttle [%]'\n"
        << "plot $pts using 4:3 with points pt 7 ps 0.8 lc rgb '#d95f0e' notitle, 0 with lines lc rgb 'gray' notitle\n";
    }
    g << "set xlabel 'speed [rpm]'\n"
      << "plot $pts using 5:3 with points pt 7 ps 0.8 lc rgb '#2ca25f' notitle, 0 with lines lc rgb 'gray' notitle\n"
      << "unset multiplot\n";
    const std::string path = dir + "/fit_" + logs::ColumnName(f.column) + ".png";
    RenderPng(path, {b}, g.str(), thr ? 1500 : 1100, 520);
    written.push_back(path);
  }
  return written;
}

}  // namespace dynosize
