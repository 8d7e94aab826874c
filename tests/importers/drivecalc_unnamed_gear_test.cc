// Geared DriveCalc motors whose name states no gear ratio (issue 51 item 3): the Kv the name
// states, the gear DriveCalc links (Gear.csv) and the motor constant against mass decide
// whether the entry is geared with the linked gear or excluded; never a direct drive at the
// output shaft's Kv (src/importers/drivecalc.cc, JudgeUnnamedGear).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "importers/importers.h"

namespace dynosize {
namespace {

const Json* FindId(const Json& arr, const std::string& id) {
  for (const auto& e : arr) {
    if (e["id"] == id) return &e;
  }
  return nullptr;
}

// The name's Kv on names as they are in Motors.csv.
TEST(DriveCalcNameKvTest, KvFromRealNames) {
  struct Case { const char* name; double kv; };  // kv 0: the name states none
  const Case cases[] = {
      {"Turnigy T600 Heli (880kv)", 880},
      {"Turnigy T600 Heli (1100kv)", 1100},
      {"HXT 63-64A 280 kV", 280},              // one space before
      {"EMGC A3714 893 Kv", 893},
      {"Lipolice DA 2209/30T KV980 ", 980},    // after
      {"Lipolice DA 2213/24T KV 880 ", 880},   // one space after
      {"R2Hobbies KV2736 6-Pol ", 2736},
      {"EMP B12-30-17 (~4050Kv)", 4050},
      {"Leopard LC3536-8T (95g, ~ 1060Kv)", 1060},
      {"Scorpion HK-4015/1070KV", 1070},
      {"Derkum F540-3650/KV3215", 3215},
      {"Tarot 5008-11-340kV TL96020", 340},
      {"Turnigy 35-30c-1100kV", 1100},
      {"parkzone 480 960Kv: T-28", 960},
      {"Scorpion HK-4025/1100KV_roxxy", 1100},
      // A number on both sides: the attached one.
      {"EMP-C5065/09 KV270", 270},
      {"SCM 3223 kv1200", 1200},
      {"HXT 42-60/06 500Kv 15-deg timing", 500},
      {"Turborix 3500kv 438W", 3500},
      {"HXT 2730 3000kV 24Gramm", 3000},
      // Makers' naming: the last token is the Kv.
      {"Himax 2825-2700", 2700},
      {"Himax HC3516-0840", 840},
      {"Medusa MR-028-032-4200", 4200},
      {"Medusa MR-12-30-4000 v2", 4000},
      // None stated.
      {"Himax C3514", 0},
      {"AXI 2212-34", 0},
      {"Mega ACn 22/30/1", 0},
      {"Kontronik KIRA 650-13/6.7:1", 0},
      {"Scorpion HK 2221-10 0,71YYY", 0},
      {"Some Motor 1,5 kV", 0},          // a decimal: not a Kv
      {"Some Motor 880kv 1100kv", 0},    // two different Kv
      {"Some Motor 12 kv 34", 0},        // two detached numbers
      {"Kvant 2212", 0},                 // "kv" inside a word
  };
  for (const Case& c : cases) {
    const NameKv k = KvFromMotorName(c.name);
    EXPECT_EQ(k.stated, c.kv > 0) << c.name;
    EXPECT_DOUBLE_EQ(k.kv_rpm_per_v, c.kv) << c.name;
  }
  EXPECT_EQ(KvFromMotorName("Turnigy T600 Heli (880kv)").token, "880kv");
  EXPECT_EQ(KvFromMotorName("Lipolice DA 2213/24T KV 880 ").token, "KV 880");
}

// A hand-made DriveCalc excerpt: the two T600 rows as they are, plus rows for the other rules.
class DriveCalcUnnamedGearTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/dynosize_dc_unnamed_gear_" + std::to_string(getpid());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    const std::string head =
        "myid,tbs,Name,Rem,custom,meas,match,StatDia,StatH,Turns,WireDia,Delta,Imax,Weight,"
        "mgear_id,mesc_id,kV,Rm,K,MvK,kL,ts\n";
    Write("Motors.csv",
          head +
              // Motors.csv rows 1807-1808 (myid 1829, 1830).
              "1829,5,Turnigy T600 Heli (880kv),\"Markus P\",0,2,0,40.0,30.0,0.0,0.0,2,150.0,365.0,39,0,"
              "164.77686197272496,0.02586378682394828,4.981365192599478e-18,0.0,0.000799882335430529,"
              "2013-10-08\n"
              "1830,5,Turnigy T600 Heli (1100kv),\"Markus P\",0,3,0,40.0,30.0,0.0,0.0,2,150.0,365.0,1,350,"
              "1027.3492896383343,0.007887456383650168,6.767807368514011e-19,0.0,3.351882158274255e-05,"
              "2013-10-08\n"
              // The name's Kv 6x the stored one, no gear linked: excluded.
              "2001,4,Test Inrunner 3000kv,,0,1,0,0,0,0,0,0,30,100,1,1,500,0.05,0,0.001,1e-6,2010-01-01\n"
              // The name's Kv 6x, a linked 4.4:1 (x6 is 36 % off it): excluded.
              "2002,4,Test Inrunner B 3000kv,,0,1,0,0,0,0,0,0,30,100,37,1,500,0.051,0,0.001,1e-6,2010-01-01\n"
              // No Kv in the name, a linked 4.4:1, Km with the stored kV = 0.0623 N*m/sqrt(W)
              // over the law's 0.0269 at 74 g = 2.3x (above 1.2x): excluded.
              "2003,4,Test Can 400/8D,,0,1,0,0,0,0,0,0,25,74,37,1,600,0.0653,0,0.001,1e-6,2010-01-01\n"
              // The same with R 16x larger: Km 0.58x the law, left direct drive.
              "2004,4,Test Can B 400/8D,,0,1,0,0,0,0,0,0,25,74,37,1,600,1.045,0,0.001,1e-6,2010-01-01\n");
    Write("Gear.csv",
          "myid,tbs,Name,Rem,ratG,EtaG,Stages,weight,ts\n"
          "1,, Direct drive,,1.0,1.0,0,,2008-12-29\n"
          "37,4,Maxon,,4.4,0.96,1,0.0,2006-03-21\n"
          "39,4,Micro-Edition,Reisenauer,5.0,0.975,1,18.0,2007-02-20\n");
    Write("ESC.csv", "myid,tbs,Name,Rem,Imax,Ipeak,R,Weight,NiMHmin,NiMHmax,LiPomin,LiPomax,ts\n");
    Write("Batteries.csv", "myid,tbs,Name,Rem,Imax,Ipeak,Capacity,Weight,Ri,Volt,ts\n");
    Write("Props.csv",
          "myid,tbs,Name,Dia,Pitch,a,b,AltThr,TmpThr,srcThr,c,d,AltPwr,TmpPwr,srcPwr,n10N,n100W,"
          "Folder,Hub,MaxRPM,match,Rely,ts\n");
    Write("MData.csv", "motor_id,U,n,I,IsNoLoad,prop_id,Alt,Temp\n");
    data_ = ImportDriveCalc(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ + "/" + name, std::ios::binary) << text;
  }
  const Json& Motor(const std::string& id) const {
    const Json* m = FindId(data_.motors, id);
    EXPECT_NE(m, nullptr) << id;
    static const Json kEmpty = Json::object();
    return m ? *m : kEmpty;
  }
  std::string dir_;
  ImportedDataset data_;
};

// Written to 6 significant digits by the importer.
constexpr double kSixDigits = 5e-6;

TEST_F(DriveCalcUnnamedGearTest, T600GearedWithItsLinkedGear) {
  const Json& m = Motor("dc_m_1829");
  ASSERT_TRUE(m.contains("gear_ratio"));
  EXPECT_FALSE(m.contains("exclude"));
  // 880/164.777 = x5.34, within 21 % of the linked 5:1 (Gear.csv myid 39, efficiency 0.975).
  EXPECT_DOUBLE_EQ(m["gear_ratio"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(m["gear_efficiency"].get<double>(), 0.975);
  EXPECT_NEAR(m["kv_rpm_per_v"].get<double>(), 5.0 * 164.77686197272496, kSixDigits * 824);
  EXPECT_EQ(m["source"]["values"]["kv_rpm_per_v"], "derived");
  EXPECT_EQ(m["source"]["values"]["gear_ratio"], "datasheet");
  EXPECT_EQ(m["source"]["values"]["gear_efficiency"], "datasheet");
  // The loss torque moves to the motor shaft: kL / N^2.
  EXPECT_NEAR(m["loss_torque_per_omega_nm_s_per_rad"].get<double>(), 0.000799882335430529 / 25,
              kSixDigits * 3.2e-5);
  const std::string note = m["source"]["note"].get<std::string>();
  EXPECT_NE(note.find("the name states 880 kV (\"880kv\"), the entry 164.8 rpm/V (x5.34)"), std::string::npos)
      << note;
}

TEST_F(DriveCalcUnnamedGearTest, NameKvMatchingTheEntryIsUntouched) {
  const Json& m = Motor("dc_m_1830");
  EXPECT_FALSE(m.contains("gear_ratio"));
  EXPECT_FALSE(m.contains("exclude"));
  EXPECT_NEAR(m["kv_rpm_per_v"].get<double>(), 1027.35, kSixDigits * 1027);
  EXPECT_EQ(m["source"]["values"]["kv_rpm_per_v"], "datasheet");
  EXPECT_EQ(m["source"]["note"].get<std::string>().find("geared"), std::string::npos);
}

TEST_F(DriveCalcUnnamedGearTest, NoRatioToRunItWithExcludes) {
  const Json& a = Motor("dc_m_2001");
  EXPECT_FALSE(a.contains("gear_ratio"));
  EXPECT_EQ(a["exclude"].get<std::string>(),
            "geared: the name states 3000 kV (\"3000kv\"), the entry 500 rpm/V (x6): the output shaft's "
            "Kv; no ratio to run it with (no gear linked in Gear.csv)");
  EXPECT_DOUBLE_EQ(a["kv_rpm_per_v"].get<double>(), 500.0);  // the source's number, kept
  const Json& b = Motor("dc_m_2002");
  EXPECT_NE(b["exclude"].get<std::string>().find(
                "no ratio to run it with (the linked Gear.csv myid 37 (4.4:1, efficiency 0.96) is not x6 within 21 %)"),
            std::string::npos)
      << b["exclude"];
  const Json& c = Motor("dc_m_2003");
  EXPECT_NE(c["exclude"].get<std::string>().find("geared: DriveCalc links Gear.csv myid 37 (4.4:1, efficiency "
                                                 "0.96) and the motor constant with the entry's 600 rpm/V is 2.3"),
            std::string::npos)
      << c["exclude"];
  EXPECT_NE(c["source"]["note"].get<std::string>().find("excluded by default: geared"), std::string::npos);
  const Json& d = Motor("dc_m_2004");
  EXPECT_FALSE(d.contains("exclude"));
  EXPECT_FALSE(d.contains("gear_ratio"));
  bool noted = false;
  for (const std::string& n : data_.report.notes) {
    noted |= n.find("1 geared with the linked gear") != std::string::npos &&
             n.find("3 excluded by default as geared without a ratio to run them with (2 by the name's Kv") !=
                 std::string::npos &&
             n.find("left direct drive: 1 linking a gear") != std::string::npos;
  }
  EXPECT_TRUE(noted);
}

// On the real files: dc_m_1829 is geared with its ratio (never a direct drive at 164.8 rpm/V),
// and no entry left direct drive has a name Kv that says its Kv is the output shaft's.
TEST(DriveCalcUnnamedGearRealTest, NoDirectDriveAtTheOutputKv) {
  const std::string dir = DYNOSIZE_SHARED_DIR "/data/drivecalc";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no ../shared/data/drivecalc: the real-data check needs it";
  const ImportedDataset d = ImportDriveCalc(dir);
  const Json* t600 = FindId(d.motors, "dc_m_1829");
  ASSERT_NE(t600, nullptr);
  ASSERT_TRUE(t600->contains("gear_ratio") || t600->contains("exclude"));
  EXPECT_GT((*t600)["kv_rpm_per_v"].get<double>(), 800.0) << "a direct drive at the output shaft's 164.8 rpm/V";
  EXPECT_DOUBLE_EQ((*t600)["gear_ratio"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ((*t600)["gear_efficiency"].get<double>(), 0.975);
  const Json* t600b = FindId(d.motors, "dc_m_1830");
  ASSERT_NE(t600b, nullptr);
  EXPECT_FALSE(t600b->contains("gear_ratio"));
  EXPECT_FALSE(t600b->contains("exclude"));

  // Every direct-drive entry whose name states a Kv: none at >= 1.4x (those are geared or
  // excluded), and the band kNameKvMatchRel = 21 % holds at least 98 % of them (271 of 275).
  int with_kv = 0, in_band = 0;
  for (const Json& m : d.motors) {
    const NameKv k = KvFromMotorName(m["name"].get<std::string>());
    if (!k.stated || m.contains("gear_ratio")) continue;
    const double q = k.kv_rpm_per_v / m["kv_rpm_per_v"].get<double>();
    if (m.contains("exclude")) continue;
    EXPECT_LT(q, 1.4) << m["id"] << " " << m["name"];
    ++with_kv;
    if (std::fabs(q - 1.0) <= 0.21) ++in_band;
  }
  EXPECT_GE(with_kv, 250);
  EXPECT_GE(in_band, 0.98 * with_kv) << in_band << " of " << with_kv;
  bool noted = false;
  for (const std::string& n : d.report.notes) {
    noted |= n.find("5 geared with the linked gear") != std::string::npos &&
             n.find("9 excluded by default as geared") != std::string::npos;
  }
  EXPECT_TRUE(noted);
}

}  // namespace
}  // namespace dynosize
