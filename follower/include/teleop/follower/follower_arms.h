#pragma once
// The follower process for a one-arm or a multi-arm robot. A `follower.arms` mapping (name ->
// that arm's joints, site and controller model; config/nodes/follower_box_task.yaml) makes one
// FollowerNode per arm on its own arm topics, all on one shared MuJoCo scene that advances once
// every arm has written; without it, the follower drives the one arm of its scene as before.

#include <vector>

#include "teleop/common/config.h"
#include "teleop/follower/follower_config.h"
#include "teleop/runtime/node_runner.h"

namespace teleop::follower {

/// The follower node's parser for run_node: one arm, or an ArmGroup of arms on a shared scene.
runtime::LogicParser follower_logic_parser();

}  // namespace teleop::follower
