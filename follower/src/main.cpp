// teleop_follower: the remote robot.
#include "teleop/follower/follower_node.h"

int main(int argc, char** argv) {
  using teleop::follower::FollowerNode;
  return teleop::runtime::run_node(argc, argv,
                                   {teleop::msg::ROLE_FOLLOWER, "follower",
                                    "teleop follower: the remote robot, tracks the leader's commands",
                                    teleop::runtime::parser_for<FollowerNode>()});
}
