// Google Benchmark of the blade-element model (src/rotor): one rotor operating point, a sized
// propeller's catalog entry (its static table and J sweeps), and a parametric rotor's hover design.
#include <benchmark/benchmark.h>

#include <cmath>

#include "importers/sized_prop.h"
#include "rotor/bemt.h"
#include "rotor/family.h"
#include "rotor/parametric.h"
#include "rotor/uiuc_polar.h"

namespace {

using namespace dynosize;

Bemt SizedBemt() {
  return Bemt(SizedBlade(*FindFamily("apc_e"), 0.254, 0.127, 2), kUiucFittedPolar);
}

// One static point of a 10x5 propeller (24 elements, each element's psi solved).
void BM_BemtStaticPoint(benchmark::State& state) {
  const Bemt bemt = SizedBemt();
  double omega = 500.0;
  for (auto _ : state) {
    const BemtPoint p = bemt.Evaluate(omega, 0.0, 1.225);
    benchmark::DoNotOptimize(p.thrust_n);
    omega = omega < 1200.0 ? omega + 1.0 : 500.0;
  }
}
BENCHMARK(BM_BemtStaticPoint);

// One point in axial flow (J about 0.4).
void BM_BemtAxialPoint(benchmark::State& state) {
  const Bemt bemt = SizedBemt();
  double omega = 500.0;
  for (auto _ : state) {
    const BemtPoint p = bemt.Evaluate(omega, 0.4 * omega / (2.0 * 3.141592653589793) * 0.254, 1.225);
    benchmark::DoNotOptimize(p.thrust_n);
    omega = omega < 1200.0 ? omega + 1.0 : 500.0;
  }
}
BENCHMARK(BM_BemtAxialPoint);

// `--prop-param 40x13x2`: the whole catalog entry (12 static speeds, 3 sweeps of up to 14 J).
void BM_SizedPropEntry(benchmark::State& state) {
  const PropSize size = ParsePropParam("40x13x2");
  for (auto _ : state) benchmark::DoNotOptimize(SizedPropJson(size));
}
BENCHMARK(BM_SizedPropEntry)->Unit(benchmark::kMillisecond);

// `rotor hover` for a 2.4 m rotor at 3,000 N: collective grid and refinement, a speed root each.
void BM_HoverDesign(benchmark::State& state) {
  ParametricRotor p;
  p.radius_m = 1.2;
  for (auto _ : state) benchmark::DoNotOptimize(DesignHover(p, kUiucFittedPolar, 3000.0, 1.225, 0.7));
}
BENCHMARK(BM_HoverDesign)->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
