#include "fit/nist_strd.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <vector>

#include "common/error.h"
#include "common/text_file.h"

namespace dynosize {
namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

[[noreturn]] void Fail(const std::string& path, int line, const std::string& what) {
  std::ostringstream os;
  os << path << ":" << line << ": " << what;
  throw DataError(os.str());
}

// Finds "<label> (lines A to B)" in the header and returns A, B.
std::pair<int, int> FindRange(const std::vector<std::string>& lines, const std::string& path,
                              const std::string& label) {
  for (size_t i = 0; i < lines.size() && i < 40; ++i) {
    const std::string l = Lower(lines[i]);
    const size_t at = l.find(label);
    if (at == std::string::npos) continue;
    const size_t paren = l.find("(lines", at);
    if (paren == std::string::npos) continue;
    int a = 0, b = 0;
    std::string word;
    std::istringstream is(l.substr(paren + 6));
    if (!(is >> a >> word >> b) || word != "to" || a < 1 || b < a) {
      Fail(path, static_cast<int>(i + 1), "expected '" + label + " (lines A to B)'");
    }
    return {a, b};
  }
  Fail(path, 0, "no header line '" + label + " (lines A to B)'");
}

}  // namespace

NistDataset ReadNistDataset(const std::string& path) {
  const std::string text = ReadTextFile(path, 1 << 20);
  std::vector<std::string> lines;
  {
    std::istringstream is(text);
    std::string l;
    while (std::getline(is, l)) {
      if (!l.empty() && l.back() == '\r') l.pop_back();  // the files come with CRLF from NIST
      lines.push_back(l);
    }
  }
  NistDataset d;
  d.path = path;
  {
    const size_t slash = path.find_last_of('/');
    std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    d.name = base.substr(0, base.find('.'));
  }
  const auto [ps, pe] = FindRange(lines, path, "starting values");
  const auto [ds, de] = FindRange(lines, path, "data ");
  if (de > static_cast<int>(lines.size())) {
    Fail(path, de, "the header promises data up to this line but the file has " +
                       std::to_string(lines.size()) + " lines");
  }
  const int p = pe - ps + 1;
  d.start1.resize(p); d.start2.resize(p); d.certified_values.resize(p); d.certified_std_devs.resize(p);
  for (int k = 0; k < p; ++k) {
    const int ln = ps + k;
    std::istringstream is(lines[ln - 1]);
    std::string name, eq;
    double v[4];
    if (!(is >> name >> eq >> v[0] >> v[1] >> v[2] >> v[3]) || eq != "=" ||
        name != "b" + std::to_string(k + 1)) {
      Fail(path, ln, "expected 'b" + std::to_string(k + 1) + " = start1 start2 certified sd'");
    }
    d.start1[k] = v[0]; d.start2[k] = v[1]; d.certified_values[k] = v[2]; d.certified_std_devs[k] = v[3];
  }
  bool found_rss = false;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string key = "residual sum of squares:";
    const size_t at = Lower(lines[i]).find(key);
    if (at == std::string::npos) continue;
    std::istringstream is(lines[i].substr(at + key.size()));
    if (!(is >> d.certified_residual_sum_of_squares)) Fail(path, static_cast<int>(i + 1), "expected a number after 'Residual Sum of Squares:'");
    found_rss = true;
    break;
  }
  if (!found_rss) Fail(path, 0, "no 'Residual Sum of Squares:' line");

  const int n = de - ds + 1;
  std::vector<std::vector<double>> rows;
  for (int ln = ds; ln <= de; ++ln) {
    std::istringstream is(lines[ln - 1]);
    std::vector<double> row;
    double v;
    while (is >> v) row.push_back(v);
    if (row.size() < 2 || !is.eof()) Fail(path, ln, "expected a data line 'y x1 [x2 ...]' of numbers");
    if (!rows.empty() && row.size() != rows[0].size()) {
      Fail(path, ln, "this data line has " + std::to_string(row.size()) + " numbers, the first had " +
                         std::to_string(rows[0].size()));
    }
    rows.push_back(row);
  }
  const int cols = static_cast<int>(rows[0].size());
  d.y.resize(n);
  d.x.resize(n, cols - 1);
  for (int i = 0; i < n; ++i) {
    d.y[i] = rows[i][0];
    for (int c = 1; c < cols; ++c) d.x(i, c - 1) = rows[i][c];
  }
  return d;
}

double LogRelativeError(double estimate, double certified) {
  const double err = certified == 0.0 ? std::abs(estimate) : std::abs(estimate - certified) / std::abs(certified);
  if (!std::isfinite(err)) return 0.0;
  if (err == 0.0) return 15.0;
  return std::clamp(-std::log10(err), 0.0, 15.0);
}

}  // namespace dynosize
