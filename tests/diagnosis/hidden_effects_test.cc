// The hidden-effect suite: campaigns made by the model (campaign.h) over many
// deterministic seeds, clean ones included and the saturation slope spread over 0.3-0.7. On every
// seed the diagnosis must name nothing but the hidden effect (no false alarm in the default suite,
// clean campaigns included; at most 1 in 50 in the long one) and, on all but kMaxMissShare of them, name it with its parameter within kStdErrBand
// of its own standard error (plus the input-noise share below). DiagnoseOptions::calibration_entry is off: the suite tests detection, not the
// entry written.
//
// Per seed: a clean campaign, one with the saturation knee (slope 0.3-0.7, spread evenly over the
// seeds) and one with each other effect of docs/model.md section 9 (random size). The default suite
// (HiddenEffects.*, 6 seeds, 42 campaigns) runs in seconds; HiddenEffectsLong.* runs 40 seeds
// (280 campaigns, about a minute), labelled long and disabled by default:
//   build/dynosize_tests --gtest_also_run_disabled_tests --gtest_filter='HiddenEffectsLong*'
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "campaign.h"
#include "diagnosis/diagnose.h"

namespace dynosize::diagnosis {
namespace {

using testing_util::Campaign;
using testing_util::CampaignOptions;
using testing_util::MakeCampaign;

// A recovered parameter lies within this many of its standard errors of the truth (3: a
// two-sided 99.7 % band, so that a suite of ~100 fits is not expected to miss once by chance).
constexpr double kStdErrBand = 3.0;
// The standard error comes from the fit's Jacobian and the residual variance; the campaigns also
// put 0.3-1 % noise on the model's inputs (VDC, torque), which biases an estimate by up to about
// that fraction of its value (errors in variables) without entering the standard error. The band
// is widened by this share of the value.
constexpr double kInputNoiseRel = 0.01;

DiagnoseOptions SuiteOptions() {
  DiagnoseOptions o;
  o.calibration_entry = false;
  return o;
}

std::string MainName(Cause c) {
  switch (c) {
    case Cause::kEscSaturation: return "sat_slope";
    case Cause::kSpeedDependentNoLoadCurrent: return "io1_a_s_per_rad";
    case Cause::kWindingTemperatureRise: return "rth_k_per_w";
    case Cause::kTorqueConstantDroop: return "kt_droop_per_a";
    case Cause::kThrottleDeadband: return "deadband";
    case Cause::kSupplyResistance: return "rsupply_ohm";
  }
  return "";
}

std::string Names(const DiagnoseResult& r) {
  std::string s;
  for (const auto& f : r.findings) s += std::string(CauseId(f.cause)) + " ";
  return s.empty() ? "(none)" : s;
}

// The share of hidden effects that may be missed or recovered outside the band: 5 %. The last
// run missed 1 of 42 (default suite: seed 7005, rth 0.971 +- 0.058 for 0.785 hidden)
// and 1 of 240 (long suite: seed 8002, rsupply 0.042 ohm at 1 % noise not found: p = 0.0035
// after the per-step correction). A false alarm - a finding on a clean campaign, or a
// cause that was not hidden - is never allowed in the default suite; in the long one at most 1 in
// 50 campaigns (the clean-campaign suite's bound, false_alarm_test.cc). The last long run had 1 of
// 280: seed 8024, a throttle offset of -0.0023 +- 0.0006 beside the hidden KT droop, p = 0.0009
// for alpha = 0.001 (0.0012 with the spreads of the preliminary fit held: the same draw of
// noise on the edge of the test, not a cause the model misses).
constexpr double kMaxMissShare = 0.05;
constexpr double kMaxLongFalseAlarmShare = 1.0 / 50.0;

struct Tally {
  int runs = 0, effects = 0, false_alarms = 0, misses = 0;
  std::string failures;
};

// One seed: the effect (or none) hidden, the diagnosis run, the verdict tallied.
void RunSeed(unsigned seed, const std::vector<Cause>& hidden, const CampaignOptions& co, Tally* t) {
  const Campaign c = MakeCampaign(seed, hidden, co);
  const DiagnoseResult r = Diagnose(c.table, SuiteOptions());
  ++t->runs;
  t->effects += hidden.empty() ? 0 : 1;
  std::string why;
  bool alarm = false;
  if (hidden.empty()) {
    alarm = !r.findings.empty();
    if (alarm) why = "false alarm: " + Names(r);
  } else if (r.findings.size() > 1 || (r.findings.size() == 1 && r.findings.front().cause != hidden.front())) {
    alarm = true;
    why = "false alarm: found " + Names(r) + "where " + CauseId(hidden.front()) + " was hidden";
  } else if (r.findings.empty()) {
    why = std::string("miss: ") + CauseId(hidden.front()) + " not found";
  } else {
    const Finding& f = r.findings.front();
    const std::string name = MainName(f.cause);
    const double v = f.parameters.at(name), se = f.stderrs.at(name), truth = c.hidden.front().second;
    if (!(std::fabs(v - truth) <= kStdErrBand * se + kInputNoiseRel * std::fabs(truth))) {
      why = name + " " + std::to_string(v) + " +- " + std::to_string(se) + " vs hidden " + std::to_string(truth);
    }
  }
  if (!why.empty()) {
    ++(alarm ? t->false_alarms : t->misses);
    t->failures += "seed " + std::to_string(seed) + ": " + why + "\n";
  }
}

void RunSuite(int seeds, unsigned base, double max_false_alarm_share) {
  Tally t;
  for (int s = 0; s < seeds; ++s) {
    const unsigned seed = base + static_cast<unsigned>(s);
    RunSeed(seed, {}, {}, &t);
    // Saturation slopes spread evenly over 0.3-0.7 (campaign.h: slope = 0.7 - 0.4*size).
    CampaignOptions sat;
    sat.size = (s + 0.5) / seeds;
    RunSeed(seed, {Cause::kEscSaturation}, sat, &t);
    for (Cause c : {Cause::kSpeedDependentNoLoadCurrent, Cause::kWindingTemperatureRise, Cause::kTorqueConstantDroop,
                    Cause::kThrottleDeadband, Cause::kSupplyResistance}) {
      RunSeed(seed, {c}, {}, &t);
    }
  }
  std::cout << "[hidden effects] " << t.runs << " campaigns (" << t.effects << " with an effect): " << t.false_alarms
            << " false alarms, " << t.misses << " effects missed or outside the band\n"
            << t.failures;
  EXPECT_LE(t.false_alarms, max_false_alarm_share * t.runs) << t.failures;
  EXPECT_LE(t.misses, kMaxMissShare * t.effects) << t.failures;
}

TEST(HiddenEffects, EveryEffectFoundNoFalseAlarmOverSeeds) { RunSuite(6, 7000, 0.0); }

TEST(HiddenEffectsLong, DISABLED_EveryEffectFoundNoFalseAlarmOverManySeeds) { RunSuite(40, 8000, kMaxLongFalseAlarmShare); }

}  // namespace
}  // namespace dynosize::diagnosis
