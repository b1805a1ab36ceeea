// Throughput of the bag writer: 300-byte messages (a joint command's size) on three topics from
// two writers, with the default commit and metadata periods, into a bag on the temporary folder's
// disk. A recorder must sustain well over 20,000 messages/s. Results: docs/recording.md.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "teleop/bag/bag_writer.h"

namespace {

using teleop::bag::BagWriter;

std::string fresh_bag_dir() {
  const auto dir = std::filesystem::temp_directory_path() / ("teleop_bag_bench_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

// per iteration: one message appended (and, every 200 ms, a commit; every second, metadata.yaml)
void BM_WriteMessages(benchmark::State& state) {
  const auto size = static_cast<size_t>(state.range(0));
  const std::string dir = fresh_bag_dir();
  {
    BagWriter writer({dir});
    int topics[3];
    for (int i = 0; i < 3; ++i)
      topics[i] = writer.add_topic({"teleop/bench/" + std::to_string(i), "teleop/msg/Bench", "", "", ""});
    std::vector<uint8_t> data(size, 0x5A);
    teleop::bag::WriterGuid writers[2] = {{1}, {2}};
    int64_t t = 1'700'000'000'000'000'000;
    uint64_t n = 0;
    for (auto _ : state) {
      writer.write(topics[n % 3], t, t, writers[n % 2], data.data(), data.size());
      t += 1'000;
      ++n;
    }
    writer.close();  // the last commit counts
    state.counters["commits"] = static_cast<double>(writer.stats().commits);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(size));
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_WriteMessages)->Arg(300)->MinTime(3.0)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
