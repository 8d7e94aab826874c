// `optimize` on the full bundled catalog for each example mission (issue #6): wall time, and
// how many combinations were evaluated exactly and pruned. One iteration each (a search takes
// seconds). Run: build/optimize_bench --benchmark_repetitions=3
// --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "catalog/catalog.h"
#include "mission/mission.h"
#include "optimization/search.h"

namespace {

void RunExample(benchmark::State& state, const char* file) {
  const dynosize::Catalog cat = dynosize::Catalog::Load(DYNOSIZE_SOURCE_DIR "/catalog");
  const dynosize::Mission m =
      dynosize::ReadMission(std::string(DYNOSIZE_SOURCE_DIR "/examples/missions/") + file);
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
}

void BM_OptimizeQuadcopter(benchmark::State& state) { RunExample(state, "quadcopter_1p5kg.json"); }
void BM_OptimizeEvtol(benchmark::State& state) { RunExample(state, "evtol_lift_cruise.json"); }
BENCHMARK(BM_OptimizeQuadcopter)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_OptimizeEvtol)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
