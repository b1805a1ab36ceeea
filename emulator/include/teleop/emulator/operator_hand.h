#pragma once
// A simulated operator's hand on one joint of an arm used as a haptic master (teleop_arm_emulator
// --hand): it grips the joint where it is, moves its grip by `delta_rad` at `speed_radps` and
// holds it there, a spring-damper (the grip's stiffness and damping) against whatever the arm's
// drives render; let go, it applies nothing. Real-time safe.

#include <cstddef>

namespace teleop::emulator {

struct OperatorHandConfig {
  size_t joint = 0;  // 0-based
  double delta_rad = 0.0;
  double speed_radps = 0.2;
  double stiffness_nm_per_rad = 60.0;
  double damping_nms_per_rad = 4.0;
};

class OperatorHand {
 public:
  explicit OperatorHand(const OperatorHandConfig& config) : config_(config) {}

  /// Takes the joint where it is (`q_rad`) and starts moving it.
  void grip(double q_rad);
  void let_go() { holding_ = false; }
  bool holding() const { return holding_; }
  const OperatorHandConfig& config() const { return config_; }
  /// The hand's torque on its joint, `dt_s` after the last call, for the joint's state.
  double torque(double q_rad, double dq_radps, double dt_s);

 private:
  OperatorHandConfig config_;
  bool holding_ = false;
  double grip_rad_ = 0.0;    // where the hand took the joint
  double target_rad_ = 0.0;  // where the hand is now
};

}  // namespace teleop::emulator
