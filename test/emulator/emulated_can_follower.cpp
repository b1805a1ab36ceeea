// teleop_follower_emulated_can: teleop_follower with one more backend, `canopen_emulated`: its
// CANopen master and the emulated drives turning the MuJoCo arm in one process on virtual buses
// (emulated_can_arm.h), for the process tests of the CAN arm on a host without CAN.
#include "emulated_can_arm.h"
#include "follower_arms.h"
#include "teleop/robot/canopen_backend.h"
#include "teleop/robot/mujoco_backend.h"

int main(int argc, char** argv) {
  teleop::robot::HardwareRegistry hardware;
  teleop::robot::add_mujoco_backend(hardware);
  teleop::robot::add_canopen_backend(hardware);
  teleop::emulator::test::add_emulated_canopen_backend(hardware);
  return teleop::runtime::run_node(argc, argv,
                                   {teleop::msg::ROLE_FOLLOWER, "follower",
                                    "teleop follower on an emulated arm of CiA 402 drives (tests)",
                                    teleop::follower::follower_logic_parser(hardware, teleop::robot::linked_probes())});
}
