// UIUC Propeller Data Site, volumes 1-3 (shared/data/uiuc_propdb/volume{1,2,3}_exp.csv):
// CT, CP vs rpm at J = 0 (static tests) and CT, CP vs J at fixed rpm (wind-tunnel sweeps).
#include <algorithm>
#include <cmath>
#include <map>

#include "catalog/prop_credibility.h"
#include "common/units.h"
#include "importers/csv.h"
#include "importers/importers.h"

namespace dynosize {

namespace {

constexpr const char* kDataset = "UIUC Propeller Data Site vol 1-3";
// Wind-tunnel runs of one propeller whose speeds differ by less than this fraction are repeats
// of the same nominal speed (e.g. 6814 and 6831 rpm): they are merged into one sweep, so that
// interpolation in rpm does not divide by a 17 rpm difference.
constexpr double kSweepMergeRelative = 0.03;

struct Point {
  double rpm, j, ct, cp;
};

struct Prop {
  std::string prop_name, blade_name;
  double d_in = 0, p_in = 0;
  int blades = 2;
  std::size_t first_line = 0, last_line = 0;
  std::vector<Point> points;
};

// Averages points with equal x (after sorting by x); returns (x, ct, cp) columns.
void SortAndMerge(std::vector<std::pair<double, std::pair<double, double>>> v,
                  std::vector<double>* x, std::vector<double>* ct, std::vector<double>* cp,
                  std::size_t* merged) {
  std::stable_sort(v.begin(), v.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < v.size();) {
    std::size_t k = i;
    double st = 0, sp = 0;
    while (k < v.size() && v[k].first == v[i].first) {
      st += v[k].second.first;
      sp += v[k].second.second;
      ++k;
    }
    const double n = static_cast<double>(k - i);
    if (k - i > 1) *merged += k - i - 1;
    x->push_back(v[i].first);
    ct->push_back(k - i > 1 ? RoundSig(st / n, 6) : st);
    cp->push_back(k - i > 1 ? RoundSig(sp / n, 6) : sp);
    i = k;
  }
}

void ImportVolume(const std::string& dir, int volume, ImportedDataset* out) {
  const std::string file = "volume" + std::to_string(volume) + "_exp.csv";
  const CsvTable t = ReadCsv(dir + "/" + file);
  const std::size_t c_prop = t.Column("PropName"), c_blade = t.Column("BladeName"),
                    c_b = t.Column("B"), c_d = t.Column("D"), c_p = t.Column("P"),
                    c_j = t.Column("J"), c_n = t.Column("N"), c_ct = t.Column("CT"),
                    c_cp = t.Column("CP");
  std::vector<Prop> props;
  std::map<std::string, std::size_t> index;
  for (const auto& r : t.rows) {
    const std::string name = t.Field(r, c_prop);
    const auto b = ParseNumber(t.Field(r, c_b)), d = ParseNumber(t.Field(r, c_d)),
               p = ParseNumber(t.Field(r, c_p)), j = ParseNumber(t.Field(r, c_j)),
               n = ParseNumber(t.Field(r, c_n)), ct = ParseNumber(t.Field(r, c_ct)),
               cp = ParseNumber(t.Field(r, c_cp));
    const std::string example = file + ":" + std::to_string(r.line) + " " + name;
    if (!b || !d || !p || !j || !n || !ct || !cp) {
      out->report.Drop("prop points", "UIUC point with a malformed or empty number", example);
      continue;
    }
    if (!(*n > 0) || *j < 0 || !(*d > 0)) {
      out->report.Drop("prop points", "UIUC point with rpm <= 0, J < 0 or D <= 0", example);
      continue;
    }
    auto it = index.find(name);
    if (it == index.end()) {
      it = index.emplace(name, props.size()).first;
      Prop pr;
      pr.prop_name = name;
      pr.blade_name = t.Field(r, c_blade);
      pr.d_in = *d;
      pr.p_in = *p;
      pr.blades = static_cast<int>(*b);
      pr.first_line = r.line;
      props.push_back(pr);
    }
    Prop& pr = props[it->second];
    pr.last_line = r.line;
    pr.points.push_back({*n, *j, *ct, *cp});
  }
  std::size_t merged_runs = 0, merged_points = 0;
  for (Prop& pr : props) {
    const double d_col = pr.d_in, p_col = pr.p_in;
    const bool size_fixed = DecodeUiucFolderSize(pr.blade_name, &pr.d_in, &pr.p_in);
    if (size_fixed) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "%s: D, P columns %g x %g in corrected to %g x %g in from the "
                    "name (decimal point lost in the flat CSV)", pr.blade_name.c_str(), d_col,
                    p_col, pr.d_in, pr.p_in);
      out->report.notes.push_back(file + ": " + buf);
    }
    std::vector<std::pair<double, std::pair<double, double>>> st;
    std::vector<Point> fwd;
    for (const Point& q : pr.points) {
      if (q.j == 0.0) st.push_back({q.rpm, {q.ct, q.cp}});
      else fwd.push_back(q);
    }
    // Group forward-flight points into sweeps by rpm, merging repeat runs.
    std::stable_sort(fwd.begin(), fwd.end(),
                     [](const Point& a, const Point& b) { return a.rpm < b.rpm; });
    Json sweeps = Json::array();
    for (std::size_t i = 0; i < fwd.size();) {
      std::size_t k = i;
      std::vector<double> rpms;
      std::vector<std::pair<double, std::pair<double, double>>> pts;
      while (k < fwd.size() && fwd[k].rpm <= fwd[i].rpm * (1 + kSweepMergeRelative)) {
        if (rpms.empty() || rpms.back() != fwd[k].rpm) rpms.push_back(fwd[k].rpm);
        pts.push_back({fwd[k].j, {fwd[k].ct, fwd[k].cp}});
        ++k;
      }
      if (rpms.size() > 1) merged_runs += rpms.size() - 1;
      double mean_rpm = 0;
      for (const Point* q = &fwd[i]; q != fwd.data() + k; ++q) mean_rpm += q->rpm;
      mean_rpm /= static_cast<double>(k - i);
      std::vector<double> jj, ct, cp;
      SortAndMerge(pts, &jj, &ct, &cp, &merged_points);
      sweeps.push_back({{"rpm", rpms.size() > 1 ? RoundSig(mean_rpm, 5) : fwd[i].rpm},
                        {"j", jj}, {"ct", ct}, {"cp", cp}});
      i = k;
    }
    std::vector<double> rpm, ct, cp;
    SortAndMerge(st, &rpm, &ct, &cp, &merged_points);
    const std::string blades = std::to_string(pr.blades);
    // Some propellers were tested in two volumes (e.g. apcsp 9x6 in vol 1 and 2): the volume
    // is part of the id so both campaigns stay.
    const std::string vol = std::to_string(volume);
    EntryBuilder b("uiuc_v" + vol + "_" + Slug(pr.prop_name),
                   "UIUC vol " + vol + " " + pr.blade_name + " (" + blades + " blades)");
    b.SetNum("diameter_m", InchToMeter(pr.d_in), size_fixed ? "derived" : "datasheet");
    if (pr.p_in > 0) b.SetNum("pitch_m", InchToMeter(pr.p_in), size_fixed ? "derived" : "datasheet");
    const bool folding = NameSaysFolding(pr.blade_name + " ");
    if (folding) b.Set("folding", true, "derived");
    b.Set("blades", pr.blades, "datasheet");
    if (!rpm.empty()) b.Set("static_table", {{"rpm", rpm}, {"ct", ct}, {"cp", cp}}, "measured");
    if (!sweeps.empty()) b.Set("j_tables", sweeps, "measured");
    std::string note = rpm.empty() ? "no static test in the data set" : "";
    auto add = [&note](const std::string& s) { note += (note.empty() ? "" : "; ") + s; };
    if (size_fixed) add("D and pitch decoded from the name (the flat CSV lost a decimal point)");
    if (folding) add("folding (UIUC family ancf: Aeronaut CAM folding blades)");
    b.Source(kDataset, file + " lines " + std::to_string(pr.first_line) + "-" +
                           std::to_string(pr.last_line) + " (" + pr.prop_name + ")", note);
    b.Tier("measured");
    out->props.push_back(b.Build());
    out->report.Keep("props");
  }
  if (merged_runs > 0 || merged_points > 0) {
    out->report.notes.push_back(file + ": " + std::to_string(merged_runs) +
                                " repeat wind-tunnel runs within 3 % rpm merged into one sweep; " +
                                std::to_string(merged_points) +
                                " points at an equal J (or static rpm) averaged");
  }
}

}  // namespace

bool DecodeUiucFolderSize(const std::string& blade_name, double* d_in, double* p_in) {
  // "ancf 125.0x6.0": the UIUC file name ancf_125x6 (12.5 x 6.0 in) with the decimal point of
  // the diameter dropped, and "ancf 13.0x65.0" (13 x 6.5 in) the one of the pitch. No Aeronaut
  // CAM folder is 100 in across or has a 20 in pitch, so such numbers are tenths.
  if (blade_name.rfind("ancf ", 0) != 0) return false;
  const std::string size = blade_name.substr(5);
  const auto x = size.find('x');
  if (x == std::string::npos) return false;
  const auto a = ParseNumber(size.substr(0, x)), b = ParseNumber(size.substr(x + 1));
  if (!a || !b || !(*a > 0) || !(*b > 0)) return false;
  const double d = *a >= 100.0 ? *a / 10.0 : *a;
  const double p = *b >= 20.0 ? *b / 10.0 : *b;
  const bool changed = std::fabs(d - *d_in) > 1e-9 || std::fabs(p - *p_in) > 1e-9;
  *d_in = d;
  *p_in = p;
  return changed;
}

ImportedDataset ImportUiuc(const std::string& dir) {
  ImportedDataset out;
  out.report.dataset = "uiuc_propdb";
  out.report.output_file = "uiuc_propdb.json";
  out.comment =
      "Generated by dynosize ImportAll from shared/data/uiuc_propdb: UIUC Propeller Data Site "
      "volumes 1-3 (Brandt, Deters, Ananda, Dantsker, Selig; m-selig.ae.illinois.edu/props/"
      "propDB.html; flat CSV from github.com/Piotrek2133/Drone-Propellers-Optimizer commit "
      "efcecfd). Measured wind-tunnel data: static_table = CT, CP vs rpm at J = 0; j_tables = CT, "
      "CP vs J = V/(n*D) at fixed rpm; T = CT*rho*n^2*D^4, P = CP*rho*n^3*D^5, n in rev/s. "
      "Repeat runs within 3 % rpm merged, equal-J points averaged. Do not edit by hand.";
  for (int v = 1; v <= 3; ++v) ImportVolume(dir, v, &out);
  return out;
}

}  // namespace dynosize
