#pragma once
// The leader station: a simulated operator moves the device (a simulated haptic arm, or the
// script itself), the device's motion is mapped into the follower's workspace and sent as the
// architecture's leader part asks (architectures/leader_architecture.h), and the feedback it
// computes is rendered on the device through the FeedbackRenderer. Losing the follower (or,
// model-mediated, the twin) freezes the command and fades the feedback out; NodeStatus reports it.

#include <teleop/msg/arm.h>
#include <teleop/msg/hand.h>

#include <memory>
#include <optional>
#include <string>

#include "teleop/common/config.h"
#include "teleop/common/joint_model.h"
#include "architectures/leader_architecture.h"
#include "arm_kinematics.h"
#include "cartesian_mapping.h"
#include "clutch.h"
#include "feedback_renderer.h"
#include "hands_off_guard.h"
#include "button_input.h"
#include "leader_config.h"
#include "operator_motion.h"
#include "teleop/leader/leader_device.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/runtime/command_authority.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::leader {

class LeaderNode final : public runtime::NodeLogic {
 public:
  /// Reads the `leader:` and `teleoperation:` sections (leader_config.h).
  static LeaderConfig parse_config(const ConfigNode& root) { return parse_leader_config(root); }

  LeaderNode(const LeaderConfig& config, runtime::NodeContext& context);

  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override { return state_; }
  /// Engaged: the command freezes where it is and no force is rendered, until an enable.
  void emergency_stop(bool engaged) override { emergency_stopped_ = engaged; }
  void active_faults(std::vector<uint32_t>& faults) const override;
  void fill_status(msg::NodeStatus& status) const override;
  void fill_report(runtime::NodeReport& report) const override;
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

  /// For tests: the torque rendered on the device in the last cycle, and the force it stands for
  /// in the follower's frame.
  const JointVector& rendered_torque() const { return renderer_.output(); }
  const Eigen::Vector3d& felt_force() const { return felt_force_; }
  /// For tests: the device's flange (or handle) speed in the last cycle [m/s].
  double device_speed_mps() const { return device_speed_mps_; }
  /// The device leader.device named.
  const LeaderDevice& device() const { return *device_impl_; }

 private:
  void poll_peers();
  /// Watches whether the writer that carries this leader's commands under its architecture is in command.
  void watch_authority(transport::Participant& participant, const std::string& self);
  void update_state(int64_t now_ns);
  /// Reads the device (and the button input); false when it could not be read.
  bool move_device(double t_s);
  /// leader.buttons: the dead-man (if any) not held; the clutch (if any) held. Either holds the command.
  bool dead_man_released() const;
  bool clutch_held() const;
  /// Where the Cartesian mapping starts: the device's pose now, the follower's home; the box.
  void start_cartesian();
  /// The device's flange (or, a Cartesian device, handle) pose and twist of this cycle.
  void device_pose(Eigen::Vector3d& x, Eigen::Matrix3d& r, control::Vector6& v) const;
  void send_command(bool frozen);
  MappedDevice mapped_device() const { return {q_cmd_, dq_cmd_, cartesian_, device_kinematics_.get()}; }
  void publish_device_state();
  /// The device's stop-chain buttons to the bus: a stop on the press of its emergency stop (and
  /// again while it stays pressed, as a latched mushroom button keeps saying stop), an enable on
  /// the press of its enable button.
  void send_stop_requests(int64_t now_ns);
  void command_hand(double t_s);
  void update_trace_values();
  /// The simulated operator's clock this cycle [s] (leader.motion_starts).
  double operator_time_s(const CycleTick& tick);

  LeaderConfig config_;
  double period_s_;
  transport::Publication<msg::JointState> device_state_;
  std::optional<transport::Publication<msg::HandCommand>> hand_command_;  // with leader.hand
  transport::Publication<msg::EmergencyStop> stop_requests_;
  transport::Subscription<msg::JointState> follower_state_;
  transport::Subscription<msg::WrenchStamped> follower_wrench_;
  transport::Subscription<msg::JointTorque> twin_feedback_;
  std::unique_ptr<LeaderArchitecture> architecture_;  // teleoperation.architecture's leader part
  std::optional<runtime::CommandAuthority> authority_;
  std::unique_ptr<LeaderDevice> device_impl_;  // the one leader.device names
  std::unique_ptr<ButtonInput> button_input_;  // leader.button_input's device, when there is one
  std::unique_ptr<ArmKinematics> device_kinematics_;
  std::unique_ptr<ArmKinematics> command_kinematics_;
  OperatorMotion motion_;
  uint64_t operator_start_index_ = 0;
  bool operator_started_ = false;
  double operator_s_ = 0.0;  // traced: the analysis aligns its windows on the operator's start
  msg::NodeState state_ = msg::STATE_STARTING;
  OperatorIntent intent_{};  // the simulated operator's, given to the device every cycle
  DeviceState device_{};
  JointVector q_cmd_{};
  JointVector dq_cmd_{};
  JointVector feedback_{};
  Clutch clutch_;
  CartesianMapping cartesian_;
  FeedbackRenderer renderer_;
  HandsOffGuard hands_off_;
  double device_speed_mps_ = 0.0;  // the flange's or handle's, last cycle
  Eigen::Vector3d felt_force_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d command_position_ = Eigen::Vector3d::Constant(std::nan(""));
  bool emergency_stopped_ = false;
  bool device_connected_ = true;  // the device's last read succeeded
  bool device_refused_ = false;   // the device refused the last write
  uint64_t device_lost_events_ = 0;
  uint64_t cycles_held_by_buttons_ = 0;
  uint32_t buttons_before_ = 0;  // the device's buttons in the last cycle
  int64_t stop_sent_ns_ = 0;     // when the last stop went out
  uint64_t stops_sent_ = 0;
  uint64_t enables_sent_ = 0;
  bool peer_was_lost_ = false;
  uint64_t peer_lost_events_ = 0;
  uint64_t not_in_command_events_ = 0;
  uint64_t cycles_not_in_command_ = 0;
  uint64_t device_faults_ = 0;
  uint64_t rejected_feedback_ = 0;
};

}  // namespace teleop::leader
