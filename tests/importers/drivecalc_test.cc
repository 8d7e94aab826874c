// The DriveCalc importer on a hand-made excerpt of its four tables (rows copied from
// shared/data/drivecalc with edge cases added), checked against values computed by hand.
#include <algorithm>
#include <cmath>
#include <map>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "catalog/catalog.h"
#include "catalog/prop_credibility.h"
#include "catalog/conventions.h"
#include "importers/csv.h"
#include "importers/importers.h"

namespace dynosize {
namespace {

// Values written with 6 significant digits by the importer.
constexpr double kSixDigits = 5e-6;

class DriveCalcExcerptTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/dynosize_dc_excerpt_" + std::to_string(getpid());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    Write("Motors.csv",
          "myid,tbs,Name,Rem,custom,meas,match,StatDia,StatH,Turns,WireDia,Delta,Imax,Weight,"
          "mgear_id,mesc_id,kV,Rm,K,MvK,kL,ts\n"
          "1,4,137x50 11Y450 Kisscatz 9N6P,\"6pol 5x1,5x1 N45\",1,3,0,13.7,5.0,11.0,0.45,1,11.2,"
          "9.0,1,63,5624.754246532947,0.09715478431947354,3.388795981058409e-05,0.0,"
          "3.2164405930089476e-07,2007-09-07 09:56:29\n"
          "7,4,137x50 11Y450 Kisscatz 9N6P,\"6pol 5x1,5x1 N45\",1,3,0,13.7,5.0,11.0,0.45,1,11.2,"
          "9.0,1,63,5624.754246532947,0.09715478431947354,3.388795981058409e-05,0.0,"
          "3.2164405930089476e-07,2007-09-07 09:56:29\n"
          "8,4,Poly-Tec 480-31,,0,1,0,0,0,0,0,0,20,50,1,1,3100,0.0,0,0.001,1e-6,2006-01-01\n"
          "9,4,GWS B\xFCrsti 300,,0,1,0,0,0,0,0,0,5,20,1,1,2000,1.2,0,0.002,0,2006-01-01\n");
    Write("ESC.csv",
          "myid,tbs,Name,Rem,Imax,Ipeak,R,Weight,NiMHmin,NiMHmax,LiPomin,LiPomax,ts\n"
          "1,4,SBL Micro Autotiming,,0.0,0.0,0.0,0.0,0,0,0,0,2006-03-21\n"
          "2,4,Aveox H-160,,60.0,100.0,7.0,74.0,0,30,2,4,2006-03-21\n"
          "3,4,No-R 40,,40.0,50.0,0.0,30.0,0,0,0,0,2006-03-21\n");
    Write("Batteries.csv",
          "myid,tbs,Name,Rem,Imax,Ipeak,Capacity,Weight,Ri,Volt,ts\n"
          "1,, Constant voltage,,,,,,,,2008-12-29\n"
          "2,4,E-Tec 1200 Li-Poly,,7.2,10.0,1200.0,12.5,33.0,3.7,2006-03-21\n"
          "4,4,GP 1100 2/3 AA,,14.0,22.0,1100.0,22.0,9.2,1.2,2006-03-21\n");
    Write("Props.csv",
          "myid,tbs,Name,Dia,Pitch,a,b,AltThr,TmpThr,srcThr,c,d,AltPwr,TmpPwr,srcPwr,n10N,n100W,"
          "Folder,Hub,MaxRPM,match,Rely,ts\n"
          "1,4,APC E,4.1,4.1,0.5022887,2.046544,200,20.0,Dr Kiwi,0.0054099,3.090473,120,18.0,"
          "DC generated,41319.2,24023.3,0,0.0,46341,0,15,2009-09-16\n"
          "102,4,APC Sport,11.0,8.0,0.0,0.0,0,15.0,,0.5010857,3.060167,155,20.0,DC generated,0,"
          "17272,0,0.0,0,0,0,2009-01-01\n"
          // A folding prop whose laws promise FM 0.91 at 4000 rpm (above the envelope: derated)
          // and its duplicate under another id (merged).
          "127,4,AeroCarbon,12.5,10.0,9.5,2.0,0,0,x,0.072,3.0,0,0,x,0,0,1,0.0,0,0,0,2009-01-01\n"
          "128,4,AeroCarbon,12.5,10.0,9.0,2.0,0,0,x,0.06,3.0,0,0,x,0,0,1,0.0,0,0,0,2009-01-01\n"
          // FM = 1.6 everywhere: beats momentum theory, refused.
          "140,4,Miracle,10.0,5.0,30.0,2.0,0,0,x,0.05,3.0,0,0,x,0,0,0,0.0,0,0,0,2009-01-01\n");
    Write("MData.csv", "motor_id,U,n,I,IsNoLoad,prop_id,Alt,Temp\n"
                       "1,10,20000,5,0,1,0,0\n1,11,25000,6,0,1,0,0\n1,10,30000,1,1,1,0,0\n");
    data_ = ImportDriveCalc(dir_);
  }
  void Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ + "/" + name, std::ios::binary) << text;
  }
  std::string dir_;
  ImportedDataset data_;
};

TEST_F(DriveCalcExcerptTest, MotorValuesByHand) {
  ASSERT_EQ(data_.motors.size(), 2u);  // duplicate (myid 7) merged, Rm = 0 (myid 8) dropped
  const Json& m = data_.motors[0];
  EXPECT_EQ(m["id"], "dc_m_1");
  EXPECT_EQ(m["type"], "bldc");
  EXPECT_NEAR(m["kv_rpm_per_v"].get<double>(), 5624.754246532947, kSixDigits * 5624.75);
  // DriveCalc's Rm is the DC circuit's (U = n/Kv + R*I): kept as rm_dc_ohm, and rm_ohm is the
  // rms circuit's K*g*R_dc = 0.675237*1.109528*R_dc = 0.7491946*R_dc (catalog/conventions.h).
  EXPECT_NEAR(m["rm_dc_ohm"].get<double>(), 0.09715478431947354, kSixDigits * 0.0971548);
  EXPECT_NEAR(m["rm_ohm"].get<double>(), 0.7491946 * 0.09715478431947354, kSixDigits * 0.0728);
  EXPECT_NEAR(m["mass_kg"].get<double>(), 0.009, 1e-15);
  // io = (MvK + kL*omega_10V)/kt, omega_10V = Kv*10*pi/30, kt = 1.10953/(Kv*pi/30):
  // 3.2164405930e-7 * (589.0264)^2 * 10 / 1.1095280 = 1.00578 A (4 digits kept).
  const double w = 5624.754246532947 * M_PI / 30;
  const double io_hand = 3.2164405930089476e-07 * w * w * 10 / 1.1095279993106997;
  EXPECT_NEAR(io_hand, 1.00578, 1e-5);
  EXPECT_NEAR(m["io_a"].get<double>(), 1.006, 1e-12);
  EXPECT_EQ(m["source"]["values"]["rm_ohm"], "derived");
  EXPECT_EQ(m["source"]["values"]["rm_dc_ohm"], "datasheet");
  EXPECT_EQ(m["source"]["values"]["io_a"], "derived");
  EXPECT_EQ(m["source"]["tier"], "user_contributed");
  // The same product under two ids becomes one entry that names both rows.
  EXPECT_NE(m["source"]["reference"].get<std::string>().find("also myid 7"), std::string::npos)
      << m["source"]["reference"];
  // Latin-1 name decoded, brushed by name.
  EXPECT_EQ(data_.motors[1]["name"], "GWS B\xC3\xBCrsti 300");
  EXPECT_EQ(data_.motors[1]["type"], "brushed");
  EXPECT_FALSE(data_.motors[1].contains("rm_dc_ohm"));  // a brushed motor's circuit is the DC one
  EXPECT_NEAR(data_.motors[1]["rm_ohm"].get<double>(), 1.2, 1e-15);
  EXPECT_EQ(data_.report.DroppedCount("motors"), 2u);
}

TEST_F(DriveCalcExcerptTest, EscValuesAndPrior) {
  ASSERT_EQ(data_.escs.size(), 2u);  // Imax = 0 row dropped
  const Json& e = data_.escs[0];
  EXPECT_NEAR(e["resc_ohm"].get<double>(), 0.007, 1e-15);  // 7 mOhm
  EXPECT_EQ(e["source"]["values"]["resc_ohm"], "datasheet");
  EXPECT_EQ(e["source"]["values"]["c1"], "assumed");
  EXPECT_NEAR(e["c1"].get<double>(), 1.10953, 1e-12);
  EXPECT_EQ(e["cells_max"], 4);
  EXPECT_NEAR(e["vdc_max_v"].get<double>(), 16.8, 1e-12);
  // R = 0 placeholder: prior 79.18*40^-0.8467 mOhm = 3.484 mOhm (3 digits kept).
  const Json& p = data_.escs[1];
  EXPECT_NEAR(79.18 * std::pow(40.0, -0.8467), 3.4841, 1e-3);
  EXPECT_NEAR(p["resc_ohm"].get<double>(), 0.00348, 1e-15);
  EXPECT_EQ(p["source"]["values"]["resc_ohm"], "assumed");
}

TEST_F(DriveCalcExcerptTest, BatteriesAndProps) {
  ASSERT_EQ(data_.batteries.size(), 2u);
  const Json& b = data_.batteries[0];
  EXPECT_EQ(b["chemistry"], "lipo");
  EXPECT_NEAR(b["capacity_ah"].get<double>(), 1.2, 1e-15);
  EXPECT_NEAR(b["ri_ohm"].get<double>(), 0.033, 1e-15);
  EXPECT_EQ(data_.batteries[1]["chemistry"], "nimh");
  EXPECT_EQ(data_.batteries[1]["source"]["values"]["chemistry"], "assumed");
  ASSERT_EQ(data_.props.size(), 2u);  // APC Sport: no thrust law; 128 merged; 140 FM > 1
  const Json& p = data_.props[0];
  // Valid range from DriveCalc's loaded measurements with this prop (the no-load row is not).
  EXPECT_EQ(p["rpm_min"].get<double>(), 20000.0);
  EXPECT_EQ(p["rpm_max"].get<double>(), 25000.0);
  EXPECT_EQ(p["source"]["values"]["rpm_min"], "measured");
  EXPECT_EQ(p["name"], "APC E 4.1x4.1");
  EXPECT_NEAR(p["diameter_m"].get<double>(), 0.10414, 1e-15);
  // a = 0.5022887 g at 200 m, 20 C: p = 101325*(1 - 2.25577e-5*200)^5.25588 = 98945 Pa,
  // rho = p/(287.058*293.15) = 1.17581; T(1000 rpm) = 0.5022887 g * 9.80665e-3 * 1.225/rho.
  const double rho = 101325 * std::pow(1 - 2.25577e-5 * 200, 5.25588) / (287.058 * 293.15);
  EXPECT_NEAR(rho, 1.17581, 1e-5);
  EXPECT_NEAR(p["thrust_law_n"].get<double>(), 0.5022887 * 9.80665e-3 * 1.225 / rho,
              kSixDigits * 0.005132);
  EXPECT_NEAR(p["thrust_law_exp"].get<double>(), 2.04654, 1e-12);
}

TEST_F(DriveCalcExcerptTest, PropAuditFoldingAndDuplicates) {
  ASSERT_EQ(data_.props.size(), 2u);
  const Json& f = data_.props[1];
  EXPECT_EQ(f["id"], "dc_p_127");
  EXPECT_TRUE(f["folding"].get<bool>());
  EXPECT_EQ(f["source"]["values"]["folding"], "datasheet");  // the Folder column
  // No measurements: rpm range = tip speed 40-230 m/s on D = 0.3175 m: 2406-13836 rpm.
  EXPECT_NEAR(f["rpm_min"].get<double>(), 40.0 / 0.15875 * 30 / M_PI, 1.0);
  EXPECT_EQ(f["source"]["values"]["rpm_min"], "assumed");
  // T = 9.5 gf*k^2, P = 0.072 W*k^3 (k = rpm/1000) at 1.225 kg/m^3: FM ~ k^(1.5*2 - 3) is the
  // same at every speed, FM = T^1.5/(P*sqrt(2*rho*A)) = 0.0931632^1.5/(0.072*0.440420) = 0.897.
  // Above the largest median FM of measured props of D >= 12 in (the envelope), so the power
  // law is raised by fm/envelope and the entry says by how much.
  const double t = 9.5 * 9.80665e-3, a = M_PI * 0.3175 * 0.3175 / 4;
  const double fm = std::pow(t, 1.5) / (0.072 * std::sqrt(2 * 1.225 * a));
  ASSERT_GT(fm, 0.76);
  ASSERT_LT(fm, 1.0);
  const double factor = f["power_derate_factor"].get<double>();
  EXPECT_NEAR(factor, fm / FmEnvelopeFor(0.3175).max, 1e-3);
  EXPECT_NEAR(f["power_law_w"].get<double>(), 0.072 * factor, 1e-6);
  EXPECT_EQ(data_.report.props_derated, 1u);
  EXPECT_NE(f["source"]["reference"].get<std::string>().find("also myid 128"), std::string::npos);
  // The miracle prop is dropped with the rule it breaks.
  bool refused = false;
  for (const auto& d : data_.report.dropped) {
    if (d.reason.find("FM > 1") != std::string::npos) refused = d.examples[0].find("Miracle") != std::string::npos;
  }
  EXPECT_TRUE(refused);
}

TEST_F(DriveCalcExcerptTest, OutputValidatesAsACatalog) {
  const std::string text = FormatCatalogDocument(data_.comment, data_.motors, data_.escs,
                                                 data_.props, data_.batteries);
  Catalog c;
  std::vector<std::string> problems;
  c.AddDocument(ParseJsonText(text, "excerpt.json"), "excerpt.json", &problems);
  EXPECT_TRUE(problems.empty()) << (problems.empty() ? "" : problems[0]);
  EXPECT_EQ(c.motors().size(), 2u);
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// The ratio a DriveCalc motor name states, on names as they are in Motors.csv.
TEST(DriveCalcGearTest, RatioFromRealNames) {
  struct Case { const char* name; bool stated; double ratio; };
  const Case cases[] = {
      {"Kontronik KIRA 650-13/6.7:1", true, 6.7},
      {"Feigao 28-8L   4,4:1", true, 4.4},
      {"Multiplex Permax BL-480/6G (4,4:1)", true, 4.4},
      {"Hacker B50 19S-6,7:1", true, 6.7},
      {"360x470 11D1520 6,8:1", true, 6.8},
      {"Mega ACn 22/10/3 4,4/1", true, 4.4},
      {"Mega ACn 22/30/2  4,4:1", true, 4.4},
      {"Poly-Tec 600-17 6,1:1 14,8V", true, 6.1},
      {"AXI 2204-54 (old:5,5mm bell)", false, 1.0},  // a ':' that is no ratio
      {"parkzone 480 960Kv: T-28", false, 1.0},
      {"Mega ACn 22/30/1", false, 1.0},               // a winding, not 30:1
      {"AXI 2212/26 GOLD LINE", false, 1.0},
  };
  for (const Case& c : cases) {
    const NameGearRatio g = GearRatioFromMotorName(c.name);
    EXPECT_EQ(g.stated, c.stated) << c.name;
    EXPECT_DOUBLE_EQ(g.ratio, c.ratio) << c.name;
    EXPECT_TRUE(g.error.empty()) << c.name << ": " << g.error;
  }
  // Ratio-like tokens the model cannot take are refused with the reason.
  const NameGearRatio two = GearRatioFromMotorName("Some Motor 3:2");
  EXPECT_FALSE(two.stated);
  EXPECT_NE(two.error.find("\"3:2\": a ratio must be written N:1"), std::string::npos) << two.error;
  const NameGearRatio half = GearRatioFromMotorName("Some Motor 0,5:1");
  EXPECT_NE(half.error.find("\"0,5:1\": the ratio must be 1-100"), std::string::npos) << half.error;
}

// On the whole data set: every name with a ratio becomes a geared entry whose Kv is N x
// DriveCalc's kV, none is refused, and the import says how many (docs/model.md section 12).
TEST(DriveCalcGearTest, TheDataSetsGearedMotors) {
  const std::string dir = DYNOSIZE_SHARED_DIR "/data/drivecalc";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no ../shared/data/drivecalc";
  const ImportedDataset d = ImportDriveCalc(dir);
  int geared = 0, from_table = 0, by_evidence = 0;
  for (const Json& m : d.motors) {
    if (!m.contains("gear_ratio")) continue;
    ++geared;
    const NameGearRatio g = GearRatioFromMotorName(m["name"].get<std::string>());
    if (m["source"]["values"]["gear_ratio"] == "datasheet") {
      // No ratio in the name: the linked gear's, confirmed by the name's Kv
      // (drivecalc_unnamed_gear_test.cc).
      ++by_evidence;
      EXPECT_FALSE(g.stated) << m["name"];
    } else {
      EXPECT_TRUE(g.stated) << m["name"];
      EXPECT_DOUBLE_EQ(m["gear_ratio"].get<double>(), g.ratio);
    }
    const double eta = m["gear_efficiency"].get<double>();
    EXPECT_GT(eta, 0.8);
    EXPECT_LE(eta, 1.0);
    if (m["source"]["values"]["gear_efficiency"] == "datasheet") ++from_table;
  }
  EXPECT_EQ(geared, 85);
  EXPECT_EQ(by_evidence, 5);
  EXPECT_EQ(from_table, 81);
  bool noted = false;
  for (const std::string& n : d.report.notes) noted |= n.find("motors geared by name: 80") != std::string::npos;
  EXPECT_TRUE(noted);
}

}  // namespace
}  // namespace dynosize

namespace dynosize {
namespace {

// The Kv a geared catalog entry holds is the motor's: DriveCalc's own no-load measurements
// (MData.csv, speeds at the output shaft) satisfy U = n_motor/Kv + R_dc*I with n_motor = N x
// the measured speed. Over the bundled catalog's geared entries with no-load points the
// median of n_motor/(Kv*(U - R_dc*I)) per motor is within 1 % of 1 (measured 0.997; 55 motors,
// 102 points); with the measured speed taken as the motor's it would be about 1/N (0.19).
TEST(DriveCalcGearTest, GearedKvIsTheMotorsOnDriveCalcsMeasurements) {
  const std::string dir = DYNOSIZE_SHARED_DIR "/data/drivecalc";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no ../shared/data/drivecalc";
  const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  std::map<std::string, const MotorEntry*> geared;  // DriveCalc myid -> entry
  for (const MotorEntry& m : cat.motors()) {
    if (!m.gear.geared() || m.id.rfind("dc_m_", 0) != 0) continue;
    geared[m.id.substr(5)] = &m;
  }
  ASSERT_EQ(geared.size(), 85u);  // 80 by the name's ratio, 5 by the name's Kv and the linked gear
  const CsvTable t = ReadCsv(dir + "/MData.csv");
  const std::size_t c_id = t.Column("motor_id"), c_u = t.Column("U"), c_n = t.Column("n"), c_i = t.Column("I"),
                    c_nl = t.Column("IsNoLoad");
  std::map<std::string, std::vector<double>> ratios;
  for (const CsvRow& r : t.rows) {
    const auto it = geared.find(t.Field(r, c_id));
    if (it == geared.end() || t.Field(r, c_nl) != "1") continue;
    const auto u = ParseNumber(t.Field(r, c_u)), n = ParseNumber(t.Field(r, c_n));
    const double i = ParseNumber(t.Field(r, c_i)).value_or(0.0);
    if (!u || !n || !(*n > 0) || !(*u > 0)) continue;
    const MotorEntry& m = *it->second;
    const double r_dc = m.json.value("rm_dc_ohm", m.params.rm_ohm / kRmsPerDcResistance);
    ratios[it->first].push_back(m.gear.ratio * *n / (*m.kv_rpm_per_v * (*u - r_dc * i)));
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  std::vector<double> per_motor;
  for (const auto& [id, v] : ratios) per_motor.push_back(median(v));
  ASSERT_GE(per_motor.size(), 50u);
  // 1 %: DriveCalc's own fit of kV reproduces its no-load points to about that (README of the
  // data set: median ratio 0.997 over all motors).
  EXPECT_NEAR(median(per_motor), 1.0, 0.01);
  for (double x : per_motor) EXPECT_NEAR(x, 1.0, 0.05) << "a geared motor off its measurements";
}

}  // namespace
}  // namespace dynosize
