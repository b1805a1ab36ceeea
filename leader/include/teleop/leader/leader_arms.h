#pragma once
// The leader process for a one- or two-handed station. A `leader.arms` mapping (name -> that
// hand's device model, site, home pose and recorded motion; config/nodes/leader_box_task.yaml)
// makes one LeaderNode per hand on its own arm topics, run together in one process so the
// operator's hands move on one clock; without it, one device as before. A program of its own
// (leader/src/main.cpp, or a lab's with its devices) passes this to runtime::run_node.

#include "teleop/leader/device_registry.h"
#include "teleop/runtime/node_runner.h"

namespace teleop::leader {

/// The leader node's parser for run_node: one hand, or an ArmGroup of hands, each driving the
/// device `leader.device` names among `devices` (which must outlive the node).
runtime::LogicParser leader_logic_parser(const DeviceRegistry& devices);

}  // namespace teleop::leader
