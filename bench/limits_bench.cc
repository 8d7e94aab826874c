// Limits: big inputs read in time proportional to their size with bounded
// memory, pathological inputs refused quickly. Inputs are generated at run time in the temp
// folder (outside the timed loops). Run:
//   ./limits_bench --benchmark_min_time=0.2 --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// Counters: items_per_second (rows or catalog entries), peak_rss_MiB (getrusage ru_maxrss of
// the whole process after the benchmark: benchmarks run smallest first, so it is the peak of the
// largest input so far), rss_growth_B_per_item (peak growth over the process's RSS before the
// benchmark, divided by the input's items: what the reader keeps per row/entry).
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "catalog/catalog.h"
#include "common/error.h"
#include "common/json_file.h"
#include "logs/log_reader.h"

namespace {

namespace fs = std::filesystem;

double PeakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

std::string TempPath(const std::string& name) {
  return (fs::temp_directory_path() / ("dynosize_limits_" + std::to_string(getpid()) + "_" + name))
      .string();
}

// A canonical log of `rows` operating points (the strict reader parses every cell).
std::string CanonicalLog(std::size_t rows) {
  const std::string p = TempPath("log_" + std::to_string(rows) + ".csv");
  if (fs::exists(p)) return p;
  std::ofstream out(p, std::ios::binary);
  out << "time_s,vdc_v,throttle,rpm,torque_nm,idc_a\n";
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.05, 1.0);
  char line[160];
  for (std::size_t i = 0; i < rows; ++i) {
    const double tr = u(rng);
    const int n = std::snprintf(line, sizeof line, "%.3f,%.4f,%.5f,%.1f,%.6f,%.5f\n",
                                0.01 * static_cast<double>(i), 16.0 - tr, tr, 20000.0 * tr,
                                0.2 * tr * tr, 20.0 * tr * tr);
    out.write(line, n);
  }
  return p;
}

// A catalog folder with one file of `entries` motors.
std::string CatalogDir(std::size_t entries) {
  const std::string dir = TempPath("catalog_" + std::to_string(entries));
  if (fs::exists(dir)) return dir;
  fs::create_directories(dir);
  std::ofstream out(dir + "/big.json", std::ios::binary);
  out << "{\n  \"motors\": [\n";
  for (std::size_t k = 0; k < entries; ++k) {
    out << (k ? ",\n" : "") << "    {\"id\": \"m" << k << "\", \"name\": \"Motor " << k
        << "\", \"type\": \"bldc\", \"kv_rpm_per_v\": " << 300 + k % 2000
        << ", \"rm_ohm\": 0.12, \"io_a\": 0.5, \"mass_kg\": 0.1, \"source\": {\"dataset\": "
           "\"generated\", \"values\": {\"rm_ohm\": \"assumed\"}}}";
  }
  out << "\n  ]\n}\n";
  return dir;
}

void BM_ReadCanonicalLog(benchmark::State& state) {
  const auto rows = static_cast<std::size_t>(state.range(0));
  const std::string path = CanonicalLog(rows);
  const double rss0 = PeakRssMiB();
  for (auto _ : state) {
    auto t = dynosize::logs::ReadLog(path);
    benchmark::DoNotOptimize(t.rows());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(rows));
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(fs::file_size(path)));
  state.counters["peak_rss_MiB"] = PeakRssMiB();
  state.counters["rss_growth_B_per_item"] = (PeakRssMiB() - rss0) * 1048576.0 / static_cast<double>(rows);
}
BENCHMARK(BM_ReadCanonicalLog)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_LoadCatalog(benchmark::State& state) {
  const auto entries = static_cast<std::size_t>(state.range(0));
  const std::string dir = CatalogDir(entries);
  const double rss0 = PeakRssMiB();
  for (auto _ : state) {
    auto c = dynosize::Catalog::Load(dir);
    benchmark::DoNotOptimize(c.size());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(entries));
  state.counters["peak_rss_MiB"] = PeakRssMiB();
  state.counters["rss_growth_B_per_item"] = (PeakRssMiB() - rss0) * 1048576.0 / static_cast<double>(entries);
}
BENCHMARK(BM_LoadCatalog)->Arg(1000)->Arg(10000)->Arg(30000)->Unit(benchmark::kMillisecond);

// A 1 GiB file whose second line never ends (a sparse file: the hole reads as NUL bytes, and
// nothing is written to disk). The reader refuses it after max_line_bytes + one buffer.
void BM_RefuseGigabyteLine(benchmark::State& state) {
  const std::string path = TempPath("gigabyte_line.csv");
  {
    std::ofstream(path) << "time_s,vdc_v,throttle,rpm,torque_nm,idc_a\n";
    if (truncate(path.c_str(), 1LL << 30) != 0) {
      state.SkipWithError("cannot make a sparse file");
      return;
    }
  }
  for (auto _ : state) {
    try {
      (void)dynosize::logs::ReadLog(path);
      state.SkipWithError("a 1 GiB line was accepted");
      break;
    } catch (const dynosize::DataError&) {
    }
  }
  state.counters["peak_rss_MiB"] = PeakRssMiB();
  fs::remove(path);
}
BENCHMARK(BM_RefuseGigabyteLine)->Unit(benchmark::kMillisecond);

// JSON nested a million levels deep: refused at the depth limit, not by a stack overflow.
void BM_RefuseDeepJson(benchmark::State& state) {
  const std::string text = std::string(1000000, '[') + std::string(1000000, ']');
  for (auto _ : state) {
    try {
      (void)dynosize::ParseJsonText(text, "deep.json");
      state.SkipWithError("deep JSON was accepted");
      break;
    } catch (const dynosize::DataError&) {
    }
  }
}
BENCHMARK(BM_RefuseDeepJson)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
