#include "catalog/catalog.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "catalog/schema.h"
#include "common/error.h"
#include "common/units.h"

namespace dynosize {
namespace {

const char* kGoodMotor = R"({"id": "m1", "name": "Test motor", "type": "bldc",
  "kv_rpm_per_v": 1000, "rm_ohm": 0.1, "io_a": 0.4,
  "source": {"dataset": "unit test", "values": {"rm_ohm": "assumed"}}})";
const char* kGoodEsc = R"({"id": "e1", "name": "Test ESC", "resc_ohm": 0.01, "c1": 1.15,
  "c0": 0.02, "tr_sat": 0.9, "sat_slope": 0.6, "max_current_a": 30,
  "source": {"dataset": "unit test"}})";

std::vector<std::string> Problems(const std::string& doc_text) {
  Catalog c;
  std::vector<std::string> problems;
  c.AddDocument(ParseJsonText(doc_text, "t.json"), "t.json", &problems);
  return problems;
}

// Replaces the first occurrence of `from` in `s` by `to`.
std::string Edit(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

std::string Doc(const std::string& motor, const std::string& esc = kGoodEsc) {
  return R"({"motors": [)" + motor + R"(], "escs": [)" + esc + "]}";
}

TEST(Catalog, ValidEntriesConvertToSi) {
  Catalog c;
  std::vector<std::string> problems;
  c.AddDocument(ParseJsonText(Doc(kGoodMotor), "t.json"), "t.json", &problems);
  ASSERT_TRUE(problems.empty()) << problems[0];
  const MotorEntry& m = c.motor("m1");
  // ke from Kv by docs/model.md section 8; kt = sqrt(27/10)*ke by section 5.
  EXPECT_NEAR(m.params.ke_v_s_per_rad, KeFromKvBldc(1000.0), 1e-15);
  EXPECT_NEAR(m.params.kt_nm_per_a, kPacPerVllIrms * KeFromKvBldc(1000.0), 1e-15);
  EXPECT_EQ(m.assumed_keys, std::vector<std::string>{"rm_ohm"});
  EXPECT_TRUE(std::isinf(m.params.max_current_a));
  EXPECT_EQ(c.esc("e1").params.max_current_a, 30.0);
  EXPECT_EQ(m.json["kv_rpm_per_v"].get<double>(), 1000.0);  // kept exactly as written
}

struct BadCase {
  const char* what;
  std::string doc;
  std::string expected;  // a substring of the one problem reported
};

TEST(Catalog, EveryRuleNamesEntryKeyValueAndRule) {
  const std::vector<BadCase> cases = {
      {"negative resistance", Doc(Edit(kGoodMotor, "\"rm_ohm\": 0.1", "\"rm_ohm\": -0.1")),
       "t.json: motors[0] id=m1: key 'rm_ohm' = -0.1: must be a finite number > 0 and <= 100"},
      {"unknown key", Doc(Edit(kGoodMotor, "\"io_a\": 0.4", "\"io_a\": 0.4, \"rm_mohm\": 100")),
       "key 'rm_mohm' = 100: unknown key for a motor"},
      {"missing key", Doc(Edit(kGoodMotor, "\"io_a\": 0.4,", "")),
       "key 'io_a': missing (required"},
      {"wrong type", Doc(Edit(kGoodMotor, "\"rm_ohm\": 0.1", "\"rm_ohm\": \"0.1\"")),
       "key 'rm_ohm' = \"0.1\": must be a finite number"},
      {"bad enum", Doc(Edit(kGoodMotor, "\"bldc\"", "\"ac\"")),
       "key 'type' = \"ac\": must be a string, one of bldc, brushed"},
      {"no ke nor kv", Doc(Edit(kGoodMotor, "\"kv_rpm_per_v\": 1000,", "")),
       "a motor needs ke_v_s_per_rad or kv_rpm_per_v"},
      {"throttle knee above 1", Doc(kGoodMotor, Edit(kGoodEsc, "\"tr_sat\": 0.9", "\"tr_sat\": 1.5")),
       "escs[0] id=e1: key 'tr_sat' = 1.5: must be a finite number > 0 and <= 1"},
      {"bad provenance", Doc(Edit(kGoodMotor, "\"assumed\"", "\"guessed\"")),
       "source.values.rm_ohm' = \"guessed\": must be one of datasheet"},
      {"provenance of absent key", Doc(Edit(kGoodMotor, "{\"rm_ohm\"", "{\"mass_kg\"")),
       "source.values.mass_kg': names a key the entry does not have"},
      {"missing dataset", Doc(Edit(kGoodMotor, "\"dataset\": \"unit test\", ", "")),
       "source.dataset': missing"},
      {"bad id", Doc(Edit(kGoodMotor, "\"m1\"", "\"m 1\"")), "must be 1-120 characters"},
      {"duplicate id", Doc(kGoodMotor, Edit(kGoodEsc, "\"e1\"", "\"m1\"")),
       "escs[0] id=m1: key 'id' = \"m1\": duplicate id: already used in t.json: motors[0] id=m1"},
      {"entry not an object", R"({"motors": [42]})", "motors[0]: must be an object, found 42"},
      {"array not an array", R"({"escs": {}})", "\"escs\" must be an array"},
      {"unknown top-level key", R"({"motor": []})", "unknown top-level key \"motor\""},
  };
  for (const auto& c : cases) {
    const auto problems = Problems(c.doc);
    ASSERT_EQ(problems.size(), 1u) << c.what << ": " << (problems.empty() ? "none" : problems[0]);
    EXPECT_NE(problems[0].find(c.expected), std::string::npos)
        << c.what << "\n got: " << problems[0] << "\n want: " << c.expected;
  }
}

TEST(Catalog, JsonSyntaxProblemsNamePosition) {
  try {
    ParseJsonText("{\n  \"motors\": [\n    {\"id\": 1,}\n  ]\n}", "x.json");
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("x.json:3:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParseJsonText(R"({"a": 1, "a": 2})", "d.json"), DataError);
  EXPECT_THROW(ParseJsonText(R"({"a": 1e999})", "d.json"), DataError);
  EXPECT_THROW(ParseJsonText(std::string(100, '[') + std::string(100, ']'), "deep.json"), DataError);
  EXPECT_THROW(ParseJsonText("", "empty.json"), DataError);
  EXPECT_THROW(ParseJsonText("\x89PNG\r\n\x1a\n\x00\x01", "bin.json"), DataError);
}

TEST(Catalog, UnknownIdSuggestsClosest) {
  Catalog c;
  std::vector<std::string> problems;
  c.AddDocument(ParseJsonText(Doc(kGoodMotor), "t.json"), "t.json", &problems);
  try {
    c.motor("m2");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown motor id 'm2'; closest: m1"), std::string::npos)
        << e.what();
  }
  try {
    c.motor("e1");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("that id is a ESC"), std::string::npos) << e.what();
  }
}

TEST(Catalog, LoadReportsAllProblemsAndMissingFolder) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("dynosize_catalog_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "a.json") << Doc(Edit(kGoodMotor, "\"rm_ohm\": 0.1", "\"rm_ohm\": -1"));
  std::ofstream(dir / "b.json") << "{ not json";
  const auto problems = Catalog::Validate(dir.string());
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_NE(problems[0].find("a.json"), std::string::npos);
  EXPECT_NE(problems[1].find("b.json:1:"), std::string::npos);
  EXPECT_THROW(Catalog::Load(dir.string()), DataError);
  EXPECT_THROW(Catalog::Load((dir / "missing").string()), NoInputError);
  fs::remove_all(dir);
}

TEST(Catalog, BundledCatalogIsValid) {
  const std::string dir = std::string(DYNOSIZE_SOURCE_DIR) + "/catalog";
  const auto problems = Catalog::Validate(dir);
  EXPECT_TRUE(problems.empty()) << problems.size() << " problems, first: " << problems[0];
  const Catalog c = Catalog::Load(dir);
  EXPECT_GE(c.motors().size(), 2u);
  EXPECT_GE(c.escs().size(), 1u);
  for (const auto& m : c.motors()) EXPECT_TRUE(m.json.contains("source")) << m.id;
}

TEST(Schema, DescribesRules) {
  for (const auto& spec : SchemaFor(ComponentKind::kEsc)) {
    if (spec.key == "tr_sat") {
      EXPECT_EQ(DescribeRule(spec), "a finite number > 0 and <= 1");
    }
  }
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// gear_ratio / gear_efficiency (model/gear.h) and the check that a geared entry's Kv is the
// motor's (motor_credibility.h, kGearedKmRatioMax). The KIRA 650-13/6.7:1 of DriveCalc (378 g,
// R_dc 36.3 mOhm): with the motor's Kv (1323 rpm/V = 6.7 x DriveCalc's kV) Km is 0.35 x a
// typical motor of its mass; with DriveCalc's kV itself (197.5 rpm/V, the output shaft's) 2.35 x.
const char* kGeared = R"({"id": "g1", "name": "Kontronik KIRA 650-13/6.7:1", "type": "bldc",
  "kv_rpm_per_v": 1323.03, "rm_ohm": 0.0272325, "rm_dc_ohm": 0.0363491, "io_a": 0.6364, "mass_kg": 0.378,
  "gear_ratio": 6.7, "gear_efficiency": 0.968,
  "source": {"dataset": "unit test"}})";

TEST(Catalog, GearKeysAreReadAndChecked) {
  {
    Catalog c;
    std::vector<std::string> problems;
    c.AddDocument(ParseJsonText(Doc(std::string(kGoodMotor) + ", " + kGeared), "t.json"), "t.json", &problems);
    ASSERT_TRUE(problems.empty()) << problems[0];
    EXPECT_DOUBLE_EQ(c.motor("g1").gear.ratio, 6.7);
    EXPECT_DOUBLE_EQ(c.motor("g1").gear.efficiency, 0.968);
    EXPECT_FALSE(c.motor("m1").gear.geared()) << "absent: direct drive";
  }
  const std::vector<BadCase> cases = {
      {"output-shaft Kv", Doc(Edit(kGeared, "\"kv_rpm_per_v\": 1323.03", "\"kv_rpm_per_v\": 197.467")),
       "motors[0] id=g1: key 'kv_rpm_per_v' = 197.467: a geared motor's Kv must be the motor's, not the output shaft's: "
       "its motor constant Km = "},
      {"no efficiency", Doc(Edit(kGeared, ", \"gear_efficiency\": 0.968", "")),
       "id=g1: key 'gear_efficiency': missing: a motor with gear_ratio > 1 needs its gearbox's efficiency"},
      {"efficiency without a gear", Doc(Edit(kGoodMotor, "\"io_a\": 0.4", "\"io_a\": 0.4, \"gear_efficiency\": 0.95")),
       "id=m1: key 'gear_efficiency' = 0.95: must be 1 without a gear"},
      {"ratio below 1", Doc(Edit(kGeared, "\"gear_ratio\": 6.7, \"gear_efficiency\": 0.968", "\"gear_ratio\": 0.15")),
       "key 'gear_ratio' = 0.15: must be a finite number >= 1"},
      {"efficiency above 1", Doc(Edit(kGeared, "\"gear_efficiency\": 0.968", "\"gear_efficiency\": 1.03")),
       "key 'gear_efficiency' = 1.03: must be a finite number > 0 and <= 1"},
  };
  for (const auto& c : cases) {
    const auto problems = Problems(c.doc);
    ASSERT_EQ(problems.size(), 1u) << c.what << ": " << (problems.empty() ? "none" : problems[0]);
    EXPECT_NE(problems[0].find(c.expected), std::string::npos)
        << c.what << "\n got: " << problems[0] << "\n want: " << c.expected;
  }
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// "prop_families" (catalog/prop_families.h): read strictly, one line per problem.
TEST(CatalogPropFamilies, ReadsFamiliesAndNamesEveryProblem) {
  const std::string good =
      R"({"id": "f1", "name": "n", "family": "multirotor", "diameter_m": [0.5, 1.5], "pitch_ratio": [0.3, 0.45],
          "blades": [2], "source": {"dataset": "d", "reference": "r"}})";
  Catalog c;
  std::vector<std::string> problems;
  c.AddDocument(ParseJsonText("{\"prop_families\": [" + good + "]}", "t.json"), "t.json", &problems);
  EXPECT_TRUE(problems.empty()) << problems.front();
  ASSERT_EQ(c.prop_families().size(), 1u);
  EXPECT_EQ(c.prop_families()[0].family, "multirotor");
  EXPECT_DOUBLE_EQ(c.prop_families()[0].diameter_max_m, 1.5);
  struct Case { std::string from, to, expect; };
  const Case cases[] = {
      {"\"multirotor\"", "\"wood\"", "prop_families[0] id=f1: family \"wood\": not a bundled family"},
      {"[0.5, 1.5]", "[1.5, 0.5]", "diameter_m [1.5, 0.5]: must be a range with 0 < min <= max"},
      {"[0.3, 0.45]", "0.3", "key 'pitch_ratio' = 0.3: must be [min, max]"},
      {"[2]", "[2.5]", "key 'blades' = [2.5]: must hold integers"},
      {"\"name\": \"n\"", "\"name\": \"n\", \"twist\": 1", "key 'twist': unknown key for a propeller family"},
      {"{\"dataset\": \"d\", \"reference\": \"r\"}", "{}", "key 'source': required"},
  };
  for (const Case& k : cases) {
    std::string e = good;
    e.replace(e.find(k.from), k.from.size(), k.to);
    Catalog bad;
    std::vector<std::string> p;
    bad.AddDocument(ParseJsonText("{\"prop_families\": [" + e + "]}", "t.json"), "t.json", &p);
    ASSERT_EQ(p.size(), 1u) << k.to;
    EXPECT_NE(p[0].find(k.expect), std::string::npos) << p[0];
    EXPECT_TRUE(bad.prop_families().empty());
  }
  std::vector<std::string> twice;
  Catalog dup;
  dup.AddDocument(ParseJsonText("{\"prop_families\": [" + good + ", " + good + "]}", "t.json"), "t.json", &twice);
  ASSERT_EQ(twice.size(), 1u);
  EXPECT_NE(twice[0].find("repeats"), std::string::npos);
}

// The bundled families the search sizes by default (issue 52: a carbon multirotor family of
// 20-62 in, an eVTOL rotor family of 1-4 m).
TEST(CatalogPropFamilies, BundledCatalogHoldsTheMultirotorAndEvtolFamilies) {
  const Catalog c = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  ASSERT_EQ(c.prop_families().size(), 2u);
  bool multirotor = false, evtol = false;
  for (const PropSizing& f : c.prop_families()) {
    if (f.family == "multirotor") {
      multirotor = true;
      EXPECT_NEAR(f.diameter_min_m, 20 * 0.0254, 1e-3);
      EXPECT_NEAR(f.diameter_max_m, 62 * 0.0254, 1e-3);
    }
    if (f.family == "evtol_rotor") {
      evtol = true;
      EXPECT_DOUBLE_EQ(f.diameter_min_m, 1.0);
      EXPECT_DOUBLE_EQ(f.diameter_max_m, 4.0);
    }
  }
  EXPECT_TRUE(multirotor && evtol);
}

}  // namespace
}  // namespace dynosize
