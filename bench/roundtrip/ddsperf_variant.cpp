// The outside reference (ddsperf): Cyclone DDS's own ping/pong at the same rate and payload
// size, best effort, run as two processes. ddsperf prints, once a second, the percentiles of
// half the round trip of that second; the figures here are the count-weighted means of those
// per-second percentiles (max/min: the extremes), doubled, over the seconds after the first.
// CPU: both processes from /proc over the same seconds.

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>

#include "pinger.h"
#include "teleop/common/clock.h"

namespace teleop::bench {
namespace {

/// ddsperf as a child process; its stdout readable from `out_fd` when asked for. Terminated and
/// reaped by the destructor.
class DdsPerfProcess {
 public:
  DdsPerfProcess(const std::vector<std::string>& args, bool capture_stdout) {
    int fds[2] = {-1, -1};
    if (capture_stdout && pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe2 failed");
    std::vector<std::string> argv_text{"ddsperf"};
    argv_text.insert(argv_text.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_text) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t parent = getpid();
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    if (pid_ == 0) {
      prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (getppid() != parent) _exit(127);
      const int devnull = open("/dev/null", O_WRONLY);
      dup2(capture_stdout ? fds[1] : devnull, STDOUT_FILENO);
      execvp("ddsperf", argv.data());
      _exit(127);
    }
    if (capture_stdout) {
      close(fds[1]);
      out_ = fdopen(fds[0], "r");
    }
  }
  ~DdsPerfProcess() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      int status = 0;
      const int64_t give_up = monotonic_now_ns() + 3 * kNsPerS;
      while (waitpid(pid_, &status, WNOHANG) == 0) {
        if (monotonic_now_ns() > give_up) {
          kill(pid_, SIGKILL);
          waitpid(pid_, &status, 0);
          break;
        }
        usleep(10'000);
      }
    }
    if (out_ != nullptr) fclose(out_);
  }
  DdsPerfProcess(const DdsPerfProcess&) = delete;
  DdsPerfProcess& operator=(const DdsPerfProcess&) = delete;

  pid_t pid() const { return pid_; }
  /// The next line of its output; false at its end.
  bool read_line(std::string& line) {
    char buf[1024];
    if (out_ == nullptr || std::fgets(buf, sizeof buf, out_) == nullptr) return false;
    line = buf;
    return true;
  }

 private:
  pid_t pid_ = -1;
  FILE* out_ = nullptr;
};

/// One per-second latency line of ddsperf's ping: "... mean Xus min Xus 50% Xus 90% Xus 99% Xus max Xus cnt N".
struct SecondLine {
  double min_us = 0, p50_us = 0, p90_us = 0, p99_us = 0, max_us = 0;
  uint64_t count = 0;
};

bool parse_latency_line(const std::string& line, SecondLine& out) {
  const auto value_after = [&line](const char* key, double& v) {
    const auto at = line.find(key);
    if (at == std::string::npos) return false;
    v = std::strtod(line.c_str() + at + std::strlen(key), nullptr);
    return true;
  };
  double cnt = 0;
  return value_after(" min ", out.min_us) && value_after(" 50% ", out.p50_us) && value_after(" 90% ", out.p90_us) &&
         value_after(" 99% ", out.p99_us) && value_after(" max ", out.max_us) && value_after(" cnt ", cnt) &&
         (out.count = static_cast<uint64_t>(cnt), true);
}

}  // namespace

bool ddsperf_available() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path != nullptr ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && access((dir + "/ddsperf").c_str(), X_OK) == 0) return true;
  }
  return false;
}

VariantResult run_ddsperf_variant(const Options& opt, size_t payload_size) {
  VariantResult result;
  result.variant = Variant::kDdsPerf;
  result.topics = 1;
  if (!ddsperf_available()) {
    std::printf("  ddsperf not installed (apt-get install cyclonedds-tools): skipped\n");
    return result;
  }
  const std::string domain = std::to_string(opt.domain);
  const int seconds = std::max(2, static_cast<int>(std::ceil(static_cast<double>(opt.samples) / opt.rate_hz)));
  DdsPerfProcess pong({"-i", domain, "-u", "pong"}, false);
  DdsPerfProcess ping({"-i", domain, "-u", "-D", std::to_string(seconds + 2), "ping",
                       std::to_string(static_cast<long>(opt.rate_hz)) + "Hz", "size", std::to_string(payload_size)},
                      true);
  // the first second holds discovery and matching: measure from the first report on
  std::string line;
  SecondLine s;
  int64_t ping_cpu0 = -1;
  int64_t pong_cpu0 = -1;
  double w50 = 0, w90 = 0, w99 = 0, max_us = 0, min_us = 1e18;
  uint64_t count = 0;
  int measured = 0;
  while (measured < seconds && ping.read_line(line)) {
    throw_if_stopped();
    if (!parse_latency_line(line, s)) continue;
    if (ping_cpu0 < 0) {
      ping_cpu0 = process_cpu_ns(ping.pid());
      pong_cpu0 = process_cpu_ns(pong.pid());
      continue;
    }
    w50 += s.p50_us * static_cast<double>(s.count);
    w90 += s.p90_us * static_cast<double>(s.count);
    w99 += s.p99_us * static_cast<double>(s.count);
    max_us = std::max(max_us, s.max_us);
    min_us = std::min(min_us, s.min_us);
    count += s.count;
    ++measured;
  }
  if (count == 0) {
    std::printf("  ddsperf gave no latency figures (discovery on domain %d blocked?): skipped\n", opt.domain);
    result.external = RttFigures{};
    return result;
  }
  result.cpu_ping_ns = process_cpu_ns(ping.pid()) - ping_cpu0;
  const int64_t pong_cpu1 = process_cpu_ns(pong.pid());
  result.cpu_echo_ns = pong_cpu0 < 0 || pong_cpu1 < 0 ? -1 : pong_cpu1 - pong_cpu0;
  const auto rtt_ns = [](double half_us) { return static_cast<int64_t>(std::llround(2.0 * half_us * 1e3)); };
  const double n = static_cast<double>(count);
  RttFigures f;
  f.received = count;
  f.p50_ns = rtt_ns(w50 / n);
  f.p90_ns = rtt_ns(w90 / n);
  f.p99_ns = rtt_ns(w99 / n);
  f.max_ns = rtt_ns(max_us);
  f.min_ns = rtt_ns(min_us);
  result.external = f;
  result.sent = count;
  return result;
}

}  // namespace teleop::bench
