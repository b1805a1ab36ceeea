#pragma once
// A 6-DoF mouse (SpaceMouse class) or a gamepad as the leader's device, read through Linux input
// (docs/devices/input_devices.md). A reader thread (evdev_reader.h) turns the device's axes into
// deflections in [-1, 1] and its keys into the leader's buttons; the control loop takes them from
// atomics, maps the axes onto the six components of a twist in the follower's base frame and
// integrates it (rate_pose.h). A relative axis (a SpaceNavigator's EV_REL) is a deflection, not a
// motion, and the kernel drops its zero values, so a released cap goes silent instead of reporting
// 0: an axis silent for release_s reads 0. An absolute axis is scaled by its own range. Unplugged,
// read() fails (the leader holds the command) until the device is found again.

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "evdev_reader.h"
#include "rate_pose.h"
#include "teleop/leader/leader_device.h"

namespace teleop::leader {

/// One of the device's axes and the twist component it drives (0..5: x y z rx ry rz).
struct InputAxis {
  unsigned type = 0;  ///< EV_REL or EV_ABS
  unsigned code = 0;
  int component = 0;
  double sign = 1.0;
};

struct InputDeviceConfig {
  /// The registry's name of the kind ("spacemouse", "gamepad"): names its key and its errors.
  std::string kind;
  /// A node, a USB vendor:product id or the name the device reports (evdev_reader.h).
  std::string device;
  std::vector<InputAxis> axes;
  /// A relative axis's value at full deflection (a SpaceNavigator reports about +-350).
  double relative_full_scale = 350.0;
  /// A relative axis silent this long reads 0 [s].
  double release_s = 0.1;
  RatePoseConfig motion;
  /// Each evdev key read, and the leader button it is.
  std::vector<std::pair<unsigned, int>> keys;
};

class AxisInput;

class InputDevice final : public LeaderDevice {
 public:
  /// Opens the device: throws std::runtime_error naming it when it is not there or lacks an axis
  /// or key the config names. Setup time.
  InputDevice(const InputDeviceConfig& config, double period_s);
  ~InputDevice() override;

  /// None: the device moves a Cartesian pose.
  size_t joints() const override { return 0; }
  /// The pose integrated from this period's deflection, and the buttons; false (and no motion)
  /// while the device is gone. Real-time safe.
  [[nodiscard]] bool read(DeviceState& state) override;
  /// Nothing to render on: accepted and dropped. Real-time safe.
  [[nodiscard]] bool write(const JointVector& feedback_nm) override {
    (void)feedback_nm;
    return true;
  }
  const char* name() const override { return config_.kind.c_str(); }

  /// The device it reads and how often it went away.
  const std::string& description() const;
  uint64_t losses() const;

 private:
  InputDeviceConfig config_;
  std::unique_ptr<AxisInput> input_;
  RatePose pose_;
};

}  // namespace teleop::leader
