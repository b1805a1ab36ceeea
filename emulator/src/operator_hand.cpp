#include "teleop/emulator/operator_hand.h"

#include <algorithm>

namespace teleop::emulator {

void OperatorHand::grip(double q_rad) {
  grip_rad_ = q_rad;
  target_rad_ = q_rad;
  holding_ = true;
}

double OperatorHand::torque(double q_rad, double dq_radps, double dt_s) {
  if (!holding_) return 0.0;
  // the hand moves towards grip + delta at its speed, then stays
  const double goal = grip_rad_ + config_.delta_rad;
  const double step = config_.speed_radps * dt_s;
  target_rad_ += std::clamp(goal - target_rad_, -step, step);
  const double moving = target_rad_ != goal ? (goal > grip_rad_ ? config_.speed_radps : -config_.speed_radps) : 0.0;
  return config_.stiffness_nm_per_rad * (target_rad_ - q_rad) + config_.damping_nms_per_rad * (moving - dq_radps);
}

}  // namespace teleop::emulator
