#include "simulated_haptic_arm.h"

#include <stdexcept>

namespace teleop::leader {

SimulatedHapticArm::SimulatedHapticArm(const HapticArmConfig& config) : config_(config), arm_(config.model) {
  if (config.model.keyframe.empty()) arm_.place(config.start_rad);
  if (arm_.read(measured_) != robot::HardwareStatus::kOk) throw std::runtime_error("the simulated haptic arm cannot be read");
  // the operator starts by holding the device where it is
  target_q_ = measured_.q_rad;
  start_q_rad_ = measured_.q_rad;
}

void SimulatedHapticArm::set_operator_intent(const OperatorIntent& intent) {
  for (size_t i = 0; i < arm_.joints(); ++i) {
    intent_target_[i] = start_q_rad_[i] + intent.q_rad[i] - config_.start_rad[i];
  }
  set_operator_target(intent_target_, intent.dq_radps, intent.tau_nm);
  hand_on_ = intent.hand_on;
}

void SimulatedHapticArm::set_operator_target(const JointVector& q_rad, const JointVector& dq_radps,
                                             const JointVector& intended_nm) {
  target_q_ = q_rad;
  target_dq_ = dq_radps;
  intended_nm_ = intended_nm;
}

bool SimulatedHapticArm::read(DeviceState& state) {
  if (arm_.read(measured_) != robot::HardwareStatus::kOk) return false;
  state.q_rad = measured_.q_rad;
  state.dq_radps = measured_.dq_radps;
  state.tau_operator_nm = operator_nm_;
  return true;
}

bool SimulatedHapticArm::write(const JointVector& feedback_nm) {
  for (size_t i = 0; i < arm_.joints(); ++i) {
    // let go, the hand holds nothing: the arm has only the feedback on it
    operator_nm_[i] = !hand_on_ ? 0.0
                                : config_.hand_stiffness_nm_per_rad * (target_q_[i] - measured_.q_rad[i]) +
                                      config_.hand_damping_nms_per_rad * (target_dq_[i] - measured_.dq_radps[i]) +
                                      intended_nm_[i];
    applied_[i] = operator_nm_[i] + feedback_nm[i];
  }
  return arm_.write(applied_) == robot::HardwareStatus::kOk;
}

}  // namespace teleop::leader
