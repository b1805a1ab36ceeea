#pragma once
// Where the simulated operator wants the device to be (joint space), as a function of time:
//   sine       home + a sin(2 pi f t + 0.4 i) per joint i, the amplitude faded in over ramp_s
//   push_hold  home + a s(t/ramp_s), s the smoothstep: moves a (e.g. into a wall) and holds
//   recorded   a recorded joint motion (CSV, e.g. the device columns of an earlier leader trace),
//              optionally with the torque the operator adds on purpose
// Real-time safe.

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "teleop/common/joint_model.h"
#include "joint_trajectory.h"

namespace teleop::leader {

/// The simulated operator pressing one of the device's buttons for a while.
struct ButtonPress {
  uint32_t button = 0;
  double at_s = 0.0;
  double hold_s = 0.2;
};

struct OperatorMotionConfig {
  enum class Kind { kSine, kPushHold, kRecorded } kind = Kind::kSine;
  size_t joints = 7;
  JointVector home_rad{};
  JointVector amplitude_rad{};
  double frequency_hz = 0.5;
  /// sine: the amplitude fades in over this time; push_hold: the duration of the push.
  double ramp_s = 1.0;
  /// kRecorded: the motion, loaded at setup, and the prefix of its position columns.
  std::shared_ptr<const JointTrajectory> recording;
  std::string recording_columns = "q_dev_";
  /// leader.button_presses: the buttons the operator presses, and when.
  std::vector<ButtonPress> presses;
  /// leader.let_go_at_s: when the operator lets go of the device (hands off, no button held).
  double let_go_at_s = std::numeric_limits<double>::infinity();
  /// leader.motion_starts: in_command: the operator's clock (motion, presses, letting go) starts
  /// when the leader is first in command, so that flows matching late take no part of the motion
  /// (experiments); at_start (the default): when the node starts.
  bool starts_in_command = false;
};

class OperatorMotion {
 public:
  explicit OperatorMotion(const OperatorMotionConfig& config) : config_(config) {}

  /// The intended position and velocity at `t_s` after the start.
  void sample(double t_s, JointVector& q_rad, JointVector& dq_radps) const;
  /// The torque the operator adds on purpose at `t_s` (a recording's tau_op_ columns, e.g. a
  /// squeeze: a person grasps by pressing, not by aiming deeper); zero for the other kinds.
  void intended_torque(double t_s, JointVector& tau_nm) const;
  /// The buttons the operator holds pressed at `t_s` (bit k: button k); none once let go.
  uint32_t pressed_buttons(double t_s) const;
  /// Whether the operator's hand is on the device at `t_s`.
  bool holding(double t_s) const { return t_s < config_.let_go_at_s; }

 private:
  void sine(double t_s, JointVector& q_rad, JointVector& dq_radps) const;
  void push_hold(double t_s, JointVector& q_rad, JointVector& dq_radps) const;

  OperatorMotionConfig config_;
};

}  // namespace teleop::leader
