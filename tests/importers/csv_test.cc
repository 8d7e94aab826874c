#include "importers/csv.h"

#include <gtest/gtest.h>

#include "common/error.h"

namespace dynosize {
namespace {

TEST(CsvTest, QuotesBomAndCommaInsideFields) {
  const CsvTable t = ParseCsv("\xEF\xBB\xBFmyid,Name,Rem\n1,\"137x50 11Y450\",\"6pol 5x1,5x1 \"\"N45\"\"\"\n",
                              "x.csv");
  EXPECT_TRUE(t.had_bom);
  ASSERT_EQ(t.header.size(), 3u);
  EXPECT_EQ(t.header[0], "myid");
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.Field(t.rows[0], 2), "6pol 5x1,5x1 \"N45\"");
  EXPECT_EQ(t.rows[0].line, 2u);
}

TEST(CsvTest, DetectsSemicolonsAndCrOnlyLineEnds) {
  const CsvTable t = ParseCsv("TYPE;Model;Kv\rAXI;AXI 2203;2300\r\rJIVE;Jive 80+ LV ;80\r", "y.csv");
  EXPECT_EQ(t.separator, ';');
  ASSERT_EQ(t.rows.size(), 2u);  // the blank line is skipped
  EXPECT_EQ(t.Field(t.rows[1], 1), "Jive 80+ LV");
  EXPECT_EQ(t.rows[1].line, 4u);
}

TEST(CsvTest, DecodesLatin1) {
  const CsvTable t = ParseCsv("Name\nGWS B\xFCrsti\n", "z.csv");
  EXPECT_TRUE(t.was_latin1);
  EXPECT_EQ(t.Field(t.rows[0], 0), "GWS B\xC3\xBCrsti");
  // Valid UTF-8 stays as it is.
  const CsvTable u = ParseCsv("Name\nG\xC3\xBCnther\n", "u.csv");
  EXPECT_FALSE(u.was_latin1);
  EXPECT_EQ(u.Field(u.rows[0], 0), "G\xC3\xBCnther");
}

TEST(CsvTest, NumbersPercentDecimalCommaAndErrors) {
  EXPECT_EQ(*ParseNumber(" 1236 "), 1236.0);
  EXPECT_EQ(*ParseNumber("40.00%"), 40.0);
  EXPECT_EQ(*ParseNumber("0,45"), 0.45);
  EXPECT_FALSE(ParseNumber(""));
  EXPECT_FALSE(ParseNumber("12 A"));
  EXPECT_FALSE(ParseNumber("1e999"));
  try {
    ParseCsv("a,b\n1,\"open\n", "bad.csv");
    FAIL() << "unterminated quote accepted";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2: unterminated quoted field"), std::string::npos)
        << e.what();
  }
  const CsvTable t = ParseCsv("a,b\n1,2\n", "c.csv");
  try {
    t.Column("c");
    FAIL();
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("no column 'c' (columns: a, b)"), std::string::npos);
  }
}

}  // namespace
}  // namespace dynosize
