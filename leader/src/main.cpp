// teleop_leader: the operator's station.
#include "teleop/leader/leader_node.h"

int main(int argc, char** argv) {
  using teleop::leader::LeaderNode;
  return teleop::runtime::run_node(argc, argv,
                                   {teleop::msg::ROLE_LEADER, "leader",
                                    "teleop leader: the operator's station, streams the commanded motion",
                                    teleop::runtime::parser_for<LeaderNode>()});
}
