#include "battery/battery.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/error.h"
#include "importers/csv.h"

namespace dynosize {
namespace {

// Closed forms evaluated in double precision.
constexpr double kExact = 1e-12;

BatteryPackParams OneCell(double cap_ah, double ri_ohm) {
  BatteryPackParams p;
  p.chemistry = BatteryChemistry::kLiPo;
  p.cell_capacity_ah = cap_ah;
  p.cell_ri_ohm = ri_ohm;
  p.cell_mass_kg = 0.05;
  return p;
}

// The OCV integral in closed form lies between the lower and upper Riemann sums of the
// rising curve on a fine grid, for every chemistry and start; the pack's bound is its cells'
// times it and never below the true integral.
TEST(BatteryTest, OcvIntegralMatchesFineRiemannSums) {
  constexpr int kPieces = 20000;  // the sums differ by (OCV(1) - OCV(from)) / kPieces, < 1e-4 V
  for (BatteryChemistry c : {BatteryChemistry::kLiPo, BatteryChemistry::kLiIon, BatteryChemistry::kLiFePo4,
                             BatteryChemistry::kNiMh}) {
    for (double from : {0.0, 0.2, 0.2371, 0.95, 1.0}) {
      double lower = 0, upper = 0;
      const double h = (1.0 - from) / kPieces;
      for (int i = 0; i < kPieces; ++i) {
        lower += CellOcvV(c, from + i * h) * h;
        upper += CellOcvV(c, from + (i + 1) * h) * h;
      }
      const double exact = CellOcvIntegral(c, from);
      EXPECT_GE(exact, lower - 1e-12) << ChemistryName(c) << " from " << from;
      EXPECT_LE(exact, upper + 1e-12) << ChemistryName(c) << " from " << from;
    }
  }
  BatteryPackParams p = OneCell(2.0, 0.01);
  p.n_series = 4;
  const BatteryPack pack(p);
  EXPECT_GE(OcvIntegralUpperBound(pack, 0.2), 4 * CellOcvIntegral(p.chemistry, 0.2));
  EXPECT_NEAR(OcvIntegralUpperBound(pack, 0.2), 4 * CellOcvIntegral(p.chemistry, 0.2), 1e-9);
}

TEST(BatteryTest, PackScalesCellsByHand) {
  BatteryPackParams p = OneCell(2.2, 0.006);
  p.n_series = 6;
  p.n_parallel = 2;
  p.cell_max_current_a = 50;
  const BatteryPack pack(p);
  EXPECT_NEAR(pack.capacity_ah(), 4.4, kExact);
  EXPECT_NEAR(pack.ri_ohm(), 0.018, kExact);  // 0.006*6/2
  EXPECT_NEAR(pack.mass_kg(), 0.6, kExact);
  EXPECT_NEAR(pack.max_current_a(), 100, kExact);
  // SOC 0.5: LiPo table 3.84 V per cell; 6S -> 23.04 V; at 20 A: 23.04 - 0.36 = 22.68 V.
  EXPECT_NEAR(pack.OcvV(0.5), 23.04, 1e-9);
  EXPECT_NEAR(pack.TerminalVoltageV(0.5, 20), 22.68, 1e-9);
  EXPECT_NEAR(pack.OcvV(1.0), 25.2, 1e-9);
  // Constant power: I solves P = (V - R*I)*I.
  double i = 0;
  ASSERT_TRUE(pack.CurrentForPower(0.5, 400, &i));
  EXPECT_NEAR((23.04 - 0.018 * i) * i, 400, 1e-9);
  EXPECT_FALSE(pack.CurrentForPower(0.5, 23.04 * 23.04 / (4 * 0.018) * 1.01, &i));
}

TEST(BatteryTest, PackFromEntryDividesTheUnit) {
  BatteryEntry e;
  e.id = "x";
  e.chemistry = BatteryChemistry::kLiPo;
  e.cells_series = 3;
  e.cells_parallel = 1;
  e.capacity_ah = 5.0;
  e.voltage_nominal_v = 11.1;
  e.ri_ohm = 0.015;
  e.mass_kg = 0.4;
  const BatteryPackParams p = PackFromEntry(e, 2, 1);  // 2 x 3S = 6S
  EXPECT_EQ(p.n_series, 6);
  EXPECT_NEAR(p.cell_ri_ohm, 0.005, kExact);
  EXPECT_NEAR(BatteryPack(p).ri_ohm(), 0.030, kExact);
  EXPECT_NEAR(BatteryPack(p).mass_kg(), 0.8, kExact);
  e.ri_ohm.reset();
  const BatteryPackParams q = PackFromEntry(e, 1, 1);
  ASSERT_EQ(q.assumed.size(), 1u);
  EXPECT_EQ(q.assumed[0], "ri_ohm");
  EXPECT_THROW(PackFromEntry(e, 0, 1), UsageError);
}

TEST(BatteryTest, TimeToEmptyAndEnergyByHand) {
  // No resistance, cut-off below the curve: constant current empties Q in Q/I.
  const BatteryPack pack(OneCell(2.0, 0.0));
  DischargeOptions o;
  o.cutoff_cell_v = 3.0;
  const DischargeResult r = pack.DischargeAtCurrent(4.0, o);
  EXPECT_EQ(r.status, DischargeStatus::kEmpty);
  EXPECT_NEAR(r.time_s, 1800.0, 1e-6);
  EXPECT_NEAR(r.charge_ah, 2.0, 1e-9);
  // Energy = Q * mean OCV; the midpoint rule on a piecewise-linear curve with knots on the
  // step grid is exact.
  EXPECT_NEAR(r.energy_j, pack.StoredEnergyJ(), 1e-6 * pack.StoredEnergyJ());
  // Constant power: time = energy/power when R = 0.
  const DischargeResult rp = pack.DischargeAtPower(20.0, o);
  EXPECT_NEAR(rp.time_s, rp.energy_j / 20.0, 1e-9 * rp.time_s);
  EXPECT_NEAR(rp.energy_j, pack.StoredEnergyJ(), 1e-4 * pack.StoredEnergyJ());
}

TEST(BatteryTest, CutOffAndUnreachablePowerAreStatuses) {
  const BatteryPack pack(OneCell(2.0, 0.05));
  const DischargeResult r = pack.DischargeAtCurrent(20.0);  // 1 V drop: cut-off 3.0 V early
  EXPECT_EQ(r.status, DischargeStatus::kReachedCutoff);
  EXPECT_LT(r.charge_ah, 2.0);
  EXPECT_NEAR(r.final_voltage_v, 3.0, 1e-12);
  const DischargeResult u = pack.DischargeAtPower(1000.0);
  EXPECT_EQ(u.status, DischargeStatus::kPowerUnreachable);
  EXPECT_THROW(pack.DischargeAtPower(-1.0), UsageError);
}

// --- Against real discharge logs (shared/data/sjkim_mfr_motor_tables/battery).

struct LogPoint {
  double t_s, v, i;
};

std::vector<LogPoint> ReadLog(const std::string& test_prefix) {
  const std::string path =
      DYNOSIZE_SHARED_DIR "/data/sjkim_mfr_motor_tables/battery/2.25Ah_Discharge_Profile.csv";
  CsvOptions o;
  o.skip_lines = 17;  // the analyser's header block; the table header is line 18
  const CsvTable t = ReadCsv(path, o);
  std::vector<LogPoint> out;
  for (const auto& r : t.rows) {
    if (r.fields.size() < 4 || Trim(r.fields[0]).rfind(test_prefix, 0) != 0) continue;
    const auto ts = ParseNumber(t.Field(r, 1)), v = ParseNumber(t.Field(r, 2)),
               i = ParseNumber(t.Field(r, 3));
    if (ts && v && i) out.push_back({*ts, *v, *i});
  }
  return out;
}

struct LogComparison {
  double rms_v = 0, max_v = 0;
  double t_cut_measured = 0, t_cut_model = 0;
};

// Model: 1S LiPo, rated 2.25 Ah (the log's header), Ri from the log's voltage 10 s into the
// load (RiAfterSettling), initial SOC 1. Predicts V(t) at the
// logged current by coulomb counting; compares up to the measured cut-off `cutoff_v`.
LogComparison CompareWithLog(const std::vector<LogPoint>& log, double ri_ohm, double cutoff_v) {
  BatteryPackParams p = OneCell(2.25, ri_ohm);
  const BatteryPack pack(p);
  LogComparison c;
  double ah = 0, ss = 0;
  int n = 0;
  for (std::size_t k = 1; k < log.size(); ++k) {
    const double dt = log[k].t_s - log[k - 1].t_s;
    ah += 0.5 * (log[k].i + log[k - 1].i) * dt / 3600.0;
    if (log[k].i <= 0) continue;
    const double soc = 1.0 - ah / pack.capacity_ah();
    const double vm = pack.TerminalVoltageV(soc, log[k].i);
    if (c.t_cut_model == 0 && vm <= cutoff_v) c.t_cut_model = log[k].t_s;
    if (c.t_cut_measured == 0 && log[k].v <= cutoff_v) c.t_cut_measured = log[k].t_s;
    if (c.t_cut_measured != 0) continue;
    const double e = vm - log[k].v;
    ss += e * e;
    ++n;
    c.max_v = std::max(c.max_v, std::abs(e));
  }
  c.rms_v = std::sqrt(ss / std::max(n, 1));
  return c;
}

// Ri as the zeroth-order model sees a sustained load: (OCV(SOC) - V)/I at the first sample
// 10 s after the load is applied (the cell's fast polarisation has settled by then; the first
// 1-2 s show only the ohmic part, about half of it). SOC by coulomb counting from 1.
constexpr double kRiSettleS = 10.0;

double RiAfterSettling(const std::vector<LogPoint>& log) {
  double ah = 0, t_on = -1;
  for (std::size_t k = 1; k < log.size(); ++k) {
    ah += 0.5 * (log[k].i + log[k - 1].i) * (log[k].t_s - log[k - 1].t_s) / 3600.0;
    if (t_on < 0 && log[k].i > 0) t_on = log[k].t_s;
    if (t_on >= 0 && log[k].t_s - t_on >= kRiSettleS) {
      return (CellOcvV(BatteryChemistry::kLiPo, 1.0 - ah / 2.25) - log[k].v) / log[k].i;
    }
  }
  return 0.0;
}

bool HaveLogs() {
  return std::filesystem::exists(DYNOSIZE_SHARED_DIR
                                 "/data/sjkim_mfr_motor_tables/battery/2.25Ah_Discharge_Profile.csv");
}

// 1C (2.25 A) discharge, 1 h. Measured at commit time: rms 33 mV, max 163 mV (near the knee
// at the end), time to 3.3 V 3545 s (model) vs 3620 s (log), -2.1 %. The tolerances (60 mV
// rms, 5 % in time) allow for the assumed generic OCV curve, the model's main error at low
// rate.
constexpr double kLowRateRmsTolV = 0.060;
constexpr double kLowRateTimeTol = 0.05;

TEST(BatteryLogTest, OneCDischargeOfA2250mAhLiPo) {
  if (!HaveLogs()) GTEST_SKIP() << "no ../shared/data: discharge logs missing";
  const auto log = ReadLog("2250mAh 1s 1C");
  ASSERT_GT(log.size(), 3000u);
  const double ri = RiAfterSettling(log);
  const LogComparison c = CompareWithLog(log, ri, 3.3);
  std::cout << "1C log: Ri after 10 s " << ri * 1e3 << " mOhm; V rms error " << c.rms_v * 1e3
            << " mV, max " << c.max_v * 1e3 << " mV; time to 3.3 V measured " << c.t_cut_measured
            << " s, model " << c.t_cut_model << " s\n";
  EXPECT_LT(c.rms_v, kLowRateRmsTolV);
  EXPECT_NEAR(c.t_cut_model, c.t_cut_measured, kLowRateTimeTol * c.t_cut_measured);
}

// 50 A (22C) discharge, 154 s: the cell heats from 67 F to 96 F and its resistance falls, so
// the voltage recovers after 20 s; the Rint model with the 10 s resistance cannot follow.
// Measured at commit time: rms 189 mV, max 532 mV; time to 3.1 V 54 s (model) vs 143 s
// (log): the model is CONSERVATIVE at high rate (under-predicts endurance by ~60 %), which
// catalog/README.md states. The test pins that behaviour: conservative, rms below 0.25 V.
constexpr double kHighRateRmsTolV = 0.25;

TEST(BatteryLogTest, FiftyAmpDischargeOfA2250mAhLiPo) {
  if (!HaveLogs()) GTEST_SKIP() << "no ../shared/data: discharge logs missing";
  const auto log = ReadLog("2250mAh 1s 50A");
  ASSERT_GT(log.size(), 100u);
  const double ri = RiAfterSettling(log);
  const LogComparison c = CompareWithLog(log, ri, 3.1);
  std::cout << "50 A log: Ri after 10 s " << ri * 1e3 << " mOhm; V rms error "
            << c.rms_v * 1e3 << " mV, max " << c.max_v * 1e3 << " mV; time to 3.1 V measured "
            << c.t_cut_measured << " s, model " << c.t_cut_model << " s\n";
  EXPECT_LT(c.rms_v, kHighRateRmsTolV);
  EXPECT_GT(c.t_cut_model, 0.0);
  EXPECT_LE(c.t_cut_model, c.t_cut_measured);  // conservative
}

}  // namespace
}  // namespace dynosize
