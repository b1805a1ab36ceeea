#pragma once
// Every leader device this build has: the simulated ones (simulated_devices.h), the Linux input
// ones (input_devices.h), a vendor's device in a plugin (`plugin`: teleop_device_v1.h), and a
// robot arm as haptic master on any of the follower's robot backends (`robot_arm`: arm_devices.h,
// with mujoco, canopen and ros2). What the leader executable registers, and what a leader's
// configuration is read against unless a caller brings its own registry, so that the shipped
// files, which carry the settings of each, read anywhere.

#include "teleop/leader/device_registry.h"

namespace teleop::leader {

/// Registers scripted, haptic_arm, replay, spacemouse, gamepad, plugin and robot_arm.
void add_builtin_devices(DeviceRegistry& registry);

/// A registry of them.
const DeviceRegistry& builtin_devices();

}  // namespace teleop::leader
