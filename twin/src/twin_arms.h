#pragma once
// The twin process for a one-arm or a multi-arm robot. A `twin.arms` mapping (name -> that arm's
// joint_prefix; config/nodes/twin_box_task.yaml) makes one TwinArm per arm on its own arm topics,
// all in one TwinScene that steps once every arm has written its target; without it, the twin is
// the one-arm TwinNode with all its modes. Lock-step, hardware in the loop and model correction
// stay one-arm: configured together with `arms` they are a ConfigError.

#include <vector>

#include "teleop/common/config.h"
#include "teleop/runtime/node_runner.h"
#include "twin_config.h"

namespace teleop::twin {

/// The twin node's parser for run_node: one TwinNode, or an ArmGroup of TwinArms on a TwinScene.
runtime::LogicParser twin_logic_parser();

}  // namespace teleop::twin
