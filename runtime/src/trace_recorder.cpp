#include "teleop/runtime/trace_recorder.h"

#include <algorithm>
#include <cinttypes>
#include <limits>
#include <memory>
#include <stdexcept>

#include "teleop/runtime/status_names.h"

namespace teleop::runtime {
namespace {

// `value` / `unit` with `decimals` digits after the point, from integers: exact, where a double
// would round the last digits of a time since the epoch
void write_fixed(FILE* f, int64_t value, int64_t unit, int decimals) {
  const int64_t magnitude = value < 0 ? -value : value;
  std::fprintf(f, "%s%" PRId64 ".%0*" PRId64, value < 0 ? "-" : "", magnitude / unit, decimals, magnitude % unit);
}

// a state column's value: its state's name; one that names no state (NaN, a fraction) as a number
void write_state(FILE* f, double value) {
  for (const msg::NodeState s : kNodeStates) {
    if (value == static_cast<double>(s)) {
      std::fprintf(f, ",%s", state_name(s));
      return;
    }
  }
  std::fprintf(f, ",%.9g", value);
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

void TraceRecorder::write_header(FILE* f) const {
  std::fputs("t_s,wall_s,lateness_us", f);
  for (const auto& c : columns_) std::fprintf(f, ",%s", c.c_str());
  std::fputc('\n', f);
}

void TraceRecorder::write_row(FILE* f, const TraceTime& time, const double* values) const {
  write_fixed(f, time.t_ns, 1'000'000'000, 9);
  std::fputc(',', f);
  write_fixed(f, time.wall_ns, 1'000'000'000, 9);
  std::fputc(',', f);
  write_fixed(f, time.lateness_ns, 1'000, 3);
  for (size_t i = 0; i < columns_.size(); ++i) {
    if (state_columns_[i]) {
      write_state(f, values[i]);
    } else {
      std::fprintf(f, ",%.9g", values[i]);
    }
  }
  std::fputc('\n', f);
}

void TraceRecorder::write_csv(const std::string& path) const {
  const std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!file) throw std::runtime_error("cannot write the trace " + path);
  FILE* f = file.get();
  write_header(f);
  // the oldest held row is the one after the newest when the ring has wrapped
  const uint64_t first = recorded() > capacity_rows_ ? recorded() % capacity_rows_ : 0;
  for (uint64_t k = 0; k < rows(); ++k) {
    const uint64_t slot = (first + k) % capacity_rows_;
    write_row(f, times_[slot], values_.data() + slot * columns_.size());
  }
  if (std::fflush(f) != 0 || std::ferror(f)) throw std::runtime_error("error writing the trace " + path);
}

}  // namespace teleop::runtime
