// teleop_leader: the operator's station. Its edge: the input devices it can drive (`leader.device`);
// a real device is one more line here (docs/architecture.md, "A new operator device").
#include "teleop/leader/builtin_devices.h"
#include "teleop/leader/leader_arms.h"

int main(int argc, char** argv) {
  teleop::leader::DeviceRegistry devices;
  teleop::leader::add_builtin_devices(devices);
  return teleop::runtime::run_node(
      argc, argv,
      {teleop::msg::ROLE_LEADER, "leader", "teleop leader: the operator's station, streams the commanded motion",
       teleop::leader::leader_logic_parser(devices)});
}
