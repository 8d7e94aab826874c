// Load time of the bundled catalog (catalog/*.json): Catalog::Load parses, validates and
// converts every entry. Run: build/catalog_bench --benchmark_repetitions=10
// --benchmark_report_aggregates_only=true  (the median is the number to quote).
#include <benchmark/benchmark.h>

#include <algorithm>

#include "catalog/catalog.h"
#include "catalog/prop_credibility.h"
#include "prop/prop_model.h"
#include "common/units.h"

namespace {

const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";

void BM_LoadBundledCatalog(benchmark::State& state) {
  std::size_t n = 0;
  for (auto _ : state) {
    const dynosize::Catalog c = dynosize::Catalog::Load(kCatalog);
    n = c.size();
    benchmark::DoNotOptimize(n);
  }
  state.counters["entries"] = static_cast<double>(n);
}
BENCHMARK(BM_LoadBundledCatalog)->Unit(benchmark::kMillisecond);

void BM_ValidateBundledCatalog(benchmark::State& state) {
  for (auto _ : state) {
    auto problems = dynosize::Catalog::Validate(kCatalog);
    benchmark::DoNotOptimize(problems);
  }
}
BENCHMARK(BM_ValidateBundledCatalog)->Unit(benchmark::kMillisecond);

// The figure-of-merit scan of every propeller (part of Load: the momentum-theory check).
void BM_ScanFigureOfMeritAllProps(benchmark::State& state) {
  const dynosize::Catalog c = dynosize::Catalog::Load(kCatalog);
  for (auto _ : state) {
    double worst = 0.0;
    for (const auto& p : c.props()) worst = std::max(worst, dynosize::ScanFigureOfMerit(p).fm_max);
    benchmark::DoNotOptimize(worst);
  }
  state.counters["props"] = static_cast<double>(c.props().size());
}
BENCHMARK(BM_ScanFigureOfMeritAllProps)->Unit(benchmark::kMillisecond);

// One propeller evaluation from measured tables (UIUC, forward flight).
void BM_PropEvaluateUiuc(benchmark::State& state) {
  const dynosize::Catalog c = dynosize::Catalog::Load(kCatalog);
  const dynosize::PropModel m(c.prop("uiuc_v1_apcsf_10.0x4.7_2"));
  double w = dynosize::RpmToRadPerSec(5000);
  for (auto _ : state) {
    auto ev = m.Evaluate(w, 1.2, 8.0);
    benchmark::DoNotOptimize(ev);
  }
}
BENCHMARK(BM_PropEvaluateUiuc);

}  // namespace

BENCHMARK_MAIN();
