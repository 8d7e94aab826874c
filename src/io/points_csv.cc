#include "io/points_csv.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "common/error.h"
#include "common/text_encoding.h"
#include "common/text_file.h"
#include "common/text_format.h"
#include "logs/csv_scan.h"

namespace dynosize {

namespace {

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> SplitComma(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(Trim(cell));
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

}  // namespace

std::string CheckPointRequest(const PointRequest& r) {
  if (!RequestVdcInRange(r.vdc_v)) {
    return "vdc_v = " + SignificantText(r.vdc_v) + ": must be > 0 V and <= " + SignificantText(kMaxRequestVdcV) + " V";
  }
  if (r.throttle && !RequestThrottleInRange(*r.throttle)) {
    return "throttle = " + SignificantText(*r.throttle) + ": must be between 0 and 1 (a fraction, not percent)";
  }
  if (r.torque_nm && !RequestTorqueInRange(*r.torque_nm)) {
    return "torque_nm = " + SignificantText(*r.torque_nm) +
           ": must be >= 0 N*m and <= " + SignificantText(kMaxRequestTorqueNm) + " N*m";
  }
  if (r.rpm && !RequestRpmInRange(*r.rpm)) {
    return "rpm = " + SignificantText(*r.rpm) + ": must be >= 0 and <= " + SignificantText(kMaxRequestRpm);
  }
  if (!r.prop.empty()) {
    if (r.torque_nm) return "a row with a prop takes its load from the propeller: leave torque_nm empty";
    const int given = (r.throttle ? 1 : 0) + (r.rpm ? 1 : 0) + (r.thrust_n ? 1 : 0);
    if (given != 1) {
      return "a row with a prop gives exactly one of throttle (forward), rpm or thrust_n (the "
             "throttle solved)";
    }
    if (r.thrust_n && !RequestThrustInRange(*r.thrust_n)) {
      return "thrust_n = " + SignificantText(*r.thrust_n) +
             ": must be > 0 N and <= " + SignificantText(kMaxRequestThrustN) + " N";
    }
    return "";
  }
  if (r.thrust_n) return "thrust_n needs a prop (a catalog propeller id) in the row";
  const int given = (r.throttle ? 1 : 0) + (r.torque_nm ? 1 : 0) + (r.rpm ? 1 : 0);
  if (given != 2) {
    return "give exactly two of throttle, torque_nm, rpm (throttle+torque_nm or throttle+rpm: "
           "forward model; torque_nm+rpm: inverse)";
  }
  return "";
}

std::vector<PointRequest> ReadPointsCsv(const std::string& path) {
  std::string text = ReadTextFile(path, 256u << 20);
  // CR-only line ends (a spreadsheet re-save, as for logs) become LF; CRLF keeps its CR, which
  // Trim removes.
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n')) text[i] = '\n';
  }
  if (const std::string enc = UnsupportedTextEncoding(std::string_view(text).substr(0, 64));
      !enc.empty()) {
    throw DataError(path + ": the file is " + enc + ": save it as UTF-8 text");
  }
  std::istringstream in(text);
  std::string line;
  std::size_t line_no = 0;
  std::vector<std::string> header;
  while (header.empty() && std::getline(in, line)) {
    ++line_no;
    if (line_no == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 BOM
    if (!Trim(line).empty()) header = SplitComma(line);
  }
  if (header.empty()) throw DataError(path + ": empty file: expected a header line");
  enum Col { kVdc, kThrottle, kTorque, kRpm, kProp, kThrust };
  std::vector<Col> cols;
  bool seen[6] = {false, false, false, false, false, false};
  for (const auto& h : header) {
    Col c;
    if (h == "vdc_v") c = kVdc;
    else if (h == "throttle") c = kThrottle;
    else if (h == "torque_nm") c = kTorque;
    else if (h == "rpm") c = kRpm;
    else if (h == "prop") c = kProp;
    else if (h == "thrust_n") c = kThrust;
    else {
      throw DataError(path + ":" + std::to_string(line_no) + ": unknown column " +
                      logs::QuoteCell(h) + ": allowed are vdc_v, throttle, torque_nm, rpm, prop, thrust_n");
    }
    if (seen[c]) throw DataError(path + ":" + std::to_string(line_no) + ": duplicate column \"" + h + "\"");
    seen[c] = true;
    cols.push_back(c);
  }
  if (!seen[kVdc]) throw DataError(path + ":" + std::to_string(line_no) + ": missing column \"vdc_v\"");
  std::vector<PointRequest> out;
  while (std::getline(in, line)) {
    ++line_no;
    if (Trim(line).empty()) continue;
    const auto cells = SplitComma(line);
    const std::string where = path + ":" + std::to_string(line_no);
    if (cells.size() != cols.size()) {
      throw DataError(where + ": " + std::to_string(cells.size()) + " cells, the header has " +
                      std::to_string(cols.size()));
    }
    PointRequest r;
    r.row = line_no;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (cells[i].empty()) {
        if (cols[i] == kVdc) throw DataError(where + ": column vdc_v is empty: a value is required");
        continue;
      }
      if (cols[i] == kProp) {
        r.prop = cells[i];  // an id; the catalog lookup names the closest ids when unknown
        continue;
      }
      double v = 0.0;
      const char* b = cells[i].data();
      const char* e = b + cells[i].size();
      const auto res = std::from_chars(b, e, v);
      if (res.ec != std::errc() || res.ptr != e || !std::isfinite(v)) {
        throw DataError(where + ": column " + header[i] + " = " + logs::QuoteCell(cells[i]) +
                        ": not a finite number");
      }
      switch (cols[i]) {
        case kVdc: r.vdc_v = v; break;
        case kThrottle: r.throttle = v; break;
        case kTorque: r.torque_nm = v; break;
        case kRpm: r.rpm = v; break;
        case kThrust: r.thrust_n = v; break;
        case kProp: break;
      }
    }
    const std::string rule = CheckPointRequest(r);
    if (!rule.empty()) throw DataError(where + ": " + rule);
    out.push_back(r);
  }
  if (out.empty()) throw DataError(path + ": no data rows after the header");
  return out;
}

}  // namespace dynosize
