// The stand exports (RCbenchmark / Tyto), on small inline tables (values made up, shapes copied
// from the files in shared/data): Tyto Flight Stand quoted exports, unitless ESC commands,
// "ESC throttle (us)", trailer rows under --drop-incomplete-rows, --decimal-comma, --where, and
// tables without torque. The real files are read in real_files_test.cc.
#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include "common/units.h"
#include "logs/log_reader.h"
#include "logs/log_test_util.h"

namespace dynosize::logs {
namespace {

using testing_util::WriteTemp;

using testing_util::Contains;
using testing_util::ErrorOf;
using testing_util::kParseRelTol;

std::size_t Dropped(const SteadyTable& t, const std::string& reason_part) {
  std::size_t n = 0;
  for (const auto& d : t.dropped) {
    if (Contains(d.reason, reason_part)) n += d.count;
  }
  return n;
}

// ------------------------------------------------------------------ Tyto Flight Stand

// The shape of tytodb_tmotor16x54_9motors: every cell quoted, "Throttle (µs)", "Rotation speed
// (rpm)", "Thrust (kgf)", "Torque (N⋅m)" with U+22C5, one averaged row per step 4-5 s apart,
// empty quoted efficiency cells in the motor-off row.
const std::string kTytoHeader =
    "\"Time (s)\",\"Throttle (\xC2\xB5s)\",\"Rotation speed (rpm)\",\"Thrust (kgf)\",\"Torque "
    "(N\xE2\x8B\x85m)\",\"Voltage (V)\",\"Current (A)\",\"Electrical power (W)\",\"Motor & ESC "
    "efficiency (%)\",\"Propeller efficiency (gf/W)\"\n";
const std::string kTytoRows =
    "\"0.3\",\"1000\",\"0\",\"0.0004\",\"-0.00006\",\"24.44\",\"-0.0002\",\"0.0056\",\"0\",\"\"\n"
    "\"9.1\",\"1150\",\"1064.0000000000193\",\"0.060\",\"0.014\",\"24.44\",\"0.19\",\"4.6\",\"34.5\",\"37.9\"\n"
    "\"13.6\",\"1300\",\"2800\",\"0.41\",\"0.081\",\"24.40\",\"1.60\",\"39.1\",\"60.8\",\"10.5\"\n"
    "\"18.2\",\"1450\",\"4100\",\"0.88\",\"0.174\",\"24.31\",\"4.40\",\"107.0\",\"70.2\",\"8.2\"\n";

TEST(TytoFlightStand, QuotedExportIsDetectedAndRead) {
  const SteadyTable t = ReadLog(WriteTemp("tyto.csv", kTytoHeader + kTytoRows));
  EXPECT_EQ(t.format, LogFormat::kRcbenchmark);
  EXPECT_FALSE(t.time_series);  // one averaged row per step
  // The motor-off row (1000 us, 0 rpm) is a speed dropout: dropped and counted.
  ASSERT_EQ(t.rows(), 3u) << t.FullReport();
  EXPECT_EQ(t.DroppedTotal(), 1u);
  EXPECT_NEAR(t.Get(Column::kThrottle)[0], 0.15, 1e-15);  // (1150 - 1000)/(2000 - 1000)
  const double w = 1064.0000000000193 * kPi / 30.0;
  EXPECT_NEAR(t.Get(Column::kOmegaRadS)[0], w, w * kParseRelTol);
  EXPECT_NEAR(t.Get(Column::kThrustN)[1], 0.41 * kNewtonPerKilogramForce,
              0.41 * kNewtonPerKilogramForce * kParseRelTol);
  EXPECT_EQ(t.Get(Column::kTorqueNm)[2], 0.174);
  EXPECT_EQ(t.Get(Column::kIdcA)[2], 4.40);
  EXPECT_EQ(t.info[static_cast<int>(Column::kThrottle)].source_header, "Throttle (\xC2\xB5s)");
  EXPECT_EQ(t.info[static_cast<int>(Column::kTorqueNm)].source_unit, "N\xE2\x8B\x85m");
  EXPECT_TRUE(Contains(t.BriefReport(), "columns: throttle vdc_v idc_a omega_rad_s torque_nm thrust_n"))
      << t.BriefReport();
}

TEST(TytoFlightStand, MapNamesAQuotedHeaderWithoutItsQuotes) {
  LogReadOptions o;
  o.column_map = {"throttle=Throttle (\xC2\xB5s)", "rpm=Rotation speed (rpm)", "idc_a=Current (A)",
                  "vdc_v=Voltage", "thrust_n=Thrust"};
  const SteadyTable t = ReadLog(WriteTemp("tyto_map.csv", kTytoHeader + kTytoRows), o);
  EXPECT_EQ(t.format, LogFormat::kMapped);
  ASSERT_EQ(t.rows(), 4u);  // mapped: the motor-off row is a point like any other
  EXPECT_EQ(t.Get(Column::kThrottle)[0], 0.0);
  EXPECT_NEAR(t.Get(Column::kThrustN)[2], 0.41 * kNewtonPerKilogramForce,
              0.41 * kNewtonPerKilogramForce * kParseRelTol);  // unit taken from the header
  EXPECT_FALSE(t.Has(Column::kTorqueNm));
}

TEST(TytoFlightStand, QuotedCellsKeepCommasAndQuotesInside) {
  // A comma inside a quoted text cell does not split it; the numbers around it stay in place.
  std::string s = kTytoHeader + kTytoRows;
  s += "\"22.0\",\"1600\",\"5200\",\"1.40\",\"0.280\",\"24.20\",\"8.10\",\"196.0\",\"note, with "
       "\"\"quotes\"\"\",\"7.1\"\n";
  const SteadyTable t = ReadLog(WriteTemp("tyto_text.csv", s));
  ASSERT_EQ(t.rows(), 4u) << t.FullReport();
  EXPECT_EQ(t.Get(Column::kIdcA)[3], 8.10);
  EXPECT_EQ(t.rows_with_extra_cells, 0u);
}

// ------------------------------------------------------------------ command columns

// RCbenchmark steps with a command column named `command` and values `v1|v2|v3|v4`.
std::string Steps(const std::string& command, const std::string& values) {
  std::string s = "Time (s)," + command + ",Torque (N\xC2\xB7m),Thrust (gf),Voltage (V),Current (A),"
                  "Motor Optical Speed (rad/s)\n";
  const char* rest[] = {",0.002,40,16.7,0.4,300\n", ",0.004,90,16.6,0.9,520\n",
                        ",0.007,160,16.5,1.8,700\n", ",0.011,250,16.4,3.1,860\n"};
  std::size_t pos = 0;
  for (int i = 0; i < 4; ++i) {
    const std::size_t next = values.find('|', pos);
    s += std::to_string(4 * i + 1) + "," + values.substr(pos, next - pos) + rest[i];
    pos = next + 1;
  }
  return s;
}

TEST(CommandColumns, UnitlessEscSignalInCommandUnits) {
  // bhabas_sar_motor_sysid: "ESC signal" without a unit, 0..2000 command units (README).
  const SteadyTable t = ReadLog(WriteTemp("cmd_units.csv", Steps("ESC signal", "0|400|800|1200")));
  ASSERT_TRUE(t.Has(Column::kThrottle)) << t.FullReport();
  ASSERT_EQ(t.rows(), 4u);
  EXPECT_EQ(t.Get(Column::kThrottle)[1], 0.2);
  EXPECT_EQ(t.Get(Column::kThrottle)[3], 0.6);
  EXPECT_TRUE(Contains(t.info[static_cast<int>(Column::kThrottle)].note, "command units 0..2000"))
      << t.FullReport();
  // Set explicitly, the range wins.
  LogReadOptions o;
  o.esc_unitless_min = 0;
  o.esc_unitless_max = 1600;
  EXPECT_EQ(ReadLog(WriteTemp("cmd_units2.csv", Steps("ESC signal", "0|400|800|1200")), o)
                .Get(Column::kThrottle)[1],
            0.25);
}

TEST(CommandColumns, UnitlessFractionAndUnknownScale) {
  const SteadyTable f = ReadLog(WriteTemp("cmd_frac.csv", Steps("ESC", "0.1|0.3|0.5|0.7")));
  EXPECT_EQ(f.Get(Column::kThrottle)[2], 0.5);
  EXPECT_TRUE(Contains(f.info[static_cast<int>(Column::kThrottle)].note, "fraction"));
  // 0..4095 (a 12-bit DAC?) is none of the known scales: throttle absent, said why.
  const SteadyTable u = ReadLog(WriteTemp("cmd_dac.csv", Steps("ESC signal", "0|1000|3000|4095")));
  EXPECT_FALSE(u.Has(Column::kThrottle));
  EXPECT_TRUE(Contains(u.info[static_cast<int>(Column::kThrottle)].note, "not a fraction, a pulse width"))
      << u.FullReport();
  EXPECT_EQ(u.rows(), 4u);  // the other columns stay
}

TEST(CommandColumns, EscThrottleUsAndThrottlePercent) {
  const SteadyTable us = ReadLog(WriteTemp("cmd_esc_thr.csv", Steps("ESC throttle (us)", "1100|1300|1500|1700")));
  EXPECT_EQ(us.format, LogFormat::kRcbenchmark);
  EXPECT_NEAR(us.Get(Column::kThrottle)[3], 0.7, 1e-15);
  const SteadyTable pct = ReadLog(WriteTemp("cmd_pct.csv", Steps("Throttle (%)", "10|30|50|70")));
  EXPECT_NEAR(pct.Get(Column::kThrottle)[1], 0.3, 1e-15);
  const SteadyTable cmd = ReadLog(WriteTemp("cmd_cmd.csv", Steps("ESC command (\xCE\xBCs)", "1100|1300|1500|1700")));
  EXPECT_NEAR(cmd.Get(Column::kThrottle)[0], 0.1, 1e-15);
}

TEST(CommandColumns, HandMadeTableIsNotGuessedAndTheMessageNamesTheFlags) {
  // sjkim's A4220 table: "ESC throttle (us)" but a bare "Current": no units to read.
  const std::string s =
      "MOTOR,Throttle,ESC throttle (us),Voltage,Current,Thrust,Torque,RPM\n"
      "A-4220,0.618,1236 ,23.86 ,2.95 ,0.57 ,0.16 ,2944 \n"
      "ESC,0.665,1330 ,23.84 ,6.29 ,1.03 ,0.28 ,3909 \n";
  const std::string e = ErrorOf(WriteTemp("a4220.csv", s));
  EXPECT_TRUE(Contains(e, "cannot tell the log format")) << e;
  EXPECT_TRUE(Contains(e, "\"Voltage\", \"Current\", \"Thrust\", \"Torque\" name no unit")) << e;
  // A ready map: the columns the synonym table names, a unit to fill in where none is written.
  EXPECT_TRUE(Contains(e, "--format mapped --map \"throttle=Throttle\" --map \"vdc_v=Voltage [UNIT]\"")) << e;
  EXPECT_TRUE(Contains(e, "--map \"omega_rad_s=RPM [rpm]\"")) << e;
  EXPECT_TRUE(Contains(e, "thrust_n: n, gf, g, kgf")) << e;
  EXPECT_FALSE(Contains(e, "LogReadOptions")) << e;
  EXPECT_FALSE(Contains(e, "column_map")) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

// ------------------------------------------------------------------ trailer rows

const std::string kA4220 =
    "MOTOR,Throttle,ESC throttle (us),Voltage,Current,Thrust,Torque,RPM\n"
    "A-4220-540kv,0.618,1236 ,23.86 ,2.95 ,0.57 ,0.16 ,2944 \n"
    "ESC,0.665,1330 ,23.84 ,6.29 ,1.03 ,0.28 ,3909 \n"
    ",0.7045,1409 ,23.80 ,10.48 ,1.49 ,0.41 ,4678 \n"
    "6s Lipo,,PEAK THRUST,,,,,\n"
    ",,2000 ,22.92 ,101.20 ,5.92 ,1.92 ,9204 \n";

LogReadOptions A4220Map() {
  LogReadOptions o;
  o.column_map = {"throttle=ESC throttle (us)", "vdc_v=Voltage", "idc_a=Current", "rpm=RPM",
                  "torque_nm=Torque [N*m]", "thrust_n=Thrust [kgf]"};
  return o;
}

TEST(TrailerRows, TextRowIsAnErrorUnlessDropIncompleteRows) {
  const std::string p = WriteTemp("a4220_trailer.csv", kA4220);
  const std::string e = ErrorOf(p, A4220Map());
  EXPECT_TRUE(Contains(e, "line 5, column \"ESC throttle (us)\": \"PEAK THRUST\": not a number")) << e;
  LogReadOptions o = A4220Map();
  o.mapped_drop_rows_with_empty_cells = true;
  const SteadyTable t = ReadLog(p, o);
  ASSERT_EQ(t.rows(), 4u);
  EXPECT_EQ(t.source_line.back(), 6u);  // the peak-thrust row after the trailer is kept
  EXPECT_NEAR(t.Get(Column::kThrottle)[3], 1.0, 1e-15);
  EXPECT_EQ(Dropped(t, "text where a number belongs"), 1u) << t.BriefReport();
  EXPECT_TRUE(Contains(t.BriefReport(), "first: line 5, column \"ESC throttle (us)\": \"PEAK THRUST\""))
      << t.BriefReport();
  EXPECT_EQ(t.rows() + t.DroppedTotal(), t.data_rows_read);
}

TEST(TrailerRows, MalformedNumberStaysAnErrorAndShortTrailerIsDropped) {
  LogReadOptions o = A4220Map();
  o.mapped_drop_rows_with_empty_cells = true;
  std::string bad = kA4220;
  bad.replace(bad.find("23.80"), 5, "23.8.0");
  const std::string e = ErrorOf(WriteTemp("a4220_bad.csv", bad), o);
  EXPECT_TRUE(Contains(e, "line 4, column \"Voltage\": \"23.8.0 \": not a number")) << e;
  // A trailer line with fewer cells (a note typed in the first cell only).
  const SteadyTable t = ReadLog(WriteTemp("a4220_short.csv", kA4220 + "Tested 2021\n"), o);
  EXPECT_EQ(t.rows(), 4u);
  EXPECT_EQ(Dropped(t, "rows shorter than the header"), 1u) << t.BriefReport();
}

TEST(TrailerRows, RcbenchmarkTrailerDroppedOnRequest) {
  const std::string s = Steps("ESC signal (us)", "1100|1300|1500|1700") + "End of test,,,,,,\n";
  const std::string p = WriteTemp("rcb_trailer.csv", s);
  EXPECT_TRUE(Contains(ErrorOf(p), "\"End of test\": not a number"));
  LogReadOptions o;
  o.mapped_drop_rows_with_empty_cells = true;
  const SteadyTable t = ReadLog(p, o);
  EXPECT_EQ(t.rows(), 4u);
  EXPECT_EQ(Dropped(t, "text where a number belongs"), 1u) << t.BriefReport();
}

// ------------------------------------------------------------------ decimal comma

TEST(DecimalComma, SemicolonFileReadsLikeTheDecimalPointFile) {
  const std::string dot = Steps("ESC signal (us)", "1100|1300|1500|1700");
  std::string comma = dot;
  for (char& c : comma) c = c == ',' ? ';' : c == '.' ? ',' : c;
  LogReadOptions o;
  o.decimal_comma = true;
  const SteadyTable a = ReadLog(WriteTemp("dc_dot.csv", dot));
  const SteadyTable b = ReadLog(WriteTemp("dc_comma.csv", comma), o);
  ASSERT_EQ(a.rows(), b.rows());
  EXPECT_EQ(b.delimiter, ';');
  for (int c = 0; c < kColumnCount; ++c) EXPECT_EQ(a.columns[c], b.columns[c]) << ColumnName(static_cast<Column>(c));
  // Without the flag: the error says what to do.
  const std::string e = ErrorOf(WriteTemp("dc_noflag.csv", comma));
  EXPECT_TRUE(Contains(e, "line 2, column \"Torque (N\xC2\xB7m)\": \"0,002\": not a number")) << e;
  EXPECT_TRUE(Contains(e, "--decimal-comma")) << e;
  // With the flag, a '.' is refused (a thousands separator would be misread).
  const std::string e2 = ErrorOf(WriteTemp("dc_mixed.csv", comma + "17;1800;0.015;330;16,3;4,5;990\n"), o);
  EXPECT_TRUE(Contains(e2, "line 6, column \"Torque (N\xC2\xB7m)\": \"0.015\": not a number with --decimal-comma"))
      << e2;
}

TEST(DecimalComma, CommaSeparatedFileNeedsQuotedCells) {
  LogReadOptions o;
  o.decimal_comma = true;
  o.column_map = {"idc_a=I (A)", "vdc_v=U (V)"};
  const std::string e = ErrorOf(WriteTemp("dc_commas.csv", "U (V),I (A)\n12,5,1,5\n12,4,2,5\n"), o);
  EXPECT_TRUE(Contains(e, "line 2: --decimal-comma, but cells are separated by ','")) << e;
  const SteadyTable t =
      ReadLog(WriteTemp("dc_quoted.csv", "\"U (V)\",\"I (A)\"\n\"12,5\",\"1,5\"\n\"12,4\",\"2,5\"\n"), o);
  EXPECT_EQ(t.Get(Column::kVdcV)[1], 12.4);
  EXPECT_EQ(t.Get(Column::kIdcA)[0], 1.5);
}

// ------------------------------------------------------------------ --where

const std::string kCtu =
    "motor,propeller,throttle_pct_nominal,thrust_g,rpm,voltage_V,current_A\n"
    "Readytosky 2312 920KV,DJI 9450,50,401,5688,16.66,3.09\n"
    "Readytosky 2312 920KV,DJI 9450,60,529,6508,16.61,4.80\n"
    "T-Motor MN3508 700KV,T-Motor 13x4.4,50,655,4633,16.63,3.95\n"
    "T-Motor MN3508 700KV,T-Motor 13x4.4,60,874,5291,16.55,6.12\n"
    "T-Motor MN3508 700KV,T-Motor 13x4.4,70,1102,5850,16.44,8.90\n";

LogReadOptions CtuMap() {
  LogReadOptions o;
  o.column_map = {"throttle=throttle_pct_nominal [%]", "thrust_n=thrust_g [g]", "rpm=rpm",
                  "vdc_v=voltage_V", "idc_a=current_A"};
  return o;
}

TEST(RowFilter, KeepsOneMotorOfAMultiMotorTable) {
  LogReadOptions o = CtuMap();
  o.row_filter = {"motor=T-Motor MN3508 700KV"};
  const SteadyTable t = ReadLog(WriteTemp("ctu.csv", kCtu), o);
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.source_line[0], 4u);
  EXPECT_NEAR(t.Get(Column::kThrottle)[2], 0.7, 1e-15);
  EXPECT_EQ(t.data_rows_read, 3u);
  EXPECT_FALSE(t.Has(Column::kTorqueNm));  // torque is optional
  EXPECT_TRUE(Contains(t.BriefReport(), "absent: torque_nm")) << t.BriefReport();
  bool noted = false;
  for (const auto& n : t.notes) noted = noted || Contains(n, "2 rows of other values skipped (--where motor=");
  EXPECT_TRUE(noted) << t.FullReport();
}

TEST(RowFilter, ErrorsNameTheFlagTheColumnsAndTheValues) {
  LogReadOptions o = CtuMap();
  o.row_filter = {"motor=T-Motor MN3510"};
  const std::string e = ErrorOf(WriteTemp("ctu_none.csv", kCtu), o);
  EXPECT_TRUE(Contains(e, "no row has motor=T-Motor MN3510 (--where; 5 rows of other values, e.g. "
                          "\"Readytosky 2312 920KV\", \"T-Motor MN3508 700KV\")"))
      << e;
  o.row_filter = {"engine=x"};
  const std::string e2 = ErrorOf(WriteTemp("ctu_col.csv", kCtu), o);
  EXPECT_TRUE(Contains(e2, "--where \"engine=x\": no column \"engine\" in the header; columns:")) << e2;
  o.row_filter = {"no equals sign"};
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_TRUE(Contains(why, "--where \"no equals sign\": expected Header=value")) << why;
  EXPECT_THROW(ReadLog(WriteTemp("ctu_syntax.csv", kCtu), o), UsageError);
}

TEST(RowFilter, HeaderlessColumnByNumber) {
  LogReadOptions o;
  o.column_map = {"idc_a=#3 [A]", "rpm=#2"};
  o.row_filter = {"#1=7"};
  const SteadyTable t = ReadLog(WriteTemp("nohdr.txt", "7 1000 0.5\n8 1100 0.6\n7 2000 1.5\n"), o);
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.Get(Column::kIdcA)[1], 1.5);
}

// ------------------------------------------------------------------ torque optional

TEST(TorqueOptional, RcbenchmarkWithoutTorqueSaysWhatIsAbsent) {
  // strawson_fpv_motor_prop: thrust but no torque cell (README: "NO torque").
  const std::string s =
      "Time (s),ESC signal (\xC2\xB5s),Thrust (gf),Voltage (V),Current (A),Motor Optical Speed (RPM),\n"
      "1.8,1145,17.6,7.42,0.71,3895,\n"
      "3.6,1240,40.1,7.40,1.52,5920,\n"
      "5.4,1335,70.3,7.37,2.63,7610,\n";
  const SteadyTable t = ReadLog(WriteTemp("no_torque.csv", s));
  EXPECT_FALSE(t.Has(Column::kTorqueNm));
  EXPECT_EQ(t.rows(), 3u);
  const std::string b = t.BriefReport();
  EXPECT_TRUE(Contains(b, "columns: throttle vdc_v idc_a omega_rad_s thrust_n; absent: torque_nm")) << b;
}

// ------------------------------------------------------------------ ThrustApp reports

// The shape of jmajew_thrusttool_6motors: a LaTeX report with step tables as filecontents
// blocks (one commented out, as in the duct comparison), and the text export of the same runs
// with bracketed standard deviations, a telemetry dropout "nan" and raw samples after them.
const std::string kThrustAppTex =
    "\\documentclass[10pt]{article}\n"
    "\\usepackage{filecontents}\n"
    "% \\begin{filecontents*}{table0.dat}\n"
    "% out, th, th_err, tq, tq_err, rpm, rpm_err, v, v_err, a, a_err, pin, theff\n"
    "%    2e+01, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1\n"
    "% \\end{filecontents*}\n"
    "\\begin{filecontents*}{table1.dat}\n"
    "out,      th,    th_err, tq,     tq_err,  rpm,   rpm_err,  v,    v_err,   a,     a_err,   pin,  theff\n"
    "    2e+01,       39.19,       2.429,       77.87,       2.069,        4139,         9.0,      12.540,"
    "      0.0049,       0.334,      0.0066,       4.188,       9.358\n"
    "       60,      306.90,       2.435,      477.78,       2.104,       10630,        77.9,      12.363,"
    "      0.0056,       3.084,      0.0359,      38.122,       8.050\n"
    "\\end{filecontents*}\n"
    "\\begin{filecontents*}{table2.dat}\n"
    "out, th, th_err, tq, tq_err, rpm, rpm_err, v, v_err, a, a_err, pin, theff,\n"
    "20, 37.82, 2.059, 75.69, 2.378, 4106, 7.1, 12.407, 0.0044, 0.328, 0.0085, 4.069, 9.295,\n"
    "100, 680.1, 3.1, 1015.0, 3.2, 15700, 90.0, 11.80, 0.006, 14.40, 0.04, 169.9, 4.0,\n"
    "\\end{filecontents*}\n"
    "\\begin{document}\n"
    "\\begin{tabular}{ll}\n"
    "Motor:        & T-Motor MN2206-13\\\\ \n"
    "KV:           & 2000\\\\ \n"
    "Propeler:     & HQProp 6x4x3\\\\ \n"
    "\\end{tabular}\n";

const std::string kThrustAppTxt =
    "## Tool info\r\n"
    "Board:      Custom STM32F401RE thrustBoard v2\r\n"
    "## Measurement info\r\n"
    "Motor :        T-Motor MT2212-16\r\n"
    "KV :           750\r\n"
    "## Measurement - 1\r\n"
    "level [%]      thrust [G]   torque [G cm]     rpm [1/min]        volt [V]        curr [A]   Pin [W] Eff [G/W]\r\n"
    "       20   24.53 [1.701]   48.08 [2.579]      1659 [7.4]  12.546 [0.003]   0.110 [0.006]     1.386    17.697\r\n"
    "       25   35.53 [1.708]   74.59 [2.560]      2071 [8.3]  12.544 [0.004]   0.182 [0.006]     2.287    15.537\r\n"
    "\r\n"
    "## Measurement - 2\r\n"
    "level [%]      thrust [G]   torque [G cm]     rpm [1/min]        volt [V]        curr [A]   Pin [W] Eff [G/W]\r\n"
    "       20   23.19 [2.065]   47.55 [2.765]       nan [nan]  12.483 [0.003]   0.111 [0.006]     1.390    16.687\r\n"
    "       25   31.94 [2.067]   74.07 [2.768]      2060 [7.7]  12.481 [0.005]   0.182 [0.006]     2.265    14.100\r\n"
    "\r\n"
    "## Measurement - 1\r\n"
    "     level [%]    thrust [G] torque [G cm]   rpm [1/min]      volt [V]      curr [A]\r\n"
    "             0      -2.50735      -20.2577             0       12.5464     0.0627197\r\n"
    "            20       24.1          48.0              1650       12.54       0.11\r\n";

TEST(ThrustAppReport, LatexReportStepTables) {
  const SteadyTable t = ReadLog(WriteTemp("report.tex", kThrustAppTex));
  EXPECT_EQ(t.format, LogFormat::kThrustApp);
  ASSERT_EQ(t.rows(), 4u) << t.FullReport();  // the commented-out table is not read
  EXPECT_EQ(t.source_line[0], 9u);            // line numbers of the file
  EXPECT_NEAR(t.Get(Column::kThrottle)[0], 0.2, 1e-15);  // "2e+01" percent
  EXPECT_NEAR(t.Get(Column::kThrustN)[1], 306.90 * kNewtonPerGramForce, 306.90 * kNewtonPerGramForce * kParseRelTol);
  EXPECT_NEAR(t.Get(Column::kTorqueNm)[0], 77.87 * 9.80665e-5, 77.87 * 9.80665e-5 * kParseRelTol);
  EXPECT_EQ(t.Get(Column::kVdcV)[3], 11.80);
  EXPECT_EQ(t.Get(Column::kIdcA)[2], 0.328);
  bool noted = false;
  for (const auto& n : t.notes) {
    noted = noted || Contains(n, "motor \"T-Motor MN2206-13\", KV label 2000, propeller \"HQProp 6x4x3\"; 2 runs");
  }
  EXPECT_TRUE(noted) << t.FullReport();
}

TEST(ThrustAppReport, TextExportSummaryTablesOnly) {
  const SteadyTable t = ReadLog(WriteTemp("report.txt", kThrustAppTxt));
  EXPECT_EQ(t.format, LogFormat::kThrustApp);
  // Two runs of two steps; the "nan" rpm step is dropped and counted; raw samples are not read.
  ASSERT_EQ(t.rows(), 3u) << t.FullReport();
  EXPECT_EQ(t.DroppedTotal(), 1u);
  EXPECT_TRUE(Contains(t.dropped.at(0).reason, "empty \"rpm\" cell")) << t.BriefReport();
  EXPECT_NEAR(t.Get(Column::kOmegaRadS)[2], 2060 * kPi / 30.0, 2060 * kPi / 30.0 * kParseRelTol);
  EXPECT_EQ(t.Get(Column::kIdcA)[1], 0.182);
  EXPECT_EQ(t.line_ends, "CRLF");
}

TEST(ThrustAppReport, ErrorsNameTheFileLineAndFlag) {
  std::string bad = kThrustAppTex;
  bad.replace(bad.rfind(" rpm, rpm_err,"), 14, " rev, rev_err,");
  const std::string e = ErrorOf(WriteTemp("bad_report.tex", bad));
  EXPECT_TRUE(Contains(e, "bad_report.tex: line 13: ThrustApp table header")) << e;
  EXPECT_TRUE(Contains(e, "has no column \"rpm\"")) << e;
  // Torque (and thrust) are optional: a report without "tq" reads without torque.
  std::string no_tq = kThrustAppTex;
  for (std::size_t at; (at = no_tq.find("tq,     tq_err,")) != std::string::npos;) no_tq.replace(at, 15, "xx,     xx_err,");
  for (std::size_t at; (at = no_tq.find(" tq, tq_err,")) != std::string::npos;) no_tq.replace(at, 12, " xx, xx_err,");
  const SteadyTable nt = ReadLog(WriteTemp("no_tq_report.tex", no_tq));
  EXPECT_FALSE(nt.Has(Column::kTorqueNm)) << nt.FullReport();
  EXPECT_EQ(nt.rows(), 4u);
  LogReadOptions o;
  o.format = LogFormat::kThrustApp;
  EXPECT_TRUE(Contains(ErrorOf(WriteTemp("not_report.csv", "a,b\n1,2\n"), o), "not a ThrustApp report"));
  o.format = LogFormat::kAuto;
  o.column_map = {"idc_a=a"};
  EXPECT_THROW(ReadLog(WriteTemp("map_report.tex", kThrustAppTex), o), UsageError);
}

}  // namespace
}  // namespace dynosize::logs
