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

/// One config per arm: the `follower:` section with each arm's own keys applied, in the file's
/// order; a single unnamed arm without `follower.arms`. Throws ConfigError naming file and key.
std::vector<FollowerConfig> parse_follower_arms(const ConfigNode& root);

/// The follower node's parser for run_node: one arm, or an ArmGroup of arms on a shared scene.
runtime::LogicParser follower_logic_parser();

}  // namespace teleop::follower
