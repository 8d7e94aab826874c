// False alarms on clean campaigns: campaigns made by the first-order model (campaign.h) with no
// effect hidden, over the shapes a stand campaign takes - with and without a torque column, one or
// two propellers per voltage, one or three supply voltages, 0.3-2 % noise, 2-3 outliers. Diagnose
// must name nothing. The default suite runs 64 campaigns (about 4 s); the long one (400
// campaigns, about 25 s, disabled by default) allows at most 1 in 50 with a finding:
//   build/dynosize_tests --gtest_also_run_disabled_tests --gtest_filter='CleanCampaignsLong*'
// Measured (docs/diagnosis.md): with the effective-variance spreads of a preliminary fit held
// fixed, 2 of 400 (and 8 of 400 without outliers) named a throttle dead band, all on logs without
// torque; with the spreads following the fitted model (prepare.cc, stage 5), 0 of 400.
#include <gtest/gtest.h>

#include <iostream>
#include <sstream>
#include <string>

#include "campaign.h"
#include "diagnosis/diagnose.h"

namespace dynosize::diagnosis {
namespace {

using testing_util::CampaignOptions;
using testing_util::MakeCampaign;

// The long suite's allowance: at most 1 in 50 campaigns with a finding. The selection tests at
// alpha = 1e-3 per step (diagnose.h), so chance alone gives about 1 in 1000; the allowance leaves
// room for the approximations of the test (linearised input noise, nonlinear fits).
constexpr double kMaxLongFalseAlarmShare = 1.0 / 50.0;

// The campaign shapes: variant v of kVariants.
constexpr int kVariants = 8;
CampaignOptions Variant(int v) {
  CampaignOptions o;
  o.torque = v % 2 == 0;
  o.props = (v / 2) % 2 == 0 ? 2 : 1;
  switch (v / 4) {
    case 0:
      break;  // three voltages, 0.3-1 % noise, 2 outliers (the hidden-effect suite's shape)
    default:    // one voltage, noisier sensors, more bad readings
      o.vdc_v = {14.8};
      o.noise_min = 0.01;
      o.noise_max = 0.02;
      o.outliers = 3;
      break;
  }
  return o;
}

std::string Describe(const CampaignOptions& o) {
  std::ostringstream s;
  s << (o.torque ? "torque" : "no torque") << ", " << o.props << " prop(s), " << o.vdc_v.size() << " voltage(s), "
    << 100.0 * o.noise_min << "-" << 100.0 * o.noise_max << " % noise";
  return s.str();
}

struct CleanTally {
  int runs = 0, alarms = 0;
  std::string failures;
};

void RunClean(int seeds_per_variant, unsigned base, CleanTally* t) {
  for (int v = 0; v < kVariants; ++v) {
    const CampaignOptions o = Variant(v);
    for (int s = 0; s < seeds_per_variant; ++s) {
      const unsigned seed = base + 100 * static_cast<unsigned>(v) + static_cast<unsigned>(s);
      DiagnoseOptions d;
      d.calibration_entry = false;
      const DiagnoseResult r = Diagnose(MakeCampaign(seed, {}, o).table, d);
      ++t->runs;
      if (r.findings.empty()) continue;
      ++t->alarms;
      std::ostringstream f;
      f << "seed " << seed << " (" << Describe(o) << "):";
      for (const Finding& x : r.findings) f << " " << CauseId(x.cause) << " p=" << x.p_value << " gain " << x.gain_percent << " %";
      t->failures += f.str() + "\n";
    }
  }
  std::cout << "[clean campaigns] " << t->runs << " campaigns, " << t->alarms << " with a finding\n" << t->failures;
}

TEST(CleanCampaigns, NoFindingOnAnyShapeOfCampaign) {
  CleanTally t;
  RunClean(8, 11000, &t);
  EXPECT_EQ(t.alarms, 0) << t.failures;
}

TEST(CleanCampaignsLong, DISABLED_AtMostOneInFiftyCarriesAFinding) {
  CleanTally t;
  RunClean(50, 12000, &t);
  EXPECT_LE(t.alarms, kMaxLongFalseAlarmShare * t.runs) << t.failures;
}

}  // namespace
}  // namespace dynosize::diagnosis
