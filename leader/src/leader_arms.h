#pragma once
// The leader process for a one- or two-handed station. A `leader.arms` mapping (name -> that
// hand's device model, site, home pose and recorded motion; config/nodes/leader_box_task.yaml)
// makes one LeaderNode per hand on its own arm topics, run together in one process so the
// operator's hands move on one clock; without it, one device as before.

#include <vector>

#include "teleop/common/config.h"
#include "leader_config.h"
#include "teleop/runtime/node_runner.h"

namespace teleop::leader {

/// The leader node's parser for run_node: one hand, or an ArmGroup of hands.
runtime::LogicParser leader_logic_parser();

}  // namespace teleop::leader
