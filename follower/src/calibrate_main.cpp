// teleop_calibrate: a follower robot's payload and estimate bias from static poses
// (follower/calibrate_tool.h, docs/calibration.md). The robots it can drive are the follower's.
#include <CLI/CLI.hpp>

#include "teleop/follower/calibrate_tool.h"
#include "teleop/robot/canopen_backend.h"
#include "teleop/robot/mujoco_backend.h"
#include "teleop/robot/ros2_backend.h"

int main(int argc, char** argv) {
  CLI::App app{"teleop_calibrate: identify the payload on a follower's flange and write the robot's calibration"};
  teleop::follower::CalibrateOptions options;
  app.add_option("-c,--config", options.config_path, "the follower's config (a file, or a name in config/nodes)")
      ->required();
  app.add_option("--set", options.sets, "override a config value KEY=VALUE (repeatable)");
  app.add_option("-o,--out", options.out_path, "the calibration file (default: follower.calibration.file)");
  CLI11_PARSE(app, argc, argv);
  teleop::robot::HardwareRegistry hardware;
  teleop::robot::add_mujoco_backend(hardware);
  teleop::robot::add_ros2_backend(hardware);
  teleop::robot::add_canopen_backend(hardware);
  return teleop::follower::run_calibration(options, hardware);
}
