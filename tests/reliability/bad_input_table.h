// The bad-input table: every input dynosize reads, broken in every way we know of,
// each row with the exit code and the words the one-line refusal must contain.
//
// A row writes `files` (name -> bytes) into a fresh folder, runs `dynosize ARGS` there and
// checks: the exit code; stdout empty; stderr exactly one line per problem, each starting with
// "dynosize: "; every string of `message_has` in stderr. In ARGS and in `message_has`, {dir} is
// the folder the files were written to, {src} the source tree. A new input (the mission reader) is new rows:
//
//   {"mission_nan_mass", {{"m.json", R"({"mass_kg": NaN})"}}, "evaluate {dir}/m.json ...", 65,
//    {"{dir}/m.json", "1:14", "invalid JSON"}},
#pragma once

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace dynosize::reliability {

struct BadInputCase {
  std::string name;  // a GoogleTest name: letters, digits, underscores
  std::vector<std::pair<std::string, std::string>> files;
  std::string args;
  int exit_code;
  std::vector<std::string> message_has;
};
inline void PrintTo(const BadInputCase& c, std::ostream* os) { *os << c.name; }

// ------------------------------------------------------------------ building blocks

// A valid catalog document with one motor and one ESC; `motor_extra` / `esc_extra` are spliced
// into the entries (",\"key\": value" to add or override a key: the reader then sees a
// duplicate key, so overrides use the Replace helper below instead).
inline std::string CatalogDoc(const std::string& motor_body, const std::string& esc_body) {
  return "{\n  \"motors\": [\n    {" + motor_body + "}\n  ],\n  \"escs\": [\n    {" + esc_body +
         "}\n  ]\n}\n";
}
inline std::string MotorBody(const std::string& rm = "0.12", const std::string& id = "m1") {
  return "\"id\": \"" + id + "\", \"name\": \"M\", \"type\": \"bldc\", \"kv_rpm_per_v\": 1900, "
         "\"rm_ohm\": " + rm + ", \"io_a\": 0.5, \"source\": {\"dataset\": \"test\"}";
}
inline std::string EscBody(const std::string& id = "e1", const std::string& c1 = "1.2") {
  return "\"id\": \"" + id + "\", \"name\": \"E\", \"resc_ohm\": 0.02, \"c1\": " + c1 +
         ", \"c0\": 0.03, \"tr_sat\": 0.9, \"sat_slope\": 0.61, \"source\": {\"dataset\": \"test\"}";
}
inline std::string ValidCatalog() { return CatalogDoc(MotorBody(), EscBody()); }

// A canonical log with distinct steady points (values only need to read, not to fit well).
inline std::string CanonicalHeader() { return "time_s,vdc_v,throttle,rpm,torque_nm,idc_a\n"; }
inline std::string CanonicalRows() {
  return "0,7.2,0.3,3000,0.010,0.8\n"
         "1,7.2,0.4,4000,0.020,1.4\n"
         "2,7.2,0.5,5000,0.030,2.1\n"
         "3,7.2,0.6,6000,0.040,2.9\n";
}
inline std::string CanonicalLog() { return CanonicalHeader() + CanonicalRows(); }

inline std::string RcbHeader() {
  return "Time (s),ESC signal (\xC2\xB5s),Torque (N\xC2\xB7m),Thrust (kgf),Voltage (V),"
         "Current (A),Motor Optical Speed (RPM),\n";
}
inline std::string DriveCalcHeader() { return "motor_id,U,n,I,IsNoLoad,Temp\n"; }

inline std::string Utf16LeWithBom(const std::string& ascii) {
  std::string s = "\xFF\xFE";
  for (char c : ascii) {
    s.push_back(c);
    s.push_back('\0');
  }
  return s;
}

inline std::string Garbage(std::size_t n, unsigned seed) {
  // A fixed linear congruential sequence: deterministic bytes, NULs and high bytes included.
  std::string s;
  unsigned x = seed;
  for (std::size_t i = 0; i < n; ++i) {
    x = x * 1103515245u + 12345u;
    s.push_back(static_cast<char>((x >> 16) & 0xFF));
  }
  return s;
}

inline std::string Nested(int depth) {
  return "{\"motors\": " + std::string(static_cast<std::size_t>(depth), '[') +
         std::string(static_cast<std::size_t>(depth), ']') + "}";
}

// ------------------------------------------------------------------ the table

// `text` with the first `from` replaced by `to` (the test fails loudly if `from` is absent).
inline std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) return "Replace: '" + from + "' not found";
  return text.replace(at, from.size(), to);
}

// A valid mission (docs/missions.md): one cruise and one hover segment.
inline std::string Mission() {
  return R"({"name": "t", "vehicle": {"mass_kg": 0.75, "rotors": 4},
  "battery": {"id": "b", "cells": 4},
  "constraints": {"max_throttle": 0.8},
  "objective": {"type": "max_endurance", "segment": "loiter"},
  "segments": [{"name": "out", "type": "cruise", "airspeed_m_s": 10, "distance_m": 2000},
               {"name": "loiter", "type": "hover", "duration_s": 300}]}
)";
}

inline std::vector<BadInputCase> BadInputCases() {
  const std::string cal = "calibrate --motor-id fm --esc-id fe ";
  const std::string list = "catalog list --catalog {dir}/cat";
  const std::string sim = "--catalog {dir}/cat simulate --motor m1 --esc e1 ";
  // {dir}/paper holds the paper's catalog file only (bad_input_test.cc puts it there).
  const std::string batch =
      "--catalog {dir}/paper simulate --motor emax_1900kv_paper --esc multistar_30a_paper --batch ";
  std::vector<BadInputCase> c;

  // ---- catalog JSON (strict)
  c.push_back({"catalog_empty_file", {{"cat/c.json", ""}}, list, 65,
               {"{dir}/cat/c.json", "empty file"}});
  c.push_back({"catalog_truncated", {{"cat/c.json", ValidCatalog().substr(0, 60)}}, list, 65,
               {"{dir}/cat/c.json:", "invalid JSON", "unexpected end of input"}});
  c.push_back({"catalog_binary_garbage", {{"cat/c.json", Garbage(300, 7)}}, list, 65,
               {"{dir}/cat/c.json:1:", "invalid JSON"}});
  c.push_back({"catalog_utf16_bom", {{"cat/c.json", Utf16LeWithBom(ValidCatalog())}}, list, 65,
               {"{dir}/cat/c.json", "UTF-16", "save it as UTF-8"}});
  c.push_back({"catalog_utf16_big_endian",
               {{"cat/c.json", "\xFE\xFF" + Utf16LeWithBom(ValidCatalog()).substr(2).insert(0, 1, '\0')}},
               list, 65, {"{dir}/cat/c.json", "UTF-16 big-endian (byte-order mark FE FF)"}});
  c.push_back({"catalog_latin1_name",
               {{"cat/c.json", CatalogDoc(MotorBody() + ", \"note_x\": 1", EscBody())}},
               list, 65, {"{dir}/cat/c.json", "motors[0]", "note_x", "unknown key"}});
  c.push_back({"catalog_latin1_string",
               {{"cat/c.json", "{\"motors\": [{\"id\": \"m\xB5\"}]}"}}, list, 65,
               {"{dir}/cat/c.json:1:", "invalid JSON", "UTF-8"}});
  c.push_back({"catalog_missing_key",
               {{"cat/c.json", CatalogDoc("\"id\": \"m1\", \"name\": \"M\", \"type\": \"bldc\", "
                                          "\"kv_rpm_per_v\": 1900, \"io_a\": 0.5, \"source\": "
                                          "{\"dataset\": \"t\"}",
                                          EscBody())}},
               list, 65, {"{dir}/cat/c.json", "motors[0]", "id=m1", "rm_ohm", "missing"}});
  c.push_back({"catalog_extra_key", {{"cat/c.json", CatalogDoc(MotorBody() + ", \"colour\": 3", EscBody())}},
               list, 65, {"{dir}/cat/c.json", "motors[0]", "colour", "unknown key"}});
  c.push_back({"catalog_duplicate_key",
               {{"cat/c.json", CatalogDoc(MotorBody() + ", \"rm_ohm\": 0.2", EscBody())}}, list, 65,
               {"{dir}/cat/c.json", "/motors/0", "duplicate key \"rm_ohm\""}});
  c.push_back({"catalog_text_in_number", {{"cat/c.json", CatalogDoc(MotorBody("\"0.12\""), EscBody())}},
               list, 65, {"{dir}/cat/c.json", "motors[0]", "rm_ohm", "\"0.12\"", "must be a finite number"}});
  c.push_back({"catalog_nan_literal", {{"cat/c.json", CatalogDoc(MotorBody("NaN"), EscBody())}}, list, 65,
               {"{dir}/cat/c.json:", "invalid JSON"}});
  c.push_back({"catalog_infinity_literal", {{"cat/c.json", CatalogDoc(MotorBody("Infinity"), EscBody())}},
               list, 65, {"{dir}/cat/c.json:", "invalid JSON"}});
  c.push_back({"catalog_number_overflow", {{"cat/c.json", CatalogDoc(MotorBody("1e999"), EscBody())}},
               list, 65, {"{dir}/cat/c.json", "1e999", "finite"}});
  c.push_back({"catalog_1e308", {{"cat/c.json", CatalogDoc(MotorBody("1e308"), EscBody())}}, list, 65,
               {"{dir}/cat/c.json", "motors[0]", "rm_ohm", "1e+308", "must be"}});
  c.push_back({"catalog_negative", {{"cat/c.json", CatalogDoc(MotorBody("-0.1"), EscBody())}}, list, 65,
               {"{dir}/cat/c.json", "motors[0]", "rm_ohm", "-0.1", "must be"}});
  c.push_back({"catalog_zero", {{"cat/c.json", CatalogDoc(MotorBody("0"), EscBody())}}, list, 65,
               {"{dir}/cat/c.json", "motors[0]", "rm_ohm", "= 0", "must be"}});
  c.push_back({"catalog_ratio_out_of_range", {{"cat/c.json", CatalogDoc(MotorBody(), EscBody("e1", "-2"))}},
               list, 65, {"{dir}/cat/c.json", "escs[0]", "c1", "-2", "must be"}});
  c.push_back({"catalog_duplicate_id",
               {{"cat/c.json", "{\"motors\": [{" + MotorBody() + "}, {" + MotorBody("0.2") + "}]}"}},
               list, 65, {"{dir}/cat/c.json", "motors[1]", "m1", "duplicate id"}});
  c.push_back({"catalog_duplicate_id_across_files",
               {{"cat/a.json", "{\"motors\": [{" + MotorBody() + "}]}"},
                {"cat/b.json", "{\"escs\": [{" + EscBody("m1") + "}]}"}},
               list, 65, {"{dir}/cat/b.json", "escs[0]", "m1", "duplicate id", "{dir}/cat/a.json"}});
  c.push_back({"catalog_top_level_array", {{"cat/c.json", "[1, 2]"}}, list, 65,
               {"{dir}/cat/c.json", "top level must be an object"}});
  c.push_back({"catalog_deeply_nested", {{"cat/c.json", Nested(100000)}}, list, 65,
               {"{dir}/cat/c.json", "nesting deeper than 32 levels"}});
  c.push_back({"catalog_folder_missing", {}, "catalog list --catalog {dir}/nope", 66,
               {"{dir}/nope", "no such catalog folder"}});
  c.push_back({"catalog_folder_empty", {{"cat/readme.txt", "x"}}, list, 65,
               {"{dir}/cat", "holds no .json file"}});
  c.push_back({"catalog_two_problems_two_lines",
               {{"cat/c.json", CatalogDoc(MotorBody("-1"), EscBody("e1", "-2"))}}, list, 65,
               {"motors[0]", "rm_ohm", "escs[0]", "c1", "\ndynosize: "}});
  c.push_back({"catalog_bad_used_by_simulate", {{"cat/c.json", CatalogDoc(MotorBody("-1"), EscBody())}},
               sim + "--vdc 7.2 --throttle 0.5 --torque 0.01", 65, {"{dir}/cat/c.json", "rm_ohm"}});
  c.push_back({"catalog_unknown_id", {{"cat/c.json", ValidCatalog()}},
               "--catalog {dir}/cat simulate --motor m2 --esc e1 --vdc 7 --throttle 0.5 --torque 0.01",
               64, {"m2", "m1"}});

  // ---- canonical log (strict)
  c.push_back({"canonical_empty", {{"log.csv", ""}}, cal + "{dir}/log.csv", 65,
               {"{dir}/log.csv", "empty file"}});
  c.push_back({"canonical_header_only", {{"log.csv", CanonicalHeader()}}, cal + "{dir}/log.csv", 65,
               {"{dir}/log.csv", "0 steady operating points", "at least 2"}});
  c.push_back({"canonical_truncated_row",
               {{"log.csv", CanonicalLog() + "4,7.2,0.7,70"}}, cal + "{dir}/log.csv", 65,
               {"{dir}/log.csv", "line 6", "4 cells, the header has 6"}});
  c.push_back({"canonical_binary_garbage", {{"log.csv", Garbage(2000, 3)}},
               cal + "--format canonical {dir}/log.csv", 65, {"{dir}/log.csv", "line"}});
  c.push_back({"canonical_binary_garbage_auto", {{"log.csv", Garbage(2000, 5)}}, cal + "{dir}/log.csv", 65,
               {"{dir}/log.csv", "cannot tell the log format"}});
  c.push_back({"canonical_utf16_bom", {{"log.csv", Utf16LeWithBom(CanonicalLog())}}, cal + "{dir}/log.csv",
               65, {"{dir}/log.csv", "UTF-16", "save it as UTF-8"}});
  c.push_back({"canonical_utf16_without_bom", {{"log.csv", Utf16LeWithBom(CanonicalLog()).substr(2)}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "UTF-16 little-endian (NUL after every character)"}});
  c.push_back({"canonical_latin1_in_number",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,0.010,0.8\xB5\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "idc_a", "0.8\\xb5", "not a number"}});
  c.push_back({"canonical_missing_column",
               {{"log.csv", "time_s,vdc_v,rpm,idc_a\n0,7.2,3000,0.8\n1,7.2,4000,1.4\n"}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 1", "missing required column(s) throttle"}});
  c.push_back({"canonical_extra_column",
               {{"log.csv", "time_s,vdc_v,throttle,rpm,torque_nm,idc_a,colour\n0,7.2,0.3,3000,0.01,0.8,1\n"}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 1", "unknown column(s) \"colour\"", "valid names"}});
  c.push_back({"canonical_duplicate_column",
               {{"log.csv", "time_s,vdc_v,throttle,rpm,torque_nm,idc_a,rpm\n0,7.2,0.3,3000,0.01,0.8,1\n"}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 1", "\"rpm\" given twice", "column 7"}});
  c.push_back({"canonical_text_in_number",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,fast,0.010,0.8\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "column \"rpm\"", "\"fast\"", "not a number"}});
  c.push_back({"canonical_decimal_comma",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,0.010,\"0,8\"\n"}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "idc_a", "\"0,8\"", "--decimal-comma"}});
  c.push_back({"canonical_decimal_comma_unquoted",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,0.010,0,8\n"}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "7 cells, the header has 6", "--decimal-comma"}});
  c.push_back({"canonical_empty_cell",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,,0.010,0.8\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "rpm", "empty cell"}});
  c.push_back({"canonical_nan",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,nan,0.8\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "torque_nm", "\"nan\"", "not a number"}});
  c.push_back({"canonical_inf",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,0.01,-inf\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "idc_a", "\"-inf\"", "not a number"}});
  c.push_back({"canonical_1e308",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,0.01,1e308\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "idc_a", "1e308", "out of range"}});
  c.push_back({"canonical_1e400",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,0.01,1e400\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "idc_a", "1e400", "not a number"}});
  c.push_back({"canonical_negative_vdc",
               {{"log.csv", CanonicalHeader() + "0,-7.2,0.3,3000,0.01,0.8\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "vdc_v", "-7.2", "must be > 0"}});
  c.push_back({"canonical_zero_vdc",
               {{"log.csv", CanonicalHeader() + "0,0,0.3,3000,0.01,0.8\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "vdc_v", "\"0\"", "must be > 0"}});
  c.push_back({"canonical_throttle_above_one",
               {{"log.csv", CanonicalHeader() + "0,7.2,1.5,3000,0.01,0.8\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "throttle", "1.5", "outside 0..1"}});
  c.push_back({"canonical_throttle_percent",
               {{"log.csv", CanonicalHeader() + "0,7.2,30,3000,0.01,0.8\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "throttle", "\"30\"", "outside 0..1"}});
  c.push_back({"canonical_throttle_negative",
               {{"log.csv", CanonicalHeader() + "0,7.2,-0.1,3000,0.01,0.8\n" + CanonicalRows()}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "throttle", "-0.1", "outside 0..1"}});
  c.push_back({"canonical_one_row", {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,0.01,0.8\n"}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "1 steady operating point", "at least 2"}});
  c.push_back({"canonical_identical_rows",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,0.01,0.8\n1,7.2,0.3,3000,0.01,0.8\n"
                                                "2,7.2,0.3,3000,0.01,0.8\n"}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "all 3 operating points are identical"}});
  c.push_back({"canonical_current_all_zero",
               {{"log.csv", CanonicalHeader() + "0,7.2,0.3,3000,0.01,0\n1,7.2,0.4,4000,0.02,0\n"}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "idc_a", "zero in every point"}});
  c.push_back({"canonical_line_too_long",
               {{"log.csv", CanonicalHeader() + std::string(3u << 20, '1') + "\n"}},
               cal + "{dir}/log.csv", 65, {"{dir}/log.csv", "line 2", "longer than 1048576 bytes"}});
  c.push_back({"log_missing_file", {}, cal + "{dir}/nope.csv", 66, {"{dir}/nope.csv", "no such file"}});
  c.push_back({"log_is_a_folder", {{"sub/x", ""}}, cal + "{dir}/sub", 66, {"{dir}/sub", "is a folder"}});

  // ---- RCbenchmark / Tyto exports (lenient only for empty cells and ESC arming rows)
  c.push_back({"rcbenchmark_text_in_number",
               {{"rc.csv", RcbHeader() + "0.1,1500,0.01,0.2,12.1,3.0,7000,\n0.2,1500,0.01,0.2,12.1,abc,7000,\n"}},
               cal + "{dir}/rc.csv", 65, {"{dir}/rc.csv", "line 3", "Current (A)", "\"abc\"", "not a number"}});
  c.push_back({"rcbenchmark_bad_unit",
               {{"rc.csv", "Time (s),ESC signal (\xC2\xB5s),Torque (furlong),Current (A),\n0,1500,1,2,\n"}},
               cal + "{dir}/rc.csv", 65, {"{dir}/rc.csv", "line 1", "Torque (furlong)", "\"furlong\"", "valid:"}});
  c.push_back({"rcbenchmark_utf16", {{"rc.csv", Utf16LeWithBom(RcbHeader() + "0.1,1500,0.01,0.2,12,3,7000,\n")}},
               cal + "{dir}/rc.csv", 65, {"{dir}/rc.csv", "UTF-16"}});
  c.push_back({"rcbenchmark_header_only", {{"rc.csv", RcbHeader()}}, cal + "{dir}/rc.csv", 65,
               {"{dir}/rc.csv", "0 steady operating points", "(0 data rows read)"}});
  c.push_back({"rcbenchmark_all_current_empty",
               {{"rc.csv", RcbHeader() + "0.1,1500,0.01,0.2,12.1,,7000,\n0.2,1600,0.01,0.2,12.1,,7000,\n"}},
               cal + "{dir}/rc.csv", 65, {"{dir}/rc.csv"}});
  c.push_back({"rcbenchmark_1e308_kgf",
               {{"rc.csv", RcbHeader() + "0.1,1500,0.01,1e308,12.1,3,7000,\n"}}, cal + "{dir}/rc.csv", 65,
               {"{dir}/rc.csv", "line 2", "Thrust (kgf)", "1e308", "out of range"}});

  // ---- DriveCalc MData
  c.push_back({"drivecalc_missing_column",
               {{"m.csv", "motor_id,U,n,I\n1,7,1000,1\n"}}, cal + "--format drivecalc {dir}/m.csv", 65,
               {"{dir}/m.csv", "line 1", "\"IsNoLoad\" missing"}});
  c.push_back({"drivecalc_text_in_number",
               {{"m.csv", DriveCalcHeader() + "1,7.4,x,2.0,0,25\n"}}, cal + "{dir}/m.csv", 65,
               {"{dir}/m.csv", "line 2", "column \"n\"", "\"x\"", "not a number"}});
  c.push_back({"drivecalc_motor_absent",
               {{"m.csv", DriveCalcHeader() + "1,7.4,9000,2.0,0,25\n1,7.4,8000,4.0,0,25\n"}},
               cal + "--drivecalc-motor 99 {dir}/m.csv", 65, {"{dir}/m.csv", "motor_id 99"}});
  c.push_back({"drivecalc_all_speed_zero",
               {{"m.csv", DriveCalcHeader() + "1,7.4,0,2.0,0,25\n1,7.4,0,4.0,0,25\n"}}, cal + "{dir}/m.csv", 65,
               {"{dir}/m.csv", "omega_rad_s", "absent"}});

  // ---- mapped tables
  c.push_back({"mapped_missing_source",
               {{"t.csv", "Volt,Amp\n7,1\n7,2\n"}}, cal + "--map idc_a=Current {dir}/t.csv", 65,
               {"{dir}/t.csv", "line 1", "no column \"Current\"", "\"Amp\""}});
  c.push_back({"mapped_unknown_canonical", {{"t.csv", "Volt,Amp\n7,1\n"}}, cal + "--map amps=Amp {dir}/t.csv",
               64, {"amps=Amp", "unknown canonical name", "idc_a"}});
  c.push_back({"mapped_no_equals", {{"t.csv", "Volt,Amp\n7,1\n"}}, cal + "--map Amp {dir}/t.csv", 64,
               {"\"Amp\"", "canonical_name=Source Header"}});
  c.push_back({"mapped_empty_cell",
               {{"t.csv", "Volt,Amp\n7,1\n7,\n"}}, cal + "--map idc_a=Amp --map vdc_v=Volt {dir}/t.csv", 65,
               {"{dir}/t.csv", "line 3", "Amp", "empty cell"}});
  c.push_back({"log_unknown_format_names_the_flags", {{"t.csv", "Volt,Amp\n7,1\n7,2\n"}}, cal + "{dir}/t.csv", 65,
               {"{dir}/t.csv", "line 1", "cannot tell the log format", "--format mapped --map"}});
  c.push_back({"mapped_where_no_match",
               {{"t.csv", "Motor,Volt,Amp\nA,7,1\nA,7,2\n"}},
               cal + "--map idc_a=Amp --where Motor=B {dir}/t.csv", 65,
               {"{dir}/t.csv", "no row has Motor=B", "--where", "\"A\""}});
  c.push_back({"mapped_where_no_column", {{"t.csv", "Motor,Volt,Amp\nA,7,1\nA,7,2\n"}},
               cal + "--map idc_a=Amp --where Engine=B {dir}/t.csv", 65,
               {"{dir}/t.csv", "line 1", "--where \"Engine=B\"", "no column \"Engine\""}});
  c.push_back({"diagnose_where_no_match", {{"t.csv", "Motor,Volt,Amp\nA,7,1\nA,7,2\n"}},
               "diagnose --map idc_a=Amp --where Motor=B {dir}/t.csv", 65,
               {"{dir}/t.csv", "no row has Motor=B", "--where"}});
  c.push_back({"diagnose_decimal_comma_with_point", {{"t.csv", "Volt;Amp\n7,2;1,5\n7,1;2.5\n"}},
               "diagnose --map idc_a=Amp --map vdc_v=Volt --decimal-comma {dir}/t.csv", 65,
               {"{dir}/t.csv", "line 3", "not a number with --decimal-comma"}});
  c.push_back({"mapped_where_syntax", {{"t.csv", "Motor,Volt,Amp\nA,7,1\nA,7,2\n"}},
               cal + "--map idc_a=Amp --where Motor {dir}/t.csv", 64, {"--where \"Motor\"", "Header=value"}});
  c.push_back({"mapped_decimal_comma_with_point", {{"t.csv", "Volt;Amp\n7,2;1,5\n7,1;2.5\n"}},
               cal + "--map idc_a=Amp --map vdc_v=Volt --decimal-comma {dir}/t.csv", 65,
               {"{dir}/t.csv", "line 3", "Amp", "\"2.5\"", "not a number with --decimal-comma"}});
  c.push_back({"mapped_decimal_comma_comma_separated", {{"t.csv", "Volt,Amp\n7,2,1,5\n7,1,2,5\n"}},
               cal + "--map idc_a=Amp --map vdc_v=Volt --decimal-comma {dir}/t.csv", 65,
               {"{dir}/t.csv", "line 2", "--decimal-comma, but cells are separated by ','"}});
  c.push_back({"tyto_quoted_text_in_number",
               {{"ty.csv", "\"Time (s)\",\"Throttle (\xC2\xB5s)\",\"Rotation speed (rpm)\",\"Voltage (V)\","
                           "\"Current (A)\"\n\"1\",\"1200\",\"3000\",\"24\",\"1\"\n\"5\",\"1300\",\"4000\",\"24\",\"x\"\n"}},
               cal + "{dir}/ty.csv", 65, {"{dir}/ty.csv", "line 3", "Current (A)", "\"x\"", "not a number"}});
  c.push_back({"thrustapp_format_on_a_table", {{"t.csv", "Volt,Amp\n7,1\n7,2\n"}},
               cal + "--format thrustapp {dir}/t.csv", 65, {"{dir}/t.csv", "line 1", "not a ThrustApp report"}});
  c.push_back({"thrustapp_with_map",
               {{"r.tex", "\\documentclass{article}\n\\begin{filecontents*}{table1.dat}\nout,th,tq,rpm,v,a\n"
                          "20,1,1,1000,12,1\n\\end{filecontents*}\n"}},
               cal + "--map idc_a=a {dir}/r.tex", 64, {"--map", "ThrustApp report", "drop --map"}});
  c.push_back({"thrustapp_header_without_voltage",
               {{"r.tex", "\\documentclass{article}\n\\begin{filecontents*}{table1.dat}\nout,th,tq,rpm,a\n"
                          "20,1,1,1000,1\n\\end{filecontents*}\n"}},
               cal + "{dir}/r.tex", 65, {"{dir}/r.tex", "line 3", "ThrustApp table header", "no column \"v\""}});
  c.push_back({"mapped_bad_unit", {{"t.csv", "Volt,Amp\n7,1\n"}}, cal + "--map \"idc_a=Amp [parsec]\" {dir}/t.csv",
               64, {"idc_a=Amp [parsec]", "\"parsec\"", "valid"}});

  // ---- batch point CSV (simulate --batch)
  c.push_back({"batch_empty", {{"p.csv", ""}}, batch + "{dir}/p.csv", 65, {"{dir}/p.csv", "empty file"}});
  c.push_back({"batch_header_only", {{"p.csv", "vdc_v,throttle,torque_nm\n"}}, batch + "{dir}/p.csv", 65,
               {"{dir}/p.csv", "no data rows"}});
  c.push_back({"batch_unknown_column", {{"p.csv", "vdc_v,throttle,speed\n7,0.5,100\n"}}, batch + "{dir}/p.csv",
               65, {"{dir}/p.csv:1", "unknown column \"speed\"", "allowed"}});
  c.push_back({"batch_duplicate_column", {{"p.csv", "vdc_v,throttle,throttle\n7,0.5,0.5\n"}},
               batch + "{dir}/p.csv", 65, {"{dir}/p.csv:1", "duplicate column \"throttle\""}});
  c.push_back({"batch_missing_vdc", {{"p.csv", "throttle,torque_nm\n0.5,0.01\n"}}, batch + "{dir}/p.csv", 65,
               {"{dir}/p.csv:1", "missing column \"vdc_v\""}});
  c.push_back({"batch_text_in_number", {{"p.csv", "vdc_v,throttle,torque_nm\n7.2,half,0.01\n"}},
               batch + "{dir}/p.csv", 65, {"{dir}/p.csv:2", "throttle", "\"half\"", "not a finite number"}});
  c.push_back({"batch_nan", {{"p.csv", "vdc_v,throttle,torque_nm\nnan,0.5,0.01\n"}}, batch + "{dir}/p.csv", 65,
               {"{dir}/p.csv:2", "vdc_v", "\"nan\"", "not a finite number"}});
  c.push_back({"batch_throttle_above_one", {{"p.csv", "vdc_v,throttle,torque_nm\n7.2,1.5,0.01\n"}},
               batch + "{dir}/p.csv", 65, {"{dir}/p.csv:2", "throttle", "1.5", "between 0 and 1"}});
  c.push_back({"batch_negative_vdc", {{"p.csv", "vdc_v,throttle,torque_nm\n-7.2,0.5,0.01\n"}},
               batch + "{dir}/p.csv", 65, {"{dir}/p.csv:2", "vdc_v", "-7.2", "> 0"}});
  c.push_back({"batch_1e308_vdc", {{"p.csv", "vdc_v,throttle,torque_nm\n1e308,0.5,0.01\n"}},
               batch + "{dir}/p.csv", 65, {"{dir}/p.csv:2", "vdc_v", "1e+308", "<="}});
  c.push_back({"batch_wrong_cell_count", {{"p.csv", "vdc_v,throttle,torque_nm\n7.2,0.5\n"}},
               batch + "{dir}/p.csv", 65, {"{dir}/p.csv:2", "2 cells, the header has 3"}});
  c.push_back({"batch_three_given", {{"p.csv", "vdc_v,throttle,torque_nm,rpm\n7.2,0.5,0.01,100\n"}},
               batch + "{dir}/p.csv", 65, {"{dir}/p.csv:2", "exactly two"}});
  c.push_back({"batch_utf16", {{"p.csv", Utf16LeWithBom("vdc_v,throttle,torque_nm\n7.2,0.5,0.01\n")}},
               batch + "{dir}/p.csv", 65, {"{dir}/p.csv", "UTF-16"}});
  c.push_back({"batch_binary", {{"p.csv", Garbage(500, 11)}}, batch + "{dir}/p.csv", 65, {"{dir}/p.csv"}});

  // ---- command-line values
  const std::string pair =
      "--catalog {dir}/paper simulate --motor emax_1900kv_paper --esc multistar_30a_paper ";
  c.push_back({"flag_throttle_above_one", {}, pair + "--vdc 7.2 --throttle 1.7 --torque 0.01", 64,
               {"--throttle", "1.7", "between 0 and 1"}});
  c.push_back({"flag_throttle_negative", {}, pair + "--vdc 7.2 --throttle -0.2 --torque 0.01", 64,
               {"--throttle", "-0.2"}});
  c.push_back({"flag_vdc_negative", {}, pair + "--vdc -5 --throttle 0.5 --torque 0.01", 64, {"--vdc", "-5"}});
  c.push_back({"flag_vdc_zero", {}, pair + "--vdc 0 --throttle 0.5 --torque 0.01", 64, {"--vdc", "0"}});
  c.push_back({"flag_vdc_nan", {}, pair + "--vdc nan --throttle 0.5 --torque 0.01", 64, {"--vdc"}});
  c.push_back({"flag_vdc_inf", {}, pair + "--vdc inf --throttle 0.5 --torque 0.01", 64, {"--vdc"}});
  c.push_back({"flag_vdc_1e308", {}, pair + "--vdc 1e308 --throttle 0.5 --torque 0.01", 64,
               {"--vdc", "1e+308", "<="}});
  c.push_back({"flag_vdc_text", {}, pair + "--vdc seven --throttle 0.5 --torque 0.01", 64, {"--vdc", "seven"}});
  c.push_back({"flag_torque_negative", {}, pair + "--vdc 7.2 --throttle 0.5 --torque -1", 64, {"--torque", "-1"}});
  c.push_back({"flag_torque_1e308", {}, pair + "--vdc 7.2 --throttle 0.5 --torque 1e308", 64,
               {"--torque", "1e+308", "<="}});
  c.push_back({"flag_rpm_negative", {}, pair + "--vdc 7.2 --throttle 0.5 --rpm -100", 64, {"--rpm", "-100"}});
  c.push_back({"flag_rpm_1e308", {}, pair + "--vdc 7.2 --throttle 0.5 --rpm 1e308", 64,
               {"--rpm", "1e+308", "<="}});
  c.push_back({"flag_torque_law_nan", {}, pair + "--vdc 7.2 --throttle 0.5 --torque-law 0,nan,1e-7", 64,
               {"--torque-law"}});
  c.push_back({"flag_torque_law_two_values", {}, pair + "--vdc 7.2 --throttle 0.5 --torque-law 0,1", 64,
               {"--torque-law"}});
  c.push_back({"flag_unknown", {}, pair + "--vdc 7.2 --colour red", 64, {"--colour"}});
  c.push_back({"flag_unknown_subcommand", {}, "fly --now", 64, {"unknown subcommand 'fly'"}});
  c.push_back({"flag_unknown_motor", {}, "--catalog {dir}/paper simulate --motor emax_1900kv_papr --esc multistar_30a_paper --vdc 7",
               64, {"emax_1900kv_papr", "emax_1900kv_paper"}});
  c.push_back({"flag_batch_missing", {}, batch + "{dir}/none.csv", 66, {"{dir}/none.csv", "no such file"}});
  c.push_back({"flag_calibrate_esc_endpoints", {{"log.csv", CanonicalLog()}},
               cal + "--esc-min-us 2000 --esc-max-us 1000 {dir}/log.csv", 64,
               {"--esc-min-us 2000", "--esc-max-us 1000", "need finite values with --esc-max-us > --esc-min-us"}});
  c.push_back({"flag_calibrate_format", {{"log.csv", CanonicalLog()}}, cal + "--format excel {dir}/log.csv", 64,
               {"--format", "excel"}});
  c.push_back({"flag_calibrate_no_ids", {{"log.csv", CanonicalLog()}}, "calibrate {dir}/log.csv", 64,
               {"--motor-id"}});
  c.push_back({"flag_catalog_show_unknown", {}, "catalog show no_such_motor", 64, {"no_such_motor"}});
  c.push_back({"flag_catalog_kind", {}, "catalog list --kind rockets", 64, {"--kind", "rockets"}});
  c.push_back({"flag_catalog_kv_nan", {}, "catalog list --kv-min nan", 64, {"--kv-min"}});
  c.push_back({"flag_catalog_kv_negative", {}, "catalog list --kv-min -5", 64, {"--kv-min", "-5"}});
  c.push_back({"flag_catalog_validate_missing", {}, "catalog validate {dir}/nope", 66, {"{dir}/nope"}});
  c.push_back({"flag_plot_into_a_file", {{"afile", "x"}}, pair + "--vdc 7.2 --plot {dir}/afile", 73,
               {"{dir}/afile"}});
  c.push_back({"flag_out_unwritable", {{"log.csv", CanonicalLog()}},
               batch + "{src}/examples/points.csv --out /proc/nope/r.csv", 73, {"/proc/nope/r.csv"}});

  // ---- mission JSON (strict; evaluate and optimize read it before the catalog)
  const std::string eval = "--catalog {dir}/paper evaluate {dir}/m.json --motor m --esc e --prop p --battery b";
  c.push_back({"mission_empty_file", {{"m.json", ""}}, eval, 65, {"{dir}/m.json", "empty file"}});
  c.push_back({"mission_truncated", {{"m.json", Mission().substr(0, 80)}}, eval, 65,
               {"{dir}/m.json:", "invalid JSON", "unexpected end of input"}});
  c.push_back({"mission_binary_garbage", {{"m.json", Garbage(200, 11)}}, eval, 65, {"{dir}/m.json", "invalid JSON"}});
  c.push_back({"mission_utf16", {{"m.json", Utf16LeWithBom(Mission())}}, eval, 65, {"{dir}/m.json", "UTF-16"}});
  c.push_back({"mission_nan_literal", {{"m.json", Replace(Mission(), "\"mass_kg\": 0.75", "\"mass_kg\": NaN")}},
               eval, 65, {"{dir}/m.json", "mass_kg", "invalid JSON"}});
  c.push_back({"mission_negative_mass", {{"m.json", Replace(Mission(), "\"mass_kg\": 0.75", "\"mass_kg\": -1")}},
               eval, 65, {"{dir}/m.json", "vehicle.mass_kg = -1", "> 0"}});
  c.push_back({"mission_mass_1e308", {{"m.json", Replace(Mission(), "\"mass_kg\": 0.75", "\"mass_kg\": 1e308")}},
               eval, 65, {"{dir}/m.json", "vehicle.mass_kg", "<= 10000"}});
  c.push_back({"mission_zero_rotors", {{"m.json", Replace(Mission(), "\"rotors\": 4", "\"rotors\": 0")}},
               eval, 65, {"{dir}/m.json", "vehicle.rotors = 0", "[1, 64]"}});
  c.push_back({"mission_throttle_above_one",
               {{"m.json", Replace(Mission(), "\"max_throttle\": 0.8", "\"max_throttle\": 1.5")}}, eval, 65,
               {"{dir}/m.json", "constraints.max_throttle = 1.5", "<= 1"}});
  c.push_back({"mission_min_hover_throttle_above_max",
               {{"m.json", Replace(Mission(), "\"max_throttle\": 0.8", "\"max_throttle\": 0.8, \"min_hover_throttle\": 0.85")}},
               eval, 65, {"{dir}/m.json", "constraints.min_hover_throttle = 0.85", "below max_throttle"}});
  c.push_back({"mission_duplicate_key", {{"m.json", Replace(Mission(), "\"rotors\": 4", "\"rotors\": 4, \"rotors\": 6")}},
               eval, 65, {"{dir}/m.json", "rotors", "duplicate key"}});
  c.push_back({"mission_unknown_key", {{"m.json", Replace(Mission(), "\"rotors\": 4", "\"rotors\": 4, \"rotorz\": 6")}},
               eval, 65, {"{dir}/m.json", "vehicle", "unknown key", "rotorz"}});
  c.push_back({"mission_text_in_number",
               {{"m.json", Replace(Mission(), "\"duration_s\": 300", "\"duration_s\": \"300\"")}}, eval, 65,
               {"{dir}/m.json", "segments[1].duration_s"}});
  c.push_back({"mission_unknown_segment_type", {{"m.json", Replace(Mission(), "\"type\": \"hover\"", "\"type\": \"hovver\"")}},
               eval, 65, {"{dir}/m.json", "segments[1].type = \"hovver\"", "climb, cruise, hover, shaft"}});
  c.push_back({"mission_zero_duration", {{"m.json", Replace(Mission(), "\"duration_s\": 300", "\"duration_s\": 0")}},
               eval, 65, {"{dir}/m.json", "segments[1].duration_s = 0", "> 0"}});
  c.push_back({"mission_objective_names_no_segment",
               {{"m.json", Replace(Mission(), "\"segment\": \"loiter\"", "\"segment\": \"loitr\"")}}, eval, 65,
               {"{dir}/m.json", "objective.segment = \"loitr\"", "names no segment"}});
  c.push_back({"mission_unknown_ranking",
               {{"m.json", Replace(Mission(), "\"segment\": \"loiter\"", "\"segment\": \"loiter\", \"ranking\": \"optimistic\"")}},
               eval, 65, {"{dir}/m.json", "objective.ranking = \"optimistic\"", "as_given, credible"}});
  c.push_back({"mission_unknown_unrated_motors",
               {{"m.json", Replace(Mission(), "\"max_throttle\": 0.8", "\"max_throttle\": 0.8, \"unrated_motors\": \"keep\"")}},
               eval, 65, {"{dir}/m.json", "constraints.unrated_motors = \"keep\"", "estimate, exclude"}});
  c.push_back({"mission_missing", {}, eval, 66, {"{dir}/m.json"}});
  return c;
}

}  // namespace dynosize::reliability
