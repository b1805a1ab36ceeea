#include "echo_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "teleop/common/clock.h"

namespace teleop::bench {
namespace {

/// The child between fork and exec: async-signal-safe calls only.
[[noreturn]] void exec_echo(pid_t parent, int ready_write_fd, const char* exe, char* const* argv) {
  prctl(PR_SET_PDEATHSIG, SIGTERM);  // the echo dies with the pinger, whatever kills it
  if (getppid() != parent) _exit(127);
  fcntl(ready_write_fd, F_SETFD, 0);  // the ready pipe survives exec
  execv(exe, argv);
  _exit(127);
}

/// This executable's path, resolved before the fork: under valgrind (bench/roundtrip_profile.sh)
/// exec of /proc/self/exe would start valgrind's own binary, its readlink gives the benchmark's.
std::string own_executable() {
  char path[4096];
  const ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
  if (n <= 0) return "/proc/self/exe";
  return std::string(path, static_cast<size_t>(n));
}

}  // namespace

std::vector<std::string> echo_args(Variant v, const Options& opt) {
  const double run_s = static_cast<double>(opt.warmup + opt.samples) / opt.rate_hz;
  // a hard upper bound on the echo's life even if the pinger vanished without a signal
  const double max_s = 2.0 * opt.timeout_s + 2.0 * run_s + 3.0 / opt.rate_hz + 30.0;
  std::vector<std::string> args{"--role",        "echo",
                                "--variant",     name_of(v),
                                "--domain",      std::to_string(opt.domain),
                                "--topics",      std::to_string(opt.topics),
                                "--warmup",      std::to_string(opt.warmup),
                                "--max-seconds", std::to_string(max_s)};
  if (!opt.pki.empty()) args.insert(args.end(), {"--pki", opt.pki});
  return args;
}

EchoProcess::EchoProcess(const std::vector<std::string>& role_args) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe2: ") + std::strerror(errno));
  std::vector<std::string> args{"teleop_roundtrip_bench"};
  args.insert(args.end(), role_args.begin(), role_args.end());
  args.push_back("--ready-fd");
  args.push_back(std::to_string(fds[1]));
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string exe = own_executable();
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) {
    const int err = errno;
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error(std::string("fork: ") + std::strerror(err));
  }
  if (pid_ == 0) exec_echo(parent, fds[1], exe.c_str(), argv.data());
  close(fds[1]);
  ready_fd_ = fds[0];
}

std::string EchoProcess::wait_ready(int64_t deadline_mono_ns) {
  std::string line;
  while (true) {
    throw_if_stopped();
    const int64_t left_ms = (deadline_mono_ns - monotonic_now_ns()) / kNsPerMs;
    if (left_ms <= 0) throw std::runtime_error("the echo process did not get ready in time");
    pollfd p{ready_fd_, POLLIN, 0};
    const int n = poll(&p, 1, static_cast<int>(std::min<int64_t>(left_ms, 100)));
    if (n <= 0) continue;  // timeout slice or EINTR
    char c = 0;
    const ssize_t r = read(ready_fd_, &c, 1);
    if (r == 0) throw std::runtime_error("the echo process exited before it was ready" + exit_description());
    if (r < 0) continue;
    if (c == '\n') break;
    line.push_back(c);
  }
  if (line.rfind("ready", 0) != 0) throw std::runtime_error("unexpected message from the echo: " + line);
  return line.substr(5);
}

void EchoProcess::check_alive() {
  if (pid_ <= 0) throw std::runtime_error("the echo process is gone");
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) {
    pid_ = -1;
    status_ = status;
    throw std::runtime_error("the echo process died" + exit_description());
  }
}

void EchoProcess::stop() {
  if (ready_fd_ >= 0) {
    close(ready_fd_);
    ready_fd_ = -1;
  }
  if (pid_ <= 0) return;
  kill(pid_, SIGTERM);
  const int64_t give_up = monotonic_now_ns() + 3 * kNsPerS;
  int status = 0;
  while (true) {
    const pid_t r = waitpid(pid_, &status, WNOHANG);
    if (r == pid_ || (r < 0 && errno == ECHILD)) break;
    if (monotonic_now_ns() > give_up) {
      std::fprintf(stderr, "teleop_roundtrip_bench: echo %d ignored SIGTERM, killing it\n", static_cast<int>(pid_));
      kill(pid_, SIGKILL);
      while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
      break;
    }
    usleep(10'000);
  }
  status_ = status;
  pid_ = -1;
}

std::string EchoProcess::exit_description() {
  if (pid_ > 0) {
    int status = 0;
    // it closed its pipe: it is exiting; give it a moment to be reapable
    for (int i = 0; i < 100; ++i) {
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        status_ = status;
        break;
      }
      usleep(10'000);
    }
  }
  if (!status_) return "";
  if (WIFEXITED(*status_)) return " (exit status " + std::to_string(WEXITSTATUS(*status_)) + ")";
  if (WIFSIGNALED(*status_)) return " (killed by signal " + std::to_string(WTERMSIG(*status_)) + ")";
  return "";
}

}  // namespace teleop::bench
