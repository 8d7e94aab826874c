// Calibration throughput: refitting every DriveCalc motor from MData.csv (target: all
// ~1,060 motors with a no-load point with rpm and >= 3 loaded points in under 1 s). The file is
// read once outside the timed loop. Run:
//   build-bench/calibrate_bench --benchmark_repetitions=5 --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "calibration/drivecalc_refit.h"
#include "logs/log_reader.h"

namespace {

const std::string kMData = std::string(DYNOSIZE_SHARED_DIR) + "/data/drivecalc/MData.csv";

void BM_RefitDriveCalcAll(benchmark::State& state) {
  if (!std::filesystem::exists(kMData)) {
    state.SkipWithError("shared/data/drivecalc/MData.csv not found");
    return;
  }
  dynosize::logs::LogReadOptions o;
  o.format = dynosize::logs::LogFormat::kDriveCalc;
  o.drivecalc_keep_no_load_without_speed = true;
  const auto table = dynosize::logs::ReadLog(kMData, o);
  std::size_t fitted = 0;
  for (auto _ : state) {
    const auto r = dynosize::calibration::RefitDriveCalc(table);
    fitted = r.fits.size();
    benchmark::DoNotOptimize(fitted);
  }
  state.counters["motors"] = static_cast<double>(fitted);
  state.counters["motors_per_s"] =
      benchmark::Counter(static_cast<double>(fitted), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_RefitDriveCalcAll)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
