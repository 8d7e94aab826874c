#include "importers/blade_geometry.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
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

std::vector<FamilyBlade> ReadUiucGeometry(const std::string& csv_path) {
  const CsvTable t = ReadCsv(csv_path);
  std::vector<FamilyBlade> out;
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
      FamilyBlade b;
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

Per3Table ReadApcPer3Csv(const std::string& path) {
  const CsvTable t = ReadCsv(path);
  const std::size_t c_rpm = t.Column("RPM"), c_q = t.Column("Torque (N-m)"), c_v = t.Column("V(speed) (m/s)"),
                    c_t = t.Column("Thrust (kg)");
  Per3Table out;
  out.name = BaseName(path);
  for (const CsvRow& row : t.rows) {
    const auto rpm = ParseNumber(t.Field(row, c_rpm)), q = ParseNumber(t.Field(row, c_q)),
               v = ParseNumber(t.Field(row, c_v)), thrust = ParseNumber(t.Field(row, c_t));
    if (!rpm || !v) throw DataError(t.Where(row) + ": RPM and V must be numbers");
    if (!q || !thrust) continue;  // truncated by APC
    out.rows.push_back({*rpm, *v, KilogramForceToNewton(*thrust), *q});
  }
  if (out.rows.empty()) throw DataError(path + ": no row with torque and thrust");
  return out;
}

bool ParseApcSize(const std::string& name, double* diameter_in, double* pitch_in) {
  std::size_t i = 0;
  auto digits = [&](double* v, std::size_t* count) {
    const std::size_t start = i;
    while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i]))) ++i;
    *count = i - start;
    if (*count == 0) return false;
    *v = std::stod(name.substr(start, *count));
    return true;
  };
  std::size_t nd = 0, np = 0;
  double d = 0.0, p = 0.0;
  if (!digits(&d, &nd) || i >= name.size() || name[i] != 'x') return false;
  ++i;
  if (!digits(&p, &np)) return false;
  if (nd == 2 && d > 30.0 && d != 42.0) d /= 10.0;  // "95x5MR" is 9.5 in; APC's 42x2 is 42 in
  if (np >= 2 && p > 1.5 * d) p /= 10.0;
  *diameter_in = d;
  *pitch_in = p;
  return true;
}

// UIUC's name of an APC propeller as APC files it: "apce 10.0x5.0" -> "10x5E", "apcsf 10.0x4.7"
// -> "10x47SF", "apcsp 10.0x5.0" -> "10x5" (apc_geometry/README.md); "" for other families.
std::string ApcFileNameOfUiuc(const std::string& family, double d_in, double p_in) {
  std::string suffix;
  if (family == "apce") suffix = "E";
  else if (family == "apcsf") suffix = "SF";
  else if (family != "apcsp") return "";
  auto digits = [](double v) {
    std::string s = SignificantText(v, 4);  // "10", "4.7", "4.5"
    s.erase(std::remove(s.begin(), s.end(), '.'), s.end());
    return s;
  };
  return digits(d_in) + "x" + digits(p_in) + suffix;
}

FamilyBlades ReadFamilyBlades(const std::string& data_dir) {
  FamilyBlades out;
  for (int v = 1; v <= 2; ++v) {
    for (FamilyBlade& b : ReadUiucGeometry(data_dir + "/uiuc_propdb/volume" + std::to_string(v) + "_geom.csv")) {
      out.uiuc.push_back(b);
    }
  }
  std::vector<FamilyBlade>& mr = out.apc_mr;
  const std::string dir = data_dir + "/apc_geometry/geometry";
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f.size() > 11 && f.substr(f.size() - 11) == "MR-PERF.PE0") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  for (const std::string& f : files) {
    FamilyBlade b;
    b.geometry = ReadApcPe0(f);
    b.family = "apcmr";
    if (!ParseApcSize(b.geometry.name, &b.diameter_in, &b.pitch_in)) {
      throw DataError(f + ": the name does not start with <diameter>x<pitch>");
    }
    mr.push_back(b);
  }
  return out;
}

std::vector<RotorFamily> DeriveBundledFamilies(const std::string& data_dir, const std::string& leave_out) {
  return DeriveBundledFamilies(ReadFamilyBlades(data_dir), leave_out);
}

std::vector<RotorFamily> DeriveBundledFamilies(const FamilyBlades& blades, const std::string& leave_out) {
  auto of = [&](const std::string& family) {
    std::vector<FamilyBlade> out;
    for (const FamilyBlade& b : blades.uiuc) {
      if (b.family == family) out.push_back(b);
    }
    return out;
  };
  const std::string uiuc_src = "UIUC Propeller Data Site vol 1-2 geometry (uiuc_propdb/volume1_geom.csv, volume2_geom.csv), family ";
  return {FamilyShape("apc_e", "APC thin electric (E)", uiuc_src + "apce", of("apce"), leave_out),
          FamilyShape("apc_sf", "APC slow flyer (SF)", uiuc_src + "apcsf", of("apcsf"), leave_out),
          FamilyShape("apc_sport", "APC sport", uiuc_src + "apcsp", of("apcsp"), leave_out),
          FamilyShape("multirotor", "multirotor (APC MR planform and twist)",
                      "APC's geometry files of its MR propellers (apc_geometry/geometry/*MR-PERF.PE0, v2022-0915)",
                      blades.apc_mr, leave_out)};
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

std::vector<RotorFitCase> UiucCases(const std::vector<PropEntry>& props,
                                    const std::map<std::string, FamilyBlade>& blades, int max_sweep_points) {
  std::vector<RotorFitCase> out;
  for (const PropEntry& p : props) {
    const auto it = blades.find(UiucBladeNameOfId(p.id));
    if (it == blades.end()) continue;
    RotorFitCase c;
    c.name = p.id;
    c.family = it->second.family;
    c.geometry = it->second.geometry;
    c.geometry.blades = p.blades.value_or(2);
    const PropStaticTable& st = p.static_table;
    for (std::size_t i = 0; i < st.rpm.size(); ++i) c.points.push_back({st.rpm[i], 0.0, st.ct[i], st.cp[i], 0.0});
    for (const PropSweep& s : p.j_tables) {
      std::vector<std::size_t> usable;
      for (std::size_t i = 0; i < s.j.size(); ++i) {
        if (s.j[i] > 0.0 && s.ct[i] > 0.0 && s.cp[i] > 0.0) usable.push_back(i);
      }
      const std::size_t n = usable.size();
      const std::size_t keep = std::min<std::size_t>(n, static_cast<std::size_t>(std::max(1, max_sweep_points)));
      for (std::size_t k = 0; k < keep; ++k) {
        const std::size_t i = usable[keep > 1 ? k * (n - 1) / (keep - 1) : 0];
        c.points.push_back({s.rpm, s.j[i], s.ct[i], s.cp[i], s.j[i] * s.ct[i] / s.cp[i]});
      }
    }
    if (!c.points.empty()) out.push_back(std::move(c));
  }
  return out;
}

}  // namespace dynosize
