#pragma once
// What the tests on a virtual CAN interface share: the interface name, can-utils as
// independent peers, and the hand emulator as a child process. The harness (run_in_vm.sh) puts
// the test binaries, teleop_hand_emulator, cansend and candump on PATH.

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace teleop::can::test {

/// vcan0, or $TELEOP_VCAN_IF (set by the harness when it runs directly on a host with vcan).
inline std::string iface() {
  const char* e = std::getenv("TELEOP_VCAN_IF");
  return e != nullptr && *e != '\0' ? e : "vcan0";
}

/// Runs `cansend <iface> <frame>`; true when it exited 0.
inline bool cansend(const std::string& frame) {
  const std::string cmd = "cansend " + iface() + " " + frame;
  return std::system(cmd.c_str()) == 0;
}

/// A program run from PATH with its arguments; stopped with SIGTERM when the object goes away.
class ChildProcess {
 public:
  explicit ChildProcess(std::vector<std::string> args) {
    pid_ = ::fork();
    if (pid_ == 0) {
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execvp(argv[0], argv.data());
      std::_Exit(127);
    }
  }
  ~ChildProcess() { stop(); }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool started() const { return pid_ > 0; }
  /// True while it runs (false once it exited; the exit status is then collected).
  bool running() {
    if (pid_ <= 0) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return false;
    }
    return true;
  }
  /// Sends a signal (SIGUSR1: the emulator releases its object's support).
  bool signal(int sig) const { return pid_ > 0 && ::kill(pid_, sig) == 0; }
  /// Sets its nice value (below 0, as root: it goes before the other processes).
  bool set_nice(int nice) const { return pid_ > 0 && ::setpriority(PRIO_PROCESS, static_cast<id_t>(pid_), nice) == 0; }
  /// SIGTERM and wait; the wait status (-1 when not running).
  int stop() {
    if (pid_ <= 0) return -1;
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return status;
  }

 private:
  pid_t pid_ = -1;
};

/// teleop_hand_emulator (or $TELEOP_HAND_EMULATOR) on the test interface, with extra arguments.
class EmulatorProcess : public ChildProcess {
 public:
  explicit EmulatorProcess(const std::vector<std::string>& extra = {}) : ChildProcess(arguments(extra)) {}

 private:
  static std::vector<std::string> arguments(const std::vector<std::string>& extra) {
    const char* env = std::getenv("TELEOP_HAND_EMULATOR");
    std::vector<std::string> args = {env != nullptr ? env : "teleop_hand_emulator", "--interface", iface()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
};

}  // namespace teleop::can::test
