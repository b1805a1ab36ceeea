// teleop_follower: the remote robot. Its edge: the robots it can drive (`follower.hardware`) and
// the probes an experiment may add (`node.probes`: those of the libraries linked in, CMakeLists.txt).
#include "follower_arms.h"
#include "teleop/robot/canopen_backend.h"
#include "teleop/robot/mujoco_backend.h"
#include "teleop/robot/ros2_backend.h"

int main(int argc, char** argv) {
  teleop::robot::HardwareRegistry hardware;
  teleop::robot::add_mujoco_backend(hardware);
  teleop::robot::add_ros2_backend(hardware);
  teleop::robot::add_canopen_backend(hardware);
  return teleop::runtime::run_node(argc, argv,
                                   {teleop::msg::ROLE_FOLLOWER, "follower",
                                    "teleop follower: the remote robot, tracks the leader's commands",
                                    teleop::follower::follower_logic_parser(hardware, teleop::robot::linked_probes())});
}
