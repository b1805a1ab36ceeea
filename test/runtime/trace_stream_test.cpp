#include "trace_stream.h"

#include <gtest/gtest.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "teleop/runtime/trace_recorder.h"
#include "test_helpers.h"

namespace teleop::runtime {
namespace {

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// the loop's side: `rows` rows, row i holding (i, 2i) at i us (wall: 1 s later), a pause of `pause` every 10 rows
// (a trace is written while this runs); `finish`: the last row is complete too
void record(TraceRecorder& trace, int rows, std::chrono::microseconds pause, bool finish = true) {
  for (int i = 0; i < rows; ++i) {
    double* row = trace.begin_row({int64_t{i} * 1000, 1'000'000'000 + int64_t{i} * 1000, 0});
    row[0] = i;
    row[1] = 2.0 * i;
    if (i % 10 == 0 && pause.count() > 0) std::this_thread::sleep_for(pause);
  }
  if (finish) trace.finish();
}

TEST(TraceStream, WritesEveryRowInOrderWhileTheLoopRecords) {
  test::TempDir dir("trace_stream");
  // a ring of 8192 rows, written every millisecond: the writer never falls half a ring behind
  TraceRecorder trace({"i", "twice"}, 8192);
  TraceStream stream(trace, dir.path("t.csv"), 1'000'000);
  record(trace, 3000, std::chrono::microseconds(500));
  EXPECT_TRUE(stream.stop());
  EXPECT_EQ(stream.rows_written(), 3000u);
  EXPECT_EQ(stream.rows_lost(), 0u);
  const auto lines = lines_of(dir.path("t.csv"));
  ASSERT_EQ(lines.size(), 3001u);
  EXPECT_EQ(lines[0], "t_s,wall_s,lateness_us,i,twice");
  EXPECT_EQ(lines[1], "0.000000000,1.000000000,0.000,0,0");
  EXPECT_EQ(lines[3000], "0.002999000,1.002999000,0.000,2999,5998");
}

TEST(TraceStream, LeavesTheRowsSoFarInTheFileBeforeTheEnd) {
  // what a SIGKILL leaves: the file up to the writer's last period, whole rows only
  test::TempDir dir("trace_stream");
  TraceRecorder trace({"i", "twice"}, 4096);
  TraceStream stream(trace, dir.path("t.csv"), 1'000'000);
  record(trace, 500, std::chrono::microseconds(0), false);
  for (int i = 0; i < 5000 && stream.rows_written() < 499; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_EQ(stream.rows_written(), 499u);
  const auto lines = lines_of(dir.path("t.csv"));
  // the row being filled (499) is not complete yet; every one before it is there
  ASSERT_EQ(lines.size(), 500u);
  EXPECT_EQ(lines.back(), "0.000498000,1.000498000,0.000,498,996");
  trace.finish();
  stream.stop();
  EXPECT_EQ(lines_of(dir.path("t.csv")).size(), 501u);
}

TEST(TraceStream, CountsTheRowsTheRingOverwroteBeforeTheWriterCame) {
  test::TempDir dir("trace_stream");
  TraceRecorder trace({"i", "twice"}, 8);
  // a writer far slower than the ring: it sleeps through the recording, stop() drains
  TraceStream stream(trace, dir.path("t.csv"), 200'000'000);
  record(trace, 1000, std::chrono::microseconds(0));
  stream.stop();
  EXPECT_EQ(stream.rows_written() + stream.rows_lost(), 1000u);
  EXPECT_GT(stream.rows_lost(), 0u);
  // what was written is whole and in order
  const auto lines = lines_of(dir.path("t.csv"));
  EXPECT_EQ(lines.size(), stream.rows_written() + 1);
  EXPECT_EQ(lines.back(), "0.000999000,1.000999000,0.000,999,1998");
}

// the log lines of a test instead of the console
class CapturedLog {
 public:
  CapturedLog() : previous_(spdlog::default_logger()), sink_(std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(64)) {
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("captured", sink_));
  }
  ~CapturedLog() { spdlog::set_default_logger(previous_); }
  CapturedLog(const CapturedLog&) = delete;
  CapturedLog& operator=(const CapturedLog&) = delete;
  /// The lines logged so far that contain `text`.
  size_t count(const std::string& text) const {
    size_t n = 0;
    for (const std::string& line : sink_->last_formatted()) n += line.find(text) != std::string::npos ? 1 : 0;
    return n;
  }

 private:
  std::shared_ptr<spdlog::logger> previous_;
  std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> sink_;
};

TEST(TraceStream, LogsARefusedWriteWhenItHappensOnlyOnceAndCountsEveryRowLost) {
  CapturedLog log;
  TraceRecorder trace({"i", "twice"}, 8192);
  // a full disk: every write is refused, the header's first
  TraceStream stream(trace, "/dev/full", 1'000'000);
  record(trace, 500, std::chrono::microseconds(0), false);
  const std::string failure = "trace /dev/full: write failed (No space left on device)";
  for (int i = 0; i < 10'000 && log.count(failure) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  // said by the writer while the node runs, not at the end
  EXPECT_EQ(log.count(failure), 1u);
  // a hundred more refused writes: not a line each
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  trace.finish();
  EXPECT_FALSE(stream.stop());
  EXPECT_EQ(log.count("write failed"), 1u);
  EXPECT_EQ(stream.rows_written(), 0u);
  EXPECT_EQ(stream.rows_lost(), 500u);
}

TEST(TraceStream, NamesAFileItCannotWrite) {
  TraceRecorder trace({"a"}, 8);
  try {
    TraceStream stream(trace, "/nonexistent/dir/t.csv");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/t.csv"), std::string::npos);
  }
}

}  // namespace
}  // namespace teleop::runtime
