#include "trace_file.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <string>

#include "test_helpers.h"

namespace teleop::runtime {
namespace {

// the process may write files up to `bytes` while it lives (a disk that fills up at a known
// byte); a write across the limit is cut short there, the next one refused (EFBIG)
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    // else the kernel ends the process with SIGXFSZ
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    set(bytes);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;
  void set(rlim_t bytes) {
    const rlimit limit{bytes, saved_.rlim_max};
    setrlimit(RLIMIT_FSIZE, &limit);
  }

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = nullptr;
};

TEST(TraceFile, CountsOnlyWholeRowsAndGoesOnWhereARefusedWriteStopped) {
  test::TempDir dir("trace_file");
  const std::string path = dir.path("t.csv");
  TraceFile file(path);
  file.text() += "h\n";
  // ten rows of ten bytes: the limit of 47 bytes cuts the fifth row after 5 of its bytes
  for (int i = 0; i < 10; ++i) {
    file.text() += "row " + std::to_string(i) + ",abc\n";
    file.end_row();
  }
  {
    FileSizeLimit limit(47);
    EXPECT_FALSE(file.flush());
    EXPECT_EQ(file.error(), "File too large");
    EXPECT_EQ(file.rows_written(), 4u);
    EXPECT_EQ(file.rows_pending(), 6u);
    EXPECT_EQ(test::read_text(path).size(), 47u);
    limit.set(RLIM_INFINITY);
    EXPECT_TRUE(file.flush());
  }
  EXPECT_EQ(file.rows_written(), 10u);
  EXPECT_EQ(file.rows_pending(), 0u);
  std::string expected = "h\n";
  for (int i = 0; i < 10; ++i) expected += "row " + std::to_string(i) + ",abc\n";
  EXPECT_EQ(test::read_text(path), expected);
}

TEST(TraceFile, WritesTheHeldRowsAndSaysWhereAFullDeviceStoppedThem) {
  TraceRecorder recorder({"v"}, 1000);
  for (int i = 0; i < 1000; ++i) recorder.begin_row({i, 0, 0})[0] = i;
  recorder.finish();
  const TraceFileResult full = write_held_rows(recorder, "/dev/full");
  EXPECT_EQ(full.rows_written, 0u);
  EXPECT_EQ(full.error, "No space left on device");
  test::TempDir dir("trace_file");
  const TraceFileResult written = write_held_rows(recorder, dir.path("t.csv"));
  EXPECT_EQ(written.rows_written, 1000u);
  EXPECT_TRUE(written.error.empty()) << written.error;
}

}  // namespace
}  // namespace teleop::runtime
