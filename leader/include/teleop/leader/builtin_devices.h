#pragma once
// Every leader device this build has: the simulated ones (simulated_devices.h), the Linux input
// ones (input_devices.h), and a vendor's device in a plugin (`plugin`: teleop_device_v1.h). What the leader executable registers, and what a leader's
// configuration is read against unless a caller brings its own registry, so that the shipped
// files, which carry the settings of each, read anywhere.

#include "teleop/leader/device_registry.h"

namespace teleop::leader {

/// Registers scripted, haptic_arm, replay, spacemouse, gamepad and plugin.
void add_builtin_devices(DeviceRegistry& registry);

/// A registry of them.
const DeviceRegistry& builtin_devices();

}  // namespace teleop::leader
