#include "teleop/runtime/trace_recorder.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "teleop/runtime/status_names.h"
#include "trace_file.h"

namespace teleop::runtime {
namespace {

// `value` / `unit` with `decimals` digits after the point, from integers: exact, where a double
// would round the last digits of a time since the epoch
void append_fixed(std::string& text, int64_t value, int64_t unit, int decimals) {
  const int64_t magnitude = value < 0 ? -value : value;
  char number[48];
  const int n = std::snprintf(number, sizeof number, "%s%" PRId64 ".%0*" PRId64, value < 0 ? "-" : "", magnitude / unit,
                              decimals, magnitude % unit);
  text.append(number, static_cast<size_t>(n));
}

void append_value(std::string& text, double value) {
  char number[32];
  const int n = std::snprintf(number, sizeof number, ",%.9g", value);
  text.append(number, static_cast<size_t>(n));
}

// a state column's value: its state's name; one that names no state (NaN, a fraction) as a number
void append_state(std::string& text, double value) {
  for (const msg::NodeState s : kNodeStates) {
    if (value == static_cast<double>(s)) {
      text += ',';
      text += state_name(s);
      return;
    }
  }
  append_value(text, value);
}

}  // namespace

bool is_state_column(std::string_view name) {
  constexpr std::string_view kSuffix = "_state";
  return name == "state" || (name.size() > kSuffix.size() && name.substr(name.size() - kSuffix.size()) == kSuffix);
}

TraceRecorder::TraceRecorder(std::vector<std::string> columns, uint64_t capacity_rows)
    : columns_(std::move(columns)),
      capacity_rows_(capacity_rows),
      times_(capacity_rows),
      values_(capacity_rows * columns_.size()) {
  if (capacity_rows == 0) throw std::invalid_argument("TraceRecorder: capacity must be at least one row");
  for (const std::string& c : columns_) state_columns_.push_back(is_state_column(c));
}

uint64_t TraceRecorder::rows() const { return std::min(recorded(), capacity_rows_); }

double* TraceRecorder::begin_row(const TraceTime& time) {
  const uint64_t index = recorded();
  // the caller filled the row before this one: a reader may take it
  complete_.store(index, std::memory_order_release);
  const uint64_t slot = index % capacity_rows_;
  // counted before the slot is written (a seqlock): a reader copying the row this overwrites
  // sees it gone when it checks again
  recorded_.store(index + 1, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);
  times_[slot] = time;
  double* row = values_.data() + slot * columns_.size();
  for (size_t i = 0; i < columns_.size(); ++i) row[i] = std::numeric_limits<double>::quiet_NaN();
  return row;
}

void TraceRecorder::finish() { complete_.store(recorded(), std::memory_order_release); }

bool TraceRecorder::copy_row(uint64_t index, TraceTime& time, double* values) const {
  if (index >= rows_complete() || !safely_held(index)) return false;
  const uint64_t slot = index % capacity_rows_;
  time = times_[slot];
  std::copy_n(values_.data() + slot * columns_.size(), columns_.size(), values);
  // still in the newest half after the copy: the recorder did not come near it meanwhile
  std::atomic_thread_fence(std::memory_order_acquire);
  return safely_held(index);
}

void TraceRecorder::append_header(std::string& text) const {
  text += "t_s,wall_s,lateness_us";
  for (const auto& c : columns_) text += "," + c;
  text += '\n';
}

void TraceRecorder::append_row(std::string& text, const TraceTime& time, const double* values) const {
  append_fixed(text, time.t_ns, 1'000'000'000, 9);
  text += ',';
  append_fixed(text, time.wall_ns, 1'000'000'000, 9);
  text += ',';
  append_fixed(text, time.lateness_ns, 1'000, 3);
  for (size_t i = 0; i < columns_.size(); ++i) {
    if (state_columns_[i]) {
      append_state(text, values[i]);
    } else {
      append_value(text, values[i]);
    }
  }
  text += '\n';
}

void TraceRecorder::write_csv(const std::string& path) const {
  const TraceFileResult result = write_held_rows(*this, path);
  if (!result.error.empty()) throw std::runtime_error("error writing the trace " + path + ": " + result.error);
}

}  // namespace teleop::runtime
