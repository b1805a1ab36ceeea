#include "builtin_robot_arm.h"

#include "teleop/leader/arm_devices.h"
#include "teleop/robot/canopen_backend.h"
#include "teleop/robot/mujoco_backend.h"
#include "teleop/robot/ros2_backend.h"

namespace teleop::leader {

void add_builtin_robot_arm(DeviceRegistry& registry) {
  robot::HardwareRegistry robots;
  robot::add_mujoco_backend(robots);
  robot::add_canopen_backend(robots);
  robot::add_ros2_backend(robots);
  add_robot_arm_device(registry, robots);
}

}  // namespace teleop::leader
