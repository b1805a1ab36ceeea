#include "teleop/follower/joint_rejoin.h"

#include <algorithm>
#include <cmath>

namespace teleop::follower {

void JointRejoin::start(const JointVector& held_rad) {
  reference_rad_ = held_rad;
  active_ = true;
  ++rejoins_;
}

const ValidCommand& JointRejoin::apply(const ValidCommand& command) {
  // Cartesian and gravity-only commands carry no joint target to approach
  const bool joint_target = command.mode == msg::CONTROL_JOINT_IMPEDANCE || command.mode == msg::CONTROL_POSITION_PD;
  if (!active_ || !joint_target) {
    active_ = false;
    return command;
  }
  bool caught_up = true;
  for (size_t i = 0; i < joints_; ++i) {
    const double gap = command.q_des_rad[i] - reference_rad_[i];
    if (std::abs(gap) > max_step_rad_) caught_up = false;
    reference_rad_[i] += std::clamp(gap, -max_step_rad_, max_step_rad_);
  }
  if (caught_up) {
    active_ = false;
    return command;
  }
  ramped_ = command;
  ramped_.q_des_rad = reference_rad_;
  // the reference moves at its own pace: the command's velocity and feed-forward belong to its target
  ramped_.dq_des_radps.fill(0.0);
  ramped_.tau_ff_nm.fill(0.0);
  return ramped_;
}

}  // namespace teleop::follower
