#include "teleop/runtime/trace_recorder.h"

#include <algorithm>
#include <cinttypes>
#include <limits>
#include <memory>
#include <stdexcept>

namespace teleop::runtime {

TraceRecorder::TraceRecorder(std::vector<std::string> columns, uint64_t capacity_rows)
    : columns_(std::move(columns)),
      capacity_rows_(capacity_rows),
      times_ns_(capacity_rows),
      values_(capacity_rows * columns_.size()) {
  if (capacity_rows == 0) throw std::invalid_argument("TraceRecorder: capacity must be at least one row");
}

uint64_t TraceRecorder::rows() const { return std::min(recorded(), capacity_rows_); }

double* TraceRecorder::begin_row(int64_t now_ns) {
  const uint64_t index = recorded();
  // the caller filled the row before this one: a reader may take it
  complete_.store(index, std::memory_order_release);
  const uint64_t slot = index % capacity_rows_;
  // counted before the slot is written (a seqlock): a reader copying the row this overwrites
  // sees it gone when it checks again
  recorded_.store(index + 1, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);
  times_ns_[slot] = now_ns;
  double* row = values_.data() + slot * columns_.size();
  for (size_t i = 0; i < columns_.size(); ++i) row[i] = std::numeric_limits<double>::quiet_NaN();
  return row;
}

void TraceRecorder::finish() { complete_.store(recorded(), std::memory_order_release); }

bool TraceRecorder::copy_row(uint64_t index, int64_t& t_ns, double* values) const {
  if (index >= rows_complete() || !safely_held(index)) return false;
  const uint64_t slot = index % capacity_rows_;
  t_ns = times_ns_[slot];
  std::copy_n(values_.data() + slot * columns_.size(), columns_.size(), values);
  // still in the newest half after the copy: the recorder did not come near it meanwhile
  std::atomic_thread_fence(std::memory_order_acquire);
  return safely_held(index);
}

void TraceRecorder::write_header(FILE* f, const std::vector<std::string>& columns) {
  std::fputs("t_s", f);
  for (const auto& c : columns) std::fprintf(f, ",%s", c.c_str());
  std::fputc('\n', f);
}

void TraceRecorder::write_row(FILE* f, int64_t t, const double* values, size_t count) {
  // integer seconds and nanoseconds: exact, where a double would round the last digits
  std::fprintf(f, "%s%" PRId64 ".%09" PRId64, t < 0 ? "-" : "", (t < 0 ? -t : t) / 1'000'000'000,
               (t < 0 ? -t : t) % 1'000'000'000);
  for (size_t i = 0; i < count; ++i) std::fprintf(f, ",%.9g", values[i]);
  std::fputc('\n', f);
}

void TraceRecorder::write_csv(const std::string& path) const {
  const std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!file) throw std::runtime_error("cannot write the trace " + path);
  FILE* f = file.get();
  write_header(f, columns_);
  // the oldest held row is the one after the newest when the ring has wrapped
  const uint64_t first = recorded() > capacity_rows_ ? recorded() % capacity_rows_ : 0;
  for (uint64_t k = 0; k < rows(); ++k) {
    const uint64_t slot = (first + k) % capacity_rows_;
    write_row(f, times_ns_[slot], values_.data() + slot * columns_.size(), columns_.size());
  }
  if (std::fflush(f) != 0 || std::ferror(f)) throw std::runtime_error("error writing the trace " + path);
}

}  // namespace teleop::runtime
