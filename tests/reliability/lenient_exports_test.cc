// Thrust-stand exports are lenient only where their real quirks demand it: empty
// cells of asynchronous sensors and ESC arming rows are dropped, and every dropped row is
// counted per reason and reported; text in a number stays an error. The canonical format
// refuses the same empty cell.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/error.h"
#include "io/points_csv.h"
#include "logs/log_reader.h"
#include "reliability/bad_input_table.h"

namespace dynosize::reliability {
namespace {

namespace fs = std::filesystem;

std::string Write(const std::string& name, const std::string& bytes) {
  const fs::path d = fs::path(::testing::TempDir()) / ("dynosize_lenient_" + std::to_string(getpid()));
  fs::create_directories(d);
  std::ofstream(d / name, std::ios::binary) << bytes;
  return (d / name).string();
}

std::size_t Dropped(const logs::SteadyTable& t, const std::string& reason_part) {
  std::size_t n = 0;
  for (const auto& d : t.dropped) {
    if (d.reason.find(reason_part) != std::string::npos) n += d.count;
  }
  return n;
}

// One averaged row every 10 s (a summary export: read row by row). Rows 3 and 5 miss the
// asynchronous torque and current readings, row 6 is an arming row (900 us), row 7 has no
// optical speed reading (0 = dropout).
const char* const kRows =
    "0,1300,0.010,0.20,12.1,3.0,7000,\n"
    "10,1400,0.015,0.30,12.0,4.0,8000,\n"
    ",1450,,0.31,12.0,4.1,8200,\n"
    "30,1500,0.020,0.40,11.9,5.0,9000,\n"
    "40,1600,0.025,0.50,11.8,,10000,\n"
    "50,900,0.000,0.00,12.2,0.1,0,\n"
    "60,1700,0.030,0.60,11.7,7.0,0,\n"
    "70,1800,0.035,0.70,11.6,8.0,12000,\n";

TEST(LenientExports, EmptyAsynchronousCellsAreDroppedAndCounted) {
  const std::string p = Write("rc.csv", RcbHeader() + kRows);
  const logs::SteadyTable t = logs::ReadLog(p);
  EXPECT_EQ(t.format, logs::LogFormat::kRcbenchmark);
  EXPECT_FALSE(t.time_series);
  EXPECT_EQ(t.data_rows_read, 8u);
  EXPECT_EQ(t.rows(), 4u);  // lines 2, 3, 5 and 9
  EXPECT_EQ(t.DroppedTotal(), 4u);
  EXPECT_EQ(Dropped(t, "ESC signal outside the end points"), 1u);
  EXPECT_EQ(Dropped(t, "empty"), 3u);  // time/torque, current, speed dropout
  // Every row is accounted for: kept + dropped = read.
  EXPECT_EQ(t.rows() + t.DroppedTotal(), t.data_rows_read);
  // The report printed by `dynosize calibrate` names the counts and reasons.
  const std::string brief = t.BriefReport();
  EXPECT_NE(brief.find("dropped 4"), std::string::npos) << brief;
  EXPECT_NE(brief.find("ESC signal outside"), std::string::npos) << brief;
}

TEST(LenientExports, TextInANumberIsStillAnError) {
  const std::string p = Write("rc_text.csv", RcbHeader() + kRows + "80,1900,0.04,0.8,11.5,n/a,13000,\n");
  try {
    (void)logs::ReadLog(p);
    FAIL() << "text in a number was accepted";
  } catch (const DataError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(p + ": line 10, column \"Current (A)\": \"n/a\": not a number"), std::string::npos) << m;
  }
}

TEST(LenientExports, TheCanonicalFormatRefusesTheSameEmptyCell) {
  const std::string p = Write("canonical.csv", CanonicalHeader() + "0,7.2,0.3,3000,,0.8\n" + CanonicalRows());
  try {
    (void)logs::ReadLog(p);
    FAIL() << "an empty canonical cell was accepted";
  } catch (const DataError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(p + ": line 2, column \"torque_nm\": \"\": empty cell"), std::string::npos) << m;
  }
}

TEST(LenientExports, BatchFileWithCarriageReturnLineEndsReads) {
  const std::string p = Write("points_cr.csv", "vdc_v,throttle,torque_nm\r7.2,0.5,0.01\r7.2,0.6,0.02\r");
  const auto points = ReadPointsCsv(p);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1].row, 3u);
  EXPECT_EQ(*points[1].throttle, 0.6);
}

}  // namespace
}  // namespace dynosize::reliability
