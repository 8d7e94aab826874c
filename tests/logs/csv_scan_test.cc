#include "logs/csv_scan.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/error.h"
#include "logs/log_test_util.h"
#include "logs/log_units.h"

namespace dynosize::logs {
namespace {

using testing_util::WriteTemp;

std::vector<std::string> AllLines(const std::string& path, std::size_t max_line = 1 << 20) {
  LineReader lr(path, max_line);
  std::vector<std::string> out;
  std::string_view v;
  while (lr.Next(&v)) out.emplace_back(v);
  return out;
}

TEST(LineReader, LfCrlfCrAndBom) {
  const std::vector<std::string> want = {"a,b", "1,2", "3,4"};
  EXPECT_EQ(AllLines(WriteTemp("lf.csv", "\xEF\xBB\xBF" "a,b\n1,2\n3,4\n")), want);
  EXPECT_EQ(AllLines(WriteTemp("crlf.csv", "a,b\r\n1,2\r\n3,4\r\n")), want);
  EXPECT_EQ(AllLines(WriteTemp("cr.csv", "a,b\r1,2\r3,4")), want);
  EXPECT_EQ(AllLines(WriteTemp("mixed.csv", "a,b\r\n1,2\r3,4\n")), want);
  LineReader lr(WriteTemp("bom.csv", "\xEF\xBB\xBF" "x\n"));
  std::string_view v;
  ASSERT_TRUE(lr.Next(&v));
  EXPECT_EQ(v, "x");
  EXPECT_TRUE(lr.had_bom());
}

TEST(LineReader, CrLfSplitAcrossBufferEdge) {
  // A line end CR LF that straddles the 1 MiB read chunk must count as one line end.
  std::string big(1 << 20, 'x');
  big[(1 << 20) - 1] = '\r';
  const std::string text = big + "\nnext\n";
  const auto lines = AllLines(WriteTemp("edge.csv", text), 2 << 20);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1], "next");
}

TEST(LineReader, TooLongLineIsDataError) {
  const std::string text(5000, 'y');
  try {
    AllLines(WriteTemp("long.csv", text), 1000);
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("longer than 1000 bytes"), std::string::npos) << e.what();
  }
  EXPECT_THROW(LineReader("/nonexistent/x.csv"), NoInputError);
}

TEST(ParseDouble, AcceptsDecimalsRejectsText) {
  double v = 0;
  EXPECT_TRUE(ParseDouble(" 1236 ", &v));
  EXPECT_EQ(v, 1236.0);
  EXPECT_TRUE(ParseDouble("-1.5e-3", &v));
  EXPECT_EQ(v, -1.5e-3);
  EXPECT_TRUE(ParseDouble("+2", &v));
  EXPECT_EQ(v, 2.0);
  for (const char* bad : {"", "abc", "1,5", "nan", "inf", "-inf", "1.0x", "0x10", "1 2"}) {
    EXPECT_FALSE(ParseDouble(bad, &v)) << bad;
  }
}

TEST(ParseDouble, DecimalComma) {
  double v = 0;
  EXPECT_TRUE(ParseDoubleDecimalComma(" 1,5 ", &v));
  EXPECT_EQ(v, 1.5);
  EXPECT_TRUE(ParseDoubleDecimalComma("-2,5E-3", &v));
  EXPECT_EQ(v, -2.5e-3);
  EXPECT_TRUE(ParseDoubleDecimalComma("1236", &v));
  EXPECT_EQ(v, 1236.0);
  // '.' is a thousands separator with decimal commas: refused, never misread.
  for (const char* bad : {"1.5", "1.234,5", "1,2,3", "", "nan", "1,5x", ","}) {
    EXPECT_FALSE(ParseDoubleDecimalComma(bad, &v)) << bad;
  }
  EXPECT_FALSE(ParseDoubleDecimalComma(std::string(70, '1'), &v));  // longer than any number
}

std::vector<std::string> Split(std::string_view line, char delim) {
  std::vector<std::string_view> f;
  SplitFields(line, delim, &f);
  return std::vector<std::string>(f.begin(), f.end());
}

TEST(SplitFields, QuotedFields) {
  using V = std::vector<std::string>;
  EXPECT_EQ(Split("a,b,,c", ','), (V{"a", "b", "", "c"}));
  EXPECT_EQ(Split("\"Time (s)\",\"Thrust (kgf)\"", ','), (V{"Time (s)", "Thrust (kgf)"}));
  EXPECT_EQ(Split("\"1,5\";\"2\";3", ';'), (V{"1,5", "2", "3"}));
  EXPECT_EQ(Split("\"a,b\",c", ','), (V{"a,b", "c"}));                 // delimiter inside quotes
  EXPECT_EQ(Split(" \"x\" ,\"\"", ','), (V{"x", ""}));               // blanks around, empty quoted
  EXPECT_EQ(Split("\"say \"\"hi\"\"\",1", ','), (V{"say \"\"hi\"\"", "1"}));  // escaped quote kept
  // A quote that does not close a field is text: the row splits as it would without quotes.
  EXPECT_EQ(Split("msg \"a,b", ','), (V{"msg \"a", "b"}));
  EXPECT_EQ(Split("\"open,1,2", ','), (V{"\"open", "1", "2"}));
  EXPECT_EQ(Split("\"ab\"c,1", ','), (V{"\"ab\"c", "1"}));
  EXPECT_EQ(DetectDelimiter("\"a,b\";\"c\";\"d\""), ';');  // commas inside quotes do not count
}

TEST(HeaderText, Latin1IsConvertedAndUnitsSplit) {
  bool latin1 = false;
  EXPECT_EQ(ToUtf8("ESC signal (\xB5s)", &latin1), "ESC signal (\xC2\xB5s)");
  EXPECT_TRUE(latin1);
  EXPECT_EQ(ToUtf8("Torque (N\xC2\xB7m)", &latin1), "Torque (N\xC2\xB7m)");
  EXPECT_FALSE(latin1);
  HeaderCell h = SplitHeaderCell(" Thrust (gf) ");
  EXPECT_EQ(h.name, "Thrust");
  EXPECT_EQ(h.unit, "gf");
  h = SplitHeaderCell("Torque [N*m]");
  EXPECT_EQ(h.name, "Torque");
  EXPECT_EQ(h.unit, "N*m");
  h = SplitHeaderCell("Thrust - kgf");
  EXPECT_EQ(h.name, "Thrust");
  EXPECT_EQ(h.unit, "kgf");
  h = SplitHeaderCell("Voltage");
  EXPECT_EQ(h.unit, "");
  EXPECT_EQ(DetectDelimiter("a;b;c"), ';');
  EXPECT_EQ(DetectDelimiter("a,b"), ',');
  EXPECT_EQ(DetectDelimiter("1100 5.9e-05 0.005"), ' ');
}

TEST(LogUnits, SpellingsAndFactors) {
  // gf -> N uses standard gravity 9.80665 m/s^2 (exact by definition).
  EXPECT_DOUBLE_EQ(ParseUnit(Quantity::kForce, "gf")->scale, 9.80665e-3);
  EXPECT_DOUBLE_EQ(ParseUnit(Quantity::kForce, "kgf")->scale, 9.80665);
  EXPECT_DOUBLE_EQ(ParseUnit(Quantity::kForce, "N")->scale, 1.0);
  EXPECT_DOUBLE_EQ(ParseUnit(Quantity::kForce, "lbf")->scale, 4.4482216152605);
  for (const char* nm : {"N\xC2\xB7m", "N*m", "Nm", "N.m", "N-m", "n m"}) {
    ASSERT_TRUE(ParseUnit(Quantity::kTorque, nm)) << nm;
    EXPECT_EQ(ParseUnit(Quantity::kTorque, nm)->scale, 1.0) << nm;
  }
  EXPECT_TRUE(ParseUnit(Quantity::kThrottle, "\xC2\xB5s")->pulse_width_us);  // U+00B5
  EXPECT_TRUE(ParseUnit(Quantity::kThrottle, "\xCE\xBCs")->pulse_width_us);  // U+03BC
  EXPECT_TRUE(ParseUnit(Quantity::kThrottle, "us")->pulse_width_us);
  EXPECT_DOUBLE_EQ(ParseUnit(Quantity::kSpeed, "RPM")->scale, 3.14159265358979323846 / 30.0);
  EXPECT_DOUBLE_EQ(ParseUnit(Quantity::kSpeed, "rad/s")->scale, 1.0);
  EXPECT_DOUBLE_EQ(ParseUnit(Quantity::kTemperature, "\xC2\xBA" "C")->scale, 1.0);  // ºC
  EXPECT_DOUBLE_EQ(ParseUnit(Quantity::kTemperature, "K")->offset, -273.15);
  EXPECT_FALSE(ParseUnit(Quantity::kForce, "N\xC2\xB7m"));
  EXPECT_DOUBLE_EQ(ParseUnit(Quantity::kTorque, "G cm")->scale, 9.80665e-5);  // jmajew's torque
  EXPECT_EQ(ParseUnit(Quantity::kTorque, "N\xE2\x8B\x85m")->scale, 1.0);       // Tyto's U+22C5
  EXPECT_FALSE(ParseUnit(Quantity::kVoltage, ""));
  EXPECT_NE(ValidUnits(Quantity::kForce).find("kgf"), std::string::npos);
}

}  // namespace
}  // namespace dynosize::logs
