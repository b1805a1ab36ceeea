#pragma once
#include <optional>

#include "teleop/teleoperation/architecture.h"
// The `follower:` section of a follower node's configuration (config/nodes/follower.yaml).

#include <string>

#include "teleop/common/config.h"
#include "teleop/follower/arm_control.h"
#include "teleop/follower/command_validator.h"
#include "teleop/follower/contact_reflex.h"
#include "teleop/follower/mujoco_hardware.h"

namespace teleop::follower {

/// The remote site's tracking of its objects for the twin (object_pose_feed.h).
struct ObjectPoseFeedConfig {
  /// Bodies of the scene to publish, by name; empty: none.
  std::vector<std::string> bodies;
  /// Samples per second of each (the loop's rate divided by a whole number of cycles).
  double rate_hz = 100.0;
};

struct FollowerConfig {
  /// Which arm of a multi-arm robot this is ("" for a one-arm robot): names its topics
  /// (transport/arm_topic.h).
  std::string arm;
  size_t joints = 7;
  /// The robot: a MuJoCo simulation of the arm (real arms plug in as other RobotHardware).
  MujocoHardwareConfig mujoco;
  /// Where joint commands come from: the leader (teleoperation) or the twin (hardware in the loop).
  enum class CommandSource { kLeader, kTwin } command_source = CommandSource::kLeader;
  /// Command limits; the torque limits are further bounded by what the hardware reports.
  JointLimits limits;
  /// Largest change of commanded torque per second (infinite: none, `off` in YAML).
  double max_torque_rate_nm_per_s = 1000.0;
  /// No valid command for this long: hold the current pose (watchdog).
  double command_timeout_s = 0.02;
  /// Joint impedance used to hold the pose in the safe state (gravity compensated).
  double hold_stiffness_nm_per_rad = 200.0;
  double hold_damping_nms_per_rad = 20.0;
  ArmControlConfig control;
  /// The collision reflex on the external-load estimate (contact_reflex.h).
  ContactReflexConfig contact_reflex;
  /// A two-arm follower on the box scene traces the box task's quantities (box_task_trace.h).
  bool trace_box_task = false;
  /// Objects of the shared scene whose measured pose goes to the twin (object_pose_feed.h).
  ObjectPoseFeedConfig tracked_objects;
  /// The architecture the follower plays its part in (absent: a plain follower of `command_source`).
  std::optional<teleoperation::TeleoperationConfig> teleoperation;
};

/// Reads the `follower:` section; throws ConfigError naming file, key and problem.
FollowerConfig parse_follower_config(const ConfigNode& root);

}  // namespace teleop::follower
