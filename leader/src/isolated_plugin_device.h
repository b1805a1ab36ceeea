#pragma once
// A leader device plugin hosted in a process of its own (leader.plugin.isolation: process): the
// leader starts teleop_device_host with a shared memory (device_channel.h), takes the device's
// newest state from it each cycle and leaves the feedback there; it never calls into the plugin.
// A host that stops beating for `host_timeout_s` (a vendor SDK that crashed, a host killed) fails
// the reads: the leader holds its command and fades its feedback as for a device unplugged, and
// goes on; a host that was only starved is taken back when it beats again. The host ends with the leader (SIGTERM, or its parent-death signal),
// closing the device first so that it stops rendering.

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "device_channel.h"
#include "plugin_device.h"
#include "teleop/leader/leader_device.h"

namespace teleop::leader {

struct HostedPluginConfig {
  std::string library;  // the plugin's path, as the leader checked it
  PluginSettings settings;
  double period_s = 1e-3;
  size_t joints = 7;
  bool cartesian = false;  // the library's kind
  double host_timeout_s = 0.05;
  /// teleop_device_host's path (default: beside the running executable).
  std::string host;
};

class IsolatedPluginDevice final : public LeaderDevice {
 public:
  /// Starts the host and waits (at most 10 s) for it to open the device. Throws
  /// std::runtime_error with the host's or the plugin's error.
  explicit IsolatedPluginDevice(const HostedPluginConfig& config);
  /// Stops the host (SIGTERM: it closes the device), SIGKILL after 1 s; logs how a host that
  /// died before ended.
  ~IsolatedPluginDevice() override;
  IsolatedPluginDevice(const IsolatedPluginDevice&) = delete;
  IsolatedPluginDevice& operator=(const IsolatedPluginDevice&) = delete;

  size_t joints() const override { return channel_->joints; }
  /// The host's newest state; false when it failed, or when the host has not beaten for the
  /// timeout. Real-time safe: no call into the plugin, no wait.
  [[nodiscard]] bool read(DeviceState& state) override;
  /// Leaves the feedback for the host; false while the host is lost. Real-time safe.
  [[nodiscard]] bool write(const JointVector& feedback_nm) override;
  const char* name() const override { return channel_->name; }
  /// The plugin's counters as the host keeps them, and plugin_host_losses.
  void report_counters(std::vector<std::pair<std::string, double>>& counters) const override;

  pid_t host_pid() const { return pid_; }

 private:
  bool host_alive(int64_t now_ns);

  HostedPluginConfig config_;
  DeviceChannel* channel_ = nullptr;
  int fd_ = -1;
  pid_t pid_ = -1;
  HostedState hosted_{};
  bool lost_ = false;
  uint64_t losses_ = 0;
};

}  // namespace teleop::leader
