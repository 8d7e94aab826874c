// `optimize` on the full bundled catalog for each example mission (issue #6, #14), and the
// quadcopter with its battery capacity sized: wall time, and how many combinations were
// evaluated exactly and pruned. One iteration each (a search takes
// seconds). Run: build/optimize_bench --benchmark_repetitions=3
// --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "optimization/search.h"

namespace {

// capacity_hi_ah > 0: the example with its battery capacity sized over [2 Ah, capacity_hi_ah]
// (a continuous variable per combination) instead of the catalog cells' own.
// airspeed_hi_m_s > 0: every cruise segment's airspeed free in [14 m/s, airspeed_hi_m_s].
void RunExample(benchmark::State& state, const char* file, double capacity_hi_ah = 0.0,
                double airspeed_hi_m_s = 0.0) {
  const dynosize::Catalog cat = dynosize::Catalog::Load(DYNOSIZE_SOURCE_DIR "/catalog");
  dynosize::Mission m =
      dynosize::ReadMission(std::string(DYNOSIZE_SOURCE_DIR "/examples/missions/") + file);
  if (capacity_hi_ah > 0) m.battery.capacity_ah = dynosize::Range{2.0, capacity_hi_ah};
  if (airspeed_hi_m_s > 0) {
    for (dynosize::Segment& s : m.segments) {
      if (s.type == dynosize::SegmentType::kCruise) s.airspeed_m_s = dynosize::Range{14.0, airspeed_hi_m_s};
    }
  }
  dynosize::SearchResult s;
  for (auto _ : state) {
    dynosize::SearchOptions o;
    o.top_n = 5;
    s = dynosize::SearchCatalog(m, cat, o);
    benchmark::DoNotOptimize(s.best.size());
  }
  state.counters["combinations"] = static_cast<double>(s.combinations);
  state.counters["searched"] = static_cast<double>(s.searched);
  state.counters["pruned"] = static_cast<double>(s.pruned);
  state.counters["search_s"] = s.seconds;
  state.counters["candidate_pairs"] = static_cast<double>(s.candidate_pairs);
  state.counters["virtual_evals"] = static_cast<double>(s.virtual_evaluations);
}

void BM_OptimizeQuadcopter(benchmark::State& state) { RunExample(state, "quadcopter_1p5kg.json"); }
void BM_OptimizeEvtol(benchmark::State& state) { RunExample(state, "evtol_lift_cruise.json"); }
void BM_OptimizeQuadcopterSizing(benchmark::State& state) { RunExample(state, "quadcopter_1p5kg.json", 8.0); }
void BM_OptimizeSprayer(benchmark::State& state) { RunExample(state, "sprayer_hexacopter_25kg.json"); }
void BM_OptimizeQuadplane(benchmark::State& state) { RunExample(state, "quadplane_2kg.json"); }
// Issue 14's third goal: the quadplane with its capacity sized in [2, 8] Ah and the cruise
// airspeed free in [14, 24] m/s (two continuous variables per combination).
void BM_OptimizeQuadplaneSizing(benchmark::State& state) { RunExample(state, "quadplane_2kg.json", 8.0, 24.0); }
BENCHMARK(BM_OptimizeQuadcopter)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_OptimizeQuadcopterSizing)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_OptimizeEvtol)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_OptimizeSprayer)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_OptimizeQuadplane)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_OptimizeQuadplaneSizing)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
