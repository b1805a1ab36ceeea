#pragma once
// The time trace of a node: one row of named values per control cycle, kept in preallocated
// memory during the run and written as CSV after it.

#include <cstdint>
#include <string>
#include <vector>

namespace teleop::runtime {

/// Keeps the most recent `capacity_rows` rows (a ring: older rows are overwritten and counted as
/// dropped). Construction and write_csv() allocate; begin_row() does not (real-time safe).
class TraceRecorder {
 public:
  /// `columns`: the value names (without the time column); `capacity_rows` >= 1.
  TraceRecorder(std::vector<std::string> columns, uint64_t capacity_rows);

  /// Starts the row of the cycle released at `now_ns` (CLOCK_MONOTONIC) and returns its
  /// `columns().size()` values, all NaN until the caller fills them. Real-time safe.
  double* begin_row(int64_t now_ns);

  const std::vector<std::string>& columns() const { return columns_; }
  uint64_t capacity_rows() const { return capacity_rows_; }
  /// Rows held now (at most the capacity).
  uint64_t rows() const { return rows_recorded_ < capacity_rows_ ? rows_recorded_ : capacity_rows_; }
  /// Rows overwritten because the ring was full.
  uint64_t rows_dropped() const { return rows_recorded_ - rows(); }

  /// Writes the held rows, oldest first: header `t_s,<columns>`, then `t_s` in seconds with 9
  /// decimals and the values as `%.9g`. Throws std::runtime_error when the file cannot be written.
  void write_csv(const std::string& path) const;

 private:
  std::vector<std::string> columns_;
  uint64_t capacity_rows_;
  uint64_t rows_recorded_ = 0;
  std::vector<int64_t> times_ns_;
  std::vector<double> values_;  ///< row-major, capacity_rows_ x columns_.size()
};

}  // namespace teleop::runtime
