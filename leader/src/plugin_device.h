#pragma once
// A leader device in a shared library of the teleop_device_v1 interface (a vendor's haptic
// device: teleop/leader/teleop_device_v1.h, docs/devices/plugins.md), loaded with dlopen. The
// plugin runs in the leader's process and on its control thread: a read that fails or measures
// something not finite fails the device's read (the leader holds its command until a read
// succeeds again); the efforts it is given never exceed the limits it declared. A plugin that
// crashes takes the leader's process with it (see the page for what that does to the device).

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/leader/device_registry.h"
#include "teleop/leader/leader_device.h"
#include "teleop/leader/teleop_device_v1.h"

namespace teleop::leader {

/// The loaded library and its interface table. Setup time.
class PluginLibrary {
 public:
  /// Loads `path` (a bare name: dlopen's search) and checks its table. Throws
  /// std::runtime_error naming the library and what is wrong.
  explicit PluginLibrary(const std::string& path);
  ~PluginLibrary();
  PluginLibrary(const PluginLibrary&) = delete;
  PluginLibrary& operator=(const PluginLibrary&) = delete;

  const teleop_device_v1& api() const { return *api_; }
  bool cartesian() const { return api_->kind == TELEOP_DEVICE_CARTESIAN; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  void* handle_ = nullptr;
  const teleop_device_v1* api_ = nullptr;
};

/// `leader.plugin.settings`, as text pairs.
using PluginSettings = std::vector<std::pair<std::string, std::string>>;

class PluginDevice final : public LeaderDevice {
 public:
  /// Opens the device. Throws std::runtime_error with the plugin's error when it fails, or when it
  /// declares more joints or efforts than it may, or another joint count than the leader's.
  PluginDevice(std::shared_ptr<const PluginLibrary> library, const PluginSettings& settings, double period_s,
               size_t leader_joints);
  /// Closes the device; logs the last failure if reads or writes failed.
  ~PluginDevice() override;
  PluginDevice(const PluginDevice&) = delete;
  PluginDevice& operator=(const PluginDevice&) = delete;

  size_t joints() const override { return info_.joints; }
  /// Real-time safe (as the plugin's read is).
  [[nodiscard]] bool read(DeviceState& state) override;
  /// The first info.feedback_dof efforts of `feedback_nm` (joint torques; a Cartesian device's
  /// force, then moment), each within the device's limit. Real-time safe.
  [[nodiscard]] bool write(const JointVector& feedback_nm) override;
  const char* name() const override { return info_.name; }
  /// plugin_failed_reads, plugin_invalid_reads, plugin_failed_writes, plugin_limited_efforts.
  void report_counters(std::vector<std::pair<std::string, double>>& counters) const override;

  uint64_t failed_reads() const { return failed_reads_; }
  uint64_t invalid_reads() const { return invalid_reads_; }
  uint64_t failed_writes() const { return failed_writes_; }
  /// Efforts cut to the device's limit.
  uint64_t limited_efforts() const { return limited_efforts_; }

 private:
  bool finite(const teleop_device_state& s) const;
  void keep_error();

  std::shared_ptr<const PluginLibrary> library_;
  const teleop_device_v1& api_;
  teleop_device* device_ = nullptr;
  teleop_device_info info_{};
  teleop_device_state state_{};
  std::array<double, TELEOP_DEVICE_MAX_DOF> effort_{};
  char last_error_[160] = "";
  uint64_t failed_reads_ = 0;
  uint64_t invalid_reads_ = 0;
  uint64_t failed_writes_ = 0;
  uint64_t limited_efforts_ = 0;
};

/// Reads `leader.plugin: {library, settings: {key: value}}` and loads the library (plugin_device_spec.cpp).
/// Throws ConfigError naming the key: no such file, not a plugin, another ABI.
std::shared_ptr<const DeviceSpec> parse_plugin_device(const ConfigNode& leader_section);

}  // namespace teleop::leader
