#pragma once
// A trace's CSV file, written in whole rows and counted exactly. The text is formatted in memory
// and handed to write(2); what the device refuses (a full disk) stays pending for the next flush,
// so that the file never holds the end of a row without its start, and a row counts as written
// only once all its bytes are in the file. One thread uses it (the trace's writer, or the node at
// exit); never the control loop.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/runtime/trace_recorder.h"

namespace teleop::runtime {

class TraceFile {
 public:
  /// Creates (or empties) `path`; throws std::runtime_error naming it when it cannot.
  explicit TraceFile(std::string path);
  ~TraceFile();
  TraceFile(const TraceFile&) = delete;
  TraceFile& operator=(const TraceFile&) = delete;

  /// Where the next text goes: append a whole row, then call end_row(); text that is no row (the
  /// header) without it.
  std::string& text() { return pending_; }
  void end_row() { row_ends_.push_back(pending_.size()); }

  /// Hands the pending text to the kernel. False on a write error (error() says which); the part
  /// not written stays pending, for the next flush.
  bool flush();

  /// Rows all of whose bytes are in the file.
  uint64_t rows_written() const { return rows_written_; }
  /// Rows formatted but not (wholly) in the file.
  uint64_t rows_pending() const { return row_ends_.size(); }
  /// The last write error ("No space left on device"); empty when none happened.
  const std::string& error() const { return error_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  std::string pending_;
  std::vector<size_t> row_ends_;  ///< offsets in pending_ just past each row
  uint64_t rows_written_ = 0;
  std::string error_;
};

/// Rows per write(2): a few tens of kB, so that a refused write keeps little pending.
inline constexpr uint64_t kTraceRowsPerWrite = 256;

/// What writing a recorder's rows to a file came to: the rows in the file, and the write error
/// that stopped it (empty when none).
struct TraceFileResult {
  uint64_t rows_written = 0;
  std::string error;
};

/// Writes the header and every row `recorder` holds, oldest first, to `path`, stopping at the first
/// refused write (at exit a full disk will not empty itself). Throws std::runtime_error naming the
/// path only when the file cannot be created.
TraceFileResult write_held_rows(const TraceRecorder& recorder, const std::string& path);

}  // namespace teleop::runtime
