// Reading speed of the log readers: rows per second on synthetic million-row files (written
// once to the temp folder, outside the timed loop). Report medians:
//   ./log_bench --benchmark_min_time=0.2   (5 repetitions, aggregates only)
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "logs/log_reader.h"

namespace {

constexpr std::size_t kRows = 1000000;

std::string TempPath(const char* name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

// Canonical: one operating point per row (the strict reader's worst case: every cell parsed).
const std::string& CanonicalFile() {
  static const std::string path = [] {
    const std::string p = TempPath("dynosize_bench_canonical.csv");
    std::ofstream out(p, std::ios::binary);
    out << "time_s,vdc_v,throttle,rpm,torque_nm,idc_a,vll_rms_v,irms_a,pac_w\n";
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0.05, 1.0);
    char line[256];
    for (std::size_t i = 0; i < kRows; ++i) {
      const double tr = u(rng);
      const int n = std::snprintf(line, sizeof line, "%.3f,%.4f,%.5f,%.1f,%.6f,%.5f,%.5f,%.5f,%.4f\n",
                                  0.01 * static_cast<double>(i), 16.0 - tr, tr, 20000.0 * tr,
                                  0.2 * tr * tr, 20.0 * tr * tr, 10.8 * tr, 18.0 * tr * tr,
                                  300.0 * tr * tr * tr);
      out.write(line, n);
    }
    return p;
  }();
  return path;
}

// RCbenchmark-style: BOM, 21 columns with trailing comma, asynchronous empty cells, a 100 Hz
// step test (0.5 s transients, 5 s steps) - the plateau search runs on it.
const std::string& RcbenchmarkFile() {
  static const std::string path = [] {
    const std::string p = TempPath("dynosize_bench_rcbenchmark.csv");
    std::ofstream out(p, std::ios::binary);
    out << "\xEF\xBB\xBFTime (s),ESC signal (\xC2\xB5s),Servo 1 (\xC2\xB5s),Servo 2 (\xC2\xB5s),"
           "Servo 3 (\xC2\xB5s),AccX (g),AccY (g),AccZ (g),Torque (N\xC2\xB7m),Thrust (gf),"
           "Voltage (V),Current (A),Motor Electrical Speed (RPM),Motor Optical Speed (RPM),"
           "Electrical Power (W),Mechanical Power (W),Motor Efficiency (%),"
           "Propeller Mech. Efficiency (gf/W),Overall Efficiency (gf/W),Vibration (g),App message,\n";
    std::mt19937 rng(2);
    std::normal_distribution<double> n01(0.0, 1.0);
    char line[512];
    for (std::size_t i = 0; i < kRows; ++i) {
      const double t = 0.01 * static_cast<double>(i);
      const int step = static_cast<int>(t / 5.0) % 20;
      const double tr = 0.05 * (step + 1);
      const double rpm = 20000.0 * tr * (1.0 + 0.003 * n01(rng));
      const double amps = 20.0 * tr * tr * (1.0 + 0.003 * n01(rng));
      const bool torque_sampled = i % 3 != 0;  // asynchronous sensor
      char torque[32] = "";
      if (torque_sampled) std::snprintf(torque, sizeof torque, "%.6f", -0.2 * tr * tr);
      const int n = std::snprintf(
          line, sizeof line,
          "%.6f,%.0f,,,,0.0125,-1.0281,-0.0003,%s,%.4f,%.5f,%.5f,%.0f,0,%.3f,%.3f,%.2f,%.3f,%.3f,0.0586,,\n",
          t, 1000.0 + 1000.0 * tr, torque, 800.0 * tr * tr, 16.0 - 0.5 * tr, amps, rpm,
          16.0 * amps, 0.2 * tr * tr * rpm * 0.1047, 70.0, 3.1, 2.5);
      out.write(line, n);
    }
    return p;
  }();
  return path;
}

// Tyto Flight Stand style: every cell quoted, one averaged row per step; written with decimal
// commas and ';' (a spreadsheet re-save in a decimal-comma locale) when `decimal_comma`. Rows
// 4.5 s apart: read row by row (no plateau search), so this times the quoted-cell splitter
// and the number parsers.
const std::string& TytoFile(bool decimal_comma) {
  static const std::string paths[2] = {
      TempPath("dynosize_bench_tyto.csv"), TempPath("dynosize_bench_tyto_decimal_comma.csv")};
  static bool written[2] = {false, false};
  const std::string& p = paths[decimal_comma ? 1 : 0];
  if (written[decimal_comma ? 1 : 0]) return p;
  written[decimal_comma ? 1 : 0] = true;
  std::ofstream out(p, std::ios::binary);
  const char d = decimal_comma ? ';' : ',';
  const char* names[] = {"Time (s)", "Throttle (\xC2\xB5s)", "Rotation speed (rpm)", "Thrust (kgf)",
                         "Torque (N\xE2\x8B\x85m)", "Voltage (V)", "Current (A)", "Electrical power (W)"};
  for (int k = 0; k < 8; ++k) out << (k ? std::string(1, d) : "") << '"' << names[k] << '"';
  out << "\n";
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.05, 1.0);
  char line[512];
  for (std::size_t i = 0; i < kRows; ++i) {
    const double tr = u(rng);
    int n = std::snprintf(line, sizeof line,
                          "\"%.4f\"%c\"%.0f\"%c\"%.3f\"%c\"%.6f\"%c\"%.6f\"%c\"%.5f\"%c\"%.5f\"%c\"%.3f\"\n",
                          4.5 * static_cast<double>(i), d, 1000.0 + 1000.0 * tr, d, 7000.0 * tr, d,
                          3.2 * tr * tr, d, 0.6 * tr * tr, d, 25.0 - tr, d, 24.0 * tr * tr, d,
                          (25.0 - tr) * 24.0 * tr * tr);
    if (decimal_comma) {
      for (int k = 0; k < n; ++k) line[k] = line[k] == '.' ? ',' : line[k];
    }
    out.write(line, n);
  }
  return p;
}

void BM_ReadTytoQuoted(benchmark::State& state) {
  const bool dc = state.range(0) != 0;
  const std::string& p = TytoFile(dc);
  dynosize::logs::LogReadOptions o;
  o.decimal_comma = dc;
  std::size_t rows = 0;
  for (auto _ : state) {
    const auto t = dynosize::logs::ReadLog(p, o);
    rows = t.rows();
    benchmark::DoNotOptimize(rows);
  }
  state.counters["rows_per_s"] =
      benchmark::Counter(static_cast<double>(kRows), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["points"] = static_cast<double>(rows);
}

void BM_ReadCanonical(benchmark::State& state) {
  const std::string& p = CanonicalFile();
  std::size_t rows = 0;
  for (auto _ : state) {
    const auto t = dynosize::logs::ReadLog(p);
    rows = t.rows();
    benchmark::DoNotOptimize(rows);
  }
  state.counters["rows_per_s"] =
      benchmark::Counter(static_cast<double>(kRows), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_s"] = benchmark::Counter(
      static_cast<double>(std::filesystem::file_size(p)), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["points"] = static_cast<double>(rows);
}

void BM_ReadRcbenchmarkStepTest(benchmark::State& state) {
  const std::string& p = RcbenchmarkFile();
  std::size_t plateaus = 0;
  for (auto _ : state) {
    const auto t = dynosize::logs::ReadLog(p);
    plateaus = t.plateaus_found;
    benchmark::DoNotOptimize(plateaus);
  }
  state.counters["rows_per_s"] =
      benchmark::Counter(static_cast<double>(kRows), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_s"] = benchmark::Counter(
      static_cast<double>(std::filesystem::file_size(p)), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["plateaus"] = static_cast<double>(plateaus);
}

BENCHMARK(BM_ReadCanonical)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_ReadRcbenchmarkStepTest)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
// Arg 0: decimal points and ','; arg 1: decimal commas and ';' (--decimal-comma).
BENCHMARK(BM_ReadTytoQuoted)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
