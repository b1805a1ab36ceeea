#pragma once
// A node's trace written while the node runs: a thread of its own appends the rows the loop has
// completed to the CSV every `period`, so that a node killed with SIGKILL (or crashed) leaves its
// trace up to the last period behind, where write_csv() at exit would leave nothing. The loop
// records as before (TraceRecorder::begin_row, real-time safe); the file is the same CSV.

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "teleop/runtime/trace_recorder.h"

namespace teleop::runtime {

class TraceStream {
 public:
  /// Opens `path` (throws std::runtime_error naming it when it cannot), writes the header and
  /// starts the writer. `recorder` must outlive this.
  TraceStream(const TraceRecorder& recorder, const std::string& path, int64_t period_ns = 50'000'000);
  ~TraceStream();
  TraceStream(const TraceStream&) = delete;
  TraceStream& operator=(const TraceStream&) = delete;

  /// Writes what is complete (call TraceRecorder::finish() first for the last row), closes the
  /// file and ends the thread. Throws std::runtime_error on a write error.
  void stop();

  /// Rows in the file (flushed to the kernel).
  uint64_t rows_written() const { return written_.load(); }
  /// Rows the ring overwrote before the writer got to them (a stalled disk).
  uint64_t rows_lost() const { return lost_.load(); }

 private:
  void run(int64_t period_ns);
  /// Appends the complete rows not yet written; false on a write error.
  bool drain();

  const TraceRecorder& recorder_;
  std::string path_;
  std::unique_ptr<FILE, int (*)(FILE*)> file_;
  std::vector<double> row_;
  uint64_t next_ = 0;
  std::atomic<uint64_t> written_{0};
  std::atomic<uint64_t> lost_{0};
  std::atomic<bool> stop_{false};
  std::atomic<bool> failed_{false};
  std::thread thread_;
};

}  // namespace teleop::runtime
