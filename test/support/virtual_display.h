#pragma once
// An X server without a screen (Xvfb, Debian's xvfb) for the tests of windows: started on a free
// display number it chooses itself (-displayfd), DISPLAY set for this process and the processes
// it starts, stopped again at the end. Mesa's software OpenGL (libgl1-mesa-dri) draws there.

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

extern char** environ;

namespace teleop::test {

class VirtualDisplay {
 public:
  /// Starts Xvfb with one 24-bit screen of `width` x `height`. Throws std::runtime_error when it
  /// is not installed or does not come up within 10 s.
  explicit VirtualDisplay(int width = 1600, int height = 1200) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
    const std::string fd = std::to_string(fds[1]);
    const std::string screen = std::to_string(width) + "x" + std::to_string(height) + "x24";
    const char* argv[] = {"Xvfb",         "-displayfd", fd.c_str(), "-screen",  "0",
                          screen.c_str(), "-nolisten",  "tcp",      "-noreset", nullptr};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addclose(&actions, fds[0]);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    const int rc = posix_spawnp(&pid_, "Xvfb", &actions, nullptr, const_cast<char**>(argv), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(fds[1]);
    if (rc != 0) {
      close(fds[0]);
      throw std::runtime_error("cannot start Xvfb (Debian's package xvfb; scripts/setup.sh installs it)");
    }
    // Xvfb writes the display number it took, then a newline, once it accepts connections
    std::string number;
    pollfd p{fds[0], POLLIN, 0};
    while (number.find('\n') == std::string::npos && poll(&p, 1, 10'000) > 0) {
      char buf[16];
      const ssize_t n = read(fds[0], buf, sizeof buf);
      if (n <= 0) break;
      number.append(buf, static_cast<size_t>(n));
    }
    close(fds[0]);
    if (number.find('\n') == std::string::npos) {
      stop();
      throw std::runtime_error("Xvfb did not report a display within 10 s");
    }
    display_ = ":" + number.substr(0, number.find('\n'));
    const char* old = std::getenv("DISPLAY");
    if (old != nullptr) old_display_ = old;
    had_display_ = old != nullptr;
    setenv("DISPLAY", display_.c_str(), 1);
  }
  ~VirtualDisplay() {
    if (had_display_) {
      setenv("DISPLAY", old_display_.c_str(), 1);
    } else {
      unsetenv("DISPLAY");
    }
    stop();
  }
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;

  const std::string& display() const { return display_; }

 private:
  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
  }

  pid_t pid_ = -1;
  std::string display_;
  std::string old_display_;
  bool had_display_ = false;
};

}  // namespace teleop::test
