// teleop_follower: the remote robot.
#include "teleop/follower/follower_arms.h"

int main(int argc, char** argv) {
  return teleop::runtime::run_node(argc, argv,
                                   {teleop::msg::ROLE_FOLLOWER, "follower",
                                    "teleop follower: the remote robot, tracks the leader's commands",
                                    teleop::follower::follower_logic_parser()});
}
