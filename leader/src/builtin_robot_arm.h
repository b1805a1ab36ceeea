#pragma once
// The built-in robot_arm device (arm_devices.h) with every robot backend of the build: mujoco,
// canopen and ros2. Apart from builtin_devices.cpp so that a program that does not link those
// backends (the configuration fuzzer) can leave it out.

#include "teleop/leader/device_registry.h"

namespace teleop::leader {

void add_builtin_robot_arm(DeviceRegistry& registry);

}  // namespace teleop::leader
