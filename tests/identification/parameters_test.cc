// The parameter table of identification/parameters.h: names as the catalog and the JSON spell
// them, boxes that keep the energy rules, and the base parameters a log frees.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "identification/parameters.h"

namespace dynosize::identification {
namespace {

TEST(ParameterTable, NamesAreTheCatalogKeysInOrder) {
  EXPECT_STREQ(ParamName(Param::kKe), "ke_v_s_per_rad");
  EXPECT_STREQ(ParamName(Param::kKt), "kt_nm_per_a");
  EXPECT_STREQ(ParamName(Param::kIo), "io_a");
  EXPECT_STREQ(ParamName(Param::kDeadband), "deadband");
  EXPECT_STREQ(ParamName(Param::kRsupply), "rsupply_ohm");
  std::set<std::string> names;
  for (const ParamSpec& p : kParamTable) names.insert(p.name);
  EXPECT_EQ(names.size(), static_cast<std::size_t>(kParamCount));  // no name twice
  EXPECT_EQ(ParamIndex(Param::kRsupply), kParamCount - 1);
  EXPECT_EQ(ParamIndex(Param::kDeadband), kBaseParamCount - 1);
}

TEST(ParameterTable, BoxesKeepTheEnergyRules) {
  for (const ParamSpec& p : kParamTable) {
    EXPECT_LT(p.lower, p.upper) << p.name;
    EXPECT_GE(p.scale, 0.0) << p.name;
  }
  // docs/model.md section 10: KT <= kp*KE (ratio f <= 1), the ESC excess and c0 >= 0, Io does not fall
  // with speed; KE and Rm strictly positive.
  EXPECT_EQ(Spec(Param::kKt).upper, 1.0);
  EXPECT_EQ(Spec(Param::kC1).lower, 0.0);
  EXPECT_EQ(Spec(Param::kC0).lower, 0.0);
  EXPECT_EQ(Spec(Param::kIo1).lower, 0.0);
  EXPECT_GT(Spec(Param::kKe).lower, 0.0);
  EXPECT_GT(Spec(Param::kRm).lower, 0.0);
  // Only diagnose frees the extensions; the first-order slots come first.
  for (int k = 0; k < kParamCount; ++k) {
    EXPECT_EQ(kParamTable[k].freed_by == FreedBy::kDiagnose, k >= kBaseParamCount) << kParamTable[k].name;
  }
  EXPECT_TRUE(IsFirstOrderParam(ParamIndex(Param::kC0)));
  EXPECT_FALSE(IsFirstOrderParam(ParamIndex(Param::kTrSat)));
}

TEST(ParameterTable, WhatEachColumnSetFrees) {
  auto freed = [](const LogContent& c) {
    std::string s;
    const auto f = FreeBaseParams(c);
    for (int k = 0; k < kParamCount; ++k) {
      if (f[k]) s += std::string(s.empty() ? "" : " ") + kParamTable[k].name;
    }
    return s;
  };
  // AC columns, torque, throttle, current at three levels: the whole first-order model.
  LogContent full{true, true, true, true, true, 3};
  EXPECT_FALSE(TieKt(full));
  EXPECT_EQ(freed(full), "ke_v_s_per_rad kt_nm_per_a rm_ohm io_a resc_ohm c1 c0");
  // A thrust stand: DC side with throttle and current, no torque: KE and Rm only (KT tied, C1/C0
  // seen only as C1/R, C0/R, Io does not enter).
  LogContent stand{false, false, true, true, false, 8};
  EXPECT_TRUE(TieKt(stand));
  EXPECT_EQ(freed(stand), "ke_v_s_per_rad rm_ohm");
  // The same with torque: Io and the ESC ratio; KT still tied (no AC columns).
  stand.has_torque = stand.any_torque_known = true;
  EXPECT_TRUE(TieKt(stand));
  EXPECT_EQ(freed(stand), "ke_v_s_per_rad rm_ohm io_a c1 c0");
  // One throttle level: C1*TR + C0 cannot be separated.
  stand.throttle_levels = 1;
  EXPECT_EQ(freed(stand), "ke_v_s_per_rad rm_ohm io_a");
  // No throttle column (DriveCalc): RESC and the ESC are never freed.
  LogContent no_throttle{true, true, false, true, true, 1};
  EXPECT_EQ(freed(no_throttle), "ke_v_s_per_rad kt_nm_per_a rm_ohm io_a");
}

}  // namespace
}  // namespace dynosize::identification
