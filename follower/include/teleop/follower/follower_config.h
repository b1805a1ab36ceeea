#pragma once
// The `follower:` section of a follower node's configuration (config/nodes/follower.yaml).

#include <optional>
#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/follower/arm_control.h"
#include "teleop/follower/command_validator.h"
#include "teleop/follower/payload_calibration.h"
#include "teleop/follower/safety_reflex.h"
#include "teleop/robot/hardware_registry.h"
#include "teleop/robot/mujoco_backend.h"
#include "teleop/runtime/architecture.h"

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
  /// The robot: the backend `follower.hardware` names with its settings (robot/hardware_registry.h);
  /// the simulation (`mujoco`) in every build, a real arm as another backend.
  std::shared_ptr<const robot::HardwareSpec> hardware;
  /// An arm of a multi-arm robot: its joints and flange site in the shared scene (follower.arms).
  std::string joint_prefix;
  std::string ee_site = "ee_site";
  /// Where joint commands come from: the leader (teleoperation) or the twin (hardware in the loop).
  enum class CommandSource { kLeader, kTwin } command_source = CommandSource::kLeader;
  /// The nodes (SampleHeader.source) whose commands are taken; empty: any node's. A name keeps
  /// two setups apart on one domain; only DDS Security's permissions authenticate a writer.
  std::vector<std::string> accept_commands_from;
  /// Command limits; the torque limits are further bounded by what the hardware reports.
  JointLimits limits;
  /// Largest change of commanded torque per second (infinite: none, `off` in YAML).
  double max_torque_rate_nm_per_s = 1000.0;
  /// No valid command for this long: hold the current pose (watchdog).
  double command_timeout_s = 0.02;
  /// Joint speed at which commands are joined after a hold (joint_rejoin.h): well below the
  /// speed reflex, so that a leader that starts far away moves the arm there calmly.
  double rejoin_speed_radps = 0.5;
  /// A hold after the commands stopped (a lost link, a dead leader, a stall) ends when they return
  /// (false, `after_hold: resume`), or only with a deliberate enable (`after_hold: enable`:
  /// `teleop enable`, the leader's enable button), as after an emergency stop.
  bool enable_after_hold = false;
  /// Joint impedance used to hold the pose in the safe state (gravity compensated).
  double hold_stiffness_nm_per_rad = 200.0;
  double hold_damping_nms_per_rad = 20.0;
  ArmControlConfig control;
  /// The reflexes on the external-load estimate and the joint speeds (safety_reflex.h).
  SafetyReflexConfig reflex;
  /// Objects of the shared scene whose measured pose goes to the twin (object_pose_feed.h).
  ObjectPoseFeedConfig tracked_objects;
  /// The architecture the follower plays its part in (absent: a plain follower of `command_source`).
  std::optional<runtime::TeleoperationConfig> teleoperation;
  /// The robot's calibration file (`follower.calibration.file`, docs/calibration.md): applied at
  /// start into control.calibration; "" when none. teleop_calibrate writes it.
  std::string calibration_file;
  /// The poses and times teleop_calibrate drives (`follower.calibration`).
  PayloadCalibrationPlan calibration_plan;
};

/// Whether parsing reads the calibration file into control.calibration (a node) or leaves the
/// model as it is (teleop_calibrate, which measures what the model lacks).
enum class CalibrationUse { kApply, kIgnore };

/// Reads the `follower:` section, the robot from `hardware`'s backends; throws ConfigError naming
/// file, key and problem.
FollowerConfig parse_follower_config(const ConfigNode& root,
                                     const robot::HardwareRegistry& hardware = robot::simulated_hardware(),
                                     CalibrationUse calibration = CalibrationUse::kApply);

/// One config per arm: the `follower:` section with each arm's own keys applied (each arm on its
/// prefix of the shared scene), in the file's order; a single unnamed arm without
/// `follower.arms`. Throws ConfigError naming file and key.
std::vector<FollowerConfig> parse_follower_arms(const ConfigNode& root,
                                                const robot::HardwareRegistry& hardware = robot::simulated_hardware());

}  // namespace teleop::follower
