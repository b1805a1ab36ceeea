#include "trace_stream.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "teleop/common/clock.h"
#include "teleop/runtime/realtime.h"

namespace teleop::runtime {
namespace {

// while writes keep failing, one line this often says how it stands
constexpr int64_t kFailureLogPeriodNs = 10'000'000'000;

}  // namespace

TraceStream::TraceStream(const TraceRecorder& recorder, const std::string& path, int64_t period_ns)
    : recorder_(recorder), file_(path), row_(recorder.columns().size()) {
  recorder_.append_header(file_.text());
  thread_ = std::thread([this, period_ns] { run(period_ns); });
}

TraceStream::~TraceStream() { stop(); }

void TraceStream::run(int64_t period_ns) {
  name_own_thread("trace");
  while (!stop_.wait_for(std::chrono::nanoseconds(period_ns))) log_outcome(drain());
}

bool TraceStream::drain() {
  // the tail of a refused write first: the file goes on where it stopped, never mid-row
  const bool ok = file_.flush() && write_complete_rows();
  if (!ok) count_overwritten_rows();
  written_ = file_.rows_written();
  return ok;
}

// while writes fail the writer formats nothing new: the rows the ring has overwritten meanwhile are
// counted lost now, not only when the disk takes rows again
void TraceStream::count_overwritten_rows() {
  TraceTime time;
  while (next_ < recorder_.rows_complete() && !recorder_.copy_row(next_, time, row_.data())) {
    ++next_;
    ++lost_;
  }
}

bool TraceStream::write_complete_rows() {
  const uint64_t complete = recorder_.rows_complete();
  for (; next_ < complete; ++next_) {
    TraceTime time;
    if (!recorder_.copy_row(next_, time, row_.data())) {
      ++lost_;
      continue;
    }
    recorder_.append_row(file_.text(), time, row_.data());
    file_.end_row();
    if (file_.rows_pending() >= kTraceRowsPerWrite && !file_.flush()) {
      ++next_;
      return false;
    }
  }
  return file_.flush();
}

void TraceStream::log_outcome(bool ok) {
  const int64_t now_ns = monotonic_now_ns();
  if (!ok && !failing_) {
    spdlog::error("trace {}: write failed ({}): {} rows in the file; the next wait in the ring, lost once it wraps",
                  file_.path(), file_.error(), file_.rows_written());
    failure_logged_ns_ = now_ns;
  } else if (!ok && now_ns - failure_logged_ns_ >= kFailureLogPeriodNs) {
    spdlog::error("trace {}: writes still failing ({}): {} rows written, {} lost so far", file_.path(), file_.error(),
                  file_.rows_written(), lost_.load());
    failure_logged_ns_ = now_ns;
  } else if (ok && failing_) {
    spdlog::warn("trace {}: writing again ({} rows written, {} lost)", file_.path(), file_.rows_written(),
                 lost_.load());
  }
  failing_ = !ok;
  failed_ = failed_ || !ok;
}

bool TraceStream::stop() {
  if (thread_.joinable()) {
    stop_.request();
    thread_.join();
    log_outcome(drain());
    // what never reached the file: the rows a refused write kept back, and those it kept from being formatted
    lost_ = recorder_.rows_complete() - file_.rows_written();
  }
  return !failed_;
}

}  // namespace teleop::runtime
