#include "importers/blade_geometry.h"

#include <array>
#include <cmath>
#include <sstream>

#include "common/error.h"
#include "common/text_file.h"
#include "common/text_format.h"
#include "common/units.h"
#include "importers/csv.h"

namespace dynosize {
namespace {

constexpr double kDegToRad = kPi / 180.0;
constexpr std::size_t kMaxPe0Bytes = 1u << 20;

std::string BaseName(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

void CheckOrThrow(const BladeGeometry& g) {
  const std::string bad = CheckBladeGeometry(g);
  if (!bad.empty()) throw DataError(bad);
}

}  // namespace

std::vector<UiucBlade> ReadUiucGeometry(const std::string& csv_path) {
  const CsvTable t = ReadCsv(csv_path);
  std::vector<UiucBlade> out;
  std::vector<int> samples;  // per blade: how many measured samples were averaged
  std::size_t station = 0;   // index of the next station within the current sample
  for (const CsvRow& row : t.rows) {
    const CsvCells c{&t, &row};
    const std::string name = c.Str("BladeName");
    const auto d = c.Pos("D"), p = c.Pos("P"), cr = c.Pos("c/R"), x = c.Pos("r/R"), beta = c.Num("beta");
    if (!d || !p || !cr || !x || !beta) {
      throw DataError(t.Where(row) + ": D, P, c/R and r/R must be numbers > 0 and beta a number");
    }
    const bool same_blade = !out.empty() && out.back().geometry.name == name;
    if (!same_blade) {
      UiucBlade b;
      b.geometry.name = name;
      b.geometry.radius_m = 0.5 * InchToMeter(*d);
      b.geometry.blades = 2;
      b.geometry.source = t.path + ":" + std::to_string(row.line) + " (" + name + ")";
      b.family = c.Str("Family");
      b.diameter_in = *d;
      b.pitch_in = *p;
      out.push_back(b);
      samples.push_back(1);
      station = 0;
    } else if (*x <= out.back().geometry.stations[station - 1].r_over_r) {
      // r/R starts again: UIUC measured another sample of the same blade. The samples are
      // averaged station by station (they share the r/R grid).
      ++samples.back();
      station = 0;
    }
    std::vector<BladeStation>& st = out.back().geometry.stations;
    if (samples.back() == 1) {
      BladeStation s;
      s.r_over_r = *x;
      s.chord_over_r = *cr;
      s.beta_rad = *beta * kDegToRad;
      st.push_back(s);
    } else {
      if (station >= st.size() || std::fabs(st[station].r_over_r - *x) > 1e-9) {
        throw DataError(t.Where(row) + ": sample " + std::to_string(samples.back()) + " of " + name +
                        " has r/R " + SignificantText(*x) + " where the first sample has another grid");
      }
      st[station].chord_over_r += *cr;
      st[station].beta_rad += *beta * kDegToRad;
    }
    ++station;
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    BladeGeometry& g = out[i].geometry;
    for (BladeStation& s : g.stations) {
      s.chord_over_r /= samples[i];
      s.beta_rad /= samples[i];
    }
    g.root_r_over_r = g.stations.front().r_over_r;
    CheckOrThrow(g);
  }
  return out;
}

namespace {

// "KEY:  value" lines of a PE0 file's trailer; nullopt-like NaN when absent.
double Pe0Value(const std::string& line, const char* key) {
  const std::size_t at = line.find(key);
  if (at == std::string::npos) return std::nan("");
  std::istringstream in(line.substr(at + std::string(key).size()));
  double v = std::nan("");
  in >> v;
  return v;
}

}  // namespace

BladeGeometry ReadApcPe0(const std::string& path) {
  const std::string text = ReadTextFile(path, kMaxPe0Bytes);
  BladeGeometry g;
  g.name = BaseName(path);
  const std::size_t suffix = g.name.find("-PERF.PE0");
  if (suffix != std::string::npos) g.name = g.name.substr(0, suffix);
  g.source = path;
  double radius_in = std::nan(""), hub_in = std::nan(""), blades = std::nan("");
  std::vector<std::array<double, 4>> rows;  // station, chord, thickness ratio, twist
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find("RADIUS:") != std::string::npos) radius_in = Pe0Value(line, "RADIUS:");
    if (line.find("HUBTRA:") != std::string::npos) hub_in = Pe0Value(line, "HUBTRA:");
    if (line.find("BLADES:") != std::string::npos) blades = Pe0Value(line, "BLADES:");
    // A station row: 13 numbers (STATION CHORD PITCH x3 SWEEP THICKNESS-RATIO TWIST MAX-THICK
    // CROSS-SECTION ZHIGH CGY CGZ).
    std::istringstream fields(line);
    std::vector<double> v;
    double x = 0.0;
    while (fields >> x) v.push_back(x);
    if (v.size() == 13 && fields.eof()) {
      rows.push_back({v[0], v[1], v[6], v[7]});
      for (double f : v) {
        if (!std::isfinite(f)) throw DataError(path + ":" + std::to_string(line_no) + ": station values must be finite");
      }
    }
  }
  if (!(radius_in > 0.0)) throw DataError(path + ": no \"RADIUS:\" line with a radius > 0 (inches)");
  if (!(blades >= 1.0)) throw DataError(path + ": no \"BLADES:\" line with a blade count >= 1");
  g.radius_m = InchToMeter(radius_in);
  g.blades = static_cast<int>(std::lround(blades));
  for (const auto& r : rows) {
    // The tip row carries a token chord (0.0001 in): the blade ends there.
    if (r[1] <= 1e-3 * radius_in) continue;
    BladeStation s;
    s.r_over_r = r[0] / radius_in;
    s.chord_over_r = r[1] / radius_in;
    s.thickness_ratio = r[2];
    s.beta_rad = r[3] * kDegToRad;
    g.stations.push_back(s);
  }
  if (g.stations.empty()) throw DataError(path + ": no station rows (13 numbers per row)");
  g.root_r_over_r = g.stations.front().r_over_r;
  if (hub_in > 0.0 && hub_in / radius_in > g.root_r_over_r && hub_in / radius_in < g.stations.back().r_over_r) {
    g.root_r_over_r = hub_in / radius_in;
  }
  CheckOrThrow(g);
  return g;
}

std::string UiucBladeNameOfId(const std::string& id) {
  // uiuc_v<volume>_<family>_<DxP>_<blades>
  if (id.rfind("uiuc_v", 0) != 0) return "";
  const std::size_t fam = id.find('_', 6);
  const std::size_t last = id.rfind('_');
  if (fam == std::string::npos || last == std::string::npos || last <= fam) return "";
  std::string rest = id.substr(fam + 1, last - fam - 1);  // "<family>_<DxP>"
  const std::size_t sep = rest.find('_');
  if (sep == std::string::npos) return "";
  rest[sep] = ' ';
  return rest;
}

}  // namespace dynosize
