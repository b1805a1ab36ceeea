#include "teleop/leader/builtin_devices.h"

#include "builtin_robot_arm.h"
#include "plugin_device.h"
#include "teleop/leader/input_devices.h"
#include "teleop/leader/simulated_devices.h"

namespace teleop::leader {

void add_builtin_devices(DeviceRegistry& registry) {
  add_simulated_devices(registry);
  add_input_devices(registry);
  registry.add("plugin", parse_plugin_device);
  add_builtin_robot_arm(registry);
}

const DeviceRegistry& builtin_devices() {
  static const DeviceRegistry registry = [] {
    DeviceRegistry r;
    add_builtin_devices(r);
    return r;
  }();
  return registry;
}

}  // namespace teleop::leader
