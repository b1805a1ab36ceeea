#include "atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "teleop/bag/bag_error.h"

namespace teleop::bag {
namespace {

[[noreturn]] void fail(const std::string& path, const char* what, int error) {
  const std::string reason = error == ENOSPC ? "disk full" : std::strerror(error);
  throw BagError(path + ": " + what + ": " + reason);
}

void write_all(int fd, const std::string& text, const std::string& path) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path, "writing", errno);
    done += static_cast<size_t>(n);
  }
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(tmp, "creating", errno);
  try {
    write_all(fd, text, tmp);
    // synced before the rename: after a crash the name holds the old or the new text, not nothing
    if (::fsync(fd) != 0) fail(tmp, "syncing", errno);
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(tmp.c_str());
    fail(tmp, "closing", error);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail(path, "renaming the new version into place", errno);
}

}  // namespace teleop::bag
