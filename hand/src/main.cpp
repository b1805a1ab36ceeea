// teleop_hand: the dexterous hand's CANopen adapter as a DDS node.
#include "teleop/hand/hand_node.h"

int main(int argc, char** argv) {
  using teleop::hand::HandNode;
  return teleop::runtime::run_node(argc, argv,
                                   {teleop::msg::ROLE_FOLLOWER, "hand",
                                    "teleop hand: drives the hand's CANopen motor controllers from HandCommand",
                                    teleop::runtime::parser_for<HandNode>()});
}
