#include "trace_stream.h"

#include <chrono>
#include <stdexcept>

namespace teleop::runtime {

TraceStream::TraceStream(const TraceRecorder& recorder, const std::string& path, int64_t period_ns)
    : recorder_(recorder), path_(path), file_(std::fopen(path.c_str(), "w"), &std::fclose), row_(recorder.columns().size()) {
  if (!file_) throw std::runtime_error("cannot write the trace " + path);
  recorder_.write_header(file_.get());
  thread_ = std::thread([this, period_ns] { run(period_ns); });
}

TraceStream::~TraceStream() {
  try {
    stop();
  } catch (const std::exception&) {
    // a destructor reports nothing; stop() called before it does
  }
}

void TraceStream::run(int64_t period_ns) {
  while (!stop_.load()) {
    std::this_thread::sleep_for(std::chrono::nanoseconds(period_ns));
    if (!stop_.load() && !drain()) failed_ = true;
  }
}

bool TraceStream::drain() {
  FILE* f = file_.get();
  const uint64_t complete = recorder_.rows_complete();
  uint64_t written = 0;
  for (; next_ < complete; ++next_) {
    TraceTime time;
    if (!recorder_.copy_row(next_, time, row_.data())) {
      ++lost_;
      continue;
    }
    recorder_.write_row(f, time, row_.data());
    ++written;
  }
  // to the kernel now: what is there survives the process; counted once it is there
  const bool ok = std::fflush(f) == 0 && !std::ferror(f);
  written_ += written;
  return ok;
}

void TraceStream::stop() {
  if (!thread_.joinable()) return;
  stop_ = true;
  thread_.join();
  const bool ok = drain() && !failed_.load();
  file_.reset();
  if (!ok) throw std::runtime_error("error writing the trace " + path_);
}

}  // namespace teleop::runtime
