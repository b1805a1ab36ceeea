#include "teleop/follower/simple_hardware.h"

namespace teleop::follower {

SimpleHardware::SimpleHardware(const JointModelParams& params, const JointVector& home_rad, double period_s,
                               double lever_m)
    : model_(params), period_s_(period_s), lever_m_(lever_m) {
  model_.reset(home_rad);
}

HardwareStatus SimpleHardware::read(ArmState& state) {
  state.q_rad = model_.q();
  state.dq_radps = model_.dq();
  state.tau_measured_nm = applied_;
  state.tau_ext_nm = model_.contact_torque();
  // the wall's torque seen as a force at the tool, normal to the lever
  double wall_torque = 0.0;
  for (size_t i = 0; i < model_.joints(); ++i) wall_torque += model_.contact_torque()[i];
  state.force_ext_n = {wall_torque / lever_m_, 0.0, 0.0};
  state.torque_ext_nm = {0.0, 0.0, wall_torque};
  return HardwareStatus::kOk;
}

HardwareStatus SimpleHardware::write(const JointVector& tau_nm) {
  applied_ = tau_nm;
  model_.step(tau_nm, period_s_);
  return HardwareStatus::kOk;
}

}  // namespace teleop::follower
