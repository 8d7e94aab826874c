// The one table of column header names per canonical quantity (docs/log-formats.md, "Header
// synonyms"), used by the format detection and by every format that names its columns
// (rcbenchmark / Tyto, unit-suffixed tables, canonical names).
//
// A header cell is matched in three steps, names compared after normalisation (ASCII lower
// case, '_' and runs of blanks as one space, a trailing '.' or ':' dropped):
//   1. "Name (unit)", "Name [unit]" or "Name - unit" (SplitHeaderCell): the name is looked up,
//      the unit is the written one ("Thrust (kgf)", "PWM throttle signal (µs)");
//   2. no bracketed unit: the whole cell is looked up ("rpm", "Amps", "throttle");
//   3. else the last word is tried as a unit of the quantity the rest names ("voltage_V",
//      "thrust_g", "Thrust g", "out_pct", "torque_Nm").
// A name that is itself a unit ("RPM", "Amps", "Volts") implies it. A temperature is any name
// holding "temp" with a temperature unit ("4N76 Temp (ºC)"). Electrical speed is the shaft speed
// the stand software computes from the pole count it was given (RCbenchmark, Tyto): read as rpm
// of the shaft; an "eRPM" (electrical revolutions, before division by the pole pairs) is not in
// the table.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "logs/log_units.h"
#include "logs/steady_table.h"

namespace dynosize::logs {

struct HeaderSynonym {
  Column column;
  const char* name;          // normalised (lower case, single spaces)
  const char* implied_unit;  // unit when the header writes none ("" = none implied)
  // Written by a stand export (RCbenchmark, Tyto Flight Stand): a command or speed column named
  // so marks a stand log (kRcbenchmark: time series, lenient cells).
  bool stand;
  // Among several columns of one quantity in a file, the lower rank is used first (the optical
  // speed probe before the electrical one, whose low-throttle readings are spurious).
  int rank;
};

// The table, in documentation order.
const std::vector<HeaderSynonym>& HeaderSynonyms();

// The quantity (valid units) of a canonical column.
Quantity ColumnQuantity(Column c);

struct HeaderMatch {
  Column column = Column::kTimeS;
  Quantity quantity = Quantity::kTime;
  std::string unit;           // written in the cell, or implied by the name; "" when none
  bool unit_written = false;  // the cell writes a unit (bracketed or as a suffix word)
  bool stand = false;
  int rank = 0;
};

// Matches one header cell (UTF-8, trimmed) against the table; nullopt when it names no
// canonical quantity. The unit is not checked against the quantity except in step 3.
std::optional<HeaderMatch> MatchHeader(std::string_view cell);

// The normalised name of a header name (without its unit), as the table stores names.
std::string NormaliseHeaderName(std::string_view name);

// Header cells (indices into `cells`, not in `skip`) whose text suggests column `c` without
// matching the table: "PWM", "signal", "throttle", "duty", ... for throttle; "rpm", "speed"
// for the speed; and so on. For the error that names the lookalikes of a missing quantity.
std::vector<std::size_t> LookalikeColumns(Column c, const std::vector<std::string>& cells,
                                          const std::vector<std::size_t>& skip);

// A --map entry reading `cell` as column `c`, quoted for a shell ("--map \"throttle=PWM signal
// (µs)\""). The unit the cell implies or writes as a suffix is spelled out ("[g]"); a cell that
// names no unit gets "[UNIT]", to be replaced by one of UnitChoices(c) (throttle excepted: no
// unit reads as a fraction 0..1).
std::string MapArgument(Column c, const std::string& cell);
// "thrust_n: n, gf, g, kgf, ..." for the message that asks for a UNIT.
std::string UnitChoices(Column c);

}  // namespace dynosize::logs
