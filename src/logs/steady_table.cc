#include "logs/steady_table.h"

#include <sstream>

#include "common/error.h"

namespace dynosize::logs {

const char* ColumnName(Column c) {
  switch (c) {
    case Column::kTimeS: return "time_s";
    case Column::kVdcV: return "vdc_v";
    case Column::kThrottle: return "throttle";
    case Column::kOmegaRadS: return "omega_rad_s";
    case Column::kTorqueNm: return "torque_nm";
    case Column::kIdcA: return "idc_a";
    case Column::kVllRmsV: return "vll_rms_v";
    case Column::kIrmsA: return "irms_a";
    case Column::kPacW: return "pac_w";
    case Column::kTempC: return "temp_c";
    case Column::kThrustN: return "thrust_n";
    case Column::kNoLoad: return "no_load";
    case Column::kMotorId: return "motor_id";
  }
  return "?";
}

const char* LogFormatName(LogFormat f) {
  switch (f) {
    case LogFormat::kAuto: return "auto";
    case LogFormat::kCanonical: return "canonical";
    case LogFormat::kRcbenchmark: return "rcbenchmark";
    case LogFormat::kMapped: return "mapped";
    case LogFormat::kDriveCalc: return "drivecalc";
    case LogFormat::kThrustApp: return "thrustapp";
  }
  return "?";
}

const std::vector<LogFormat>& AllLogFormats() {
  static const std::vector<LogFormat> all = {LogFormat::kAuto,    LogFormat::kCanonical, LogFormat::kRcbenchmark,
                                             LogFormat::kMapped,  LogFormat::kDriveCalc, LogFormat::kThrustApp};
  return all;
}

std::vector<std::string> LogFormatNames() {
  std::vector<std::string> names;
  for (const LogFormat f : AllLogFormats()) names.emplace_back(LogFormatName(f));
  return names;
}

std::string LogFormatHelp() {
  std::string help;
  for (const LogFormat f : AllLogFormats()) {
    const char* what = "";
    switch (f) {
      case LogFormat::kAuto: what = "detected from the file"; break;
      case LogFormat::kCanonical: what = "dynosize's CSV"; break;
      case LogFormat::kRcbenchmark: what = "RCbenchmark / Tyto exports; --map adds columns"; break;
      case LogFormat::kMapped: what = "any table through --map"; break;
      case LogFormat::kDriveCalc: what = "DriveCalc MData.csv"; break;
      case LogFormat::kThrustApp: what = "ThrustApp .tex/.txt reports"; break;
    }
    help += std::string(help.empty() ? "" : ", ") + LogFormatName(f) + " (" + what + ")";
  }
  return help;
}

LogFormat LogFormatFromName(const std::string& name) {
  std::string valid;
  for (const LogFormat f : AllLogFormats()) {
    if (name == LogFormatName(f)) return f;
    valid += std::string(valid.empty() ? "" : ", ") + LogFormatName(f);
  }
  throw UsageError("--format '" + name + "': valid are " + valid);
}

const std::vector<double>& SteadyTable::Get(Column c) const {
  if (!Has(c)) {
    throw InternalError(std::string("SteadyTable::Get: column ") + ColumnName(c) +
                        " is absent in " + file + " (check Has() first)");
  }
  return columns[static_cast<int>(c)];
}

std::size_t SteadyTable::DroppedTotal() const {
  std::size_t n = 0;
  for (const auto& d : dropped) n += d.count;
  return n;
}

void AddDrop(SteadyTable* table, const std::string& reason, std::size_t n) {
  if (n == 0) return;
  for (auto& d : table->dropped) {
    if (d.reason == reason) {
      d.count += n;
      return;
    }
  }
  table->dropped.push_back({reason, n});
}

std::string SteadyTable::BriefReport() const {
  std::ostringstream out;
  out << file << ": " << LogFormatName(format) << ", " << data_rows_read << " rows read, ";
  if (time_series) {
    out << plateaus_found << " plateaus (" << transient_samples << " transient, "
        << outlier_samples << " outlier samples dropped)";
  } else {
    out << rows() << " points";
  }
  const std::size_t d = DroppedTotal();
  if (d > 0) {
    out << ", dropped " << d << " (";
    for (std::size_t i = 0; i < dropped.size(); ++i) {
      if (i > 0) out << "; ";
      out << dropped[i].count << " " << dropped[i].reason;
    }
    out << ")";
  }
  // Which columns the fit gets: what it can identify follows from them (steady_table.h).
  std::string found, missing;
  for (const Column c : {Column::kThrottle, Column::kVdcV, Column::kIdcA, Column::kOmegaRadS,
                         Column::kTorqueNm, Column::kThrustN, Column::kVllRmsV, Column::kIrmsA,
                         Column::kPacW}) {
    std::string& to = Has(c) ? found : missing;
    to += std::string(to.empty() ? "" : " ") + ColumnName(c);
  }
  out << "; columns: " << (found.empty() ? "none" : found);
  if (!missing.empty()) out << "; absent: " << missing;
  return out.str();
}

std::string SteadyTable::FullReport() const {
  std::ostringstream out;
  out << BriefReport() << "\n";
  out << "  line ends " << (line_ends.empty() ? "?" : line_ends) << (had_bom ? ", BOM" : "")
      << (header_latin1 ? ", Latin-1 header" : "") << ", delimiter '"
      << (delimiter == '\t' ? std::string("\\t") : std::string(1, delimiter)) << "'\n";
  for (int i = 0; i < kColumnCount; ++i) {
    const ColumnInfo& ci = info[i];
    out << "  " << ColumnName(static_cast<Column>(i)) << ": ";
    if (ci.present) {
      out << "from \"" << ci.source_header << "\"";
      if (!ci.source_unit.empty()) out << " [" << ci.source_unit << "]";
    } else {
      out << "absent";
    }
    if (!ci.note.empty()) out << " (" << ci.note << ")";
    out << "\n";
  }
  for (const auto& n : notes) out << "  note: " << n << "\n";
  return out.str();
}

}  // namespace dynosize::logs
