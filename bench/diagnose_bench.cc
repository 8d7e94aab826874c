// Detection and false-alarm rates of `dynosize diagnose` over many seeded campaigns:
// for each cause and effect size (fraction of the generator's range, tests/diagnosis/campaign.h)
// the share of campaigns where it is named first ("detected"), named at all, and its parameter
// recovered within 25 %; for clean campaigns the share with any finding ("false_alarm"). Run:
//   build/diagnose_bench --benchmark_counters_tabular=true
// Each benchmark runs its seeds once (Iterations(1)); the counters are the rates.
#include <benchmark/benchmark.h>

#include <cmath>

#include "../tests/diagnosis/campaign.h"

namespace {

using dynosize::diagnosis::Cause;
using dynosize::diagnosis::Diagnose;
using dynosize::diagnosis::testing_util::CampaignOptions;
using dynosize::diagnosis::testing_util::MakeCampaign;

constexpr int kSeeds = 30;

double MainParameter(const dynosize::diagnosis::Finding& f) {
  switch (f.cause) {
    case Cause::kEscSaturation: return f.parameters.at("sat_slope");
    case Cause::kSpeedDependentNoLoadCurrent: return f.parameters.at("io1_a_s_per_rad");
    case Cause::kWindingTemperatureRise: return f.parameters.at("rth_k_per_w");
    case Cause::kTorqueConstantDroop: return f.parameters.at("kt_droop_per_a");
    case Cause::kThrottleDeadband: return f.parameters.at("deadband");
    case Cause::kSupplyResistance: return f.parameters.at("rsupply_ohm");
  }
  return NAN;
}

void BM_Detection(benchmark::State& state) {
  const Cause cause = static_cast<Cause>(state.range(0));
  CampaignOptions co;
  co.size = static_cast<double>(state.range(1)) / 100.0;
  co.torque = state.range(2) != 0;
  int first = 0, named = 0, within = 0;
  double gain = 0.0;
  for (auto _ : state) {
    for (int s = 0; s < kSeeds; ++s) {
      const auto c = MakeCampaign(5000 + static_cast<unsigned>(s), {cause}, co);
      const auto r = Diagnose(c.table);
      bool any = false;
      for (const auto& f : r.findings) any = any || f.cause == cause;
      named += any;
      if (!r.findings.empty() && r.findings.front().cause == cause) {
        ++first;
        gain += r.findings.front().gain_percent;
        const double truth = c.hidden.front().second;
        within += std::fabs(MainParameter(r.findings.front()) - truth) <= 0.25 * truth;
      }
    }
  }
  state.SetLabel(std::string(dynosize::diagnosis::CauseId(cause)) + (co.torque ? "" : " (no torque)"));
  state.counters["detected"] = static_cast<double>(first) / kSeeds;
  state.counters["named"] = static_cast<double>(named) / kSeeds;
  state.counters["param_25pct"] = static_cast<double>(within) / kSeeds;
  state.counters["mean_gain_pct"] = first > 0 ? gain / first : 0.0;
}

void BM_FalseAlarm(benchmark::State& state) {
  CampaignOptions co;
  co.torque = state.range(0) != 0;
  const int seeds = 100;
  int alarms = 0;
  for (auto _ : state) {
    for (int s = 0; s < seeds; ++s) {
      alarms += !Diagnose(MakeCampaign(9000 + static_cast<unsigned>(s), {}, co).table).findings.empty();
    }
  }
  state.SetLabel(co.torque ? "clean, torque" : "clean, no torque");
  state.counters["false_alarm"] = static_cast<double>(alarms) / seeds;
}

void DetectionArgs(benchmark::internal::Benchmark* b) {
  for (int c = 0; c < dynosize::diagnosis::kCauseCount; ++c) {
    for (int size : {0, 50, 100}) b->Args({c, size, 1});
  }
  // DC logs without torque: the causes such logs can show.
  for (int c : {0, 2, 4, 5}) b->Args({c, 50, 0});
}

BENCHMARK(BM_Detection)->Apply(DetectionArgs)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_FalseAlarm)->Arg(1)->Arg(0)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
