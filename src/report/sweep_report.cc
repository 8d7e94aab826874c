#include "report/sweep_report.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "common/numbers.h"
#include "common/text_file.h"
#include "common/text_format.h"
#include "report/gnuplot.h"
#include "report/mission_report.h"

namespace dynosize::study {

namespace {

// A value as the user wrote it: numbers in JSON form, strings bare.
std::string ValueText(const Json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string UnitColumn(const Mission& m) {
  const std::string unit = DisplayUnit(m) + 1;
  return "objective_" + (unit == "%" ? std::string("pct") : unit == "Wh" ? std::string("wh") : unit);
}

std::string SafeName(const std::string& s) {
  std::string out = s;
  for (char& c : out) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return out;
}

// For a gnuplot string in single quotes.
std::string GpText(const std::string& s) {
  std::string q;
  for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q;
}

// A gnuplot title in double quotes (where \n is a line break).
std::string GpTitle(const std::string& line1, const std::string& line2) {
  std::string q = "\"";
  for (char c : line1 + "\n" + line2) {
    if (c == '"' || c == '\\') q += '\\';
    q += c == '\n' ? std::string("\\n") : std::string(1, c);
  }
  return q + "\"";
}

double AsNumber(const Json& v, double index) { return v.is_number() ? v.get<double>() : index; }

// The best pick's objective, low and high of every grid point (NaN where none).
struct PointObjective {
  double y = kNaN, lo = kNaN, hi = kNaN;
};
std::vector<PointObjective> Objectives(const SweepResult& r) {
  std::vector<PointObjective> out(r.total);
  for (const SweepRow& row : r.rows) {
    if (row.picks.empty() || !row.picks.front().feasible) continue;
    const SweepPick& p = row.picks.front();
    out[row.index] = {p.objective, p.objective_low, p.objective_high};
  }
  return out;
}

const char* kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

std::string ObjectiveVsKey(const Mission& m, const SweepResult& r, const std::vector<VaryKey>& keys, std::size_t k,
                           const std::string& dir) {
  const std::vector<PointObjective> obj = Objectives(r);
  const std::size_t nk = keys[k].values.size();
  const std::size_t lines = r.total / nk;  // combinations of the other keys
  DataBlock d{"d", {}, false};
  std::vector<std::string> titles;
  for (std::size_t l = 0; l < lines; ++l) {
    std::vector<double> x, y, lo, hi;
    std::string title;
    for (std::size_t v = 0; v < nk; ++v) {
      // Grid index of value v of key k within line l (GridPoint's order: the last key fastest).
      std::size_t inner = 1;
      for (std::size_t j = k + 1; j < keys.size(); ++j) inner *= keys[j].values.size();
      const std::size_t index = (l / inner) * inner * nk + v * inner + l % inner;
      x.push_back(AsNumber(keys[k].values[v], static_cast<double>(v)));
      y.push_back(obj[index].y);
      lo.push_back(obj[index].lo);
      hi.push_back(obj[index].hi);
      if (v == 0) {
        const std::vector<Json> point = GridPoint(keys, index);
        for (std::size_t j = 0; j < keys.size(); ++j) {
          if (j != k) title += (title.empty() ? "" : ", ") + keys[j].key + " = " + ValueText(point[j]);
        }
      }
    }
    d.series.push_back({x, y, lo, hi});
    titles.push_back(title.empty() ? "best pick" : title);
  }
  std::ostringstream g;
  g << "set title " << GpTitle(m.name + ": " + ObjectiveLabel(m) + " vs " + keys[k].key,
                               "best pick per point; band: its objective range (pessimistic to optimistic data; "
                               "none where an end cannot fly)") << "\n"
    << "set xlabel '" << GpText(keys[k].key) << "'\nset ylabel '" << GpText(ObjectiveLabel(m)) << "'\n"
    << "set key inside bottom left\n";
  if (!keys[k].values.front().is_number()) {
    g << "set xtics (";
    for (std::size_t v = 0; v < nk; ++v) g << (v ? ", " : "") << "'" << GpText(ValueText(keys[k].values[v])) << "' " << v;
    g << ")\n";
  }
  if (lines > 10) g << "unset key\n";
  g << "plot ";
  for (std::size_t l = 0; l < lines; ++l) {
    const char* c = kColors[l % 10];
    g << (l ? ", " : "") << "$d index " << l << " using 1:3:4 with filledcurves fs transparent solid 0.15 lc rgb '"
      << c << "' notitle, $d index " << l << " using 1:2 with linespoints pt 7 lw 2 lc rgb '" << c << "' title '"
      << GpText(titles[l]) << "'";
  }
  g << "\n";
  const std::string path = dir + "/objective_vs_" + SafeName(keys[k].key) + ".png";
  RenderPng(path, {d}, g.str(), 1000, 700);
  return path;
}

// Lines of constant B over A and of constant A over B, each B step shifting the abscissa by
// half an A step: the x axis carries no unit, the lines' labels say which is which.
std::string Carpet(const Mission& m, const SweepResult& r, const std::vector<VaryKey>& keys, const std::string& dir) {
  const std::vector<PointObjective> obj = Objectives(r);
  const std::size_t na = keys[0].values.size(), nb = keys[1].values.size();
  std::size_t inner = 1;  // the other keys at their first value
  for (std::size_t j = 2; j < keys.size(); ++j) inner *= keys[j].values.size();
  constexpr double kShift = 0.5;
  auto at = [&](std::size_t ia, std::size_t ib) { return obj[(ia * nb + ib) * inner]; };
  DataBlock bl{"b", {}, false}, al{"a", {}, false};
  std::ostringstream labels;
  for (std::size_t ib = 0; ib < nb; ++ib) {
    std::vector<double> x, y;
    for (std::size_t ia = 0; ia < na; ++ia) {
      x.push_back(static_cast<double>(ia) + kShift * static_cast<double>(ib));
      y.push_back(at(ia, ib).y);
    }
    for (std::size_t ia = na; ia-- > 0;) {
      if (std::isfinite(y[ia])) {
        labels << "set label '" << GpText(keys[1].key + " = " + ValueText(keys[1].values[ib])) << "' at " << x[ia]
               << "," << y[ia] << " offset 1,0 left tc rgb '#1f77b4'\n";
        break;
      }
    }
    bl.series.push_back({x, y});
  }
  for (std::size_t ia = 0; ia < na; ++ia) {
    std::vector<double> x, y;
    for (std::size_t ib = 0; ib < nb; ++ib) {
      x.push_back(static_cast<double>(ia) + kShift * static_cast<double>(ib));
      y.push_back(at(ia, ib).y);
    }
    for (std::size_t ib = 0; ib < nb; ++ib) {
      if (std::isfinite(y[ib])) {
        labels << "set label '" << GpText(keys[0].key + " = " + ValueText(keys[0].values[ia])) << "' at " << x[ib]
               << "," << y[ib] << " offset -0.8,0 right tc rgb '#d62728'\n";
        break;
      }
    }
    al.series.push_back({x, y});
  }
  std::string fixed;
  for (std::size_t j = 2; j < keys.size(); ++j) {
    fixed += (fixed.empty() ? "; " : ", ") + keys[j].key + " = " + ValueText(keys[j].values.front());
  }
  std::ostringstream g;
  g << "set title " << GpTitle(m.name + ": carpet of " + ObjectiveLabel(m) + ", best pick per point",
                               "over " + keys[0].key + " (red) and " + keys[1].key + " (blue)" + fixed) << "\n"
    << "set ylabel '" << GpText(ObjectiveLabel(m)) << "'\nunset xtics\nset xlabel 'carpet: each " << GpText(keys[1].key)
    << " step shifts the lines right by half a " << GpText(keys[0].key) << " step'\nunset key\n"
    << "set offsets 1.2, 1.2, 0.5, 0.5\n"
    << labels.str() << "plot $b using 1:2 with linespoints pt 7 lw 2 lc rgb '#1f77b4', "
    << "$a using 1:2 with lines lw 1 dt 2 lc rgb '#d62728'\n";
  const std::string path = dir + "/carpet_" + SafeName(keys[0].key) + "_" + SafeName(keys[1].key) + ".png";
  RenderPng(path, {bl, al}, g.str(), 1000, 700);
  return path;
}

}  // namespace

Json SweepRowJson(const SweepRow& row, const std::vector<VaryKey>& keys) {
  Json j;
  j["index"] = row.index;
  Json values = Json::object();
  for (std::size_t i = 0; i < keys.size() && i < row.values.size(); ++i) values[keys[i].key] = row.values[i];
  j["values"] = values;
  j["status"] = row.status;
  if (!row.reason.empty()) j["reason"] = row.reason;
  if (!row.no_design_because.empty()) j["no_design_because"] = UnmetRequirementsJson(row.no_design_because);
  Json picks = Json::array();
  for (const SweepPick& p : row.picks) {
    Json q;
    q["rank"] = p.rank;
    q["feasible"] = p.feasible;
    q["objective"] = p.objective;
    q["objective_unit"] = p.objective_unit;
    q["objective_range"] = {NumberOrNull(p.objective_low), NumberOrNull(p.objective_high)};
    Json parts = Json::array();
    for (std::size_t g = 0; g < p.motor.size(); ++g) {
      Json part;
      if (g < p.groups.size() && !p.groups[g].empty()) part["group"] = p.groups[g];
      part["motor"] = p.motor[g];
      part["esc"] = p.esc[g];
      part["prop"] = p.prop[g];
      parts.push_back(part);
    }
    q["parts"] = parts;
    q["battery"] = p.battery;
    q["cells"] = p.cells;
    q["capacity_ah"] = p.capacity_ah;
    q["total_mass_kg"] = p.total_mass_kg;
    q["thrust_to_weight"] = p.thrust_to_weight;
    q["binding_limit"] = p.binding_limit.empty() ? Json(nullptr) : Json(p.binding_limit);
    picks.push_back(q);
  }
  j["picks"] = picks;
  return j;
}

Json SweepDocument(const Mission& base, const std::vector<VaryKey>& keys, std::size_t points, Json rows,
                   bool interrupted, double seconds) {
  Json j;
  j["mission"] = base.name;
  j["objective_type"] = ObjectiveTypeName(base.objective.type);
  j["objective_unit"] = DisplayUnit(base) + 1;
  Json ks = Json::array();
  for (const VaryKey& k : keys) ks.push_back({{"key", k.key}, {"values", k.values}});
  j["keys"] = ks;
  std::size_t failed = 0;
  for (const Json& r : rows) failed += r.at("status") == "failed";
  j["points"] = points;
  j["done"] = rows.size();
  j["failed"] = failed;
  j["interrupted"] = interrupted;
  j["seconds"] = seconds;
  j["rows"] = std::move(rows);
  return j;
}

Json SweepJson(const Mission& base, const SweepResult& result, const std::vector<VaryKey>& keys) {
  Json rows = Json::array();
  for (const SweepRow& r : result.rows) rows.push_back(SweepRowJson(r, keys));
  return SweepDocument(base, keys, result.total, std::move(rows), result.interrupted, result.seconds);
}

std::string SweepCsv(const Mission& base, const SweepResult& result, const std::vector<VaryKey>& keys) {
  std::ostringstream o;
  o << "index";
  for (const VaryKey& k : keys) o << "," << CsvField(k.key);
  o << ",status,rank,feasible," << UnitColumn(base) << ",objective_low,objective_high";
  for (int g = 0; g < GroupCount(base); ++g) {
    const std::string p = base.groups.empty() ? "" : GroupName(base, g) + "_";
    o << "," << CsvField(p + "motor") << "," << CsvField(p + "esc") << "," << CsvField(p + "prop");
  }
  o << ",battery,cells,capacity_ah,total_mass_kg,thrust_to_weight,binding_limit,reason\n";
  for (const SweepRow& r : result.rows) {
    std::ostringstream head;
    head << r.index;
    for (const Json& v : r.values) head << "," << CsvField(ValueText(v));
    head << "," << r.status;
    if (r.picks.empty()) {
      o << head.str() << ",,,,,";
      for (int g = 0; g < GroupCount(base); ++g) o << ",,,";
      o << ",,,,,,," << CsvField(r.reason) << "\n";
      continue;
    }
    for (const SweepPick& p : r.picks) {
      o << head.str() << "," << p.rank << "," << (p.feasible ? "true" : "false") << ","
        << SignificantTextOr(p.objective, "") << "," << SignificantTextOr(p.objective_low, "") << ","
        << SignificantTextOr(p.objective_high, "");
      for (int g = 0; g < GroupCount(base); ++g) {
        const std::size_t gi = static_cast<std::size_t>(g);
        const bool has = gi < p.motor.size();
        o << "," << CsvField(has ? p.motor[gi] : "") << "," << CsvField(has ? p.esc[gi] : "") << ","
          << CsvField(has ? p.prop[gi] : "");
      }
      o << "," << CsvField(p.battery) << "," << p.cells << "," << SignificantTextOr(p.capacity_ah, "") << ","
        << SignificantTextOr(p.total_mass_kg, "") << "," << SignificantTextOr(p.thrust_to_weight, "") << ","
        << CsvField(p.binding_limit) << "," << CsvField(r.reason) << "\n";
    }
  }
  return o.str();
}

std::vector<std::string> WriteSweepFigures(const Mission& base, const SweepResult& result,
                                           const std::vector<VaryKey>& keys, const std::string& dir) {
  MakeOutputDir(dir);
  std::vector<std::string> paths;
  for (std::size_t k = 0; k < keys.size(); ++k) paths.push_back(ObjectiveVsKey(base, result, keys, k, dir));
  if (keys.size() >= 2) paths.push_back(Carpet(base, result, keys, dir));
  return paths;
}

}  // namespace dynosize::study
