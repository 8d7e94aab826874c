// Google Benchmark of the batch path of `simulate --batch` and dynosize.simulate (api/simulate.h
// SimulateBatch) on the paper's pair: 10^5 points, the inverse model (torque and rpm given, the
// throttle solved) and the forward one (throttle and torque given). The per-point time is the
// reference of bench/python_simulate_bench.py (docs/python.md: Python's overhead over it).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "api/simulate.h"
#include "catalog/catalog.h"

namespace {

using namespace dynosize;

constexpr std::size_t kPoints = 100000;

const Catalog& PaperCatalog() {
  static const Catalog cat = Catalog::Load(std::string(DYNOSIZE_SOURCE_DIR) + "/catalog");
  return cat;
}

// The same inputs as bench/python_simulate_bench.py: VDC 6-8.4 V, torque 0-0.04 N*m, speed
// 2000-12000 rpm (inverse) or throttle 0.2-1 (forward), seeded.
std::vector<PointRequest> Requests(bool inverse) {
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<PointRequest> r(kPoints);
  for (std::size_t i = 0; i < kPoints; ++i) {
    r[i].row = i;
    r[i].vdc_v = 6.0 + 2.4 * u(rng);
    r[i].torque_nm = 0.04 * u(rng);
    if (inverse) {
      r[i].rpm = 2000.0 + 10000.0 * u(rng);
    } else {
      r[i].throttle = 0.2 + 0.8 * u(rng);
    }
  }
  return r;
}

void Run(benchmark::State& state, bool inverse) {
  const Catalog& cat = PaperCatalog();
  const Drive drive(cat.motor("emax_1900kv_paper").params, cat.esc("multistar_30a_paper").params);
  const auto requests = Requests(inverse);
  for (auto _ : state) {
    auto points = api::SimulateBatch(cat, drive, requests, "bench");
    benchmark::DoNotOptimize(points.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kPoints));
}

void BM_SimulateBatchInverse(benchmark::State& state) { Run(state, true); }
void BM_SimulateBatchForward(benchmark::State& state) { Run(state, false); }

BENCHMARK(BM_SimulateBatchInverse)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SimulateBatchForward)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
