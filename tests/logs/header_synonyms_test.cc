// The header synonym table (logs/header_synonyms.h). Every synonym of every canonical
// column reads the same numbers; the Tyto Flight Stand variant with "PWM throttle signal (µs)"
// reads; a missing quantity names its lookalikes and the arguments that read them; canonical
// steady tables without time_s and torque_nm; the --decimal-comma hint on a shifted cell.
// Tables are written here from strings (values made up).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <map>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/units.h"
#include "logs/header_synonyms.h"
#include "logs/log_reader.h"
#include "logs/log_test_util.h"

namespace dynosize::logs {
namespace {

using testing_util::Contains;
using testing_util::ErrorOf;
using testing_util::RelErr;
using testing_util::WriteTemp;

// Values written with 17 significant digits and converted once (a percent, rad/s from rpm) on
// each side: a few roundings of one double operation each.
constexpr double kSynonymRelTol = 1e-12;

// One canonical column of the fuzz table: its canonical header cell, the unit written after a
// synonym that implies none, and the values in the canonical unit.
struct FuzzColumn {
  Column column;
  std::string canonical_cell;
  std::string unit;  // written as "Name (unit)"
};

const std::vector<FuzzColumn> kFuzzColumns = {
    {Column::kTimeS, "time_s", "s"},         {Column::kVdcV, "vdc_v", "V"},
    {Column::kThrottle, "throttle", "%"},    {Column::kOmegaRadS, "rpm", "rpm"},
    {Column::kTorqueNm, "torque_nm", "N*m"}, {Column::kIdcA, "Current (A)", "A"},
    {Column::kVllRmsV, "vll_rms_v", "V"},    {Column::kIrmsA, "irms_a", "A"},
    {Column::kPacW, "pac_w", "W"},           {Column::kTempC, "temp_c", "C"},
    {Column::kThrustN, "thrust_n", "N"},
};

// The value of row r of column c in its canonical unit (throttle a fraction, speed in rpm).
double FuzzValue(Column c, int r) {
  switch (c) {
    case Column::kTimeS: return 2.0 * r;  // 2 s apart: one steady point per row
    case Column::kVdcV: return 16.8 - 0.1 * r;
    case Column::kThrottle: return 0.2 + 0.1 * r;
    case Column::kOmegaRadS: return 4000.0 + 1234.5 * r;
    case Column::kTorqueNm: return 0.02 + 0.013 * r * r;
    case Column::kIdcA: return 0.7 + 1.9 * r * r;
    case Column::kVllRmsV: return 5.0 + 0.8 * r;
    case Column::kIrmsA: return 0.9 + 2.1 * r * r;
    case Column::kPacW: return 10.0 + 25.0 * r * r;
    case Column::kTempC: return 31.0 + 0.5 * r;
    case Column::kThrustN: return 1.5 + 1.1 * r * r;
    default: return 0.0;
  }
}

// The value written under `unit` (the column's fuzz unit, or a synonym's implied unit).
double InUnit(Column c, double canonical, const std::string& unit) {
  if (c == Column::kThrottle && unit == "%") return 100.0 * canonical;
  if (c == Column::kOmegaRadS && unit == "rad/s") return canonical * kRadPerSecPerRpm;
  return canonical;
}

// The fuzz table with column `renamed` headed `cell` and written in `unit`.
std::string FuzzTable(Column renamed, const std::string& cell, const std::string& unit) {
  std::string s;
  for (std::size_t k = 0; k < kFuzzColumns.size(); ++k) {
    s += (k ? "," : "") + (kFuzzColumns[k].column == renamed ? cell : kFuzzColumns[k].canonical_cell);
  }
  s += "\n";
  for (int r = 0; r < 6; ++r) {
    for (std::size_t k = 0; k < kFuzzColumns.size(); ++k) {
      const Column c = kFuzzColumns[k].column;
      double v = FuzzValue(c, r);
      if (c == renamed) v = InUnit(c, v, unit);
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.17g", v);
      s += (k ? "," : "") + std::string(buf);
    }
    s += "\n";
  }
  return s;
}

TEST(HeaderSynonyms, EveryColumnRenamedToEverySynonymReadsTheSameNumbers) {
  // The reference: the table with canonical names (current as "Current (A)", read as a table
  // named by the synonym table).
  const SteadyTable ref = ReadLog(WriteTemp("fuzz_ref.csv", FuzzTable(Column::kTimeS, "time_s", "s")));
  ASSERT_EQ(ref.rows(), 6u);
  for (const FuzzColumn& fc : kFuzzColumns) {
    ASSERT_TRUE(ref.Has(fc.column)) << fc.canonical_cell;
    const double want = fc.column == Column::kOmegaRadS ? FuzzValue(fc.column, 3) * kRadPerSecPerRpm
                                                        : FuzzValue(fc.column, 3);
    EXPECT_LT(RelErr(ref.Get(fc.column)[3], want), kSynonymRelTol) << fc.canonical_cell;
  }
  std::size_t tried = 0;
  for (const HeaderSynonym& syn : HeaderSynonyms()) {
    const FuzzColumn* fc = nullptr;
    for (const FuzzColumn& f : kFuzzColumns) {
      if (f.column == syn.column) fc = &f;
    }
    ASSERT_NE(fc, nullptr) << syn.name;
    // A synonym that implies its unit is written bare; any other as "Name (unit)".
    const std::string unit = syn.implied_unit[0] != '\0' ? syn.implied_unit : fc->unit;
    const std::string cell = syn.implied_unit[0] != '\0' ? syn.name : std::string(syn.name) + " (" + unit + ")";
    SCOPED_TRACE(cell);
    SteadyTable t;
    try {
      t = ReadLog(WriteTemp("fuzz.csv", FuzzTable(syn.column, cell, unit)));
    } catch (const Error& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    ++tried;
    EXPECT_EQ(t.format, syn.stand ? LogFormat::kRcbenchmark : LogFormat::kMapped);
    EXPECT_EQ(t.info[static_cast<int>(syn.column)].source_header, cell);
    ASSERT_EQ(t.rows(), ref.rows());
    for (const FuzzColumn& f : kFuzzColumns) {
      ASSERT_TRUE(t.Has(f.column)) << f.canonical_cell;
      for (std::size_t r = 0; r < t.rows(); ++r) {
        EXPECT_LT(RelErr(t.Get(f.column)[r], ref.Get(f.column)[r]), kSynonymRelTol)
            << f.canonical_cell << " row " << r;
      }
    }
  }
  EXPECT_EQ(tried, HeaderSynonyms().size());
}

TEST(HeaderSynonyms, UnitsAreReadFromTheHeaderInEveryForm) {
  struct Case {
    const char* cell;
    Column column;
    const char* unit;
  };
  const Case cases[] = {
      {"Thrust (kgf)", Column::kThrustN, "kgf"},       {"thrust_g", Column::kThrustN, "g"},
      {"Thrust g", Column::kThrustN, "g"},             {"Thrust [lbf]", Column::kThrustN, "lbf"},
      {"Thrust - gf", Column::kThrustN, "gf"},         {"torque_Nm", Column::kTorqueNm, "Nm"},
      {"Torque (kgf\xC2\xB7" "cm)", Column::kTorqueNm, "kgf\xC2\xB7" "cm"},
      {"throttle_pct", Column::kThrottle, "%"},        {"out_pct", Column::kThrottle, "%"},
      {"Throttle (%)", Column::kThrottle, "%"},        {"voltage_V", Column::kVdcV, "V"},
      {"Batt. Volts", Column::kVdcV, "V"},             {"Amps", Column::kIdcA, "A"},
      {"curr_A", Column::kIdcA, "A"},                  {"RPM", Column::kOmegaRadS, "rpm"},
      {"Motor Electrical Speed (RPM)", Column::kOmegaRadS, "RPM"},
      {"omega_rad_s", Column::kOmegaRadS, "rad/s"},    {"4N76 Temp (\xC2\xBA" "C)", Column::kTempC, "\xC2\xBA" "C"},
  };
  for (const Case& c : cases) {
    const auto m = MatchHeader(c.cell);
    ASSERT_TRUE(m.has_value()) << c.cell;
    EXPECT_EQ(m->column, c.column) << c.cell;
    EXPECT_EQ(m->unit, c.unit) << c.cell;
    EXPECT_TRUE(ParseUnit(m->quantity, m->unit).has_value()) << c.cell;
  }
  // Not columns of the fit: accelerations in g, servos, efficiencies, powers, eRPM.
  for (const char* cell : {"AccX (g)", "Servo 1 (\xC2\xB5s)", "Propeller efficiency (gf/W)",
                           "Electrical power (W)", "thrust_sd_g", "eRPM", "TargetRPM", "App message"}) {
    EXPECT_FALSE(MatchHeader(cell).has_value()) << cell;
  }
}

// ------------------------------------------------------------------ Tyto Flight Stand variant

// The header of the issue (a Tyto Flight Stand export of an MN6007II KV160), cells quoted,
// steps of 1 s at 10 Hz.
std::string TytoPwmVariant(const std::string& command_header) {
  std::string s = "\"Time (s)\",\"" + command_header +
                  "\",\"Rotation speed (rpm)\",\"Thrust (kgf)\",\"Torque (N\xE2\x8B\x85m)\",\"Voltage (V)\","
                  "\"Current (A)\",\"Electrical power (W)\",\"Mechanical power (W)\"\n";
  int k = 0;
  for (const int us : {1200, 1400, 1600, 1800}) {
    const double x = (us - 1000) / 1000.0;
    for (int i = 0; i < 10; ++i, ++k) {
      char buf[256];
      std::snprintf(buf, sizeof buf, "\"%.1f\",\"%d\",\"%.1f\",\"%.4f\",\"%.4f\",\"%.3f\",\"%.3f\",\"%.1f\",\"%.1f\"\n",
                    0.1 * k, us, 4800.0 * x, 2.5 * x * x, 0.6 * x * x, 33.4 - 0.5 * x, 0.6 + 30.0 * x * x,
                    (33.4 - 0.5 * x) * (0.6 + 30.0 * x * x), 300.0 * x * x * x);
      s += buf;
    }
  }
  return s;
}

TEST(TytoFlightStandVariant, PwmThrottleSignalHeaderReadsInMicrosecondsRpmKgfNmVA) {
  const SteadyTable t = ReadLog(WriteTemp("mn6007.csv", TytoPwmVariant("PWM throttle signal (\xC2\xB5s)")));
  EXPECT_EQ(t.format, LogFormat::kRcbenchmark);
  ASSERT_EQ(t.rows(), 4u);  // four plateaus
  for (const Column c : {Column::kThrottle, Column::kOmegaRadS, Column::kThrustN, Column::kTorqueNm,
                         Column::kVdcV, Column::kIdcA}) {
    EXPECT_TRUE(t.Has(c)) << ColumnName(c);
  }
  EXPECT_EQ(t.info[static_cast<int>(Column::kThrottle)].source_unit, "\xC2\xB5s");
  EXPECT_EQ(t.info[static_cast<int>(Column::kTorqueNm)].source_unit, "N\xE2\x8B\x85m");
  // Plateau 2 (1400 us): throttle 0.4 of 1000..2000 us, 1920 rpm, 0.4 kgf, 0.096 N*m.
  EXPECT_LT(RelErr(t.Get(Column::kThrottle)[1], 0.4), 1e-12);
  EXPECT_LT(RelErr(t.Get(Column::kOmegaRadS)[1], 1920.0 * kRadPerSecPerRpm), 1e-12);
  EXPECT_LT(RelErr(t.Get(Column::kThrustN)[1], 0.4 * kNewtonPerKilogramForce), 1e-12);
  EXPECT_LT(RelErr(t.Get(Column::kTorqueNm)[1], 0.096), 1e-12);
  EXPECT_LT(RelErr(t.Get(Column::kVdcV)[1], 33.2), 1e-12);
  EXPECT_LT(RelErr(t.Get(Column::kIdcA)[1], 5.4), 1e-12);
}

TEST(TytoFlightStandVariant, TableNameWithAnUnreadUnitIsLeftOutOfAStandExport) {
  // A wind-tunnel column "Speed (km/h)" beside the stand's own "Rotation speed (rpm)".
  std::string s = TytoPwmVariant("PWM throttle signal (\xC2\xB5s)");
  s.insert(s.find('\n'), ",\"Speed (km/h)\"");
  const SteadyTable t = ReadLog(WriteTemp("kmh.csv", s));
  EXPECT_EQ(t.info[static_cast<int>(Column::kOmegaRadS)].source_header, "Rotation speed (rpm)");
  bool noted = false;
  for (const auto& n : t.notes) noted = noted || Contains(n, "\"Speed (km/h)\" not read");
  EXPECT_TRUE(noted);
}

TEST(MissingQuantity, UnknownCommandColumnIsNamedWithTheArgumentsThatReadIt) {
  const std::string path = WriteTemp("cmd.csv", TytoPwmVariant("Motor command signal (\xC2\xB5s)"));
  const SteadyTable t = ReadLog(path);
  ASSERT_FALSE(t.Has(Column::kThrottle));
  const std::string& note = t.info[static_cast<int>(Column::kThrottle)].note;
  EXPECT_TRUE(Contains(note, "no throttle column found; \"Motor command signal (\xC2\xB5s)\" looks like one")) << note;
  const std::string args = "--format rcbenchmark --map \"throttle=Motor command signal (\xC2\xB5s)\"";
  EXPECT_TRUE(Contains(note, args)) << note;
  // The arguments as printed read it.
  LogReadOptions o;
  o.format = LogFormat::kRcbenchmark;
  o.column_map = {"throttle=Motor command signal (\xC2\xB5s)"};
  const SteadyTable with = ReadLog(path, o);
  ASSERT_TRUE(with.Has(Column::kThrottle));
  EXPECT_EQ(with.rows(), 4u);
  EXPECT_LT(RelErr(with.Get(Column::kThrottle)[2], 0.6), 1e-12);
}

TEST(MissingQuantity, TableWithoutCommandGetsAFullMapThatReads) {
  const std::string path = WriteTemp("amps.csv", "Amps,Batt. Volts,RPM,Duty\n1,12,1000,50\n2,12,2000,70\n3,12,3000,90\n");
  const SteadyTable t = ReadLog(path);
  EXPECT_EQ(t.format, LogFormat::kMapped);
  ASSERT_FALSE(t.Has(Column::kThrottle));
  const std::string& note = t.info[static_cast<int>(Column::kThrottle)].note;
  EXPECT_TRUE(Contains(note, "\"Duty\" looks like one")) << note;
  EXPECT_TRUE(Contains(note, "--map \"idc_a=Amps [A]\" --map \"vdc_v=Batt. Volts [V]\" --map \"omega_rad_s=RPM [rpm]\" "
                             "--map \"throttle=Duty\"")) << note;
  LogReadOptions o;
  o.column_map = {"idc_a=Amps [A]", "vdc_v=Batt. Volts [V]", "omega_rad_s=RPM [rpm]", "throttle=Duty [%]"};
  const SteadyTable with = ReadLog(path, o);
  ASSERT_TRUE(with.Has(Column::kThrottle));
  EXPECT_LT(RelErr(with.Get(Column::kThrottle)[1], 0.7), 1e-12);
}

TEST(MissingQuantity, NoCurrentColumnNamesTheLookalikeAndTheFormatError) {
  // A stand export whose current column is not in the table: CheckTable's error names it.
  std::string s = "Time (s),ESC signal (\xC2\xB5s),Voltage (V),Battery amps (A),Motor Optical Speed (RPM)\n";
  for (int i = 0; i < 4; ++i) s += std::to_string(2 * i) + ",1" + std::to_string(2 + i) + "00,12," + std::to_string(1 + i) + ",5000\n";
  const std::string e = ErrorOf(WriteTemp("noamp.csv", s));
  EXPECT_TRUE(Contains(e, "no current column found; \"Battery amps (A)\" looks like one")) << e;
  EXPECT_TRUE(Contains(e, "--format rcbenchmark --map \"idc_a=Battery amps (A)\"")) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(MissingQuantity, SecondMotorInATableNamesTheWhere) {
  const std::string s = "motor,throttle,voltage_V,current_A,rpm\nA,0.5,12,2,5000\nA,0.7,12,4,7000\nB,0.5,12,3,4000\n";
  const std::string path = WriteTemp("two.csv", s);
  const std::string e = ErrorOf(path);
  EXPECT_TRUE(Contains(e, "line 4, column \"motor\": \"B\" after \"A\"")) << e;
  EXPECT_TRUE(Contains(e, "--where \"motor=A\"")) << e;
  LogReadOptions o;
  o.row_filter = {"motor=A"};
  EXPECT_EQ(ReadLog(path, o).rows(), 2u);
}

// ------------------------------------------------------------------ canonical steady tables

TEST(CanonicalSteadyTable, TimeAndTorqueAreOptional) {
  const SteadyTable t = ReadLog(WriteTemp("steady.csv",
                                          "throttle,vdc_v,idc_a,rpm,thrust_n\n0.5,22.2,3.1,5200,4.1\n0.75,22.0,8.4,7600,9.0\n"));
  EXPECT_EQ(t.format, LogFormat::kCanonical);
  EXPECT_EQ(t.rows(), 2u);
  EXPECT_FALSE(t.Has(Column::kTimeS));
  EXPECT_FALSE(t.Has(Column::kTorqueNm));
  EXPECT_LT(RelErr(t.Get(Column::kIdcA)[1], 8.4), 1e-14);
  // Still strict: an unknown name among canonical ones with time_s is refused as before.
  const std::string e = ErrorOf(WriteTemp("steady_bad.csv", "time_s,throttle,vdc_v,idc_a,rpm,colour\n0,.5,22,3,5200,1\n"));
  EXPECT_TRUE(Contains(e, "unknown column(s) \"colour\"")) << e;
}

// ------------------------------------------------------------------ decimal commas

TEST(DecimalComma, ShiftedCellOfAnUnquotedCommaFileGetsTheHint) {
  // Written with decimal commas and ',' between cells, no quotes: "0,00211..." splits in two and
  // the next column reads an absurd number.
  const std::string s =
      "Time (s),ESC signal (\xC2\xB5s),Current (A),Voltage (V),Motor Optical Speed (RPM)\n"
      "0,00,1100,0,00000000000000000000,20,000,5000\n"
      "0,10,1100,0,00211530382032610502,20,010,5010\n";
  const std::string e = ErrorOf(WriteTemp("dc_shift.csv", s));
  EXPECT_TRUE(Contains(e, "out of range")) << e;
  EXPECT_TRUE(Contains(e, "decimal commas? read the file with --decimal-comma")) << e;
  // A plain absurd value in a decimal-point file gets no such hint.
  const std::string plain = ErrorOf(WriteTemp("absurd.csv",
                                              "Time (s),ESC signal (\xC2\xB5s),Current (A),Voltage (V),Motor Optical Speed (RPM)\n"
                                              "0.1,1100,2e16,20.0,5000\n0.2,1100,2.1,20.0,5000\n"));
  EXPECT_TRUE(Contains(plain, "out of range")) << plain;
  EXPECT_FALSE(Contains(plain, "--decimal-comma")) << plain;
}

TEST(HeaderSynonyms, EveryNameIsDocumented) {
  std::ifstream in(std::string(DYNOSIZE_SOURCE_DIR) + "/docs/log-formats.md");
  ASSERT_TRUE(in.good());
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string text = doc.str();
  const std::size_t section = text.find("## Header synonyms");
  ASSERT_NE(section, std::string::npos);
  for (const HeaderSynonym& syn : HeaderSynonyms()) {
    const std::string want = std::string("`") + syn.name + "`" + (syn.stand ? "*" : "") +
                             (syn.implied_unit[0] != '\0' ? std::string(" (") + syn.implied_unit + ")" : "");
    EXPECT_NE(text.find(want, section), std::string::npos) << want;
  }
}

TEST(FormatList, EveryReaderIsNamedOnce) {
  const std::vector<std::string> names = LogFormatNames();
  EXPECT_EQ(names, (std::vector<std::string>{"auto", "canonical", "rcbenchmark", "mapped", "drivecalc", "thrustapp"}));
  for (const std::string& n : names) EXPECT_TRUE(Contains(LogFormatHelp(), n + " (")) << n;
}

}  // namespace
}  // namespace dynosize::logs
