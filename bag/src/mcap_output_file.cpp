#include "mcap_output_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "mcap_compression.h"

namespace teleop::bag::mcap {
namespace {

std::string io_error(const std::string& path, const char* doing, int err) {
  const std::string full = err == ENOSPC || err == EDQUOT ? " (disk full)" : "";
  return path + ": " + doing + " failed" + full + ": " + std::strerror(err);
}

}  // namespace

OutputFile::OutputFile(std::string path, int64_t max_bytes) : path_(std::move(path)), max_bytes_(max_bytes) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    const int err = errno;
    throw BagError(err == EEXIST ? path_ + ": exists already (a recording is never overwritten)"
                                 : io_error(path_, "creating the file", err));
  }
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::append(ByteSpan bytes, bool capped) {
  if (fd_ < 0) throw BagError(path_ + ": the file is closed");
  if (torn_) throw BagError(path_ + ": not written further after a failed write (it ends in a partial record)");
  if (capped && max_bytes_ > 0 && offset_ + bytes.size > static_cast<uint64_t>(max_bytes_)) {
    throw BagError(path_ + ": disk full (the size cap of " + std::to_string(max_bytes_) + " bytes is reached)");
  }
  size_t done = 0;
  while (done < bytes.size) {
    const ssize_t n = ::write(fd_, bytes.data + done, bytes.size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      // a partial record is left behind: readers stop before it, and a summary is never put after it
      offset_ += done;
      torn_ = done > 0;
      throw BagError(io_error(path_, "writing", err));
    }
    done += static_cast<size_t>(n);
  }
  crc_ = crc32_of(bytes, crc_);
  offset_ += bytes.size;
}

void OutputFile::close() {
  if (fd_ < 0) return;
  const int fd = std::exchange(fd_, -1);
  const bool synced = ::fsync(fd) == 0;
  const int err = errno;
  ::close(fd);
  if (!synced) throw BagError(io_error(path_, "syncing", err));
}

}  // namespace teleop::bag::mcap
