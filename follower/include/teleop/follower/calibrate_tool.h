#pragma once
// teleop_calibrate: drives a follower's robot through its config's calibration poses at the
// node's rate with the follower's own controller, identifies the payload on its flange and the
// bias of its external-torque estimate, and writes the robot's calibration file, which the
// follower applies at start (docs/calibration.md).

#include <string>
#include <vector>

#include "teleop/robot/hardware_registry.h"

namespace teleop::follower {

struct CalibrateOptions {
  std::string config_path;
  std::vector<std::string> sets;  ///< KEY=VALUE overrides of the config
  std::string out_path;           ///< "" : the config's follower.calibration.file
};

/// Runs the calibration; returns the process's exit status (0: written; 1: the run or the fit
/// failed; 2: the config or the output path is wrong), saying what happened on stdout/stderr.
int run_calibration(const CalibrateOptions& options, const robot::HardwareRegistry& hardware);

}  // namespace teleop::follower
