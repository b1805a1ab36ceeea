#include "teleop/common/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "teleop/common/config.h"

namespace teleop {
namespace {

// closes the descriptor on every way out
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

const char* kind_of(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// refuses anything but a regular file, by what the open descriptor is (no race with a rename)
void check_regular(int fd, const std::string& path) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw ConfigError(path + ": cannot read the file: " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw ConfigError(path + ": is a folder, not a configuration file");
  if (!S_ISREG(st.st_mode)) {
    throw ConfigError(path + ": is " + kind_of(st.st_mode) +
                      ", not a regular file: refused (reading it could wait or run forever)");
  }
}

std::string read_all(int fd, const std::string& path) {
  std::string text;
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) return text;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw ConfigError(path + ": cannot read the file: " + std::strerror(errno));
    }
    text.append(buffer, static_cast<size_t>(n));
  }
}

}  // namespace

std::string read_input_file(const std::string& path) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait until some process opens it for writing
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (fd.get() < 0) throw ConfigError(path + ": cannot open the file");
  check_regular(fd.get(), path);
  return read_all(fd.get(), path);
}

}  // namespace teleop
