// Google Benchmark of the batch path of `simulate --batch` and dynosize.simulate (api/simulate.h
// SimulateBatch, SimulateColumns; the model's structure-of-arrays batch of model/drive_batch.h)
// on the paper's pair: 10^5 points, the inverse model (torque and rpm given, the throttle solved)
// and the forward one (throttle and torque given), beside the point-by-point path it replaced.
// BM_SimulateColumnsInverse's per-point time is the reference of bench/python_simulate_bench.py
// (docs/python.md: Python's overhead over it).
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

// api::SimulateBatch: the requests of a --batch file (std::optional fields) gathered into the
// model's structure-of-arrays batch (model/drive_batch.h); the result columns allocated per call.
void Run(benchmark::State& state, bool inverse) {
  const Catalog& cat = PaperCatalog();
  const Drive drive(cat.motor("emax_1900kv_paper").params, cat.esc("multistar_30a_paper").params);
  const auto requests = Requests(inverse);
  for (auto _ : state) {
    api::BatchResult points = api::SimulateBatch(cat, drive, requests, "bench");
    benchmark::DoNotOptimize(points.columns().pdc_w);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kPoints));
}

// The previous batch path, kept as the reference: point by point through Drive (api::SolvePoint)
// into OperatingPoint structs.
void RunPointByPoint(benchmark::State& state, bool inverse) {
  const Catalog& cat = PaperCatalog();
  const Drive drive(cat.motor("emax_1900kv_paper").params, cat.esc("multistar_30a_paper").params);
  const auto requests = Requests(inverse);
  for (auto _ : state) {
    std::vector<OperatingPoint> points(requests.size());
    for (std::size_t i = 0; i < requests.size(); ++i) points[i] = api::SolvePoint(drive, requests[i]);
    benchmark::DoNotOptimize(points.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kPoints));
}

// The columns as dynosize.simulate hands them over (api::SimulateColumns: contiguous inputs, VDC
// and torque read in place, rpm converted chunk by chunk), into result columns allocated per call
// as Python's numpy arrays are: the C++ reference of bench/python_simulate_bench.py.
void RunColumns(benchmark::State& state, bool reuse_output) {
  const Catalog& cat = PaperCatalog();
  const Drive drive(cat.motor("emax_1900kv_paper").params, cat.esc("multistar_30a_paper").params);
  const auto requests = Requests(true);
  std::vector<double> vdc(kPoints), torque(kPoints), rpm(kPoints);
  for (std::size_t i = 0; i < kPoints; ++i) {
    vdc[i] = requests[i].vdc_v;
    torque[i] = *requests[i].torque_nm;
    rpm[i] = *requests[i].rpm;
  }
  api::BatchColumns in;
  in.n = kPoints;
  in.vdc_v = {vdc.data(), false};
  in.torque_nm = {torque.data(), false};
  in.rpm = {rpm.data(), false};
  api::BatchResult kept(kPoints);
  for (auto _ : state) {
    if (reuse_output) {
      api::SimulateColumns(cat, drive, in, "bench", kept.columns());
      benchmark::DoNotOptimize(kept.columns().pdc_w);
    } else {
      api::BatchResult out(kPoints);
      api::SimulateColumns(cat, drive, in, "bench", out.columns());
      benchmark::DoNotOptimize(out.columns().pdc_w);
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kPoints));
}

void BM_SimulateBatchInverse(benchmark::State& state) { Run(state, true); }
void BM_SimulateBatchForward(benchmark::State& state) { Run(state, false); }
void BM_PointByPointInverse(benchmark::State& state) { RunPointByPoint(state, true); }
void BM_PointByPointForward(benchmark::State& state) { RunPointByPoint(state, false); }
void BM_SimulateColumnsInverse(benchmark::State& state) { RunColumns(state, false); }
void BM_SimulateColumnsInverseKeptOutput(benchmark::State& state) { RunColumns(state, true); }

BENCHMARK(BM_SimulateBatchInverse)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SimulateBatchForward)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PointByPointInverse)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PointByPointForward)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SimulateColumnsInverse)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SimulateColumnsInverseKeptOutput)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
