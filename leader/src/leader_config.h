#pragma once
// The `leader:` section of a leader node's configuration (config/nodes/leader*.yaml), and its
// reading: the hands of a two-handed station (leader.arms), the operator's motion, the device,
// the feedback and the architecture.

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "button_input.h"
#include "teleop/common/config.h"
#include "teleop/common/joint_model.h"
#include "feedback_renderer.h"
#include "hands_off_guard.h"
#include "hand_plan.h"
#include "joint_trajectory.h"
#include "operator_motion.h"
#include "scripted_device.h"
#include "teleop/leader/device_registry.h"
#include "teleop/leader/builtin_devices.h"
#include "teleop/runtime/architecture.h"

namespace teleop::leader {

struct CartesianGains {
  std::array<double, 3> translational_n_per_m{1500, 1500, 1500};
  std::array<double, 3> rotational_nm_per_rad{100, 100, 100};
  double damping_ratio = 0.7;
  double nullspace_stiffness_nm_per_rad = 10.0;
};

/// The device's buttons of the stop chain (docs/stop_chain.md) and of motion, by index; -1: none.
struct StopButtons {
  int emergency_stop = -1;
  int enable = -1;
  /// Held: the command follows the device; released: it holds (an enabling device). -1: always follows.
  int dead_man = -1;
  /// Held: the command holds while the device moves freely (indexing).
  int clutch = -1;
};

/// A box in the follower's base frame that the Cartesian command stays in [m]; none: unbounded.
struct WorkspaceBox {
  std::array<double, 3> min_m{};
  std::array<double, 3> max_m{};
};

/// The highest button index a configuration may name (DeviceState::buttons is 32 bits).
inline constexpr int64_t kMaxButton = 31;

struct LeaderConfig {
  /// Which hand of a two-handed station this is ("" for a one-arm station): names its topics
  /// (transport/arm_topic.h) and those of the follower's arm it commands.
  std::string arm;
  size_t joints = 7;
  /// The follower's home pose [rad]: the command starts here whatever the device's pose.
  JointVector home_rad{};
  /// What the simulated operator intends (its home is home_rad).
  OperatorMotionConfig motion;
  /// Joint impedance commanded to the follower (position_position); the leader feels the same
  /// spring and damper between its command and the follower's state.
  double stiffness_nm_per_rad = 200.0;
  double damping_nms_per_rad = 10.0;
  /// Cartesian impedance commanded to the follower (pfc, pfc_tdpa).
  CartesianGains cartesian;
  /// Follower (or twin) silent longer than this: freeze the command and report the peer lost.
  double peer_timeout_s = 0.1;
  /// The device `leader.device` names, with its settings (device_registry.h): the script itself
  /// unless the configuration says otherwise.
  std::shared_ptr<const DeviceSpec> device = scripted_device_spec();
  /// Model of the arm class (device and follower): Cartesian architectures and the traces.
  std::string arm_model;
  std::string ee_site = "ee_site";
  /// false: nothing is rendered (the architecture's feedback is still computed and traced).
  bool feedback_enabled = true;
  FeedbackConfig feedback;
  /// `feedback.hands_off_speed_mps`, `hands_off_resume_ms`: the device counts as let go when faster.
  HandsOffConfig hands_off;
  /// Scaling from the device to the follower's command (joint angles or positions).
  double workspace_scale = 1.0;
  /// `leader.workspace_box_m: {min: [x, y, z], max: [x, y, z]}`: where the Cartesian command may go.
  std::optional<WorkspaceBox> workspace_box;
  runtime::TeleoperationConfig teleoperation;
  /// `leader.hand` (optional): the simulated operator's hand, a HandCommand plan for the
  /// teleop_hand node (hand_plan.h); without it the leader commands no hand.
  std::optional<HandPlan> hand;
  /// `leader.buttons`: the device's emergency stop, enable, dead-man and clutch buttons.
  StopButtons stop_buttons;
  /// Buttons of a Linux input device beside the operator's (`leader.button_input`: an e-stop
  /// button, a pedal), merged into the device's; absent: none.
  std::optional<ButtonInputConfig> button_input;
};

/// The recorded operator motion whose CSV file is `section.key` (joints and column prefix from
/// `motion`). Throws ConfigError naming the file, line and problem.
std::shared_ptr<const JointTrajectory> load_recording(const ConfigNode& section, const std::string& key,
                                                     const OperatorMotionConfig& motion);

/// Reads the `leader:` and `teleoperation:` sections of one hand, the device from `devices`. Throws
/// ConfigError naming file, key and problem; loads every file it names (models, recordings) on the way.
LeaderConfig parse_leader_config(const ConfigNode& root, const DeviceRegistry& devices = builtin_devices());

/// One config per hand of `leader.arms`, in the file's order; a single unnamed hand without it.
std::vector<LeaderConfig> parse_leader_arms(const ConfigNode& root, const DeviceRegistry& devices = builtin_devices());

}  // namespace teleop::leader
