// Google Benchmark of the closed-form model: one operating point, and a batch over many points.
// Target: under 20 ns per point on one core, the batch path vectorised.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "model/drive.h"
#include "model/drive_batch.h"
#include "model/paper_drive.h"

namespace {

using namespace dynosize;

// The tests' paper drive with a 30 A motor rating, so that the limits are checked on the way.
Drive MakeDrive() {
  MotorParams m = paper_drive::Motor();
  m.max_current_a = 30;
  return Drive(m, paper_drive::Esc());
}

struct Inputs {
  std::vector<double> vdc, tr, a, b, c;
  explicit Inputs(std::size_t n) : vdc(n), tr(n), a(n), b(n), c(n) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
      vdc[i] = 7.0 + 10.0 * u(rng);
      tr[i] = 0.1 + 0.9 * u(rng);
      a[i] = 0.002 * u(rng);
      b[i] = 1e-6 * u(rng);
      c[i] = 1.5e-7 * u(rng);
    }
  }
};

constexpr std::size_t kInputs = 4096;  // cycled through so the inputs are not constants

void BM_AtTorque(benchmark::State& state) {
  const Drive d = MakeDrive();
  const Inputs in(kInputs);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(d.AtTorque(in.vdc[i], in.tr[i], 10 * in.a[i]));
    i = (i + 1) & (kInputs - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_AtTorque);

void BM_AtLoadPropeller(benchmark::State& state) {
  const Drive d = MakeDrive();
  const Inputs in(kInputs);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(d.AtLoad(in.vdc[i], in.tr[i], TorqueLaw{in.a[i], in.b[i], in.c[i]}));
    i = (i + 1) & (kInputs - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_AtLoadPropeller);

void BM_Inverse(benchmark::State& state) {
  const Drive d = MakeDrive();
  const Inputs in(kInputs);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(d.Inverse(in.vdc[i], 10 * in.a[i], 500.0 + 1e6 * in.b[i]));
    i = (i + 1) & (kInputs - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Inverse);

// The structure-of-arrays batch (model/drive_batch.h, what the CLI's and the Python module's
// columns run): n points of one mode, the limits checked per point, into 19 output columns
// allocated once (PointColumnsStorage).
void SolveBatchBench(benchmark::State& state, BatchMode mode) {
  const Drive d = MakeDrive();
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const Inputs in(n);
  std::vector<double> torque(n), omega(n);
  for (std::size_t i = 0; i < n; ++i) {
    torque[i] = 10 * in.a[i];
    omega[i] = 500.0 + 1e6 * in.b[i];
  }
  BatchInputs bi;
  bi.vdc_v = in.vdc.data();
  bi.throttle = in.tr.data();
  bi.torque_nm = torque.data();
  bi.omega_rad_s = omega.data();
  const PointColumnsStorage out(n);
  for (auto _ : state) {
    SolveBatch(d, mode, n, bi, out.columns());
    benchmark::DoNotOptimize(out.columns().pdc_w);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
void BM_BatchAtTorque(benchmark::State& state) { SolveBatchBench(state, BatchMode::kAtTorque); }
void BM_BatchInverse(benchmark::State& state) { SolveBatchBench(state, BatchMode::kInverse); }
void BM_BatchAtSpeed(benchmark::State& state) { SolveBatchBench(state, BatchMode::kAtSpeed); }
BENCHMARK(BM_BatchAtTorque)->Arg(1024)->Arg(65536);
BENCHMARK(BM_BatchInverse)->Arg(1024)->Arg(65536);
BENCHMARK(BM_BatchAtSpeed)->Arg(1024)->Arg(65536);

}  // namespace

BENCHMARK_MAIN();
