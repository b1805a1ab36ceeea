#pragma once
// The leader station with a scripted operator: streams a smooth joint motion as the commanded
// motion of the follower and as the device state for the twin, and receives the follower's
// state and wrench and the twin's feedback torque.

#include <teleop/msg/arm.h>

#include "teleop/common/config.h"
#include "teleop/common/joint_model.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::leader {

struct ScriptedLeaderConfig {
  size_t joints = 7;
  /// Centre of the motion per joint [rad] (the home pose).
  JointVector home_rad{};
  /// Amplitude of each joint's sinusoid [rad] (`amplitudes_rad`, or `amplitude_rad` for all).
  JointVector amplitude_rad{};
  double frequency_hz = 0.5;
  /// The amplitude fades in over this time from the start (no step to the first target).
  double ramp_s = 1.0;
  /// Joint impedance commanded to the follower.
  double stiffness_nm_per_rad = 200.0;
  double damping_nms_per_rad = 10.0;
  /// Follower silent longer than this: freeze the command and report the peer lost.
  double peer_timeout_s = 0.1;
};

class ScriptedLeader final : public runtime::NodeLogic {
 public:
  /// Reads the `leader:` section.
  static ScriptedLeaderConfig parse_config(const ConfigNode& root);

  ScriptedLeader(const ScriptedLeaderConfig& config, runtime::NodeContext& context);

  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override { return state_; }
  void active_faults(std::vector<uint32_t>& faults) const override;
  void fill_report(runtime::NodeReport& report) const override;

 private:
  void update_state(int64_t now_ns);
  void operator_motion(double t_s);

  ScriptedLeaderConfig config_;
  double period_s_;
  transport::Publication<msg::JointCommand> command_;
  transport::Publication<msg::JointState> device_state_;
  transport::Subscription<msg::JointState> follower_state_;
  transport::Subscription<msg::WrenchStamped> follower_wrench_;
  transport::Subscription<msg::JointTorque> twin_feedback_;
  msg::NodeState state_ = msg::STATE_STARTING;
  JointVector q_des_{};
  JointVector dq_des_{};
  JointVector feedback_{};
  uint64_t peer_lost_events_ = 0;
};

}  // namespace teleop::leader
