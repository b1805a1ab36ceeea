// teleop_device_host: a leader's device plugin in a process of its own (leader.plugin.isolation:
// process, docs/devices/plugins.md), so that a vendor SDK that crashes takes this process down and
// not the leader, which sees the heartbeat stop and holds. Started by the leader with the shared
// memory it made (device_channel.h) as an inherited descriptor:
//   teleop_device_host --fd N --library PATH --period S --joints J [--setting KEY=VALUE ...]
// It opens the device (its failure written into the channel for the leader to report), then at
// the leader's period reads the device into the channel and renders the newest feedback. It ends
// on SIGTERM, or when the leader dies (PR_SET_PDEATHSIG), closing the device: it stops rendering.
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "device_channel.h"
#include "plugin_device.h"
#include "teleop/common/clock.h"
#include "teleop/common/rate_pacer.h"
#include "teleop/common/version.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

teleop::leader::PluginSettings parse_settings(const std::vector<std::string>& pairs) {
  teleop::leader::PluginSettings settings;
  for (const std::string& p : pairs) {
    const size_t eq = p.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("--setting " + p + ": expected KEY=VALUE");
    settings.emplace_back(p.substr(0, eq), p.substr(eq + 1));
  }
  return settings;
}

void publish_counters(const teleop::leader::PluginDevice& device, teleop::leader::DeviceChannel& channel) {
  channel.failed_reads.store(device.failed_reads(), std::memory_order_relaxed);
  channel.invalid_reads.store(device.invalid_reads(), std::memory_order_relaxed);
  channel.failed_writes.store(device.failed_writes(), std::memory_order_relaxed);
  channel.limited_efforts.store(device.limited_efforts(), std::memory_order_relaxed);
}

// one period: the device's state out, the newest feedback in
void serve(teleop::leader::PluginDevice& device, teleop::leader::DeviceChannel& channel,
           teleop::leader::HostedState& hosted, teleop::JointVector& feedback, int64_t now_ns) {
  hosted.state.buttons = 0;
  hosted.read_ok = device.read(hosted.state) ? 1u : 0u;
  channel.state.store(hosted);
  channel.heartbeat_ns.store(now_ns, std::memory_order_release);
  (void)channel.feedback.load(feedback);  // kept: the last one whole
  (void)device.write(feedback);
  publish_counters(device, channel);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"teleop_device_host: a leader's device plugin in a process of its own"};
  app.set_version_flag("--version", teleop::version_text());
  int fd = -1;
  std::string library;
  double period_s = 1e-3;
  size_t joints = 7;
  std::vector<std::string> pairs;
  app.add_option("--fd", fd, "the leader's shared memory (device_channel.h)")->required();
  app.add_option("--library", library, "the plugin")->required();
  app.add_option("--period", period_s, "the leader's period [s]")->check(CLI::PositiveNumber);
  app.add_option("--joints", joints, "leader.joints");
  app.add_option("--setting", pairs, "KEY=VALUE of leader.plugin.settings; repeatable");
  CLI11_PARSE(app, argc, argv);
  // the leader gone, the device stops rendering: SIGTERM closes it
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  const pid_t leader = ::getppid();
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  void* shared = ::mmap(nullptr, sizeof(teleop::leader::DeviceChannel), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  if (shared == MAP_FAILED) {
    std::fprintf(stderr, "teleop_device_host: cannot map the leader's channel (--fd %d): %s\n", fd, std::strerror(errno));
    return 1;
  }
  auto& channel = *static_cast<teleop::leader::DeviceChannel*>(shared);
  std::unique_ptr<teleop::leader::PluginDevice> device;
  try {
    device = std::make_unique<teleop::leader::PluginDevice>(std::make_shared<const teleop::leader::PluginLibrary>(library),
                                                            parse_settings(pairs), period_s, joints);
  } catch (const std::exception& e) {
    std::snprintf(channel.error, sizeof channel.error, "%s", e.what());
    channel.phase.store(teleop::leader::DeviceChannel::kFailed, std::memory_order_release);
    return 1;
  }
  channel.joints = static_cast<uint32_t>(device->joints());
  std::snprintf(channel.name, sizeof channel.name, "%s", device->name());
  teleop::MonotonicClock clock;
  teleop::RatePacer pacer(clock, static_cast<int64_t>(period_s * 1e9));
  teleop::leader::HostedState hosted;
  teleop::JointVector feedback{};
  pacer.start();
  serve(*device, channel, hosted, feedback, clock.now_ns());
  channel.phase.store(teleop::leader::DeviceChannel::kOpen, std::memory_order_release);
  while (!g_stop && ::getppid() == leader) {
    const teleop::CycleTick tick = pacer.wait_next();
    serve(*device, channel, hosted, feedback, tick.now_ns);
  }
  return 0;
}
