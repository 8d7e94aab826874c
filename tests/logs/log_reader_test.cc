// Readers on small excerpts written inside the tests: every quirk of ecosystem-notes.md, the
// strict canonical format and the reliability rules of docs/log-formats.md (error text checked).
#include "logs/log_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error.h"
#include "common/units.h"
#include "logs/log_test_util.h"

namespace dynosize::logs {
namespace {

using testing_util::WriteTemp;

using testing_util::Contains;
using testing_util::ErrorOf;
using testing_util::kParseRelTol;

// ------------------------------------------------------------------ canonical

const char* kCanonical =
    "time_s,vdc_v,throttle,rpm,torque_nm,idc_a,vll_rms_v,irms_a,pac_w\n"
    "0,12.0,0.5,6000,0.05,2.5,4.0,3.0,19.7\n"
    "10,11.9,0.7,8500,0.09,5.0,5.6,5.5,50.6\n"
    "20,11.8,0.9,10500,0.14,9.0,7.1,8.8,102.7\n";

TEST(CanonicalLog, ReadsValuesInSi) {
  const SteadyTable t = ReadLog(WriteTemp("canon.csv", kCanonical));
  EXPECT_EQ(t.format, LogFormat::kCanonical);
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_FALSE(t.time_series);
  EXPECT_NEAR(t.Get(Column::kOmegaRadS)[1], 8500.0 * kPi / 30.0, 8500.0 * kParseRelTol * 4);
  EXPECT_EQ(t.Get(Column::kThrottle)[2], 0.9);
  EXPECT_EQ(t.Get(Column::kPacW)[0], 19.7);
  EXPECT_EQ(t.source_line[0], 2u);
  EXPECT_TRUE(t.Has(Column::kVllRmsV));
  EXPECT_FALSE(t.Has(Column::kThrustN));
  EXPECT_FALSE(t.Has(Column::kTempC));
  EXPECT_EQ(t.DroppedTotal(), 0u);
}

TEST(CanonicalLog, AcColumnsMayBeAbsentAndOmegaAccepted) {
  const SteadyTable t = ReadLog(WriteTemp("canon_dc.csv",
                                          "time_s,vdc_v,throttle,omega_rad_s,torque_nm,idc_a,thrust_n,temp_c\r\n"
                                          "0,12,0.5,600,0.05,2.5,3.1,25\r\n"
                                          "1,12,0.6,700,0.06,3.0,4.2,26\r\n"));
  EXPECT_FALSE(t.Has(Column::kPacW));
  EXPECT_EQ(t.Get(Column::kOmegaRadS)[1], 700.0);
  EXPECT_EQ(t.Get(Column::kThrustN)[1], 4.2);
  EXPECT_EQ(t.line_ends, "CRLF");
}

TEST(CanonicalLog, StrictErrorsNameFileLineColumnValueRule) {
  const std::string head = "time_s,vdc_v,throttle,rpm,torque_nm,idc_a\n";
  std::string e = ErrorOf(WriteTemp("text.csv", head + "0,12,0.5,6000,0.05,2.5\n1,12,0.6,7000,0.06,abc\n"));
  EXPECT_TRUE(Contains(e, "text.csv: line 3, column \"idc_a\": \"abc\": not a number")) << e;

  e = ErrorOf(WriteTemp("empty.csv", head + "0,12,0.5,6000,,2.5\n1,12,0.6,7000,0.06,3\n"));
  EXPECT_TRUE(Contains(e, "line 2, column \"torque_nm\": \"\": empty cell")) << e;

  e = ErrorOf(WriteTemp("cells.csv", head + "0,12,0.5,6000,0.05\n"));
  EXPECT_TRUE(Contains(e, "line 2: 5 cells, the header has 6")) << e;

  e = ErrorOf(WriteTemp("thr.csv", head + "0,12,1.5,6000,0.05,2\n1,12,0.6,7000,0.06,3\n"));
  EXPECT_TRUE(Contains(e, "line 2, column \"throttle\": \"1.5\": throttle outside 0..1")) << e;

  e = ErrorOf(WriteTemp("vdc.csv", head + "0,-12,0.5,6000,0.05,2\n1,12,0.6,7000,0.06,3\n"));
  EXPECT_TRUE(Contains(e, "line 2, column \"vdc_v\": \"-12\": vdc_v must be > 0")) << e;

  e = ErrorOf(WriteTemp("nan.csv", head + "0,12,0.5,nan,0.05,2\n1,12,0.6,7000,0.06,3\n"));
  EXPECT_TRUE(Contains(e, "column \"rpm\": \"nan\": not a number")) << e;
}

TEST(CanonicalLog, HeaderErrors) {
  std::string e = ErrorOf(WriteTemp("missing.csv", "time_s,vdc_v,rpm,idc_a\n0,12,6000,2\n"));
  EXPECT_TRUE(Contains(e, "missing required column(s) throttle")) << e;

  e = ErrorOf(WriteTemp("unknown.csv",
                        "time_s,vdc_v,throttle,rpm,torque_nm,idc_a,zeta,alpha\n0,12,.5,1,1,1,1,1\n"));
  EXPECT_TRUE(Contains(e, "unknown column(s) \"alpha\", \"zeta\"")) << e;  // sorted
  EXPECT_TRUE(Contains(e, "valid names: time_s, vdc_v")) << e;

  // A trailing comma is a quirk of thrust-stand exports, not of the canonical format.
  e = ErrorOf(WriteTemp("trail.csv", "time_s,vdc_v,throttle,rpm,torque_nm,idc_a,\n0,12,.5,1,1,1,\n"));
  EXPECT_TRUE(Contains(e, "(empty: trailing delimiter?)")) << e;

  e = ErrorOf(WriteTemp("twice.csv", "time_s,vdc_v,throttle,rpm,omega_rad_s,torque_nm,idc_a\n"));
  EXPECT_TRUE(Contains(e, "given twice")) << e;

  e = ErrorOf(WriteTemp("what.csv", "a,b,c\n1,2,3\n"));
  EXPECT_TRUE(Contains(e, "cannot tell the log format")) << e;

  EXPECT_THROW(ReadLog("/nonexistent/log.csv"), NoInputError);
}

TEST(ReliabilityRules, DegenerateLogsAreClearErrors) {
  const std::string head = "time_s,vdc_v,throttle,rpm,torque_nm,idc_a\n";
  std::string e = ErrorOf(WriteTemp("one.csv", head + "0,12,0.5,6000,0.05,2.5\n"));
  EXPECT_TRUE(Contains(e, "one.csv: 1 steady operating point (1 data rows read): a calibration needs at least 2")) << e;

  e = ErrorOf(WriteTemp("same.csv", head + "0,12,0.5,6000,0.05,2.5\n1,12,0.5,6000,0.05,2.5\n"
                                            "2,12,0.5,6000,0.05,2.5\n"));
  EXPECT_TRUE(Contains(e, "all 3 operating points are identical")) << e;

  e = ErrorOf(WriteTemp("zeroi.csv", head + "0,12,0.5,6000,0.05,0\n1,12,0.6,7000,0.06,0\n"));
  EXPECT_TRUE(Contains(e, "(idc_a) is zero in every point")) << e;

  e = ErrorOf(WriteTemp("headeronly.csv", head));
  EXPECT_TRUE(Contains(e, "0 steady operating points")) << e;

  e = ErrorOf(WriteTemp("nothing.csv", ""));
  EXPECT_TRUE(Contains(e, "empty file")) << e;
}

// ------------------------------------------------------------------ RCbenchmark quirks

// One averaged row per step, 4 s apart, as the stands' "steps" scripts write them.
std::string RcbSteps(const std::string& micro, const std::string& eol, bool trailing_comma,
                     const std::string& thrust_header, const std::string& thrust_values3) {
  const std::string tc = trailing_comma ? "," : "";
  // In a Latin-1 re-save the product dot is Latin-1 too.
  const std::string dot = micro == "\xB5" ? "\xB7" : "\xC2\xB7";
  std::string s = "Time (s),ESC signal (" + micro + "s),Servo 1 (" + micro + "s),Torque (N" +
                  dot + "m)," + thrust_header +
                  ",Voltage (V),Current (A),Motor Electrical Speed (RPM),Motor Optical Speed "
                  "(RPM),App message" + tc + eol;
  std::string v[3];
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t next = thrust_values3.find('|', pos);
    v[i] = thrust_values3.substr(pos, next - pos);
    pos = next + 1;
  }
  s += "0.4,1200,,0.010," + v[0] + ",12.0,1.5,6000,0," + tc + eol;
  s += "4.4,1400,,0.020," + v[1] + ",11.9,3.0,9000,0," + tc + eol;
  s += "8.4,1600,,0.030," + v[2] + ",11.8,5.0,12000,0," + tc + eol;
  return s;
}

void ExpectStepValues(const SteadyTable& t, double thrust_scale) {
  ASSERT_EQ(t.rows(), 3u) << t.FullReport();
  EXPECT_EQ(t.format, LogFormat::kRcbenchmark);
  EXPECT_FALSE(t.time_series);
  EXPECT_NEAR(t.Get(Column::kThrottle)[0], 0.2, 1e-15);  // (1200 - 1000)/(2000 - 1000)
  EXPECT_NEAR(t.Get(Column::kThrottle)[2], 0.6, 1e-15);
  EXPECT_NEAR(t.Get(Column::kOmegaRadS)[1], 9000.0 * kPi / 30.0, 9000.0 * kPi / 30.0 * kParseRelTol);
  EXPECT_EQ(t.Get(Column::kIdcA)[2], 5.0);
  EXPECT_EQ(t.Get(Column::kVdcV)[0], 12.0);
  EXPECT_EQ(t.Get(Column::kTorqueNm)[1], 0.020);
  EXPECT_NEAR(t.Get(Column::kThrustN)[2], 300.0 * thrust_scale, 300.0 * thrust_scale * kParseRelTol);
  // The optical probe is not fitted (0 everywhere): the electrical one is used.
  EXPECT_EQ(t.info[static_cast<int>(Column::kOmegaRadS)].source_header, "Motor Electrical Speed (RPM)");
}

TEST(RcbenchmarkLog, Utf8BomLfTrailingComma) {
  const std::string s = "\xEF\xBB\xBF" + RcbSteps("\xC2\xB5", "\n", true, "Thrust (gf)", "100|200|300");
  const SteadyTable t = ReadLog(WriteTemp("rcb_utf8.csv", s));
  ExpectStepValues(t, kNewtonPerGramForce);
  EXPECT_TRUE(t.had_bom);
  EXPECT_FALSE(t.header_latin1);
  EXPECT_EQ(t.line_ends, "LF");
  EXPECT_EQ(t.rows_with_extra_cells, 0u);  // the trailing comma is the format, not an extra
}

TEST(RcbenchmarkLog, Latin1CrOnlyNoTrailingComma) {
  // The same file re-saved by a spreadsheet: Latin-1 micro sign 0xB5, CR line ends.
  const std::string s = RcbSteps("\xB5", "\r", false, "Thrust (gf)", "100|200|300");
  const SteadyTable t = ReadLog(WriteTemp("rcb_latin1.csv", s));
  ExpectStepValues(t, kNewtonPerGramForce);
  EXPECT_TRUE(t.header_latin1);
  EXPECT_EQ(t.line_ends, "CR");
  EXPECT_EQ(t.info[static_cast<int>(Column::kThrottle)].source_unit, "\xC2\xB5s");
}

TEST(RcbenchmarkLog, CrlfAndThrustUnitVariants) {
  ExpectStepValues(ReadLog(WriteTemp("rcb_kgf.csv", RcbSteps("\xC2\xB5", "\r\n", true, "Thrust (kgf)",
                                                               "0.1|0.2|0.3"))),
                   kNewtonPerKilogramForce / 1000.0);
  ExpectStepValues(ReadLog(WriteTemp("rcb_n.csv", RcbSteps("\xC2\xB5", "\n", true, "Thrust (N)",
                                                             "100|200|300"))),
                   1.0);
  // Other stands: "Name [unit]" and "Name - unit".
  ExpectStepValues(ReadLog(WriteTemp("rcb_bracket.csv", RcbSteps("u", "\n", false, "Thrust [gf]",
                                                                   "100|200|300"))),
                   kNewtonPerGramForce);
  ExpectStepValues(ReadLog(WriteTemp("rcb_dash.csv", RcbSteps("u", "\n", false, "Thrust - kgf",
                                                                "0.1|0.2|0.3"))),
                   kNewtonPerKilogramForce / 1000.0);
  const std::string e = ErrorOf(WriteTemp("rcb_badunit.csv", RcbSteps("u", "\n", false, "Thrust (furlong)",
                                                                       "1|2|3")));
  EXPECT_TRUE(Contains(e, "unit \"furlong\" is not a unit of N; valid: n, gf, g, kgf")) << e;
}

TEST(RcbenchmarkLog, EmptyCellsDropRowsAndAreCounted) {
  std::string s = RcbSteps("u", "\n", true, "Thrust (gf)", "100|200|300");
  s += "12.4,1800,,,400,11.7,7.0,14000,0,,\n";  // torque not sampled (asynchronous sensor)
  const SteadyTable t = ReadLog(WriteTemp("rcb_empty.csv", s));
  EXPECT_EQ(t.rows(), 3u);
  ASSERT_EQ(t.dropped.size(), 1u);
  EXPECT_EQ(t.dropped[0].count, 1u);
  EXPECT_TRUE(Contains(t.dropped[0].reason, "empty \"Torque (N\xC2\xB7m)\" cell")) << t.dropped[0].reason;
  // Text in a number is still an error in a lenient format.
  std::string bad = RcbSteps("u", "\n", true, "Thrust (gf)", "100|2OO|300");
  const std::string e = ErrorOf(WriteTemp("rcb_text.csv", bad));
  EXPECT_TRUE(Contains(e, "line 3, column \"Thrust (gf)\": \"2OO\": not a number")) << e;
}

TEST(RcbenchmarkLog, EscEndPointsAndUnitlessCommand) {
  const std::string s = RcbSteps("u", "\n", true, "Thrust (gf)", "100|200|300");
  LogReadOptions o;
  o.esc_min_us = 1100;
  o.esc_max_us = 1900;
  const SteadyTable t = ReadLog(WriteTemp("rcb_ends.csv", s), o);
  EXPECT_NEAR(t.Get(Column::kThrottle)[0], 100.0 / 800.0, 1e-15);
  // A command outside the end points (arming pulse) is dropped and counted, not clamped.
  o.esc_min_us = 1300;
  const SteadyTable t2 = ReadLog(WriteTemp("rcb_ends2.csv", s), o);
  EXPECT_EQ(t2.rows(), 2u);
  EXPECT_TRUE(Contains(t2.dropped.at(0).reason, "ESC signal outside the end points 1300-1900 us"))
      << t2.dropped.at(0).reason;
  // "ESC signal" without a unit, values 1200..1600: a pulse width (the scale follows the
  // values; stand_exports_test.cc checks the 0..2000 command units of bhabas_sar_motor_sysid).
  std::string u = s;
  u.replace(u.find("ESC signal (us)"), 15, "ESC signal");
  const SteadyTable t3 = ReadLog(WriteTemp("rcb_unitless.csv", u));
  ASSERT_TRUE(t3.Has(Column::kThrottle)) << t3.FullReport();
  EXPECT_NEAR(t3.Get(Column::kThrottle)[0], 0.2, 1e-15);
  EXPECT_TRUE(Contains(t3.info[static_cast<int>(Column::kThrottle)].note, "read as a pulse width in us"))
      << t3.FullReport();
  LogReadOptions o4;
  o4.esc_unitless_min = 0;
  o4.esc_unitless_max = 2000;
  const SteadyTable t4 = ReadLog(WriteTemp("rcb_unitless2.csv", u), o4);
  EXPECT_NEAR(t4.Get(Column::kThrottle)[0], 0.6, 1e-15);
  EXPECT_TRUE(LogReadOptions{}.IsValid(nullptr));
  LogReadOptions bad;
  bad.esc_max_us = 900;
  EXPECT_THROW(ReadLog(WriteTemp("rcb_bad_opts.csv", s), bad), UsageError);
}

TEST(RcbenchmarkLog, NegativeTorqueAndThrustAreFlippedWithANote) {
  std::string s = RcbSteps("u", "\n", true, "Thrust (N)", "-1|-2|-3");
  for (const char* from : {"0.010", "0.020", "0.030"}) {
    s.replace(s.find(std::string(",") + from), std::string(from).size() + 1, std::string(",-") + from);
  }
  const SteadyTable t = ReadLog(WriteTemp("rcb_neg.csv", s));
  EXPECT_EQ(t.Get(Column::kTorqueNm)[0], 0.010);
  EXPECT_EQ(t.Get(Column::kThrustN)[2], 3.0);
  EXPECT_TRUE(Contains(t.info[static_cast<int>(Column::kThrustN)].note, "sign flipped"));
  LogReadOptions keep;
  keep.normalize_signs = false;
  EXPECT_EQ(ReadLog(WriteTemp("rcb_neg2.csv", s), keep).Get(Column::kThrustN)[2], -3.0);
}

TEST(RcbenchmarkLog, CommaInsideAppMessageKeepsTheRow) {
  std::string s = RcbSteps("u", "\n", true, "Thrust (gf)", "100|200|300");
  s += "12.4,1800,,0.04,400,11.7,7.0,14000,0,Cutoff: limitSwitch (val=1, limit=0),\n";
  const SteadyTable t = ReadLog(WriteTemp("rcb_msg.csv", s));
  EXPECT_EQ(t.rows(), 4u);
  EXPECT_EQ(t.rows_with_extra_cells, 1u);
}

// ------------------------------------------------------------------ mapped tables

TEST(MappedLog, ManufacturerTableWithUnitsInTheMap) {
  // Shape of the T-Motor table in sjkim_mfr_motor_tables (values made up).
  const std::string s =
      "Throttle,Voltage,Current,Power,Rpm,Torque,Thrust,Efficiency\n"
      "0.4,15.10,11.63,175.60,8205,0.141,868,4.94\n"
      "0.5,15.03,15.84,238.11,9162,0.177,1085,4.55\n";
  LogReadOptions o;
  o.column_map = {"throttle=Throttle", "vdc_v=Voltage", "idc_a=Current", "rpm=Rpm",
                  "torque_nm=Torque [N*m]", "thrust_n=Thrust [g]"};
  const SteadyTable t = ReadLog(WriteTemp("tmotor.csv", s), o);
  EXPECT_EQ(t.format, LogFormat::kMapped);
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_NEAR(t.Get(Column::kThrustN)[1], 1085 * kNewtonPerGramForce, 1e-12);
  EXPECT_EQ(t.Get(Column::kThrottle)[0], 0.4);
  EXPECT_FALSE(t.Has(Column::kTimeS));
  EXPECT_EQ(t.info[static_cast<int>(Column::kThrustN)].source_unit, "g");
}

TEST(MappedLog, HeaderlessColumnsByNumber) {
  // Shape of mit_multicopter_kde2814 (space separated, no header; values made up).
  const std::string s = "1100 6e-05 0.0052 0 0\n1150 0.0026 0.126 1267 0.11\n1200 0.0083 0.476 2388 0.36\n";
  LogReadOptions o;
  o.column_map = {"throttle=#1 [us]", "torque_nm=#2 [N*m]", "thrust_n=#3 [N]", "rpm=#4",
                  "idc_a=#5 [A]"};
  const SteadyTable t = ReadLog(WriteTemp("mit.txt", s), o);
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.source_line[0], 1u);
  EXPECT_NEAR(t.Get(Column::kThrottle)[1], 0.15, 1e-15);
  EXPECT_FALSE(t.Has(Column::kVdcV));
  EXPECT_EQ(t.delimiter, ' ');
}

TEST(MappedLog, Errors) {
  const std::string s = "Thr,I\n0.5,2\n0.6,3\n";
  LogReadOptions o;
  o.column_map = {"throtle=Thr", "idc_a=I"};
  std::string e = ErrorOf(WriteTemp("m1.csv", s), o);
  EXPECT_TRUE(Contains(e, "unknown canonical name \"throtle\"; valid: time_s, vdc_v, throttle")) << e;
  o.column_map = {"throttle=Throttle", "idc_a=I"};
  e = ErrorOf(WriteTemp("m2.csv", s), o);
  EXPECT_TRUE(Contains(e, "no column \"Throttle\" in the header; columns: \"I\", \"Thr\"")) << e;
  o.column_map = {"throttle=Thr", "idc_a=I [furlong]"};
  e = ErrorOf(WriteTemp("m3.csv", s), o);
  EXPECT_TRUE(Contains(e, "unit \"furlong\" is not valid for idc_a")) << e;
  o.column_map = {"throttle=Thr"};
  e = ErrorOf(WriteTemp("m4.csv", s), o);
  EXPECT_TRUE(Contains(e, "idc_a must be mapped")) << e;
  // Annotation rows: strict by default, dropped and counted on request.
  const std::string ann = "Thr,I\n0.5,2\n0.6,3\n,PEAK\n";
  o.column_map = {"throttle=Thr", "idc_a=I"};
  e = ErrorOf(WriteTemp("m5.csv", ann), o);
  EXPECT_TRUE(Contains(e, "line 4, column \"Thr\": \"\": empty cell")) << e;
  // With --drop-incomplete-rows the row goes (trailer rows such as "PEAK THRUST"),
  // named in the drop reason; stand_exports_test.cc checks a malformed number stays an error.
  o.mapped_drop_rows_with_empty_cells = true;
  const SteadyTable t6 = ReadLog(WriteTemp("m6.csv", ann), o);
  EXPECT_EQ(t6.rows(), 2u);
  ASSERT_EQ(t6.dropped.size(), 1u);
  EXPECT_TRUE(Contains(t6.dropped[0].reason, "line 4, column \"I\": \"PEAK\"")) << t6.dropped[0].reason;
}

// ------------------------------------------------------------------ DriveCalc

TEST(DriveCalcLog, MotorFilterNoLoadFlagAndZeroSpeed) {
  const std::string s =
      "myid,tbs,motor_id,U,n,I,IsNoLoad,prop_id,Alt,Temp\r\n"
      "1,4,1,7.19,39315.0,0.78,1,0,0,15.0\r\n"
      "2,4,1,6.9,36816.0,1.43,0,0,0,15.0\r\n"
      "3,4,1,6.19,29165.0,4.55,0,0,0,15.0\r\n"
      "4,4,2,7.58,0.0,0.34,1,0,0,15.0\r\n"
      "5,4,2,7.00,20000.0,3.0,0,0,0,15.0\r\n"
      "6,4,2,6.50,18000.0,5.0,0,0,0,15.0\r\n";
  const SteadyTable all = ReadLog(WriteTemp("mdata.csv", s));
  EXPECT_EQ(all.format, LogFormat::kDriveCalc);
  EXPECT_EQ(all.rows(), 5u);  // n = 0 dropped
  EXPECT_EQ(all.DroppedTotal(), 1u);
  EXPECT_TRUE(all.Has(Column::kMotorId));
  EXPECT_FALSE(all.Has(Column::kThrottle));
  LogReadOptions o;
  o.drivecalc_motor_id = 1;
  const SteadyTable m1 = ReadLog(WriteTemp("mdata1.csv", s), o);
  ASSERT_EQ(m1.rows(), 3u);
  EXPECT_FALSE(m1.Has(Column::kMotorId));
  EXPECT_EQ(m1.Get(Column::kNoLoad)[0], 1.0);
  EXPECT_EQ(m1.Get(Column::kNoLoad)[1], 0.0);
  EXPECT_EQ(m1.Get(Column::kVdcV)[2], 6.19);
  EXPECT_NEAR(m1.Get(Column::kOmegaRadS)[0], 39315.0 * kPi / 30.0, 1e-9);
  o.drivecalc_motor_id = 7;
  const std::string e = ErrorOf(WriteTemp("mdata7.csv", s), o);
  EXPECT_TRUE(Contains(e, "no MData row has motor_id 7 (6 rows of other motors)")) << e;
}

TEST(DriveCalcLog, NoLoadPointsWithoutSpeedKeptOnRequest) {
  const std::string s =
      "myid,tbs,motor_id,U,n,I,IsNoLoad,prop_id,Alt,Temp\n"
      "4,4,2,7.58,0.0,0.34,1,0,0,15.0\n"
      "5,4,2,7.00,20000.0,3.0,0,0,0,15.0\n"
      "6,4,2,6.50,0,5.0,0,0,0,15.0\n";
  LogReadOptions o;
  o.drivecalc_keep_no_load_without_speed = true;
  const SteadyTable t = ReadLog(WriteTemp("mdata_nl.csv", s), o);
  ASSERT_EQ(t.rows(), 2u);  // the no-load row stays, the loaded n = 0 row does not
  EXPECT_EQ(t.Get(Column::kNoLoad)[0], 1.0);
  EXPECT_EQ(t.Get(Column::kOmegaRadS)[0], 0.0);
  ASSERT_EQ(t.dropped.size(), 1u);
  EXPECT_EQ(t.dropped[0].reason, "loaded points with n = 0 (speed not measured)");
  EXPECT_EQ(t.dropped[0].count, 1u);
  ASSERT_EQ(t.notes.size() >= 1, true);
  EXPECT_TRUE(Contains(t.notes[0], "1 no-load points without a speed reading")) << t.notes[0];
}

}  // namespace
}  // namespace dynosize::logs
