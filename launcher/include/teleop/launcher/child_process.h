#pragma once
// A node started as a child process, its stdout and stderr merged into one pipe that the
// launcher reads line by line.

#include <sys/types.h>

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace teleop::launcher {

class ChildProcess {
 public:
  /// Starts argv[0] (a path) with the given arguments. The child gets SIGTERM if the launcher
  /// dies, so that no node outlives it. Throws std::runtime_error when it cannot start.
  static ChildProcess spawn(const std::vector<std::string>& argv);

  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  /// Kills (SIGKILL) and reaps a child that is still running.
  ~ChildProcess();

  pid_t pid() const { return pid_; }
  /// The read end of the output pipe (for poll()); -1 once it reached EOF.
  int output_fd() const { return output_fd_; }

  /// Reads what is available without blocking and calls `on_line` for each complete line.
  /// At EOF, flushes a last unterminated line and closes the pipe.
  void read_output(const std::function<void(std::string_view)>& on_line);

  /// Sends a signal if the child is still running.
  void signal(int sig);
  /// Reaps the child if it has exited; returns its exit status (128 + signal if killed).
  std::optional<int> try_wait();
  /// Waits up to `timeout_ms` for the exit; nullopt if still running then.
  std::optional<int> wait_for(int timeout_ms);
  std::optional<int> exit_status() const { return exit_status_; }

 private:
  ChildProcess(pid_t pid, int output_fd) : pid_(pid), output_fd_(output_fd) {}
  void close_output();

  pid_t pid_ = -1;
  int output_fd_ = -1;
  std::string partial_line_;
  std::optional<int> exit_status_;
};

}  // namespace teleop::launcher
