#include "common/json_pretty.h"

#include <gtest/gtest.h>

#include <limits>

#include "common/error.h"

namespace dynosize {
namespace {

TEST(JsonReadable, ScalarArraysOnOneLineAndSameValue) {
  const Json j = ParseJsonText(
      R"({"id": "p", "static_table": {"rpm": [3000.0, 4000.0], "ct": [0.1, 0.11]},
          "empty": [], "obj": {}, "nested": [[1, 2], {"a": "x"}], "s": "a\"b"})",
      "test");
  const std::string s = DumpJsonReadable(j);
  EXPECT_NE(s.find("\"rpm\": [3000.0, 4000.0]"), std::string::npos) << s;
  EXPECT_NE(s.find("\"empty\": []"), std::string::npos) << s;
  EXPECT_NE(s.find("\"obj\": {}"), std::string::npos) << s;
  // A nested array is not a scalar array: one element per line.
  EXPECT_NE(s.find("\"nested\": [\n    [1, 2],\n    {\n"), std::string::npos) << s;
  // Round trip: the same document, key order included.
  EXPECT_EQ(ParseJsonText(s, "round trip"), j);
  EXPECT_EQ(s.back(), '\n');
}

TEST(JsonReadable, RefusesNonFinite) {
  Json j;
  j["x"] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(DumpJsonReadable(j), Error);
}

}  // namespace
}  // namespace dynosize
