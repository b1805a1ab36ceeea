#include "trace_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace teleop::runtime {

TraceFile::TraceFile(std::string path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot write the trace " + path_ + ": " + std::strerror(errno));
}

TraceFile::~TraceFile() { ::close(fd_); }

bool TraceFile::flush() {
  size_t written = 0;
  bool ok = true;
  while (written < pending_.size()) {
    const ssize_t n = ::write(fd_, pending_.data() + written, pending_.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error_ = n < 0 ? std::strerror(errno) : "the device took nothing";
      ok = false;
      break;
    }
    written += static_cast<size_t>(n);
  }
  // the rows that are wholly in the file now; the rest (a row's tail, the rows after it) stays
  size_t done = 0;
  while (done < row_ends_.size() && row_ends_[done] <= written) ++done;
  rows_written_ += done;
  row_ends_.erase(row_ends_.begin(), row_ends_.begin() + static_cast<std::ptrdiff_t>(done));
  for (size_t& end : row_ends_) end -= written;
  pending_.erase(0, written);
  return ok;
}

TraceFileResult write_held_rows(const TraceRecorder& recorder, const std::string& path) {
  TraceFile file(path);
  recorder.append_header(file.text());
  bool ok = true;
  for (uint64_t k = 0; ok && k < recorder.rows(); ++k) {
    recorder.append_row(file.text(), recorder.held_time(k), recorder.held_values(k));
    file.end_row();
    if (file.rows_pending() >= kTraceRowsPerWrite) ok = file.flush();
  }
  if (ok) ok = file.flush();
  return {file.rows_written(), ok ? std::string() : file.error()};
}

}  // namespace teleop::runtime
