// `sweep` (goal: a 3 x 3 sweep of the quadcopter example in <= 3x the time of one optimize per
// point on 2 threads): the 3 x 3 grid (battery capacity x vehicle mass) as
// RunSweep runs it (points on 2 threads, each search on one), against the nine searches one
// after the other as nine optimize runs do them (each on 2 threads). The catalog is loaded once
// in both (the CLI loads it once per run: `time` the commands for that). Counter "ratio":
// sweep time / time of the nine searches. Run: build/sweep_bench --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <vector>

#include "catalog/catalog.h"
#include "common/json_file.h"
#include "mission/mission.h"
#include "optimization/search.h"
#include "study/sweep.h"

namespace {

const char* kMission = DYNOSIZE_SOURCE_DIR "/examples/missions/quadcopter_1p5kg.json";

std::vector<dynosize::study::VaryKey> Grid() {
  return {dynosize::study::ParseVary("battery.capacity_ah=3:7:2"),
          dynosize::study::ParseVary("vehicle.mass_kg=0.5:1.0:0.25")};
}

void BM_Sweep3x3VsNineOptimize(benchmark::State& state) {
  const dynosize::Catalog cat = dynosize::Catalog::Load(DYNOSIZE_SOURCE_DIR "/catalog");
  const dynosize::Json doc = dynosize::ReadJsonFile(kMission);
  const std::vector<dynosize::study::VaryKey> keys = Grid();
  double sweep_s = 0, nine_s = 0;
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    dynosize::study::SweepOptions so;
    so.threads = 2;
    const dynosize::study::SweepResult r = dynosize::study::RunSweep(doc, kMission, cat, keys, so);
    benchmark::DoNotOptimize(r.rows.size());
    sweep_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < dynosize::study::GridSize(keys); ++i) {
      const dynosize::Mission m = dynosize::ParseMission(
          dynosize::study::MissionAt(doc, keys, dynosize::study::GridPoint(keys, i)), kMission);
      dynosize::SearchOptions o;
      o.top_n = 1;
      o.threads = 2;
      o.distinct_designs = true;
      const dynosize::SearchResult s = dynosize::SearchCatalog(m, cat, o);
      benchmark::DoNotOptimize(s.best.size());
    }
    nine_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  state.counters["sweep_s"] = sweep_s;
  state.counters["nine_optimize_s"] = nine_s;
  state.counters["ratio"] = sweep_s / nine_s;
}

}  // namespace

BENCHMARK(BM_Sweep3x3VsNineOptimize)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

BENCHMARK_MAIN();
