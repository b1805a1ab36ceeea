// teleop_twin: the digital twin.
#include "twin_arms.h"

int main(int argc, char** argv) {
  return teleop::runtime::run_node(argc, argv,
                                   {teleop::msg::ROLE_TWIN, "twin",
                                    "teleop twin: simulated copy of the robot, renders contact forces back",
                                    teleop::twin::twin_logic_parser()});
}
