#include "teleop/follower/joint_rejoin.h"

namespace teleop::follower {

const ValidCommand& JointRejoin::apply(const ValidCommand& command) {
  // Cartesian and gravity-only commands carry no joint target to approach
  const bool joint_target = command.mode == msg::CONTROL_JOINT_IMPEDANCE || command.mode == msg::CONTROL_POSITION_PD;
  if (!joint_target) {
    ramp_.stop();
    return command;
  }
  if (!ramp_.step(command.q_des_rad)) return command;
  ramped_ = command;
  ramped_.q_des_rad = ramp_.reference();
  // the reference moves at its own pace: the command's velocity and feed-forward belong to its target
  ramped_.dq_des_radps.fill(0.0);
  ramped_.tau_ff_nm.fill(0.0);
  return ramped_;
}

}  // namespace teleop::follower
