// Every real public log in shared/data listed below reads without error, with what the
// data allows (columns present / absent as documented in each folder's README). Skipped when
// ../shared is absent. The per-file counts are printed (rows read, plateaus, dropped).
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "common/error.h"
#include "logs/log_reader.h"
#include "logs/log_test_util.h"

namespace dynosize::logs {
namespace {

using testing_util::HaveShared;
using testing_util::SharedData;

std::vector<std::string> CsvFilesIn(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(SharedData() + dir)) {
    if (e.is_regular_file() && e.path().extension() == ".csv") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string Present(const SteadyTable& t) {
  std::string s;
  for (int c = 0; c < kColumnCount; ++c) {
    if (t.info[c].present) s += std::string(s.empty() ? "" : " ") + ColumnName(static_cast<Column>(c));
  }
  return s;
}

SteadyTable ReadAndPrint(const std::string& path, const LogReadOptions& o = LogReadOptions()) {
  SCOPED_TRACE(path);
  SteadyTable t;
  try {
    t = ReadLog(path, o);
  } catch (const Error& e) {
    ADD_FAILURE() << e.what();
    return t;
  }
  EXPECT_GE(t.rows(), 2u);
  EXPECT_TRUE(t.Has(Column::kIdcA));
  for (int c = 0; c < kColumnCount; ++c) {
    for (double v : t.columns[c]) EXPECT_TRUE(std::isfinite(v)) << ColumnName(static_cast<Column>(c));
    if (t.info[c].present) {
      EXPECT_EQ(t.columns[c].size(), t.rows()) << ColumnName(static_cast<Column>(c));
    } else {
      EXPECT_TRUE(t.columns[c].empty()) << ColumnName(static_cast<Column>(c));
    }
  }
  const std::string rel = path.substr(SharedData().size());
  std::cout << "[real] " << rel << " | " << LogFormatName(t.format) << " | read " << t.data_rows_read
            << " | points " << t.rows() << (t.time_series ? " (plateaus)" : "") << " | dropped "
            << t.DroppedTotal() << " | transient " << t.transient_samples << " | outliers "
            << t.outlier_samples << " | " << Present(t) << "\n";
  return t;
}

#define REQUIRE_SHARED() \
  if (!HaveShared()) GTEST_SKIP() << "shared data folder " << SharedData() << " not found"

// Every stand log of shared/data reads with format auto and no --map, except the files
// docs/log-formats.md lists (no header, or no units), whose error names what is missing and a
// ready --map line; tables of several motors need --where only. Auto reads give the numbers of
// the documented --map reads.
TEST(RealLogs, EveryStandLogReadsWithAutoExceptTheDocumentedOnes) {
  REQUIRE_SHARED();
  std::vector<std::string> files;
  for (const char* dir : {"tytodb_tmotor16x54_9motors", "elodin_2300kv_6x3_4s", "bhabas_sar_motor_sysid",
                          "aerostack2_xnova_thrustmap", "alspitz_esc_test", "diegosdantonio_tinywhoop",
                          "heinzgerhard_rcb_large_motor", "strawson_fpv_motor_prop/rawdata", "crazyflie_brushed_bitcraze2021",
                          "ctu_mrs_motor_tests"}) {
    for (const auto& f : CsvFilesIn(dir)) files.push_back(f);
  }
  for (const auto& e : std::filesystem::directory_iterator(SharedData() + "sjkim_mfr_motor_tables")) {
    if (e.path().extension() == ".csv") files.push_back(e.path().string());
  }
  for (const auto& e : std::filesystem::recursive_directory_iterator(SharedData() + "jmajew_thrusttool_6motors")) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".tex" || ext == ".txt" || ext == ".csv")) files.push_back(e.path().string());
  }
  for (const char* f : {"mit_multicopter_kde2814/motor_10inch_prop.txt", "mit_multicopter_kde2814/motor_14inch_prop.txt",
                        "dronebuildcalc_mfr_tables/motordata.csv", "drivecalc/MData.csv"}) {
    files.push_back(SharedData() + f);
  }
  // The documented exceptions: the file's name and a part of the error it gets.
  const std::map<std::string, std::vector<std::string>> exceptions = {
      {"motor_10inch_prop.txt", {"cannot tell the log format", "--format mapped --map"}},  // no header
      {"motor_14inch_prop.txt", {"cannot tell the log format", "--format mapped --map"}},
      {"TMotor_AT2814_1200kv.csv", {"\"Voltage\", \"Current\", \"Torque\", \"Thrust\" name no unit", "[UNIT]"}},
      {"A4220_540kv_stand_test.csv", {"\"Voltage\", \"Current\", \"Thrust\", \"Torque\" name no unit", "[UNIT]"}},
      {"cf2.1-stock-prop.csv", {"no current column", "--map \"idc_a=i[A]\""}},
      {"cf21_stock2.csv", {"no current column", "--map \"idc_a=i[A]\""}},
      {"motordata.csv", {"no current column", "--map \"vdc_v=V [V]\" --map \"idc_a=A [A]\""}},
      {"ctu_mrs_motor_tests.csv", {"several motors", "--where \"motor=Readytosky 2312 920KV\""}},
      {"extracted_steady_points.csv", {"several motors", "--where \"source_file="}},
  };
  std::size_t read = 0, refused = 0;
  for (const auto& f : files) {
    SCOPED_TRACE(f);
    const std::string name = std::filesystem::path(f).filename().string();
    const auto ex = exceptions.find(name);
    const std::string e = testing_util::ErrorOf(f);
    if (ex == exceptions.end()) {
      EXPECT_EQ(e, "(no error)");
      ++read;
    } else {
      for (const auto& part : ex->second) EXPECT_TRUE(testing_util::Contains(e, part)) << e;
      EXPECT_EQ(e.find('\n'), std::string::npos) << e;
      ++refused;
    }
  }
  std::cout << "[real] stand logs with --format auto, no --map: " << read << " read, " << refused
            << " refused as documented\n";
  EXPECT_EQ(refused, exceptions.size());
  EXPECT_EQ(read + refused, 320u);  // every stand log of the shared data sets

  // Tables that read now give the numbers of their documented --map reads.
  auto same = [](const SteadyTable& a, const SteadyTable& b) {
    ASSERT_EQ(a.rows(), b.rows());
    for (int c = 0; c < kColumnCount; ++c) {
      ASSERT_EQ(a.info[c].present, b.info[c].present) << ColumnName(static_cast<Column>(c));
      if (!a.info[c].present) continue;
      for (std::size_t r = 0; r < a.rows(); ++r) {
        EXPECT_EQ(a.columns[c][r], b.columns[c][r]) << ColumnName(static_cast<Column>(c)) << " row " << r;
      }
    }
  };
  const std::string d = SharedData() + "sjkim_mfr_motor_tables/";
  LogReadOptions m;
  m.column_map = {"throttle=throttle", "vdc_v=voltage_V", "idc_a=current_A", "rpm=rpm", "torque_nm=torque_Nm",
                  "thrust_n=thrust_g [g]"};
  same(ReadLog(d + "TMotor_AT3520_550kv.csv"), ReadLog(d + "TMotor_AT3520_550kv.csv", m));
  LogReadOptions ctu_map, ctu_auto;
  ctu_map.column_map = {"throttle=throttle_pct_nominal [%]", "thrust_n=thrust_g [g]", "rpm=rpm", "vdc_v=voltage_V",
                        "idc_a=current_A"};
  ctu_map.row_filter = ctu_auto.row_filter = {"motor=T-Motor 3110 780KV"};
  const std::string ctu = SharedData() + "ctu_mrs_motor_tests/ctu_mrs_motor_tests.csv";
  same(ReadLog(ctu, ctu_auto), ReadLog(ctu, ctu_map));
  LogReadOptions jm_map, jm_auto;
  jm_map.column_map = {"throttle=out_pct [%]", "thrust_n=thrust_g [g]", "torque_nm=torque_gcm [G cm]", "rpm=rpm",
                       "vdc_v=volt_V", "idc_a=curr_A"};
  jm_map.row_filter = jm_auto.row_filter = {"source_file=tmotor-mn2206/grp01__mn2206_hqprop6x4x3_3s.tex"};
  const std::string jm = SharedData() + "jmajew_thrusttool_6motors/extracted_steady_points.csv";
  same(ReadLog(jm, jm_auto), ReadLog(jm, jm_map));
}

TEST(RealLogs, AlspitzEscTest) {
  REQUIRE_SHARED();
  for (const auto& f : CsvFilesIn("alspitz_esc_test/data/rcbench")) {
    const SteadyTable t = ReadAndPrint(f);
    EXPECT_EQ(t.format, LogFormat::kRcbenchmark);
    EXPECT_TRUE(t.time_series);
    // Only the Aikon test (2019-11-09) drove the ESC from the stand.
    EXPECT_EQ(t.Has(Column::kThrottle), f.find("2019-11-09") != std::string::npos) << f;
    EXPECT_TRUE(t.Has(Column::kTorqueNm));
    EXPECT_TRUE(t.Has(Column::kVdcV));
  }
}

TEST(RealLogs, StrawsonFpvMotorProp) {
  REQUIRE_SHARED();
  const auto files = CsvFilesIn("strawson_fpv_motor_prop/rawdata");
  EXPECT_EQ(files.size(), 208u);
  std::size_t rows = 0, dropped = 0;
  for (const auto& f : files) {
    SteadyTable t;
    ASSERT_NO_THROW(t = ReadLog(f)) << f;
    EXPECT_FALSE(t.time_series) << f;  // one averaged row per step
    EXPECT_FALSE(t.Has(Column::kTorqueNm)) << f;  // "NO torque" (README)
    EXPECT_TRUE(t.Has(Column::kThrottle) && t.Has(Column::kThrustN) && t.Has(Column::kOmegaRadS)) << f;
    rows += t.rows();
    dropped += t.DroppedTotal();
  }
  std::cout << "[real] strawson_fpv_motor_prop/rawdata/*.csv (208 files) | rcbenchmark | read 2288 | points "
            << rows << " | dropped " << dropped << " (speed 0: motor not started / dropout)\n";
  EXPECT_EQ(rows + dropped, 2288u);  // README: 2288 data rows
}

TEST(RealLogs, Aerostack2Xnova) {
  REQUIRE_SHARED();
  for (const auto& f : CsvFilesIn("aerostack2_xnova_thrustmap")) {
    const SteadyTable t = ReadAndPrint(f);
    EXPECT_TRUE(t.Has(Column::kThrottle) && t.Has(Column::kThrustN) && t.Has(Column::kVdcV)) << f;
    if (f.find("TM-S") != std::string::npos) {
      EXPECT_EQ(t.delimiter, ';');
    }
    if (f.find("TM-") != std::string::npos) {
      EXPECT_FALSE(t.Has(Column::kTimeS));
    }
    if (f.find("SR-ramp") != std::string::npos) {
      EXPECT_FALSE(t.Has(Column::kOmegaRadS));  // rpm all 0
    }
  }
}

TEST(RealLogs, DiegosdantonioTinywhoop) {
  REQUIRE_SHARED();
  for (const auto& f : CsvFilesIn("diegosdantonio_tinywhoop")) {
    const SteadyTable t = ReadAndPrint(f);
    // 2023 tests had no rpm sensor (README).
    if (f.find("StepsTest2023") != std::string::npos) {
      EXPECT_FALSE(t.Has(Column::kOmegaRadS)) << f;
    }
  }
}

TEST(RealLogs, BhabasSarMotorSysid) {
  REQUIRE_SHARED();
  // README: "ESC signal" has no unit, 0..2000 command units (not us): detected from the values.
  for (const auto& f : CsvFilesIn("bhabas_sar_motor_sysid")) {
    const SteadyTable t = ReadAndPrint(f);
    ASSERT_TRUE(t.Has(Column::kThrottle)) << f;
    EXPECT_NE(t.info[static_cast<int>(Column::kThrottle)].note.find("command units 0..2000"), std::string::npos)
        << t.FullReport();
    EXPECT_EQ(t.info[static_cast<int>(Column::kOmegaRadS)].source_unit, "rad/s");
    if (f.find("StepsTestV2_2024-02-06_130449") != std::string::npos) {
      // Steps of 100 command units from 0 (the motor-off row, speed 0, is dropped): 100/2000.
      EXPECT_EQ(t.Get(Column::kThrottle)[0], 0.05) << t.FullReport();
      EXPECT_EQ(t.Get(Column::kThrottle).back(), 0.9);  // 1800 of 2000
    }
  }
  // The explicit range still wins.
  LogReadOptions o;
  o.esc_unitless_min = 0.0;
  o.esc_unitless_max = 1000.0;
  const SteadyTable t =
      ReadLog(SharedData() + "bhabas_sar_motor_sysid/Motor_SO_V5/StepsTestV2_2024-02-06_103903.csv", o);
  EXPECT_NE(t.info[static_cast<int>(Column::kThrottle)].note.find("as configured"), std::string::npos);
}

TEST(RealLogs, TytoDatabaseQuotedExports) {
  REQUIRE_SHARED();
  const auto files = CsvFilesIn("tytodb_tmotor16x54_9motors");
  EXPECT_EQ(files.size(), 9u);
  std::size_t rows = 0;
  for (const auto& f : files) {
    const SteadyTable t = ReadAndPrint(f);
    EXPECT_EQ(t.format, LogFormat::kRcbenchmark) << f;
    EXPECT_FALSE(t.time_series) << f;  // one averaged row per step
    EXPECT_TRUE(t.Has(Column::kThrottle) && t.Has(Column::kTorqueNm) && t.Has(Column::kThrustN) &&
                t.Has(Column::kVdcV) && t.Has(Column::kOmegaRadS))
        << t.FullReport();
    EXPECT_EQ(t.info[static_cast<int>(Column::kOmegaRadS)].source_header, "Rotation speed (rpm)");
    // Every row is a point or counted: the motor-off one (1000 us, 0 rpm) in each file, and
    // NeuMotor's 2050 and 2100 us steps beyond the default end point 2000 us.
    EXPECT_EQ(t.rows() + t.DroppedTotal(), t.data_rows_read) << t.BriefReport();
    EXPECT_EQ(t.DroppedTotal(), f.find("NeuMotor") != std::string::npos ? 3u : 1u) << t.BriefReport();
    rows += t.rows();
  }
  EXPECT_EQ(rows, 156u);  // README: 158 spinning steady rows, 2 of them above 2000 us
  LogReadOptions o;
  o.esc_max_us = 2100;
  EXPECT_EQ(ReadLog(SharedData() + "tytodb_tmotor16x54_9motors/T-motor_16x54_static_NeuMotor 3819.csv", o).rows(),
            20u);
}

TEST(RealLogs, ElodinStandExports) {
  REQUIRE_SHARED();
  for (const auto& f : CsvFilesIn("elodin_2300kv_6x3_4s")) {
    const SteadyTable t = ReadAndPrint(f);
    EXPECT_EQ(t.format, LogFormat::kRcbenchmark) << f;
    EXPECT_TRUE(t.Has(Column::kThrottle) && t.Has(Column::kTorqueNm) && t.Has(Column::kThrustN)) << f;
  }
}

TEST(RealLogs, JmajewExtractedPointsOneReportAtATime) {
  REQUIRE_SHARED();
  LogReadOptions o;
  o.column_map = {"throttle=out_pct [%]", "thrust_n=thrust_g [g]", "torque_nm=torque_gcm [G cm]",
                  "rpm=rpm", "vdc_v=volt_V", "idc_a=curr_A"};
  o.row_filter = {"source_file=tmotor-mn2206/grp01__mn2206_hqprop6x4x3_3s.tex"};
  const std::string f = SharedData() + "jmajew_thrusttool_6motors/extracted_steady_points.csv";
  const SteadyTable t = ReadAndPrint(f, o);
  EXPECT_EQ(t.rows(), 75u);  // 5 runs x 15 steps (README)
  EXPECT_NEAR(t.Get(Column::kThrottle)[0], 0.2, 1e-15);  // written "2e+01"
  // Torque in g*cm: the report's first step, 77.87 g*cm.
  EXPECT_NEAR(t.Get(Column::kTorqueNm)[0], 77.87 * 9.80665e-5, 1e-12);
  o.row_filter = {"motor_dir=tmotor-mt2212", "cells_from_path=4"};
  EXPECT_EQ(ReadAndPrint(f, o).rows(), 150u);  // two 4S reports of 5 x 15
}

TEST(RealLogs, JmajewThrustAppReports) {
  REQUIRE_SHARED();
  std::vector<std::string> files;
  for (const auto& e :
       std::filesystem::recursive_directory_iterator(SharedData() + "jmajew_thrusttool_6motors")) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".tex" || ext == ".txt")) files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files.size(), 37u);  // 34 reports, 3 text exports
  std::size_t steps = 0;
  for (const auto& f : files) {
    const SteadyTable t = ReadAndPrint(f);
    EXPECT_EQ(t.format, LogFormat::kThrustApp) << f;
    EXPECT_TRUE(t.Has(Column::kTorqueNm) && t.Has(Column::kThrustN) && t.Has(Column::kThrottle)) << f;
    const bool comparison = f.find("duct_comp") != std::string::npos;
    if (f.size() > 4 && f.substr(f.size() - 4) == ".tex" && !comparison) steps += t.data_rows_read;
  }
  // README: 1617 step means in the extracted CSV, taken from the same reports (the duct
  // comparison report excluded).
  EXPECT_EQ(steps, 1617u);
}

TEST(RealLogs, CtuMrsOneMotorAtATime) {
  REQUIRE_SHARED();
  LogReadOptions o;
  o.column_map = {"throttle=throttle_pct_nominal [%]", "thrust_n=thrust_g [g]", "rpm=rpm",
                  "vdc_v=voltage_V", "idc_a=current_A"};
  const std::string f = SharedData() + "ctu_mrs_motor_tests/ctu_mrs_motor_tests.csv";
  std::size_t rows = 0;
  for (const char* m : {"Readytosky 2312 920KV", "T-Motor 3110 780KV", "Tarot 4114 320KV"}) {
    o.row_filter = {std::string("motor=") + m};
    const SteadyTable t = ReadAndPrint(f, o);
    EXPECT_FALSE(t.Has(Column::kTorqueNm));  // no torque (README)
    rows += t.rows();
  }
  EXPECT_EQ(rows, 60u);
}

TEST(RealLogs, DronebuildcalcOneMotorAtATime) {
  REQUIRE_SHARED();
  LogReadOptions o;
  o.column_map = {"throttle=T", "vdc_v=V", "idc_a=A", "rpm=RPM", "thrust_n=Thrust g [g]"};
  o.row_filter = {"Brand=Uangel", "Motor=A2807"};
  const SteadyTable t = ReadAndPrint(SharedData() + "dronebuildcalc_mfr_tables/motordata.csv", o);
  EXPECT_GE(t.rows(), 3u);
  EXPECT_NEAR(t.Get(Column::kThrottle)[0], 0.4, 1e-15);  // written "40.00%"
}

TEST(RealLogs, HeinzgerhardLargeMotor) {
  REQUIRE_SHARED();
  for (const auto& f : CsvFilesIn("heinzgerhard_rcb_large_motor")) {
    const SteadyTable t = ReadAndPrint(f);
    EXPECT_TRUE(t.Has(Column::kTempC)) << f;  // "4N76 Temp (ºC)"
    EXPECT_EQ(t.info[static_cast<int>(Column::kOmegaRadS)].source_header, "Motor Optical Speed (RPM)");
    // Torque is negative as mounted (README): flipped, with a note.
    EXPECT_NE(t.info[static_cast<int>(Column::kTorqueNm)].note.find("sign flipped"), std::string::npos);
  }
}

TEST(RealLogs, SjkimManufacturerTables) {
  REQUIRE_SHARED();
  const std::string d = SharedData() + "sjkim_mfr_motor_tables/";
  LogReadOptions o;
  o.column_map = {"throttle=Throttle", "vdc_v=Voltage", "idc_a=Current", "rpm=Rpm",
                  "torque_nm=Torque [N*m]", "thrust_n=Thrust [g]"};
  ReadAndPrint(d + "TMotor_AT2814_1200kv.csv", o);
  o.column_map = {"throttle=throttle", "vdc_v=voltage_V", "idc_a=current_A", "rpm=rpm",
                  "torque_nm=torque_Nm", "thrust_n=thrust_g [g]"};
  ReadAndPrint(d + "TMotor_AT3520_550kv.csv", o);
  ReadAndPrint(d + "TMotor_AT4125_540kv.csv", o);
  o.column_map = {"throttle=throttle", "vdc_v=voltage_V", "idc_a=current_A", "rpm=rpm",
                  "torque_nm=torque_Nm"};
  ReadAndPrint(d + "Scorpion_1100kv.csv", o);
  // The A-4220 stand table: thrust in kgf (README), an annotation row "6s Lipo,,PEAK THRUST"
  // and a peak-thrust row without throttle: strict by default, dropped on request.
  o.column_map = {"throttle=Throttle", "vdc_v=Voltage", "idc_a=Current", "rpm=RPM",
                  "torque_nm=Torque", "thrust_n=Thrust [kgf]"};
  try {
    ReadLog(d + "A4220_540kv_stand_test.csv", o);
    ADD_FAILURE() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("line 13, column \"Throttle\": \"\": empty cell"), std::string::npos)
        << e.what();
  }
  o.mapped_drop_rows_with_empty_cells = true;
  const SteadyTable t = ReadAndPrint(d + "A4220_540kv_stand_test.csv", o);
  EXPECT_EQ(t.rows(), 11u);
  EXPECT_EQ(t.DroppedTotal(), 2u);
  EXPECT_NEAR(t.Get(Column::kThrustN)[0], 0.57 * 9.80665, 1e-12);
  // Through the "ESC throttle (us)" column the trailer row "6s Lipo,,PEAK THRUST" is text in
  // the command column: dropped under --drop-incomplete-rows, and the peak-thrust row kept.
  o.column_map[0] = "throttle=ESC throttle (us)";
  const SteadyTable us = ReadAndPrint(d + "A4220_540kv_stand_test.csv", o);
  EXPECT_EQ(us.rows(), 12u);
  ASSERT_EQ(us.dropped.size(), 1u);
  EXPECT_NE(us.dropped[0].reason.find("line 13, column \"ESC throttle (us)\": \"PEAK THRUST\""),
            std::string::npos)
      << us.BriefReport();
  o.mapped_drop_rows_with_empty_cells = false;
  try {
    ReadLog(d + "A4220_540kv_stand_test.csv", o);
    ADD_FAILURE() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("\"PEAK THRUST\": not a number"), std::string::npos) << e.what();
  }
}

TEST(RealLogs, MitKde2814) {
  REQUIRE_SHARED();
  LogReadOptions o;
  o.column_map = {"throttle=#1 [us]", "torque_nm=#2 [N*m]", "thrust_n=#3 [N]", "rpm=#4",
                  "idc_a=#5 [A]"};
  for (const char* f : {"motor_10inch_prop.txt", "motor_14inch_prop.txt"}) {
    const SteadyTable t = ReadAndPrint(SharedData() + "mit_multicopter_kde2814/" + f, o);
    EXPECT_FALSE(t.Has(Column::kVdcV));  // no voltage column (README)
    EXPECT_TRUE(t.Has(Column::kThrottle));
  }
}

TEST(RealLogs, DriveCalcMData) {
  REQUIRE_SHARED();
  const SteadyTable all = ReadAndPrint(SharedData() + "drivecalc/MData.csv");
  EXPECT_EQ(all.data_rows_read, 8214u);      // README: 8214 rows
  EXPECT_EQ(all.DroppedTotal(), 448u);       // README: 448 rows have n = 0
  EXPECT_FALSE(all.Has(Column::kThrottle));
  EXPECT_TRUE(all.Has(Column::kNoLoad) && all.Has(Column::kMotorId));
  LogReadOptions o;
  o.drivecalc_motor_id = 1;
  const SteadyTable m1 = ReadAndPrint(SharedData() + "drivecalc/MData.csv", o);
  EXPECT_EQ(m1.rows(), 3u);
  EXPECT_EQ(m1.Get(Column::kNoLoad)[0], 1.0);
  EXPECT_EQ(m1.Get(Column::kVdcV)[0], 7.19);  // first MData row: 1,4,1,7.19,39315.0,0.78,1,...
}

}  // namespace
}  // namespace dynosize::logs
