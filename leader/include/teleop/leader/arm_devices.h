#pragma once
// A robot arm as the operator's device (registry entry `robot_arm`): a torque-controlled arm used
// as a haptic master, driven through any robot backend the follower has (an arm of CiA 402 drives
// on SocketCAN: `hardware: canopen`), its weight carried by g(q) from its model:
//   leader:
//     device: robot_arm
//     robot_arm:
//       hardware: canopen          # a backend of `robots`, with its own keys beside it
//       canopen: {...}             # as in a follower's section (docs/robots.md)
//       gravity_model: ../models/panda.xml   # default: leader.arm_model
//       max_torque_nm: [...]       # the device's bound per joint, within the robot's limits
//       damping_nms_per_rad: [...] # a viscous damping it renders (optional)
// (docs/devices/robot_arm.md).

#include "teleop/leader/device_registry.h"
#include "teleop/robot/hardware_registry.h"

namespace teleop::leader {

/// Registers `robot_arm`, built by the backends of `robots` (copied).
void add_robot_arm_device(DeviceRegistry& registry, const robot::HardwareRegistry& robots);

}  // namespace teleop::leader
