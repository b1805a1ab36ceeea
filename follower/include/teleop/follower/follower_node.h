#pragma once
// The follower robot: validates joint and Cartesian commands, runs the arm's controllers
// (ArmControl) on a robot::RobotHardware, watches for silent or dead command sources, limits the
// torque, and publishes its state with the estimated external torque and end-effector wrench.

#include <teleop/msg/arm.h>

#include <memory>
#include <optional>

#include "teleop/common/error_stats.h"
#include "teleop/common/stall_watch.h"
#include "teleop/follower/arm_control.h"
#include "teleop/follower/safety_reflex.h"
#include "teleop/follower/speed_brake.h"
#include "teleop/follower/follower_config.h"
#include "teleop/follower/joint_rejoin.h"
#include "teleop/robot/robot_hardware.h"
#include "teleop/follower/torque_limiter.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::follower {

class FollowerArchitecture;  // its architecture's part (follower/src/architectures/)

class FollowerNode final : public runtime::NodeLogic {
 public:
  /// Reads the `follower:` section.
  static FollowerConfig parse_config(const ConfigNode& root) { return parse_follower_config(root); }

  /// Drives the robot of `config.hardware`.
  FollowerNode(const FollowerConfig& config, runtime::NodeContext& context);
  /// Drives `hardware` (tests, other robots).
  FollowerNode(const FollowerConfig& config, std::unique_ptr<robot::RobotHardware> hardware, runtime::NodeContext& context);
  ~FollowerNode() override;

  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override { return state_; }
  /// Engaged: brings the robot to rest by the safe hold's damping alone (no spring pulls it back
  /// to where the stop came) and holds it where it came to rest, following no command, until
  /// disengaged (an enable); then commands are joined from the held pose.
  void emergency_stop(bool engaged) override;
  bool enable_requested() override;
  void active_faults(std::vector<uint32_t>& faults) const override;
  void fill_status(msg::NodeStatus& status) const override;
  void fill_report(runtime::NodeReport& report) const override;
  /// The robot's cycle, where it keeps one (a ROS 2 robot): the loop starts just after its state.
  int64_t pacing_phase_ns() const override { return hardware_->cycle_phase_ns(); }
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

  /// For tests and benchmarks: what the robot measured last, and the control stack.
  const robot::ArmState& arm() const { return arm_; }
  const ArmControl& control() const { return control_; }
  /// The torque written to the hardware in the last cycle, before its gravity compensation.
  const JointVector& commanded_torque() const { return command_nm_; }

 private:
  void take_commands(int64_t now_ns);
  enum class Source { kNone, kJoint, kCartesian };
  /// Takes the newest command of one stream when valid; the first of a new session (a new
  /// sender) clears the reflex.
  template <typename Command>
  void take(transport::Subscription<Command>& commands, Source source, uint64_t& last_session, int64_t now_system_ns,
            int64_t now_ns);
  void take_reset_requests();
  /// `stalled`: the loop missed more than the command timeout since its last cycle;
  /// `robot_current`: the robot's state is current (a stale one holds the robot by its own means).
  void run_watchdog(int64_t now_ns, bool stalled, bool robot_current);
  /// Computes and writes the torque (and hands a position robot its reference); false when the
  /// robot refused it.
  bool command_robot();
  void run_reflex();
  /// An emergency stop's first phase: the hold follows the robot until no joint moves faster than
  /// kAtRestRadps, so that only its damping acts; then it stays where the robot came to rest.
  void bring_to_rest();
  bool source_lost(double silence_s) const;
  /// Makes `hold` a joint impedance at the current pose with these gains.
  void hold_current_pose(ValidCommand& hold, double stiffness, double damping);
  void apply_passivity();
  void command_torque(const ValidCommand& command);
  void record_metrics();
  void publish_state();

  FollowerConfig config_;
  std::unique_ptr<robot::RobotHardware> hardware_;
  ArmControl control_;
  CommandValidator validator_;
  TorqueLimiter limiter_;
  transport::Subscription<msg::JointCommand> joint_commands_;
  transport::Subscription<msg::CartesianCommand> cartesian_commands_;
  transport::Reader<msg::ResetRequest> reset_requests_;
  msg::ResetRequest reset_request_;
  std::string name_;
  transport::Publication<msg::JointState> state_pub_;
  transport::Publication<msg::WrenchStamped> wrench_pub_;
  robot::ArmState arm_{};
  msg::NodeState state_ = msg::STATE_STARTING;
  ValidCommand active_{};
  // teleoperation.architecture's part: which stream is awaited, the correction of the command
  std::unique_ptr<FollowerArchitecture> architecture_;
  const ValidCommand* controlled_ = &active_;
  SafetyReflex reflex_;
  bool emergency_stopped_ = false;
  bool awaiting_enable_ = false;  // a hold with after_hold: enable, until an enable
  bool coming_to_rest_ = false;
  SpeedBrake brake_;
  ValidCommand reflex_hold_{};
  JointRejoin rejoin_;
  JointVector held_q_rad_{};
  // the command sessions (writers followed in turn) of the joint and Cartesian streams
  uint64_t joint_session_ = 0;
  uint64_t cartesian_session_ = 0;
  uint64_t command_sessions_ = 0;
  uint64_t command_seq_ = 0;  // of the last valid command
  uint64_t resets_ = 0;
  // which source gave the last valid command, and its liveliness losses then
  Source source_ = Source::kNone;
  uint64_t liveliness_lost_at_command_ = 0;
  int64_t last_valid_command_ns_ = 0;
  JointVector total_nm_{};
  JointVector command_nm_{};
  // counters and metrics for the report
  uint64_t watchdog_trips_ = 0;
  uint64_t stall_holds_ = 0;
  uint64_t holds_awaiting_enable_ = 0;
  // holds because the robot's own state was stale, and the cycles it held through hold()
  uint64_t robot_state_holds_ = 0;
  uint64_t robot_stale_cycles_ = 0;
  // why the robot holds (msg::FAULT_*), while it holds
  uint32_t hold_cause_ = msg::FAULT_STALE_INPUT;
  StallWatch stall_watch_;
  uint64_t liveliness_trips_ = 0;
  double watchdog_latency_max_s_ = 0.0;
  uint64_t hardware_faults_ = 0;
  uint64_t mode_changes_ = 0;
  msg::ControlMode last_mode_ = msg::CONTROL_JOINT_IMPEDANCE;
  ErrorStats joint_tracking_;
  ErrorStats cartesian_tracking_;
  ErrorStats observer_vs_hardware_;
  ErrorStats direct_vs_hardware_;
  // the estimated external load's peaks: force and moment at the flange, largest joint torque
  double peak_external_force_n_ = 0.0;
  double peak_external_moment_nm_ = 0.0;
  double peak_external_joint_torque_nm_ = 0.0;
  double torque_ratio_ = 0.0;  // this cycle: max over joints of |tau| / limit
};

}  // namespace teleop::follower
