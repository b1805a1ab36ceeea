#pragma once
// A node's trace written while the node runs: a thread of its own appends the rows the loop has
// completed to the CSV every `period`, so that a node killed with SIGKILL (or crashed) leaves its
// trace up to the last period behind, where writing it at exit would leave nothing. The loop
// records as before (TraceRecorder::begin_row, real-time safe); the file is the same CSV.
//
// A write the device refuses (a full disk) is logged by the writer at once, then at most every
// 10 s while it lasts, and once more when writing works again; the rows wait in the recorder's ring
// meanwhile and count as lost when the ring overwrote them first. After stop(), rows_written() +
// rows_lost() is every row the loop completed: the file holds exactly rows_written() of them.

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "stop_request.h"
#include "teleop/runtime/trace_recorder.h"
#include "trace_file.h"

namespace teleop::runtime {

class TraceStream {
 public:
  /// Opens `path` (throws std::runtime_error naming it when it cannot), writes the header and
  /// starts the writer. `recorder` must outlive this.
  TraceStream(const TraceRecorder& recorder, const std::string& path, int64_t period_ns = 50'000'000);
  ~TraceStream();
  TraceStream(const TraceStream&) = delete;
  TraceStream& operator=(const TraceStream&) = delete;

  /// Writes what is complete (call TraceRecorder::finish() first for the last row), ends the
  /// thread and closes the file. False when a row did not reach the file (logged when it happened).
  bool stop();

  /// Rows in the file (handed to the kernel whole).
  uint64_t rows_written() const { return written_.load(); }
  /// Rows that will never be in the file: overwritten in the ring before the writer got to them
  /// (a stalled or full disk); after stop() also those a refused write kept back.
  uint64_t rows_lost() const { return lost_.load(); }

 private:
  void run(int64_t period_ns);
  /// Appends the complete rows not yet written; false on a write error.
  bool drain();
  /// Formats the complete rows from next_ on, flushing every kTraceRowsPerWrite rows.
  bool write_complete_rows();
  void count_overwritten_rows();
  /// Logs a refused write at once, then at most every 10 s, and the recovery once.
  void log_outcome(bool ok);

  const TraceRecorder& recorder_;
  TraceFile file_;
  std::vector<double> row_;
  uint64_t next_ = 0;
  std::atomic<uint64_t> written_{0};
  std::atomic<uint64_t> lost_{0};
  StopRequest stop_;
  bool failing_ = false;
  bool failed_ = false;
  int64_t failure_logged_ns_ = 0;
  std::thread thread_;
};

}  // namespace teleop::runtime
