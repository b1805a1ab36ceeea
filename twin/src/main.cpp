// teleop_twin: the digital twin.
#include "teleop/twin/twin_node.h"

int main(int argc, char** argv) {
  using teleop::twin::TwinNode;
  return teleop::runtime::run_node(argc, argv,
                                   {teleop::msg::ROLE_TWIN, "twin",
                                    "teleop twin: simulated copy of the robot, renders contact forces back",
                                    teleop::runtime::parser_for<TwinNode>()});
}
