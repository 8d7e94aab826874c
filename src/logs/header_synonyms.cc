#include "logs/header_synonyms.h"

#include <algorithm>

#include "logs/csv_scan.h"

namespace dynosize::logs {

namespace {

// Who writes which name (docs/log-formats.md lists the same table):
//   RCbenchmark Series 1520/1580/1585/1780: "ESC signal (µs)", "ESC (µs)", "Motor Optical Speed
//     (RPM)", "Motor Electrical Speed (RPM)", "Torque (N·m)", "Thrust (gf)", "Voltage (V)",
//     "Current (A)";
//   Tyto Flight Stand: "Throttle (µs)", "PWM throttle signal (µs)", "Rotation speed (rpm)",
//     "Thrust (kgf)", "Torque (N⋅m)", quoted cells;
//   ThrustApp (jmajew): "out", "level [%]", "thrust [G]", "torque [G cm]", "rpm";
//   student rigs and manufacturer tables: "throttle", "throttle_pct", "voltage_V", "current_A",
//     "thrust_g", "torque_Nm", "rpm", "Amps", "Batt. Volts".
// The canonical names themselves ("vdc_v", "omega_rad_s", ...) read through step 3 or by name.
const std::vector<HeaderSynonym> kSynonyms = {
    {Column::kTimeS, "time", "", false, 0},
    {Column::kTimeS, "elapsed time", "", false, 0},

    {Column::kThrottle, "esc signal", "", true, 0},
    {Column::kThrottle, "esc", "", true, 0},
    {Column::kThrottle, "esc throttle", "", true, 0},
    {Column::kThrottle, "esc command", "", true, 0},
    {Column::kThrottle, "throttle", "", true, 0},
    {Column::kThrottle, "pwm throttle signal", "", true, 0},
    {Column::kThrottle, "throttle signal", "", true, 0},
    {Column::kThrottle, "pwm signal", "", true, 0},
    {Column::kThrottle, "esc pwm", "", true, 0},
    {Column::kThrottle, "throttle pct nominal", "%", false, 0},
    {Column::kThrottle, "throttle pct", "%", false, 0},
    {Column::kThrottle, "throttle percent", "%", false, 0},
    {Column::kThrottle, "out", "", false, 0},
    {Column::kThrottle, "level", "", false, 0},

    {Column::kOmegaRadS, "motor optical speed", "", true, 0},
    {Column::kOmegaRadS, "rotation speed", "", true, 1},
    {Column::kOmegaRadS, "motor speed", "", true, 1},
    {Column::kOmegaRadS, "motor electrical speed", "", true, 1},
    {Column::kOmegaRadS, "optical speed", "", false, 0},
    {Column::kOmegaRadS, "optical rpm", "rpm", false, 0},
    {Column::kOmegaRadS, "electrical speed", "", false, 1},
    {Column::kOmegaRadS, "electrical rpm", "rpm", false, 1},
    {Column::kOmegaRadS, "rotational speed", "", false, 1},
    {Column::kOmegaRadS, "speed", "", false, 1},
    {Column::kOmegaRadS, "rpm", "rpm", false, 1},
    {Column::kOmegaRadS, "motor rpm", "rpm", false, 1},
    {Column::kOmegaRadS, "omega", "", false, 1},
    {Column::kOmegaRadS, "omega rad s", "rad/s", false, 1},

    {Column::kVdcV, "voltage", "", false, 0},
    {Column::kVdcV, "vdc", "", false, 0},
    {Column::kVdcV, "volt", "V", false, 0},
    {Column::kVdcV, "volts", "V", false, 0},
    {Column::kVdcV, "batt volts", "V", false, 0},
    {Column::kVdcV, "battery voltage", "", false, 0},
    {Column::kVdcV, "supply voltage", "", false, 0},
    {Column::kVdcV, "bus voltage", "", false, 0},
    {Column::kVdcV, "dc voltage", "", false, 0},
    {Column::kVdcV, "vbat", "", false, 0},

    {Column::kIdcA, "current", "", false, 0},
    {Column::kIdcA, "idc", "", false, 0},
    {Column::kIdcA, "curr", "", false, 0},
    {Column::kIdcA, "amps", "A", false, 0},
    {Column::kIdcA, "amp", "A", false, 0},
    {Column::kIdcA, "battery current", "", false, 0},
    {Column::kIdcA, "supply current", "", false, 0},
    {Column::kIdcA, "bus current", "", false, 0},
    {Column::kIdcA, "dc current", "", false, 0},

    {Column::kTorqueNm, "torque", "", false, 0},
    {Column::kTorqueNm, "motor torque", "", false, 0},
    {Column::kTorqueNm, "shaft torque", "", false, 0},

    {Column::kThrustN, "thrust", "", false, 0},
    {Column::kThrustN, "thrust force", "", false, 0},
    {Column::kThrustN, "propeller thrust", "", false, 0},

    {Column::kTempC, "temp", "", false, 0},
    {Column::kTempC, "temperature", "", false, 0},
    {Column::kTempC, "motor temperature", "", false, 0},

    {Column::kVllRmsV, "vll rms", "", false, 0},
    {Column::kIrmsA, "irms", "", false, 0},
    {Column::kPacW, "pac", "", false, 0},
};

const HeaderSynonym* Find(const std::string& norm) {
  for (const HeaderSynonym& s : kSynonyms) {
    if (norm == s.name) return &s;
  }
  return nullptr;
}

HeaderMatch FromEntry(const HeaderSynonym& s, const std::string& unit, bool written) {
  HeaderMatch m;
  m.column = s.column;
  m.quantity = ColumnQuantity(s.column);
  m.unit = written ? unit : std::string(s.implied_unit);
  m.unit_written = written;
  m.stand = s.stand;
  m.rank = s.rank;
  return m;
}

// Words that suggest a column without naming it as the table does (LookalikeColumns).
struct Hint {
  Column column;
  const char* words[10];
};
const Hint kHints[] = {
    {Column::kThrottle, {"throttle", "pwm", "signal", "esc", "duty", "command", "cmd", "level", "input", nullptr}},
    {Column::kOmegaRadS, {"rpm", "speed", "omega", "rotation", "rev", "tacho", nullptr}},
    {Column::kVdcV, {"volt", "vbat", "batt", "vdc", nullptr}},
    {Column::kIdcA, {"curr", "amp", "idc", nullptr}},
    {Column::kTorqueNm, {"torque", "moment", nullptr}},
    {Column::kThrustN, {"thrust", "force", "weight", "lift", nullptr}},
    {Column::kTimeS, {"time", nullptr}},
};

}  // namespace

const std::vector<HeaderSynonym>& HeaderSynonyms() { return kSynonyms; }

Quantity ColumnQuantity(Column c) {
  switch (c) {
    case Column::kTimeS: return Quantity::kTime;
    case Column::kVdcV: case Column::kVllRmsV: return Quantity::kVoltage;
    case Column::kThrottle: return Quantity::kThrottle;
    case Column::kOmegaRadS: return Quantity::kSpeed;
    case Column::kTorqueNm: return Quantity::kTorque;
    case Column::kIdcA: case Column::kIrmsA: return Quantity::kCurrent;
    case Column::kPacW: return Quantity::kPower;
    case Column::kTempC: return Quantity::kTemperature;
    case Column::kThrustN: return Quantity::kForce;
    case Column::kNoLoad: return Quantity::kFlag;
    case Column::kMotorId: return Quantity::kId;
  }
  return Quantity::kId;
}

std::string NormaliseHeaderName(std::string_view name) {
  std::string out;
  for (const char ch : name) {
    char c = ch;
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c == '_' || c == '\t' || c == '.') c = ' ';
    if (c == ' ' && (out.empty() || out.back() == ' ')) continue;
    out.push_back(c);
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ':')) out.pop_back();
  return out;
}

std::optional<HeaderMatch> MatchHeader(std::string_view cell) {
  const HeaderCell hc = SplitHeaderCell(cell);
  const std::string name = NormaliseHeaderName(hc.name);
  if (const HeaderSynonym* s = Find(name)) return FromEntry(*s, hc.unit, !hc.unit.empty());
  if (hc.unit.empty()) {
    // Step 3: the last word as the unit ("voltage_V" -> "voltage" in V).
    const std::size_t sp = name.rfind(' ');
    if (sp != std::string::npos && sp > 0) {
      // The unit as written: the same last word of the raw cell (case kept for messages).
      const std::string raw(Trim(cell));
      std::size_t cut = raw.find_last_of(" _\t");
      const std::string unit = cut == std::string::npos ? std::string() : raw.substr(cut + 1);
      const HeaderSynonym* s = Find(name.substr(0, sp));
      const std::string norm_unit = AsciiLower(unit) == "pct" ? "%" : unit;
      if (s != nullptr && !unit.empty() && ParseUnit(ColumnQuantity(s->column), norm_unit)) {
        return FromEntry(*s, norm_unit, true);
      }
    }
  }
  // A temperature probe of any name ("4N76 Temp (ºC)").
  if (name.find("temp") != std::string::npos && !hc.unit.empty() &&
      ParseUnit(Quantity::kTemperature, hc.unit)) {
    HeaderMatch m;
    m.column = Column::kTempC;
    m.quantity = Quantity::kTemperature;
    m.unit = hc.unit;
    m.unit_written = true;
    return m;
  }
  return std::nullopt;
}

std::vector<std::size_t> LookalikeColumns(Column c, const std::vector<std::string>& cells,
                                          const std::vector<std::size_t>& skip) {
  std::vector<std::size_t> out;
  // A cell that is a unit of the quantity ("V", "A" in a manufacturer table) or writes one
  // ("i[A]") first.
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (std::find(skip.begin(), skip.end(), i) != skip.end()) continue;
    const std::string unit = SplitHeaderCell(cells[i]).unit;
    const bool is_unit = !cells[i].empty() && ParseUnit(ColumnQuantity(c), cells[i]);
    const bool has_unit = !unit.empty() && ParseUnit(ColumnQuantity(c), unit);
    if (c != Column::kThrottle && (is_unit || has_unit)) out.push_back(i);
  }
  for (const Hint& h : kHints) {
    if (h.column != c) continue;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (std::find(skip.begin(), skip.end(), i) != skip.end()) continue;
      if (std::find(out.begin(), out.end(), i) != out.end()) continue;
      const std::string lower = AsciiLower(cells[i]);
      for (const char* const* w = h.words; *w != nullptr; ++w) {
        if (lower.find(*w) != std::string::npos) {
          out.push_back(i);
          break;
        }
      }
    }
  }
  return out;
}

std::string MapArgument(Column c, const std::string& cell) {
  const Quantity q = ColumnQuantity(c);
  const HeaderCell hc = SplitHeaderCell(cell);
  const bool unit_ok = !hc.unit.empty() && ParseUnit(q, hc.unit).has_value();
  const auto m = MatchHeader(cell);
  std::string unit;  // written in brackets after the header
  if (!unit_ok && m && m->column == c && !m->unit.empty() && ParseUnit(q, m->unit)) {
    unit = m->unit;
  } else if (!unit_ok && c != Column::kThrottle && !cell.empty() && ParseUnit(q, cell)) {
    unit = cell;  // the cell is its unit ("V")
  } else if (!unit_ok && c == Column::kOmegaRadS && AsciiLower(cell).find("rpm") != std::string::npos) {
    unit = "rpm";  // "rpm1", "TargetRPM"
  } else if (!unit_ok && c != Column::kThrottle) {
    unit = "UNIT";
  }
  return "--map \"" + std::string(ColumnName(c)) + "=" + cell + (unit.empty() ? "" : " [" + unit + "]") +
         "\"";
}

std::string UnitChoices(Column c) {
  return std::string(ColumnName(c)) + ": " + ValidUnits(ColumnQuantity(c));
}

}  // namespace dynosize::logs
