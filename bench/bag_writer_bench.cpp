// Throughput of the recording writers: 300-byte messages (a joint command's size) on three topics
// from two writers into the temporary folder's disk, as the recorder writes them: a sqlite3 bag
// (default commit and metadata periods) and an MCAP file (zstd, lz4, uncompressed chunks; default
// chunk period and size). A recorder must sustain well over 20,000 messages/s. Results:
// docs/recording.md.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "teleop/bag/bag_writer.h"
#include "teleop/bag/mcap_writer.h"

namespace {

using namespace teleop::bag;
using OpenWriter = std::function<std::unique_ptr<RecordingWriter>(const std::string& path)>;

std::string fresh_path() {
  const auto path = std::filesystem::temp_directory_path() / ("teleop_bag_bench_" + std::to_string(getpid()));
  std::filesystem::remove_all(path);
  return path.string();
}

std::unique_ptr<RecordingWriter> sqlite3_bag(const std::string& path) { return std::make_unique<BagWriter>(BagWriterOptions{path}); }

OpenWriter mcap_file(McapCompression compression) {
  return [compression](const std::string& path) {
    McapWriterOptions options{path};
    options.compression = compression;
    return std::make_unique<McapWriter>(options);
  };
}

// per iteration: one message appended (and, on their periods, commits or chunks)
void BM_WriteMessages(benchmark::State& state, const OpenWriter& open) {
  const auto size = static_cast<size_t>(state.range(0));
  const std::string path = fresh_path();
  uint64_t file_bytes = 0;
  {
    const std::unique_ptr<RecordingWriter> writer = open(path);
    int topics[3];
    for (int i = 0; i < 3; ++i)
      topics[i] = writer->add_topic({"teleop/bench/" + std::to_string(i), "teleop_msgs/msg/Bench", "", "int32 x\n", ""});
    std::vector<uint8_t> data(size, 0x5A);
    for (size_t i = 0; i < size; ++i) data[i] = static_cast<uint8_t>(i % 7 == 0 ? i : 0x5A);  // some structure
    const WriterGuid writers[2] = {{1}, {2}};
    int64_t t = 1'700'000'000'000'000'000;
    uint64_t n = 0;
    for (auto _ : state) {
      writer->write({topics[n % 3], t, t, t, writers[n % 2], data.data(), data.size()});
      t += 1'000;
      ++n;
    }
    writer->close();  // the last commit or chunk counts
    file_bytes = std::filesystem::file_size(writer->data_path());
  }
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(size));
  state.counters["file_bytes_per_msg"] = static_cast<double>(file_bytes) / static_cast<double>(state.iterations());
  std::filesystem::remove_all(path);
}
BENCHMARK_CAPTURE(BM_WriteMessages, sqlite3, OpenWriter(sqlite3_bag))->Arg(300)->MinTime(3.0)->UseRealTime();
BENCHMARK_CAPTURE(BM_WriteMessages, mcap_zstd, mcap_file(McapCompression::kZstd))->Arg(300)->MinTime(3.0)->UseRealTime();
BENCHMARK_CAPTURE(BM_WriteMessages, mcap_lz4, mcap_file(McapCompression::kLz4))->Arg(300)->MinTime(3.0)->UseRealTime();
BENCHMARK_CAPTURE(BM_WriteMessages, mcap_none, mcap_file(McapCompression::kNone))->Arg(300)->MinTime(3.0)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
