#pragma once
// The follower process for a one-arm or a multi-arm robot. A `follower.arms` mapping (name ->
// that arm's joints, site and controller model; config/nodes/follower_box_task.yaml) makes one
// FollowerNode per arm on its own arm topics, all on one shared MuJoCo scene that advances once
// every arm has written; without it, the follower drives the one arm of its robot. Probes an
// experiment asks for (`node.probes`) and tracked objects watch that scene beside the arms.

#include <vector>

#include "teleop/common/config.h"
#include "teleop/follower/follower_config.h"
#include "teleop/robot/hardware_registry.h"
#include "teleop/robot/scene_probes.h"
#include "teleop/runtime/node_runner.h"

namespace teleop::follower {

/// The follower node's parser for run_node: one arm, or an ArmGroup of arms on a shared scene.
/// The robot comes from `hardware`'s backends, the probes of `node.probes` from `probes` (both
/// must outlive the parser: the executable's own).
runtime::LogicParser follower_logic_parser(const robot::HardwareRegistry& hardware, const robot::SceneProbes& probes);
/// The same with the simulation and no probes (tests).
runtime::LogicParser follower_logic_parser();

}  // namespace teleop::follower
