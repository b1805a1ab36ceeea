#include "isolated_plugin_device.h"

#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <new>
#include <stdexcept>
#include <thread>

#include "teleop/common/clock.h"

extern char** environ;

namespace teleop::leader {
namespace {

// the host's arguments, as posix_spawn takes them
std::vector<std::string> host_arguments(const HostedPluginConfig& c, int fd) {
  std::vector<std::string> args{c.host, "--fd", std::to_string(fd), "--library", c.library, "--period",
                                std::to_string(c.period_s), "--joints", std::to_string(c.joints)};
  for (const auto& [key, value] : c.settings) args.insert(args.end(), {"--setting", key + "=" + value});
  return args;
}

// how a child ended, for the log
std::string how_it_ended(int status) {
  if (WIFSIGNALED(status)) {
    return std::string("was killed by signal ") + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  }
  return "exited with " + std::to_string(WEXITSTATUS(status));
}

}  // namespace

IsolatedPluginDevice::IsolatedPluginDevice(const HostedPluginConfig& config) : config_(config) {
  // an anonymous memory the host inherits (no CLOEXEC): nothing named left behind after a crash
  fd_ = ::memfd_create("teleop_device_channel", 0);
  if (fd_ < 0 || ::ftruncate(fd_, sizeof(DeviceChannel)) != 0) {
    throw std::runtime_error(std::string("leader.plugin: cannot make the device host's memory: ") + std::strerror(errno));
  }
  void* shared = ::mmap(nullptr, sizeof(DeviceChannel), PROT_READ | PROT_WRITE, MAP_SHARED, fd_, 0);
  if (shared == MAP_FAILED) throw std::runtime_error(std::string("leader.plugin: cannot map it: ") + std::strerror(errno));
  channel_ = new (shared) DeviceChannel();
  std::vector<std::string> args = host_arguments(config_, fd_);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  if (const int e = ::posix_spawn(&pid_, config_.host.c_str(), nullptr, nullptr, argv.data(), environ); e != 0) {
    throw std::runtime_error("leader.plugin: cannot start " + config_.host + ": " + std::strerror(e));
  }
  // setup time: wait for the host to open the device
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (channel_->phase.load(std::memory_order_acquire) == DeviceChannel::kOpening) {
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      throw std::runtime_error("leader.plugin: the device host " + how_it_ended(status) + " before it opened the device");
    }
    if (std::chrono::steady_clock::now() > until) throw std::runtime_error("leader.plugin: the device host did not open the device within 10 s");
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (channel_->phase.load() == DeviceChannel::kFailed) {
    channel_->error[sizeof channel_->error - 1] = '\0';
    throw std::runtime_error(channel_->error);
  }
  channel_->name[sizeof channel_->name - 1] = '\0';
}

IsolatedPluginDevice::~IsolatedPluginDevice() {
  int status = 0;
  const pid_t ended = pid_ > 0 ? ::waitpid(pid_, &status, WNOHANG) : -1;
  if (ended == pid_) {
    std::fprintf(stderr, "leader.plugin: the device host of %s %s\n", channel_->name, how_it_ended(status).c_str());
  } else if (ended == 0) {
    // running: SIGTERM closes the device, which stops rendering
    ::kill(pid_, SIGTERM);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > until) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  if (channel_ != nullptr) {
    channel_->~DeviceChannel();
    ::munmap(channel_, sizeof(DeviceChannel));
  }
  if (fd_ >= 0) ::close(fd_);
}

bool IsolatedPluginDevice::host_alive(int64_t now_ns) {
  const int64_t beat = channel_->heartbeat_ns.load(std::memory_order_acquire);
  const bool alive = static_cast<double>(now_ns - beat) * 1e-9 <= config_.host_timeout_s;
  // a host starved beyond the timeout that beats again is back, like a device plugged in again;
  // a crashed one never beats again
  if (!alive && !lost_) ++losses_;
  lost_ = !alive;
  return alive;
}

bool IsolatedPluginDevice::read(DeviceState& state) {
  if (!host_alive(monotonic_now_ns())) return false;
  // a host preempted in the middle of its write leaves the last whole state, one period older
  (void)channel_->state.load(hosted_);
  if (hosted_.read_ok == 0) return false;
  // what a device of its kind reports, the rest left as the leader set it (plugin_device.h)
  const DeviceState& h = hosted_.state;
  if (config_.cartesian) {
    state.position_m = h.position_m;
    state.orientation_wxyz = h.orientation_wxyz;
    state.twist = h.twist;
  } else {
    state.q_rad = h.q_rad;
    state.dq_radps = h.dq_radps;
  }
  state.buttons |= h.buttons;
  return true;
}

bool IsolatedPluginDevice::write(const JointVector& feedback_nm) {
  if (lost_) return false;
  channel_->feedback.store(feedback_nm);
  return true;
}

void IsolatedPluginDevice::report_counters(std::vector<std::pair<std::string, double>>& counters) const {
  counters.emplace_back("plugin_failed_reads", static_cast<double>(channel_->failed_reads.load()));
  counters.emplace_back("plugin_invalid_reads", static_cast<double>(channel_->invalid_reads.load()));
  counters.emplace_back("plugin_failed_writes", static_cast<double>(channel_->failed_writes.load()));
  counters.emplace_back("plugin_limited_efforts", static_cast<double>(channel_->limited_efforts.load()));
  counters.emplace_back("plugin_host_losses", static_cast<double>(losses_));
}

}  // namespace teleop::leader
