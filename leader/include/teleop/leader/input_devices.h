#pragma once
// The leader devices read through Linux input (libevdev), as registry entries (device_registry.h),
// both Cartesian rate devices (docs/devices/input_devices.md):
//   spacemouse  a 6-DoF mouse (3Dconnexion SpaceNavigator, SpaceMouse): its cap's six axes
//   gamepad     a gamepad's sticks (an Xbox-class pad under xpad or hid-generic)
// Their keys (leader.<kind>): device (node, vendor:product or name), axes ({REL_X: x, ABS_Y: -z}),
// full_scale, release_ms, dead_band, linear_speed_mps, angular_speed_radps, keys ({BTN_0: 0}).

#include "teleop/leader/device_registry.h"

namespace teleop::leader {

/// Registers spacemouse and gamepad.
void add_input_devices(DeviceRegistry& registry);

}  // namespace teleop::leader
