#include "teleop/runtime/trace_recorder.h"

#include <cinttypes>
#include <cstdio>
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

double* TraceRecorder::begin_row(int64_t now_ns) {
  const uint64_t slot = rows_recorded_ % capacity_rows_;
  ++rows_recorded_;
  times_ns_[slot] = now_ns;
  double* row = values_.data() + slot * columns_.size();
  for (size_t i = 0; i < columns_.size(); ++i) row[i] = std::numeric_limits<double>::quiet_NaN();
  return row;
}

void TraceRecorder::write_csv(const std::string& path) const {
  const std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!file) throw std::runtime_error("cannot write the trace " + path);
  FILE* f = file.get();
  std::fputs("t_s", f);
  for (const auto& c : columns_) std::fprintf(f, ",%s", c.c_str());
  std::fputc('\n', f);
  // the oldest held row is the one after the newest when the ring has wrapped
  const uint64_t first = rows_recorded_ > capacity_rows_ ? rows_recorded_ % capacity_rows_ : 0;
  for (uint64_t k = 0; k < rows(); ++k) {
    const uint64_t slot = (first + k) % capacity_rows_;
    const int64_t t = times_ns_[slot];
    // integer seconds and nanoseconds: exact, where a double would round the last digits
    std::fprintf(f, "%s%" PRId64 ".%09" PRId64, t < 0 ? "-" : "", (t < 0 ? -t : t) / 1'000'000'000,
                 (t < 0 ? -t : t) % 1'000'000'000);
    const double* row = values_.data() + slot * columns_.size();
    for (size_t i = 0; i < columns_.size(); ++i) std::fprintf(f, ",%.9g", row[i]);
    std::fputc('\n', f);
  }
  if (std::fflush(f) != 0 || std::ferror(f)) throw std::runtime_error("error writing the trace " + path);
}

}  // namespace teleop::runtime
