// Cost of the node time trace: one row per cycle on the control path (begin_row + filling it)
// and writing the CSV after the run. Results: docs/experiments.md.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "teleop/runtime/trace_recorder.h"

namespace {

std::vector<std::string> columns(int n) {
  std::vector<std::string> out;
  for (int i = 0; i < n; ++i) out.push_back("c" + std::to_string(i));
  return out;
}

// per cycle: start a row and write every column, as a node's trace_row() does
void BM_RecordRow(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  teleop::runtime::TraceRecorder recorder(columns(n), 20'000);
  int64_t t = 0;
  for (auto _ : state) {
    t += 1'000'000;
    double* row = recorder.begin_row({t, t, 0});
    for (int c = 0; c < n; ++c) row[c] = static_cast<double>(t) * 1e-9 + c;
    benchmark::DoNotOptimize(row);
  }
}
BENCHMARK(BM_RecordRow)->Arg(16)->Arg(37);

// after the run: 10 s at 1 kHz written as CSV
void BM_WriteTenSecondsAt1kHz(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  teleop::runtime::TraceRecorder recorder(columns(n), 10'000);
  for (int64_t i = 0; i < 10'000; ++i) {
    double* row = recorder.begin_row({i * 1'000'000, i * 1'000'000, 0});
    for (int c = 0; c < n; ++c) row[c] = 0.123456789 * static_cast<double>(i + c);
  }
  const std::string path = (std::filesystem::temp_directory_path() / "teleop_trace_bench.csv").string();
  for (auto _ : state) recorder.write_csv(path);
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteTenSecondsAt1kHz)->Arg(16)->Arg(37)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
