// The fuzzer's stand-in for leader/src/builtin_robot_arm.cpp: no robot_arm device, as the fuzzer
// does not link its robot backends (a CANopen master, a ROS 2 robot's DDS); a seed naming it is
// refused as an unknown device, the ConfigError the fuzzer expects of a configuration it cannot
// read.
#include "builtin_robot_arm.h"

namespace teleop::leader {

void add_builtin_robot_arm(DeviceRegistry& registry) { (void)registry; }

}  // namespace teleop::leader
