#include "teleop/common/output_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "teleop/common/config.h"

namespace teleop {

void check_output_file(const std::string& path, const std::string& flag) {
  // O_EXCL tells a file this check creates (and removes again) from one that was there
  constexpr int kFlags = O_WRONLY | O_NONBLOCK | O_CLOEXEC;
  int fd = ::open(path.c_str(), kFlags | O_CREAT | O_EXCL, 0644);
  const bool created = fd >= 0;
  if (!created && errno == EEXIST) fd = ::open(path.c_str(), kFlags);
  if (fd < 0) throw ConfigError(flag + " " + path + ": cannot be written: " + std::strerror(errno));
  ::close(fd);
  if (created) ::unlink(path.c_str());
}

}  // namespace teleop
