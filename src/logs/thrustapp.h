// jmajew's ThrustApp reports (github.com/jmajew/thrust_tool; shared/data/jmajew_thrusttool_6motors):
// a DIY thrust + torque stand whose application writes, per motor and propeller, either a LaTeX
// report (*.tex) embedding every run's step table as a `filecontents` CSV block
//
//   \begin{filecontents*}{table1.dat}
//   out,      th,    th_err, tq,     tq_err,  rpm,   rpm_err,  v,    v_err,   a,     a_err,   pin,  theff
//       2e+01,       39.19,       2.429,       77.87,  ...
//   \end{filecontents*}
//
// or a text export (*.txt) with the same tables ("level [%]  thrust [G] ... Pin [W] Eff [G/W]",
// each mean followed by its standard deviation in brackets) and then the raw 10 Hz samples.
// Units (README of the data set): out/level % of motor output, thrust gram-force, torque
// gram-force centimetre, rpm from ESC telemetry, battery volts and amperes.
//
// ThrustAppLines turns such a file into the rows of one plain table, header kHeader, one row per
// step of every run (the raw samples of a .txt are skipped: the step means are the steady
// points), so that the ordinary mapped reader reads them. Lines commented out with '%' in a
// report are skipped; a telemetry dropout written "nan" becomes an empty cell.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "logs/csv_scan.h"

namespace dynosize::logs {

// True when `first_line` (the first non-blank line of a file) opens a ThrustApp report or text
// export ("\documentclass" or "## Tool info").
bool IsThrustAppStart(std::string_view first_line);

class ThrustAppLines {
 public:
  // The header of the rows returned by Next (the map the reader applies to it).
  static constexpr const char* kHeader = "out,th,tq,rpm,v,a";

  // `reader` is positioned after the first line (IsThrustAppStart); it must outlive this.
  explicit ThrustAppLines(LineReader* reader) : reader_(reader) {}

  // The next step row as "out,th,tq,rpm,v,a"; false at the end. Line numbers are the file's.
  bool Next(std::string_view* line);
  std::size_t line_number() const { return reader_->line_number(); }

  // What the report says about itself, for the table's notes: "motor T-Motor MN2206-13, KV 200,
  // propeller HQProp 6x4x3; 5 runs (tables)".
  std::string Summary() const;
  std::size_t tables() const { return tables_; }

 private:
  bool TakeRow(std::string_view line, bool bracketed_std);
  void TakeMetadata(std::string_view line);

  LineReader* reader_;
  std::string row_;  // the rewritten row, valid until the next call
  bool in_tex_table_ = false;   // between \begin{filecontents*} and \end{filecontents*}
  bool expect_tex_header_ = false;
  bool in_txt_table_ = false;   // after a summary header "level [%] ... Pin [W]" until a blank line
  static constexpr std::size_t kNoColumn = static_cast<std::size_t>(-1);  // th or tq not written
  std::size_t col_[6] = {0, 1, 3, 5, 7, 9};  // out, th, tq, rpm, v, a in a .tex table
  std::size_t tables_ = 0;
  std::string motor_, kv_, prop_;
};

}  // namespace dynosize::logs
