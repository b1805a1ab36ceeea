#pragma once
// The time trace of a node: one row of named values per control cycle, kept in preallocated
// memory during the run and written as CSV after it, or streamed to the file while the node runs
// (trace_stream.h). Every row starts with when its cycle ran (TraceTime); a column holding a
// msg::NodeState (is_state_column) is stored as its number and written as its name.

#include <atomic>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace teleop::runtime {

/// When a row's cycle ran. All three are written before the node's columns.
struct TraceTime {
  int64_t t_ns = 0;         ///< its release on CLOCK_MONOTONIC: `t_s` (aligns the traces of one host)
  int64_t wall_ns = 0;      ///< CLOCK_REALTIME at its release: `wall_s` (aligns hosts as far as their clocks agree)
  int64_t lateness_ns = 0;  ///< its release minus its deadline: `lateness_us`
};

/// The trace's convention for a column holding a msg::NodeState: `state`, or `<prefix>_state` (an
/// arm of a group). Written as state_name() (`running`, `safe_hold`), so a trace reads without the IDL.
bool is_state_column(std::string_view name);

/// Keeps the most recent `capacity_rows` rows (a ring: older rows are overwritten and counted as
/// dropped). Construction and write_csv() allocate; begin_row() does not (real-time safe). One
/// thread records; another may read completed rows while it does (copy_row()).
class TraceRecorder {
 public:
  /// `columns`: the value names (without the time columns); `capacity_rows` >= 1.
  TraceRecorder(std::vector<std::string> columns, uint64_t capacity_rows);

  /// Starts the row of the cycle that ran at `time` and returns its `columns().size()` values, all
  /// NaN until the caller fills them; the row before is complete from now on. Real-time safe.
  double* begin_row(const TraceTime& time);
  /// Marks the last row complete (the recording has ended).
  void finish();

  const std::vector<std::string>& columns() const { return columns_; }
  uint64_t capacity_rows() const { return capacity_rows_; }
  /// Rows held now (at most the capacity).
  uint64_t rows() const;
  /// Rows overwritten because the ring was full.
  uint64_t rows_dropped() const { return recorded() - rows(); }
  /// Rows recorded since the start and filled completely (their index is below this).
  uint64_t rows_complete() const { return complete_.load(std::memory_order_acquire); }
  /// Copies the complete row `index` (counted from the start) into `time` and `values`
  /// (columns().size() of them). False when the row is no longer in the newest half of the ring
  /// (the recorder is half a ring from overwriting it: a reader that far behind would race with
  /// it) or was overwritten during the copy. Any thread.
  bool copy_row(uint64_t index, TraceTime& time, double* values) const;

  /// Row `k` of the rows held now, oldest first (k < rows()): for writing them once the recording
  /// has ended (no begin_row() meanwhile).
  const TraceTime& held_time(uint64_t k) const { return times_[held_slot(k)]; }
  const double* held_values(uint64_t k) const { return values_.data() + held_slot(k) * columns_.size(); }

  /// Writes the held rows, oldest first: header `t_s,wall_s,lateness_us,<columns>`, then `t_s` and
  /// `wall_s` in seconds with 9 decimals (exact ns), `lateness_us` with 3, the values as `%.9g`
  /// (a state column: its state's name; `nan` where unset). Throws std::runtime_error when the file
  /// cannot be written.
  void write_csv(const std::string& path) const;
  /// Appends the CSV's header line, or one row (columns().size() values), in that format, to `text`.
  void append_header(std::string& text) const;
  void append_row(std::string& text, const TraceTime& time, const double* values) const;

 private:
  uint64_t recorded() const { return recorded_.load(std::memory_order_relaxed); }
  /// The ring's slot of held row `k`: the oldest held row is the one after the newest when the ring has wrapped.
  uint64_t held_slot(uint64_t k) const {
    const uint64_t first = recorded() > capacity_rows_ ? recorded() % capacity_rows_ : 0;
    return (first + k) % capacity_rows_;
  }
  /// Row `index` is in the newest half of the ring (the ring holds [recorded - capacity, recorded)).
  bool safely_held(uint64_t index) const {
    return index + (capacity_rows_ + 1) / 2 >= recorded_.load(std::memory_order_relaxed);
  }

  std::vector<std::string> columns_;
  std::vector<bool> state_columns_;  ///< is_state_column() of each column
  uint64_t capacity_rows_;
  std::atomic<uint64_t> recorded_{0};
  std::atomic<uint64_t> complete_{0};
  std::vector<TraceTime> times_;
  std::vector<double> values_;  ///< row-major, capacity_rows_ x columns_.size()
};

}  // namespace teleop::runtime
