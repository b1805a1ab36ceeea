#pragma once
// The leader station: a simulated operator moves the device (a simulated haptic arm, or the
// script itself), the device's motion is mapped into the follower's workspace and sent as the
// architecture asks (teleoperation/architecture.h), and the architecture's feedback is rendered
// on the device through the FeedbackRenderer. Losing the follower (or, model-mediated, the twin)
// freezes the command and fades the feedback out; NodeStatus reports it.

#include <teleop/msg/arm.h>

#include <memory>
#include <optional>
#include <string>

#include "teleop/common/config.h"
#include "teleop/common/joint_model.h"
#include "teleop/leader/arm_kinematics.h"
#include "teleop/leader/cartesian_mapping.h"
#include "teleop/leader/clutch.h"
#include "teleop/leader/feedback_renderer.h"
#include "teleop/leader/operator_motion.h"
#include "teleop/leader/replay_device.h"
#include "teleop/leader/simulated_haptic_arm.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/teleoperation/architecture.h"
#include "teleop/teleoperation/tdpa_link.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::leader {

struct CartesianGains {
  std::array<double, 3> translational_n_per_m{1500, 1500, 1500};
  std::array<double, 3> rotational_nm_per_rad{100, 100, 100};
  double damping_ratio = 0.7;
  double nullspace_stiffness_nm_per_rad = 10.0;
};

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
  /// The device: `scripted` (exactly where the operator wants it), a simulated haptic arm
  /// pulled there by the operator's hand, feeling the feedback, or the replay of a recorded
  /// device motion (open loop: it renders nothing).
  enum class Device { kScripted, kHapticArm, kReplay } device = Device::kScripted;
  HapticArmConfig haptic_arm;
  std::shared_ptr<const JointTrajectory> replay;
  /// Model of the arm class (device and follower): Cartesian architectures and the traces.
  std::string arm_model;
  std::string ee_site = "ee_site";
  /// false: nothing is rendered (the architecture's feedback is still computed and traced).
  bool feedback_enabled = true;
  FeedbackConfig feedback;
  /// Scaling from the device to the follower's command (joint angles or positions).
  double workspace_scale = 1.0;
  teleoperation::TeleoperationConfig teleoperation;
};

/// The recorded operator motion whose CSV file is `section.key` (joints and column prefix from
/// `motion`). Throws ConfigError naming the file, line and problem.
std::shared_ptr<const JointTrajectory> load_recording(const ConfigNode& section, const std::string& key,
                                                     const OperatorMotionConfig& motion);

class LeaderNode final : public runtime::NodeLogic {
 public:
  /// Reads the `leader:` and `teleoperation:` sections.
  static LeaderConfig parse_config(const ConfigNode& root);

  LeaderNode(const LeaderConfig& config, runtime::NodeContext& context);

  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override { return state_; }
  void active_faults(std::vector<uint32_t>& faults) const override;
  void fill_report(runtime::NodeReport& report) const override;
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

  /// For tests: the torque rendered on the device in the last cycle, and the force it stands for
  /// in the follower's frame.
  const JointVector& rendered_torque() const { return renderer_.output(); }
  const Eigen::Vector3d& felt_force() const { return felt_force_; }

 private:
  teleoperation::Architecture architecture() const { return config_.teleoperation.architecture; }
  void poll_peers();
  void update_state(int64_t now_ns);
  void move_device(double t_s);
  void send_command(bool frozen);
  void send_joint_command(const JointVector& q_cmd, bool frozen);
  void send_cartesian_command();
  bool compute_feedback(int64_t now_ns);
  bool position_coupling_feedback(int64_t now_ns);
  bool wrench_feedback(int64_t now_ns);
  void publish_device_state();
  void update_trace_values();

  LeaderConfig config_;
  double period_s_;
  std::optional<transport::Publication<msg::JointCommand>> joint_command_;
  std::optional<transport::Publication<msg::CartesianCommand>> cartesian_command_;
  transport::Publication<msg::JointState> device_state_;
  transport::Subscription<msg::JointState> follower_state_;
  transport::Subscription<msg::WrenchStamped> follower_wrench_;
  transport::Subscription<msg::JointTorque> twin_feedback_;
  std::optional<teleoperation::TdpaLink> tdpa_;
  std::unique_ptr<LeaderDevice> device_impl_;  // none: the scripted device
  SimulatedHapticArm* haptic_arm_ = nullptr;     // device_impl_ when it is the haptic arm
  std::unique_ptr<ArmKinematics> device_kinematics_;
  std::unique_ptr<ArmKinematics> command_kinematics_;
  OperatorMotion motion_;
  msg::NodeState state_ = msg::STATE_STARTING;
  JointVector q_operator_{};
  JointVector dq_operator_{};
  JointVector operator_target_{};
  JointVector tau_intended_{};  // the torque the operator adds on purpose (e.g. a squeeze)
  DeviceState device_{};
  JointVector device_home_{};
  JointVector q_cmd_{};
  JointVector dq_cmd_{};
  JointVector feedback_{};
  Clutch clutch_;
  CartesianMapping cartesian_;
  FeedbackRenderer renderer_;
  Eigen::Vector3d felt_force_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d command_position_ = Eigen::Vector3d::Constant(std::nan(""));
  bool peer_was_lost_ = false;
  uint64_t peer_lost_events_ = 0;
  uint64_t device_faults_ = 0;
  uint64_t rejected_feedback_ = 0;
};

}  // namespace teleop::leader
