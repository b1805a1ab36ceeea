// teleop_leader: the operator's station.
#include "leader_arms.h"

int main(int argc, char** argv) {
  return teleop::runtime::run_node(argc, argv,
                                   {teleop::msg::ROLE_LEADER, "leader",
                                    "teleop leader: the operator's station, streams the commanded motion",
                                    teleop::leader::leader_logic_parser()});
}
