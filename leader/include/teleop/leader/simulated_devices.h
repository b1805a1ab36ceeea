#pragma once
// The leader devices every build has, as registry entries (device_registry.h):
//   scripted    the device is where the simulated operator wants it (no keys of its own)
//   haptic_arm  a MuJoCo arm as a torque-controlled device, held by a spring-damper hand
//               (leader.haptic_arm: model, keyframe, hand_stiffness_nm_per_rad, hand_damping_nms_per_rad)
//   replay      a recorded joint motion played open loop (leader.replay: file, columns)

#include "teleop/leader/device_registry.h"

namespace teleop::leader {

/// Registers scripted (first, so the default), haptic_arm and replay.
void add_simulated_devices(DeviceRegistry& registry);

/// A registry of the simulated devices: what the leader executable and tests start from.
const DeviceRegistry& simulated_devices();

}  // namespace teleop::leader
